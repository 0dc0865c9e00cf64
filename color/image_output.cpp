#include "color/image_output.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/strings.h"

namespace prism {
namespace fs = std::filesystem;

namespace {

constexpr float kHalfMax = 65504.0f;

fs::path folder_of(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

// A hidden file beside the target, unique per process and call, so concurrent writers never
// share one.
fs::path temp_path_for(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  std::string name = ".";
  name += target.filename().string();
  name += ".prism-tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
  return folder_of(target) / name;
}

Error output_error(const fs::path& path, const std::string& message) {
  return Error(ErrorKind::kOutput, message, ErrorLocation{path.string(), 0, {}});
}

// The written file replaces the target only once complete and on disk: a crash or error leaves
// the previous file, never a partial one.
class TempFile {
 public:
  explicit TempFile(const fs::path& target) : target_(target), temp_(temp_path_for(target)) {}
  ~TempFile() {
    if (!committed_) {
      std::error_code ec;
      fs::remove(temp_, ec);
    }
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const fs::path& path() const { return temp_; }

  void commit() {
    const int fd = ::open(temp_.c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0) {
      const std::string reason = std::strerror(errno);
      if (fd >= 0) ::close(fd);
      throw output_error(target_, "cannot flush the written file to disk: " + reason);
    }
    ::close(fd);
    std::error_code ec;
    fs::rename(temp_, target_, ec);
    if (ec) throw output_error(target_, "cannot replace the file: " + ec.message());
    committed_ = true;
    // Make the rename itself durable; a failure here loses nothing already written.
    if (const int dir = ::open(folder_of(target_).c_str(), O_RDONLY | O_DIRECTORY); dir >= 0) {
      ::fsync(dir);
      ::close(dir);
    }
  }

 private:
  fs::path target_;
  fs::path temp_;
  bool committed_ = false;
};

// Writes interleaved pixels of `type` with OpenImageIO's writer for `format` to a temporary file
// and renames it over `target`.
void write_atomically(const fs::path& target, const std::string& format,
                      const OIIO::ImageSpec& spec, const OIIO::TypeDesc& type, const void* pixels) {
  TempFile temp(target);
  try {
    auto out = OIIO::ImageOutput::create(format);
    if (!out) throw output_error(target, "no " + format + " writer: " + OIIO::geterror());
    const bool ok =
        out->open(temp.path().string(), spec) && out->write_image(type, pixels) && out->close();
    if (!ok) {
      const std::string reason = out->geterror();
      throw output_error(target, "cannot write the " + format +
                                     " file: " + (reason.empty() ? "unknown error" : reason));
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw output_error(target, "cannot write the " + format + " file: " + e.what());
  }
  temp.commit();
}

// NaN and Inf never reach a file: the film drops them, so one here is a bug to report, not a
// value to patch.
void check_finite(const std::vector<float>& values, const fs::path& path) {
  const size_t bad =
      std::count_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); });
  if (bad > 0) {
    throw Error(ErrorKind::kInternal,
                std::to_string(bad) + " NaN/Inf values would be written; refusing to write",
                ErrorLocation{path.string(), 0, {}});
  }
}

std::string layer_of(const std::string& channel) {
  const auto dot = channel.rfind('.');
  return dot == std::string::npos ? channel : channel.substr(0, dot);
}

// Layers whose values half precision would damage (depths, positions, counts and ids above 2048).
bool needs_float(const std::string& channel) {
  constexpr const char* kLayers[] = {"z",           "depth", "p",        "position",
                                     "samplecount", "id",    "objectid", "materialid"};
  const std::string layer = to_lower(layer_of(channel));
  return std::any_of(std::begin(kLayers), std::end(kLayers),
                     [&](const char* l) { return layer == l; });
}

void add_metadata(OIIO::ImageSpec& spec, const ImageMetadata& metadata) {
  for (const auto& [name, value] : metadata) {
    if (!name.empty()) spec.attribute(name, value);
  }
}

void add_pipeline_metadata(OIIO::ImageSpec& spec, const ColorPipeline& pipeline) {
  spec.attribute("prism:ocioConfig", pipeline.config_name());
  spec.attribute("prism:ocioConfigHash", pipeline.config_hash());
  spec.attribute("prism:ocioConfigSource", pipeline.config_source());
  spec.attribute("prism:workingSpace", pipeline.working_space());
  if (!pipeline.display().empty()) {
    spec.attribute("prism:display", pipeline.display());
    spec.attribute("prism:view", pipeline.view());
  }
  if (!pipeline.look().empty()) spec.attribute("prism:look", pipeline.look());
}

std::string display_format(const fs::path& path) {
  const std::string ext = lower_case_extension(path);
  if (ext == ".png") return "png";
  if (ext == ".jpg" || ext == ".jpeg") return "jpeg";
  if (ext == ".tif" || ext == ".tiff") return "tiff";
  return {};
}

}  // namespace

void validate_exr_options(const ExrOptions& options) {
  if (options.pixel_type != "half" && options.pixel_type != "float") {
    throw Error(ErrorKind::kUsage,
                "unknown EXR pixel type '" + options.pixel_type + "'; available: half, float");
  }
  if (options.compression != "zip" && options.compression != "piz" &&
      options.compression != "dwaa" && options.compression != "none") {
    throw Error(ErrorKind::kUsage, "unknown EXR compression '" + options.compression +
                                       "'; available: zip, piz, dwaa, none");
  }
}

void write_exr(const fs::path& path, const Image& image, const ImageMetadata& metadata,
               const ColorPipeline& pipeline, const ExrOptions& options) {
  validate_exr_options(options);
  PRISM_CHECK(image.width > 0 && image.height > 0);
  PRISM_CHECK(image.pixels.size() == size_t(image.width) * image.height * image.channels());
  check_output_writable(path);

  Image converted = image;
  pipeline.working_to_output(converted);

  // Beauty RGBA first, as compositors expect, then every AOV in the image's order.
  const auto find = [&](const std::string& name) {
    const auto it = std::find(image.channel_names.begin(), image.channel_names.end(), name);
    return it == image.channel_names.end() ? -1 : int(it - image.channel_names.begin());
  };
  std::vector<int> source = {find("R"), find("G"), find("B"), find("A")};
  PRISM_CHECK(source[0] >= 0 && source[1] >= 0 && source[2] >= 0);
  std::vector<std::string> names = {"R", "G", "B", "A"};
  for (int c = 0; c < image.channels(); ++c) {
    const std::string& name = image.channel_names[c];
    if (name == "R" || name == "G" || name == "B" || name == "A") continue;
    PRISM_CHECK(std::find(names.begin(), names.end(), name) == names.end());
    names.push_back(name);
    source.push_back(c);
  }
  const int channels = int(names.size());
  const size_t count = size_t(image.width) * image.height;
  std::vector<float> pixels(count * channels);
  for (size_t i = 0; i < count; ++i) {
    for (int c = 0; c < channels; ++c) {
      pixels[i * channels + c] =
          source[c] < 0 ? 1.0f : converted.pixels[i * converted.channels() + source[c]];
    }
  }
  check_finite(pixels, path);

  const OIIO::TypeDesc type =
      options.pixel_type == "float" ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF;
  OIIO::ImageSpec spec(image.width, image.height, channels, type);
  spec.channelnames = names;
  spec.alpha_channel = 3;
  if (const auto z = std::find(names.begin(), names.end(), "Z"); z != names.end()) {
    spec.z_channel = int(z - names.begin());
  }
  size_t clamped = 0;
  if (type == OIIO::TypeDesc::HALF) {
    spec.channelformats.assign(channels, OIIO::TypeDesc::HALF);
    for (int c = 0; c < channels; ++c) {
      if (needs_float(names[c])) {
        spec.channelformats[c] = OIIO::TypeDesc::FLOAT;
        continue;
      }
      // Beyond the half range a value would become Inf in the file.
      for (size_t i = 0; i < count; ++i) {
        float& v = pixels[i * channels + c];
        if (std::abs(v) > kHalfMax) {
          v = std::copysign(kHalfMax, v);
          ++clamped;
        }
      }
    }
  }

  add_metadata(spec, metadata);
  add_pipeline_metadata(spec, pipeline);
  spec.attribute("prism:colorSpace", pipeline.output_space());
  spec.attribute("oiio:ColorSpace", pipeline.output_space());
  if (const auto chroma = pipeline.output_chromaticities()) {
    spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chroma->data());
  }
  if (clamped > 0) {
    spec.attribute("prism:halfClampedValues", int(std::min<size_t>(clamped, INT_MAX)));
  }
  spec.attribute("compression", options.compression);
  write_atomically(path, "openexr", spec, OIIO::TypeDesc::FLOAT, pixels.data());
}

void write_display_image(const fs::path& path, const Image& image, const ImageMetadata& metadata,
                         const ColorPipeline& pipeline) {
  const std::string format = display_format(path);
  if (format.empty()) {
    throw Error(ErrorKind::kUsage, "unsupported image type '" + path.extension().string() +
                                       "' for '" + path.string() +
                                       "'; available: .exr, .png, .jpg, .jpeg, .tif, .tiff");
  }
  PRISM_CHECK(image.width > 0 && image.height > 0);
  check_output_writable(path);
  // Checked before the view, whose clipping would hide an Inf.
  const auto triples = color_channel_triples(image);
  PRISM_CHECK(!triples.empty());
  std::vector<float> beauty;
  beauty.reserve(size_t(image.width) * image.height * 3);
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
    for (int c : triples[0]) beauty.push_back(image.pixels[i * image.channels() + c]);
  }
  check_finite(beauty, path);
  const Image display = pipeline.working_to_display(image);
  check_finite(display.pixels, path);

  std::vector<unsigned char> bytes(display.pixels.size());
  for (size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = static_cast<unsigned char>(std::lround(display.pixels[i] * 255.0f));
  }
  OIIO::ImageSpec spec(display.width, display.height, 3, OIIO::TypeDesc::UINT8);
  add_metadata(spec, metadata);
  add_pipeline_metadata(spec, pipeline);
  spec.attribute("prism:colorSpace", pipeline.display_color_space());
  // Tags the file as sRGB (PNG sRGB chunk) only when the display really is sRGB.
  if (to_lower(pipeline.display_color_space()).find("srgb") != std::string::npos) {
    spec.attribute("oiio:ColorSpace", "sRGB");
  }
  if (format == "jpeg") spec.attribute("Compression", "jpeg:95");
  write_atomically(path, format, spec, OIIO::TypeDesc::UINT8, bytes.data());
}

bool is_display_image_path(const fs::path& path) { return !display_format(path).empty(); }

void check_output_writable(const fs::path& path) {
  const fs::path folder = folder_of(path);
  std::error_code ec;
  if (path.filename().empty()) throw output_error(path, "the output path names no file");
  if (!fs::exists(folder, ec)) {
    throw output_error(path, "the output folder '" + folder.string() + "' does not exist");
  }
  if (!fs::is_directory(folder, ec)) {
    throw output_error(path, "'" + folder.string() + "' is not a folder");
  }
  if (fs::is_directory(path, ec)) throw output_error(path, "the output path is a folder");
  // Creating a file is the only reliable test (permissions, read-only mounts, ACLs, quotas).
  const fs::path probe = temp_path_for(path);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    throw output_error(path, "cannot create files in the output folder '" + folder.string() +
                                 "': " + std::strerror(errno));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

std::string ImageFileContents::attribute(const std::string& name) const {
  for (const auto& [key, value] : attributes) {
    if (key == name) return value;
  }
  return {};
}

int ImageFileContents::channel(const std::string& name) const {
  const auto& names = image.channel_names;
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : int(it - names.begin());
}

ImageFileContents read_image_file(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    throw Error(ErrorKind::kInput, "cannot read the image: " + OIIO::geterror(),
                ErrorLocation{path.string(), 0, {}});
  }
  const OIIO::ImageSpec& spec = in->spec();
  ImageFileContents contents;
  contents.format = in->format_name();
  contents.image.width = spec.width;
  contents.image.height = spec.height;
  contents.image.channel_names = spec.channelnames;
  contents.image.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                      contents.image.pixels.data())) {
    throw Error(ErrorKind::kInput, "cannot read the pixels: " + in->geterror(),
                ErrorLocation{path.string(), 0, {}});
  }
  for (int c = 0; c < spec.nchannels; ++c) {
    contents.channel_formats.push_back(spec.channelformat(c).c_str());
  }
  contents.compression = spec.get_string_attribute("compression");
  if (const auto* chroma =
          spec.find_attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8))) {
    std::array<float, 8> values{};
    std::memcpy(values.data(), chroma->data(), sizeof(values));
    contents.chromaticities = values;
  }
  for (const auto& p : spec.extra_attribs) {
    contents.attributes.emplace_back(p.name().string(), p.get_string());
  }
  return contents;
}

}  // namespace prism
