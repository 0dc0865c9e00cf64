// Textures (color/texture_image.*, color/texture_set.*): reading images from files, embedded
// bytes and raw texels into the working space by the colour-space rule, and the
// TextureSystem's lookups (orientation, repetition, MIP-map filtering, averages).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "color/texture_image.h"
#include "color/texture_set.h"
#include "core/error.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/model_test_files.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

/// The sRGB transfer function's inverse, for 8-bit codes.
float srgb_to_linear(int code) {
  const float v = float(code) / 255.0f;
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

class ColorTexture : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::make_temp_dir("color_texture");
    pipeline_ = std::make_unique<ColorPipeline>(test::bundled_config());
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  TextureSource file_source(const std::string& name, const test::Bytes& bytes,
                            const std::string& color_space = "") const {
    test::write_bytes(dir_ / name, bytes);
    TextureSource source;
    source.name = name;
    source.file = dir_ / name;
    source.color_space = color_space;
    source.origin = {"scene.json", 7, "materials[0].reflectance.texture"};
    return source;
  }
  TextureImage read(const TextureSource& source) {
    return read_texture_image(source, *pipeline_, warnings_);
  }
  Error read_error(const TextureSource& source) {
    try {
      read(source);
    } catch (const Error& e) {
      return e;
    }
    ADD_FAILURE() << source.name << " was read";
    return Error(ErrorKind::kInternal, "read");
  }

  fs::path dir_;
  std::unique_ptr<ColorPipeline> pipeline_;
  std::vector<std::string> warnings_;
};

TEST_F(ColorTexture, EightBitImagesAreSrgbEncoded) {
  // 50% sRGB grey: 128 / 255 encodes a linear 0.2158.
  const TextureImage grey = read(file_source("grey.png", test::png_rgb8(1, 1, {128, 128, 128})));
  EXPECT_EQ(grey.color_space, "sRGB - Texture");
  EXPECT_EQ(grey.space_rule, "oiio:ColorSpace");
  ASSERT_EQ(grey.image.channel_names, (std::vector<std::string>{"R", "G", "B"}));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(grey.image.at(0, 0, c), srgb_to_linear(128), 1e-4f);
    EXPECT_NEAR(grey.image.at(0, 0, c), 0.2158f, 1e-3f);
  }
  const TextureImage colour = read(file_source("c.png", test::png_rgb8(1, 1, {255, 64, 0})));
  EXPECT_NEAR(colour.image.at(0, 0, 0), 1.0f, 1e-4f);
  EXPECT_NEAR(colour.image.at(0, 0, 1), srgb_to_linear(64), 1e-4f);
  EXPECT_NEAR(colour.image.at(0, 0, 2), 0.0f, 1e-6f);
  EXPECT_TRUE(warnings_.empty());
}

TEST_F(ColorTexture, FloatImagesAreSceneLinear) {
  test::write_pfm(dir_ / "hdr.pfm", 1, 1, {0.5f, 2.0f, 8.0f});
  TextureSource source;
  source.name = "hdr.pfm";
  source.file = dir_ / "hdr.pfm";
  const TextureImage hdr = read(source);
  EXPECT_EQ(hdr.color_space, "Linear Rec.709 (sRGB)");
  EXPECT_NEAR(hdr.image.at(0, 0, 0), 0.5f, 1e-6f);
  EXPECT_NEAR(hdr.image.at(0, 0, 1), 2.0f, 1e-6f);
  EXPECT_NEAR(hdr.image.at(0, 0, 2), 8.0f, 1e-6f);
}

TEST_F(ColorTexture, TheScenesDeclarationWins) {
  const TextureImage raw =
      read(file_source("data.png", test::png_rgb8(1, 1, {128, 128, 128}), "Raw"));
  EXPECT_EQ(raw.color_space, "Raw");
  EXPECT_EQ(raw.space_rule, "scene file");
  EXPECT_NEAR(raw.image.at(0, 0, 0), 128.0f / 255.0f, 1e-6f);

  const Error e = read_error(file_source("x.png", test::png_rgb8(1, 1, {1, 2, 3}), "sRGB-ish"));
  EXPECT_EQ(e.kind(), ErrorKind::kInput);
  EXPECT_EQ(e.location().file, "scene.json");
  EXPECT_EQ(e.location().line, 7);
  EXPECT_NE(e.message().find("x.png"), std::string::npos) << e.message();
  EXPECT_NE(e.message().find("sRGB-ish"), std::string::npos) << e.message();
}

TEST_F(ColorTexture, EmbeddedBytesAndRawTexelsReadLikeFiles) {
  TextureSource embedded;
  embedded.name = "model.glb: embedded texture *0";
  embedded.bytes = test::png_rgb8(2, 1, {128, 128, 128, 255, 0, 0});
  embedded.format_hint = "jpg";  // a wrong hint: the bytes decide
  const TextureImage a = read(embedded);
  EXPECT_EQ(a.image.width, 2);
  EXPECT_NEAR(a.image.at(0, 0, 1), srgb_to_linear(128), 1e-4f);
  EXPECT_NEAR(a.image.at(1, 0, 0), 1.0f, 1e-4f);

  TextureSource raw;
  raw.name = "model.fbx: embedded texture *1";
  raw.raw_width = 1;
  raw.raw_height = 2;
  raw.bytes = {128, 128, 128, 255, 0, 0, 255, 255};
  const TextureImage b = read(raw);
  EXPECT_EQ(b.image.height, 2);
  EXPECT_EQ(b.space_rule, "integer image");
  EXPECT_NEAR(b.image.at(0, 0, 0), srgb_to_linear(128), 1e-4f);
  EXPECT_NEAR(b.image.at(0, 1, 2), 1.0f, 1e-4f);
}

TEST_F(ColorTexture, UnreadableImagesAreInputErrorsNamingThem) {
  test::Bytes noise(300);
  for (size_t i = 0; i < noise.size(); ++i) noise[i] = (unsigned char)(i * 37 + 11);
  TextureSource bad = file_source("broken.png", noise);
  const Error e = read_error(bad);
  EXPECT_EQ(e.kind(), ErrorKind::kInput);
  EXPECT_NE(e.message().find("broken.png"), std::string::npos) << e.message();
  EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();

  TextureSource embedded;
  embedded.name = "m.glb: embedded texture *3";
  embedded.bytes = noise;
  const Error f = read_error(embedded);
  EXPECT_NE(f.message().find("embedded texture *3"), std::string::npos) << f.message();

  TextureSource gone = file_source("gone.png", test::png_rgb8(1, 1, {0, 0, 0}));
  fs::remove(gone.file);
  EXPECT_NE(read_error(gone).message().find("gone.png"), std::string::npos);
}

/// A 2 x 2 image: red, green on the top row; blue, white below.
Image quadrants() {
  Image image;
  image.width = image.height = 2;
  image.channel_names = {"R", "G", "B"};
  image.pixels = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  return image;
}

void expect_rgb(const Rgb& got, const Rgb& expected, float tolerance, const std::string& what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(got[c], expected[c], tolerance) << what << " channel " << c;
}

TEST_F(ColorTexture, LookupsHaveVUpAndRepeat) {
  const auto lookup = make_texture_lookup({quadrants()}, {"quadrants"});
  ASSERT_EQ(lookup->size(), 1u);
  const Vec2 zero(0.0f);
  expect_rgb(lookup->lookup(0, {0.25f, 0.75f}, zero, zero), {1, 0, 0}, 1e-3f, "top left");
  expect_rgb(lookup->lookup(0, {0.75f, 0.75f}, zero, zero), {0, 1, 0}, 1e-3f, "top right");
  expect_rgb(lookup->lookup(0, {0.25f, 0.25f}, zero, zero), {0, 0, 1}, 1e-3f, "bottom left");
  expect_rgb(lookup->lookup(0, {0.75f, 0.25f}, zero, zero), {1, 1, 1}, 1e-3f, "bottom right");
  expect_rgb(lookup->lookup(0, {1.25f, -0.25f}, zero, zero), {1, 0, 0}, 1e-3f, "repeated");
  expect_rgb(lookup->average(0), {0.5f, 0.5f, 0.5f}, 1e-6f, "average");
}

TEST_F(ColorTexture, WideFootprintsFilterToTheMean) {
  // A 64 x 64 checkerboard of 0 and 1 in cells of 4: sharp up close, grey from afar.
  Image board;
  board.width = board.height = 64;
  board.channel_names = {"R", "G", "B"};
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const float v = ((x / 4) + (y / 4)) % 2 == 0 ? 1.0f : 0.0f;
      board.pixels.insert(board.pixels.end(), {v, v, v});
    }
  }
  const auto lookup = make_texture_lookup({board}, {"board"});
  const Vec2 cell_centre((2.0f) / 64.0f, 1.0f - 2.0f / 64.0f);  // inside the top-left cell
  EXPECT_NEAR(lookup->lookup(0, cell_centre, Vec2(0.0f), Vec2(0.0f)).r, 1.0f, 1e-3f);
  EXPECT_NEAR(lookup->lookup(0, cell_centre, {1.0f / 64, 0}, {0, 1.0f / 64}).r, 1.0f, 0.05f);
  EXPECT_NEAR(lookup->lookup(0, cell_centre, {0.5f, 0}, {0, 0.5f}).r, 0.5f, 0.02f);
  // Anisotropic: a footprint long along u only still averages across cells.
  EXPECT_NEAR(lookup->lookup(0, cell_centre, {0.5f, 0}, {0, 1.0f / 256}).r, 0.5f, 0.1f);
}

TEST_F(ColorTexture, SceneTexturesLoadInOrder) {
  Scene scene;
  scene.textures.push_back(file_source("grey.png", test::png_rgb8(1, 1, {128, 128, 128})));
  scene.textures.push_back(file_source("red.png", test::png_rgb8(1, 1, {255, 0, 0})));
  const SceneTexturesReport report = load_scene_textures(scene, *pipeline_);
  ASSERT_NE(scene.texture_lookup, nullptr);
  ASSERT_EQ(scene.texture_lookup->size(), 2u);
  ASSERT_EQ(report.descriptions.size(), 2u);
  EXPECT_EQ(report.descriptions[0], "grey.png: sRGB - Texture (oiio:ColorSpace)");
  const Vec2 zero(0.0f);
  EXPECT_NEAR(scene.texture_lookup->lookup(0, {0.5f, 0.5f}, zero, zero).g, 0.2158f, 1e-3f);
  EXPECT_NEAR(scene.texture_lookup->lookup(1, {0.5f, 0.5f}, zero, zero).r, 1.0f, 1e-3f);
  const uint64_t hash = scene.texture_lookup->content_hash();

  Scene other = scene;
  other.textures[1] = file_source("blue.png", test::png_rgb8(1, 1, {0, 0, 255}));
  load_scene_textures(other, *pipeline_);
  EXPECT_NE(other.texture_lookup->content_hash(), hash);

  Scene none;
  load_scene_textures(none, *pipeline_);
  EXPECT_EQ(none.texture_lookup, nullptr);
}

}  // namespace
}  // namespace prism
