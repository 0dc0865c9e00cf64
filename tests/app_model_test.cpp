// Model files end to end: `prism render MODEL` (textures from a GLB, sRGB decoding, the default
// lighting, the file's camera), `prism info`, `validate` and `bench` on models, JSON scenes with
// textures, and the one-line errors of missing textures and hostile files.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "color/image_output.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/model_test_files.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

namespace fs = std::filesystem;
using test::GltfBuilder;

/// A quad seen straight on by the file's camera, which it fills: yfov 2 atan(1/3) at distance 3
/// sees y in [-1, 1]; the aspect 1 keeps x the same. `material` is its material.
GltfBuilder framed_quad(int material_of_builder(GltfBuilder&)) {
  GltfBuilder b;
  const int material = material_of_builder(b);
  b.add_node({{"name", "quad"}, {"mesh", b.add_quad_mesh(material)}});
  b.add_node({{"name", "cam"},
              {"camera", b.add_camera(2.0 * std::atan(1.0 / 3.0), 1.0, 0.1, 10)},
              {"translation", {0, 0, 3}}});
  return b;
}

/// R, G, B of channel triple `first` at pixel (x, y).
Rgb rgb_at(const ImageFileContents& file, int first, int x, int y) {
  return {file.image.at(x, y, first), file.image.at(x, y, first + 1),
          file.image.at(x, y, first + 2)};
}

TEST(AppModel, AGlbRendersWithItsEmbeddedTexture) {
  const test::TestDirs dirs("app_model_glb");
  // Red and white cells, 4 x 4 of 8 pixels: red in the top-left one.
  GltfBuilder b = framed_quad([](GltfBuilder& g) {
    const int texture = g.embed_image(test::png_checkerboard(4, 8, {255, 0, 0}, {255, 255, 255}));
    return g.add_material("checker",
                          {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0}});
  });
  const fs::path model = dirs.in / "checker.glb";
  test::write_bytes(model, b.glb());
  const fs::path out = dirs.out / "checker.exr";
  const test::ProgramResult r =
      test::run_prism({"render", model.string(), "--literal-camera", "-r", "64", "64", "-s", "4",
                       "-f", out.string(), "--exr-type", "float"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("default lighting"), std::string::npos) << r.err;
  const ImageFileContents image = read_image_file(out);
  const int albedo = image.channel("albedo.R");
  ASSERT_GE(albedo, 0);
  // Cells are 16 pixels wide in the image: sample the middle of the first two of the top row.
  const Rgb red = rgb_at(image, albedo, 8, 8), white = rgb_at(image, albedo, 24, 8);
  EXPECT_NEAR(red.r, 1.0f, 1e-3f);
  EXPECT_NEAR(red.g, 0.0f, 1e-3f);
  EXPECT_NEAR(white.g, 1.0f, 1e-3f);
  EXPECT_NEAR(rgb_at(image, albedo, 8, 24).g, 1.0f, 1e-3f);  // the second row starts white
  // The beauty: lit by the default lighting, red cells red and white cells grey-white.
  const Rgb lit_red = rgb_at(image, 0, 8, 8), lit_white = rgb_at(image, 0, 24, 8);
  EXPECT_GT(lit_red.r, 0.05f);
  EXPECT_LT(lit_red.g, 0.02f * lit_red.r);
  EXPECT_GT(lit_white.g, 0.8f * lit_white.r);
}

TEST(AppModel, EightBitTexturesAreDecodedFromSrgb) {
  const test::TestDirs dirs("app_model_srgb");
  test::write_bytes(dirs.in / "grey.png", test::png_rgb8(2, 2, std::vector<uint8_t>(12, 128)));
  GltfBuilder b = framed_quad([](GltfBuilder& g) {
    const int texture = g.file_image("grey.png");
    return g.add_material("grey",
                          {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0}});
  });
  test::write_text(dirs.in / "grey.gltf", b.gltf());
  const fs::path out = dirs.out / "grey.exr";
  ASSERT_EQ(test::run_prism({"render", (dirs.in / "grey.gltf").string(), "--literal-camera", "-r",
                             "16", "16", "-s", "1", "-f", out.string(), "--exr-type", "float"})
                .exit_code,
            0);
  const ImageFileContents image = read_image_file(out);
  const int albedo = image.channel("albedo.R");
  ASSERT_GE(albedo, 0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.image.at(8, 8, albedo + c), 0.2158f, 2e-3f);
}

TEST(AppModel, TheFirstRenderOfAModelWithoutLightsIsNotBlack) {
  const test::TestDirs dirs("app_model_unlit");
  const std::string stl = dirs.scene("part.stl", R"(solid part
facet normal 0 0 1
outer loop
vertex -1 -1 0
vertex 1 -1 0
vertex 0 1 0
endloop
endfacet
endsolid part
)");
  const fs::path out = dirs.out / "part.exr";
  const test::ProgramResult r =
      test::run_prism({"render", stl, "-r", "48", "36", "-s", "4", "-f", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageFileContents image = read_image_file(out);
  double sum = 0.0;
  for (int y = 0; y < image.image.height; ++y) {
    for (int x = 0; x < image.image.width; ++x) sum += image.image.at(x, y, 1);
  }
  EXPECT_GT(sum / (48.0 * 36.0), 0.02);
}

TEST(AppModel, InfoValidateAndBenchTakeModels) {
  const test::TestDirs dirs("app_model_commands");
  GltfBuilder b;
  b.add_node({{"mesh", b.add_quad_mesh(-1)}, {"translation", {0, 0, -1}}});
  b.add_node({{"mesh", b.add_quad_mesh(-1)}, {"rotation", {0.7071068, 0, 0, 0.7071068}}});
  const fs::path model = dirs.in / "two.glb";
  test::write_bytes(model, b.glb());
  const test::ProgramResult info = test::run_prism({"info", model.string(), "--accel", "bvh"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("triangles        4"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("meshes           2"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("ambient 1, directional 1"), std::string::npos) << info.out;

  const test::ProgramResult validate = test::run_prism(
      {"validate", model.string(), "--rays", "200", "--against", "brute", "--failures",
       (dirs.out / "f.txt").string(), "--heatmap", (dirs.out / "h.png").string()});
  EXPECT_EQ(validate.exit_code, 0) << validate.err;

  const fs::path json = dirs.out / "bench.json";
  const test::ProgramResult bench =
      test::run_prism({"bench", model.string(), "--json", json.string(), "--resolution", "16",
                       "--threads", "1", "--backend", "bvh"});
  EXPECT_EQ(bench.exit_code, 0) << bench.err;
  EXPECT_TRUE(fs::exists(json));
}

TEST(AppModel, JsonScenesRenderTheirTextures) {
  const test::TestDirs dirs("app_model_json");
  test::write_bytes(dirs.in / "cells.png", test::png_checkerboard(2, 4, {0, 255, 0}, {0, 0, 255}));
  const std::string scene = dirs.scene("textured.json", R"({
    "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov": 36.8699},
    "materials": [{"name": "cells", "type": "diffuse",
                   "reflectance": {"texture": "cells.png", "scale": 0.5}}],
    "lights": [{"type": "directional", "direction": [0, 0, -1], "color": 3.14159265}],
    "meshes": [{"material": "cells",
                "positions": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
                "indices": [[0, 1, 2], [0, 2, 3]],
                "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]]}]
  })");
  const fs::path out = dirs.out / "textured.exr";
  const test::ProgramResult r = test::run_prism(
      {"render", scene, "-r", "32", "32", "-s", "1", "-f", out.string(), "--exr-type", "float"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageFileContents image = read_image_file(out);
  // Top left green, top right blue, each half of 0.5 x the texture's 1.
  EXPECT_NEAR(rgb_at(image, 0, 8, 8).g, 0.5f, 1e-3f);
  EXPECT_NEAR(rgb_at(image, 0, 8, 8).b, 0.0f, 1e-3f);
  EXPECT_NEAR(rgb_at(image, 0, 24, 8).b, 0.5f, 1e-3f);
}

TEST(AppModel, MissingTexturesAndBrokenModelsAreOneLineErrors) {
  const test::TestDirs dirs("app_model_errors");
  const std::string obj = dirs.scene("quad.obj",
                                     "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
                                     "vt 0 1\nusemtl m\nf 1/1 2/2 3/3\n");
  dirs.scene("quad.mtl", "newmtl m\nKd 1 1 1\nmap_Kd textures/missing_wood.png\n");
  const fs::path out = dirs.out / "x.exr";
  for (const std::string& command : {std::string("render"), std::string("info")}) {
    SCOPED_TRACE(command);
    std::vector<std::string> args = {command, obj};
    if (command == "render") args.insert(args.end(), {"-r", "8", "8", "-f", out.string()});
    test::expect_one_line_error(test::run_prism(args), 2, {"quad.obj", "missing_wood.png"});
  }
  EXPECT_FALSE(fs::exists(out));

  // A texture that exists but is not an image fails when the render reads it, before it starts.
  test::write_text(dirs.in / "fake.png", "not an image");
  const std::string json = dirs.scene("fake.json", R"({
    "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov": 40},
    "materials": [{"name": "m", "type": "diffuse", "reflectance": {"texture": "fake.png"}}],
    "meshes": [{"material": "m", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                "indices": [[0, 1, 2]]}]
  })");
  test::expect_one_line_error(test::run_prism({"render", json, "-r", "8", "8", "-f", out.string()}),
                              2, {"fake.json", "fake.png"});

  test::Bytes noise(2000);
  for (size_t i = 0; i < noise.size(); ++i) noise[i] = (unsigned char)(i * 131 + 7);
  for (const std::string name : {"broken.glb", "broken.fbx", "broken.stl"}) {
    SCOPED_TRACE(name);
    test::write_bytes(dirs.in / name, noise);
    test::expect_one_line_error(
        test::run_prism({"render", (dirs.in / name).string(), "-f", out.string()}), 2, {name});
  }
  const std::string plain = dirs.scene("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  test::expect_one_line_error(
      test::run_prism({"render", plain, "--literal-camera", "-f", out.string()}), 2,
      {"plain.obj", "no camera"});
}

}  // namespace
}  // namespace prism
