// The image writers of color/image_output.h, EXR and display images (PNG, JPEG, TIFF): round
// trips through OpenImageIO, header contents, encodings, atomicity and the writability check.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "core/error.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

using test::read_bytes;
namespace fs = std::filesystem;

class ColorImageOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* v = std::getenv("OCIO")) saved_ocio_ = v;
    unsetenv("OCIO");  // the bundled config, whatever the caller's environment
    dir_ = test::make_temp_dir("color_exr");
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
    if (saved_ocio_) setenv("OCIO", saved_ocio_->c_str(), 1);
  }

  fs::path dir_;
  std::optional<std::string> saved_ocio_;
};

const std::vector<std::string> channel_list = {
    "R",   "G",   "B", "albedo.R",      "albedo.G",   "albedo.B",   "N.X",
    "N.Y", "N.Z", "Z", "sampleCount.Y", "variance.R", "variance.G", "variance.B"};

// A small render-like image with fixed pseudo-random content.
Image make_image(int width, int height, uint32_t seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Image image;
  image.width = width;
  image.height = height;
  image.channel_names = channel_list;
  for (int i = 0; i < width * height; ++i) {
    for (int c = 0; c < 3; ++c) image.pixels.push_back(unit(rng) * 8.0f);  // HDR beauty
    for (int c = 0; c < 3; ++c) image.pixels.push_back(unit(rng));         // albedo
    const glm::vec3 n = glm::normalize(glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, 0.3f));
    image.pixels.insert(image.pixels.end(), {n.x, n.y, n.z});
    image.pixels.push_back(1000.0f + 37.123f * float(i));  // depth beyond half precision
    image.pixels.push_back(float(4097 + i));               // counts half cannot hold
    for (int c = 0; c < 3; ++c) image.pixels.push_back(unit(rng) * 0.01f);
  }
  return image;
}

const ImageMetadata metadata_pairs = {{"prism:version", "0.1.0"},
                                      {"prism:scene", "scenes/cornell.json"},
                                      {"prism:integrator", "path"}};

// Files in `dir` other than `keep` (temporaries left behind would show up here).
std::vector<std::string> other_files(const fs::path& dir, const std::string& keep) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename() != keep) names.push_back(e.path().filename().string());
  }
  return names;
}

template <typename F>
Error expect_error(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "expected prism::Error";
  return Error(ErrorKind::kInternal, "no error");
}

TEST_F(ColorImageOutput, HalfZipRoundTripKeepsPixelsChannelsAndHeader) {
  ColorPipeline pipeline({});
  const Image image = make_image(7, 5);
  const fs::path path = dir_ / "beauty.exr";
  write_exr(path, image, metadata_pairs, pipeline);
  const ImageFileContents file = read_image_file(path);

  EXPECT_EQ(file.format, "openexr");
  EXPECT_EQ(file.compression, "zip");
  ASSERT_EQ(file.image.width, 7);
  ASSERT_EQ(file.image.height, 5);
  ASSERT_EQ(file.image.channels(), int(channel_list.size()) + 1);
  EXPECT_EQ(std::vector<std::string>(file.image.channel_names.begin(),
                                     file.image.channel_names.begin() + 4),
            (std::vector<std::string>{"R", "G", "B", "A"}));
  for (const std::string& name : channel_list) {
    const int c = file.channel(name);
    ASSERT_GE(c, 0) << name;
    const bool wide = name == "Z" || name == "sampleCount.Y";
    EXPECT_EQ(file.channel_formats[c], wide ? "float" : "half") << name;
    const int source =
        int(std::find(channel_list.begin(), channel_list.end(), name) - channel_list.begin());
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const float want = image.at(x, y, source), got = file.image.at(x, y, c);
        // Half keeps 11 significant bits: relative error at most 2^-11.
        const float tolerance = wide ? 0.0f : std::abs(want) * 4.9e-4f + 1e-7f;
        EXPECT_NEAR(got, want, tolerance) << name << " at " << x << "," << y;
      }
    }
  }
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) EXPECT_EQ(file.image.at(x, y, 3), 1.0f);
  }

  ASSERT_TRUE(file.chromaticities.has_value());
  const std::array<float, 8> rec709{0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  EXPECT_EQ(*file.chromaticities, rec709);
  EXPECT_EQ(file.attribute("prism:version"), "0.1.0");
  EXPECT_EQ(file.attribute("prism:scene"), "scenes/cornell.json");
  EXPECT_EQ(file.attribute("prism:integrator"), "path");
  EXPECT_EQ(file.attribute("prism:ocioConfig"), "prism-default-v1");
  EXPECT_EQ(file.attribute("prism:ocioConfigHash"), pipeline.config_hash());
  EXPECT_EQ(file.attribute("prism:ocioConfigSource"), "bundled");
  EXPECT_EQ(file.attribute("prism:workingSpace"), "Linear Rec.709 (sRGB)");
  EXPECT_EQ(file.attribute("prism:colorSpace"), "Linear Rec.709 (sRGB)");
  EXPECT_EQ(file.attribute("prism:display"), "sRGB - Display");
  EXPECT_EQ(file.attribute("prism:view"), "Standard");
  EXPECT_EQ(file.attribute("prism:halfClampedValues"), "");
  EXPECT_EQ(other_files(dir_, "beauty.exr"), std::vector<std::string>{});
}

TEST_F(ColorImageOutput, FloatPizInAcescgConvertsColourLayersOnly) {
  ColorOptions options;
  options.output_space = "ACEScg";
  ColorPipeline pipeline(options);
  const Image image = make_image(4, 3, 11);
  const fs::path path = dir_ / "acescg.exr";
  write_exr(path, image, metadata_pairs, pipeline, ExrOptions{"float", "piz"});
  const ImageFileContents file = read_image_file(path);
  EXPECT_EQ(file.compression, "piz");
  for (const std::string& f : file.channel_formats) EXPECT_EQ(f, "float");
  const std::array<float, 8> ap1{0.713f, 0.293f, 0.165f,   0.830f,
                                 0.128f, 0.044f, 0.32168f, 0.33767f};
  ASSERT_TRUE(file.chromaticities.has_value());
  EXPECT_EQ(*file.chromaticities, ap1);
  EXPECT_EQ(file.attribute("prism:colorSpace"), "ACEScg");
  EXPECT_EQ(file.attribute("prism:workingSpace"), "Linear Rec.709 (sRGB)");
  float largest_change = 0.0f;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int layer : {0, 3}) {  // beauty, albedo
        const Rgb in(image.at(x, y, layer), image.at(x, y, layer + 1), image.at(x, y, layer + 2));
        const Rgb want = pipeline.convert(in, "Linear Rec.709 (sRGB)", "ACEScg");
        const int c = file.channel(channel_list[layer]);
        for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(file.image.at(x, y, c + k), want[k]);
        largest_change = std::max(largest_change, std::abs(want.x - in.x));
      }
      for (size_t source = 6; source < channel_list.size(); ++source) {  // data: untouched
        EXPECT_EQ(file.image.at(x, y, file.channel(channel_list[source])),
                  image.at(x, y, int(source)))
            << channel_list[source];
      }
    }
  }
  EXPECT_GT(largest_change, 0.01f);  // the conversion did something
}

TEST_F(ColorImageOutput, EveryCompressionIsWrittenAndBadOptionsAreUsageErrors) {
  ColorPipeline pipeline({});
  const Image image = make_image(16, 16);
  for (const char* compression : {"zip", "piz", "dwaa", "none"}) {
    const fs::path path = dir_ / (std::string(compression) + ".exr");
    write_exr(path, image, {}, pipeline, ExrOptions{"half", compression});
    const ImageFileContents file = read_image_file(path);
    EXPECT_EQ(file.compression, compression);
    // DWAA is lossy on colour channels only; the others are lossless on half data.
    const float tolerance = std::string(compression) == "dwaa" ? 0.05f : 4.9e-4f;
    EXPECT_NEAR(file.image.at(3, 4, 0), image.at(3, 4, 0), tolerance * image.at(3, 4, 0) + 1e-3f);
    EXPECT_EQ(file.image.at(3, 4, file.channel("Z")), image.at(3, 4, 9));
  }
  for (const ExrOptions& bad :
       {ExrOptions{"half", "zip9"}, ExrOptions{"half", "b44"}, ExrOptions{"double", "zip"}}) {
    const fs::path path = dir_ / "bad.exr";
    const Error e = expect_error([&] { write_exr(path, image, {}, pipeline, bad); });
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_NE(e.message().find("available:"), std::string::npos) << e.message();
    EXPECT_FALSE(fs::exists(path));
  }
  EXPECT_EQ(expect_error([] {
              validate_exr_options({"half", "PIZ"});
            }).message(),
            "unknown EXR compression 'PIZ'; available: zip, piz, dwaa, none");
}

TEST_F(ColorImageOutput, HalfClampsOverflowVisiblyAndFloatKeepsIt) {
  ColorPipeline pipeline({});
  Image image;
  image.width = 2;
  image.height = 1;
  image.channel_names = {"R", "G", "B"};
  image.pixels = {1e6f, 0.5f, -2e5f, 1.0f, 2.0f, 3.0f};
  write_exr(dir_ / "half.exr", image, {}, pipeline);
  const ImageFileContents half = read_image_file(dir_ / "half.exr");
  EXPECT_EQ(half.image.at(0, 0, 0), 65504.0f);
  EXPECT_EQ(half.image.at(0, 0, 2), -65504.0f);
  EXPECT_EQ(half.attribute("prism:halfClampedValues"), "2");
  write_exr(dir_ / "float.exr", image, {}, pipeline, ExrOptions{"float", "zip"});
  const ImageFileContents full = read_image_file(dir_ / "float.exr");
  EXPECT_EQ(full.image.at(0, 0, 0), 1e6f);
  EXPECT_EQ(full.attribute("prism:halfClampedValues"), "");

  // Channels already in the file's order (R, G, B, A): the writer uses the image's own pixels
  // when nothing changes them, and must still see the value to clamp, in a copy.
  Image rgba;
  rgba.width = 2;
  rgba.height = 1;
  rgba.channel_names = {"R", "G", "B", "A"};
  rgba.pixels = {0.25f, 0.5f, 0.75f, 1.0f, 1.0f, 2.0f, -3e5f, 0.5f};
  const ImagePixels before = rgba.pixels;
  write_exr(dir_ / "rgba_half.exr", rgba, {}, pipeline);
  const ImageFileContents rgba_half = read_image_file(dir_ / "rgba_half.exr");
  EXPECT_EQ(rgba_half.image.at(1, 0, 2), -65504.0f);
  EXPECT_EQ(rgba_half.image.at(0, 0, 1), 0.5f);
  EXPECT_EQ(rgba_half.attribute("prism:halfClampedValues"), "1");
  EXPECT_TRUE(rgba.pixels == before) << "the image itself was changed";
  write_exr(dir_ / "rgba_float.exr", rgba, {}, pipeline, ExrOptions{"float", "zip"});
  const ImageFileContents rgba_float = read_image_file(dir_ / "rgba_float.exr");
  ASSERT_EQ(rgba_float.image.pixels.size(), before.size());
  for (size_t i = 0; i < before.size(); ++i) EXPECT_EQ(rgba_float.image.pixels[i], before[i]) << i;
}

TEST_F(ColorImageOutput, MissingFolderIsAnOutputErrorAndLeavesNoFile) {
  ColorPipeline pipeline({});
  const fs::path path = dir_ / "no_such_folder" / "beauty.exr";
  Error e = expect_error([&] { check_output_writable(path); });
  EXPECT_EQ(e.kind(), ErrorKind::kOutput);
  EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  e = expect_error([&] { write_exr(path, make_image(2, 2), metadata_pairs, pipeline); });
  EXPECT_EQ(e.kind(), ErrorKind::kOutput);
  EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  e = expect_error(
      [&] { write_display_image(dir_ / "none" / "a.png", make_image(2, 2), {}, pipeline); });
  EXPECT_EQ(e.kind(), ErrorKind::kOutput);
  EXPECT_FALSE(fs::exists(dir_ / "no_such_folder"));
  EXPECT_EQ(other_files(dir_, ""), std::vector<std::string>{});

  EXPECT_NO_THROW(check_output_writable(dir_ / "fine.exr"));
  EXPECT_EQ(expect_error([&] { check_output_writable(dir_); }).kind(), ErrorKind::kOutput);
  EXPECT_EQ(other_files(dir_, ""), std::vector<std::string>{});  // the probe file is gone
}

// An I/O failure in the middle of writing: the file-size limit makes writes past 64 KiB fail
// (EFBIG), as a full disk would. The previous file must survive byte for byte.
TEST_F(ColorImageOutput, FailedWriteLeavesThePreviousFileUntouched) {
  ColorPipeline pipeline({});
  const fs::path path = dir_ / "beauty.exr";
  write_exr(path, make_image(8, 8), metadata_pairs, pipeline);
  const std::string previous = read_bytes(path);
  ASSERT_FALSE(previous.empty());
  ASSERT_LT(previous.size(), 64u * 1024u);

  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit limited = saved;
  limited.rlim_cur = rlim_t{64} * 1024;
  auto* const saved_handler = signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limited), 0);
  std::optional<Error> error;
  try {
    // 128 x 128 x 15 uncompressed floats: about 1 MB, far past the limit.
    write_exr(path, make_image(128, 128, 3), metadata_pairs, pipeline, ExrOptions{"float", "none"});
  } catch (const Error& e) {
    error = e;
  }
  setrlimit(RLIMIT_FSIZE, &saved);
  signal(SIGXFSZ, saved_handler);

  ASSERT_TRUE(error.has_value()) << "the write should have failed";
  EXPECT_EQ(error->kind(), ErrorKind::kOutput);
  EXPECT_NE(std::string(error->what()).find(path.string()), std::string::npos) << error->what();
  EXPECT_NE(error->message().find("cannot write the openexr file"), std::string::npos)
      << error->what();
  EXPECT_EQ(read_bytes(path), previous);
  EXPECT_EQ(other_files(dir_, "beauty.exr"), std::vector<std::string>{});
}

TEST_F(ColorImageOutput, NonFiniteValuesAreRefusedBeforeAnythingIsWritten) {
  ColorPipeline pipeline({});
  const fs::path path = dir_ / "beauty.exr";
  write_exr(path, make_image(3, 3), metadata_pairs, pipeline);
  const std::string previous = read_bytes(path);
  for (float bad : {std::nanf(""), INFINITY}) {
    Image image = make_image(3, 3);
    image.at(1, 2, 10) = bad;  // a data channel: nothing converts it on the way
    const Error e = expect_error([&] { write_exr(path, image, metadata_pairs, pipeline); });
    EXPECT_EQ(e.kind(), ErrorKind::kInternal);
    EXPECT_NE(e.message().find("1 NaN/Inf"), std::string::npos) << e.message();
    image.at(1, 2, 10) = 1.0f;
    image.at(0, 0, 1) = bad;
    EXPECT_EQ(
        expect_error([&] { write_display_image(dir_ / "d.png", image, {}, pipeline); }).kind(),
        ErrorKind::kInternal);
  }
  EXPECT_EQ(read_bytes(path), previous);
  EXPECT_EQ(other_files(dir_, "beauty.exr"), std::vector<std::string>{});
}

TEST_F(ColorImageOutput, DisplayImagesAreEightBitThroughTheView) {
  ColorPipeline pipeline({});
  Image image;
  image.width = 3;
  image.height = 2;
  image.channel_names = {"R", "G", "B", "N.X"};
  for (int i = 0; i < 6; ++i) image.pixels.insert(image.pixels.end(), {0.18f, 1.0f, 4.0f, -1.0f});
  image.at(2, 1, 0) = 0.0f;
  for (const char* name : {"out.png", "out.jpg", "out.tif", "out.TIFF", "out.jpeg"}) {
    const fs::path path = dir_ / name;
    ASSERT_TRUE(is_display_image_path(path)) << name;
    write_display_image(path, image, metadata_pairs, pipeline);
    const ImageFileContents file = read_image_file(path);
    ASSERT_EQ(file.image.channels(), 3) << name;
    EXPECT_EQ(file.channel_formats[0], "uint8") << name;
    // sRGB(0.18) = 0.4613561 -> 117.65 -> 118; JPEG may be off by a little.
    const float tolerance = file.format == "jpeg" ? 3.0f / 255.0f : 0.0f;
    EXPECT_NEAR(file.image.at(0, 0, 0), 118.0f / 255.0f, tolerance + 1e-6f) << name;
    EXPECT_NEAR(file.image.at(0, 0, 1), 1.0f, tolerance + 1e-6f) << name;
    EXPECT_NEAR(file.image.at(0, 0, 2), 1.0f, tolerance + 1e-6f) << name;  // clipped
    if (file.format != "jpeg") {
      EXPECT_EQ(file.image.at(2, 1, 0), 0.0f) << name;
    }
  }
  EXPECT_EQ(read_image_file(dir_ / "out.png").attribute("prism:view"), "Standard");
  EXPECT_FALSE(is_display_image_path(dir_ / "out.exr"));
  EXPECT_FALSE(is_display_image_path(dir_ / "out.bmp"));
  const Error e = expect_error([&] { write_display_image(dir_ / "out.bmp", image, {}, pipeline); });
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
  EXPECT_FALSE(fs::exists(dir_ / "out.bmp"));
}

/// check_exr_header() (read_image_file, state files): an attribute claiming more bytes than the
/// file holds is Error(kInput) naming it, before OpenEXR allocates them (found by the fuzzer:
/// tests/fuzz/regressions/). A whole header passes, and so does a file that is not an EXR.
TEST_F(ColorImageOutput, ExrHeaderClaimingMoreThanTheFileIsAnInputError) {
  const auto write_bytes = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return dir_ / name;
  };
  using namespace std::string_literals;
  const std::string magic = "\x76\x2f\x31\x01\x02\x00\x00\x00"s;
  const fs::path huge =
      write_bytes("huge.exr", magic + "comments\0string\0"s + "\xff\xff\xff\x7f"s + "abc");
  const Error e = expect_error([&] { check_exr_header(huge); });
  EXPECT_EQ(e.kind(), ErrorKind::kInput);
  EXPECT_NE(std::string(e.what()).find("attribute 'comments' (string) claims 2147483647 bytes"),
            std::string::npos)
      << e.what();
  EXPECT_THROW(read_image_file(huge), Error);
  EXPECT_THROW(check_exr_header(write_bytes("cut.exr", magic + "comm")), Error);
  // A header without the attributes every EXR has, and one with a window of 2^31 lines.
  const Error missing = expect_error([&] {
    check_exr_header(write_bytes("few.exr", magic + "a\0int\0\x04\0\0\0"
                                                    "1234\0"s));
  });
  EXPECT_NE(std::string(missing.what()).find("has no 'channels' attribute"), std::string::npos)
      << missing.what();
  const Error tall = expect_error([&] {
    check_exr_header(write_bytes("tall.exr", magic +
                                                 "dataWindow\0box2i\0\x10\0\0\0"
                                                 "\0\0\0\0\0\0\0\x80\0\0\0\0\xff\xff\xff\x7f"s));
  });
  EXPECT_NE(std::string(tall.what()).find("dataWindow of 1 x 4294967296 pixels"), std::string::npos)
      << tall.what();
  // A channel of a pixel type OpenEXR does not define (OpenImageIO aborts on it) or sampled
  // other than 1 x 1.
  const auto one_channel = [](const std::string& type, const std::string& sampling) {
    return "channels\0chlist\0\x13\0\0\0R\0"s + type + "\0\0\0\0"s + sampling + "\0"s;
  };
  const Error type = expect_error([&] {
    check_exr_header(
        write_bytes("type.exr", magic + one_channel("\xfc\xff\xff\xff"s, "\1\0\0\0\1\0\0\0"s)));
  });
  EXPECT_NE(std::string(type.what()).find("channel 'R' has pixel type 4294967292"),
            std::string::npos)
      << type.what();
  const Error sampling = expect_error([&] {
    check_exr_header(
        write_bytes("sampling.exr", magic + one_channel("\2\0\0\0"s, "\1\0\0\0\0\0\0\0"s)));
  });
  EXPECT_NE(std::string(sampling.what()).find("channel 'R' is sampled 1 x 0"), std::string::npos)
      << sampling.what();
  const Error wide = expect_error([&] {
    check_exr_header(
        write_bytes("subsampled.exr", magic + one_channel("\2\0\0\0"s, "\1\0\x08\0\1\0\0\0"s)));
  });
  EXPECT_NE(std::string(wide.what()).find("channel 'R' is sampled 524289 x 1"), std::string::npos)
      << wide.what();
  // Scanlines of 2^20 pixels x two float channels: 8 MiB a line, OpenEXR's buffers sized by it.
  const Error wide_lines = expect_error([&] {
    check_exr_header(write_bytes(
        "wide_lines.exr",
        magic + "channels\0chlist\0\x25\0\0\0"s + "A\0\2\0\0\0\0\0\0\0\1\0\0\0\1\0\0\0"s +
            "B\0\2\0\0\0\0\0\0\0\1\0\0\0\1\0\0\0\0"s + "dataWindow\0box2i\0\x10\0\0\0"s +
            "\0\0\0\0\0\0\0\0\xff\xff\x0f\0\0\0\0\0"s + "\0"s));
  });
  EXPECT_NE(std::string(wide_lines.what()).find("scanlines of 1048576 pixels x 8 bytes"),
            std::string::npos)
      << wide_lines.what();
  // What prism writes passes, and so does a file that is not an EXR.
  ColorPipeline pipeline({});
  write_exr(dir_ / "beauty.exr", make_image(3, 2), metadata_pairs, pipeline);
  EXPECT_NO_THROW(check_exr_header(dir_ / "beauty.exr"));
  EXPECT_NO_THROW(check_exr_header(write_bytes("not.exr", "PF\n1 1\n-1\n")));
}

/// read_image_file: rows so wide that OpenImageIO's buffer of 256 scanlines would pass 1 GiB are
/// Error(kInput) before it is allocated (found by fuzzing environment_map: a 55555555 x 1 PFM
/// asked for 170 GB). A 16384-wide image, wider than any film, reads.
TEST_F(ColorImageOutput, ImageWithRowsTooWideToReadIsAnInputError) {
  const auto pfm = [&](const std::string& name, int width) {
    std::string bytes = "PF\n" + std::to_string(width) + " 1\n-1\n";
    bytes.append(size_t(width) * 12, '\0');
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return dir_ / name;
  };
  const Error e = expect_error([&] { read_image_file(pfm("wide.pfm", 1 << 20)); });
  EXPECT_EQ(e.kind(), ErrorKind::kInput);
  EXPECT_NE(std::string(e.what()).find("1048576 x 1 pixels of 3 channels in scanlines"),
            std::string::npos)
      << e.what();
  EXPECT_NE(std::string(e.what()).find("wide.pfm"), std::string::npos) << e.what();
  const ImageFileContents ok = read_image_file(pfm("ok.pfm", 16384));
  EXPECT_EQ(ok.image.width, 16384);
  EXPECT_EQ(ok.image.height, 1);
}

/// read_image_file opens a file with the reader its first bytes name, whatever its extension (a
/// JPEG named .png reads), and tries no other when that one fails; bytes of no format it knows
/// are Error(kInput) naming the file (OpenImageIO would try each of its readers: its DICOM
/// reader took seconds, found by fuzzing environment_map).
TEST_F(ColorImageOutput, ImagesAreReadAsWhatTheirFirstBytesSay) {
  using namespace std::string_literals;
  const fs::path jpeg_named_png = dir_ / "photo.png";
  {
    auto out = OIIO::ImageOutput::create("jpeg");
    ASSERT_TRUE(out);
    const OIIO::ImageSpec spec(4, 2, 3, OIIO::TypeDesc::UINT8);
    ASSERT_TRUE(out->open(jpeg_named_png.string(), spec));
    const std::vector<unsigned char> pixels(4 * 2 * 3, 128);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    ASSERT_TRUE(out->close());
  }
  const ImageFileContents jpeg = read_image_file(jpeg_named_png);
  EXPECT_EQ(jpeg.format, "jpeg");
  EXPECT_EQ(jpeg.image.width, 4);

  // Formats prism does not read, GIF among them (OpenImageIO's GIF reader can end the process).
  for (const std::string& bytes :
       {std::string(), std::string("plain text, no image"), std::string("GIF89a\1\0\1\0")}) {
    const fs::path path = dir_ / "unknown.exr";
    std::ofstream(path, std::ios::binary) << bytes;
    const Error e = expect_error([&] { read_image_file(path); });
    EXPECT_EQ(e.kind(), ErrorKind::kInput);
    EXPECT_NE(std::string(e.what()).find("not a format prism reads"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("unknown.exr"), std::string::npos) << e.what();
  }
  // A broken PNG is a PNG error, from the PNG reader alone.
  const fs::path broken = dir_ / "broken.png";
  std::ofstream(broken, std::ios::binary) << "\x89PNG\r\n\x1a\n broken";
  const Error e = expect_error([&] { read_image_file(broken); });
  EXPECT_NE(std::string(e.what()).find("cannot read the image (png)"), std::string::npos)
      << e.what();
  // A PNG chunk claiming more bytes than the file has (libpng would allocate them first).
  const fs::path claims = dir_ / "claims.png";
  std::ofstream(claims, std::ios::binary) << "\x89PNG\r\n\x1a\n"s
                                          << "\x6c\x65\x78\x35tEXtabc"s;
  const Error chunk = expect_error([&] { read_image_file(claims); });
  EXPECT_NE(std::string(chunk.what()).find("chunk 'tEXt' at byte 8 claims 1818589237 bytes"),
            std::string::npos)
      << chunk.what();
}

}  // namespace
}  // namespace prism
