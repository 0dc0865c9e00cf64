#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scenes/json_scene_loader.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// A temporary folder with one scene file in it, removed at the end of the test.
class ScenesJson : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::make_temp_dir("scenes_json"); }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  fs::path write(const std::string& text, const std::string& name = "scene.json") {
    const fs::path path = dir_ / name;
    test::write_text(path, text);
    return path;
  }
  Scene load(const std::string& text) { return load_json_scene(write(text)); }

  /// The error loading `text` raises; records a failure if there is none or it is not kInput.
  Error error_of(const std::string& text) {
    try {
      load(text);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInput) << e.what();
      EXPECT_EQ(e.location().file, (dir_ / "scene.json").string()) << e.what();
      return e;
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return Error(ErrorKind::kInternal, "no error");
  }
  Error error_of_scene(const json& scene) { return error_of(scene.dump(2)); }

  /// Asserts the error names `element` as its JSON path and says `words`.
  void expect_error(const json& scene, const std::string& element, const std::string& words) {
    const Error e = error_of_scene(scene);
    EXPECT_EQ(e.location().element, element) << e.what();
    EXPECT_NE(e.message().find(words), std::string::npos) << e.what();
  }

  fs::path dir_;
};

/// The smallest complete scene: a camera, one material, a triangle and a sphere.
json base_scene() {
  return json::parse(R"({
    "camera": {"position": [0, 0, 5], "target": [0, 0, 0], "fov": 45},
    "materials": [{"name": "white", "type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}],
    "meshes": [{"name": "tri", "material": "white",
                "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2]]}],
    "spheres": [{"center": [0, 0, -1], "radius": 0.5, "material": "white"}]
  })");
}

TEST_F(ScenesJson, LoadsEveryFeature) {
  const Scene scene = load(R"({
    "render": {"width": 640, "height": 320, "spp": 8, "max_depth": 7, "integrator": "path",
               "seed": 12345678901234},
    "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov": 30,
               "lens_radius": 0.05, "focal_distance": 4.5},
    "materials": [
      {"name": "d", "type": "diffuse", "reflectance": 0.25},
      {"name": "m", "type": "mirror", "reflectance": [0.9, 0.8, 0.7]},
      {"name": "g", "type": "glass", "reflectance": [1, 1, 1], "transmittance": [0.9, 0.9, 1],
       "roughness": 0.1, "ior": 1.45},
      {"name": "r", "type": "refraction", "transmittance": 1, "ior": 1.33},
      {"name": "c", "type": "microfacet", "alpha": 0.3, "eta": [0.2, 0.4, 1.4], "k": [4, 2.4, 1.6]},
      {"name": "e", "type": "emission", "radiance": [5, 4, 3]}
    ],
    "lights": [
      {"type": "point", "name": "p", "position": [1, 2, 3], "color": [10, 10, 10],
       "attenuation": [1, 0, 0.5]},
      {"type": "spot", "position": [0, 3, 0], "direction": [0, -2, 0], "color": 5,
       "falloff_angle": 60, "falloff_exponent": 2},
      {"type": "directional", "direction": [0, 0, -1], "color": [1, 1, 1]},
      {"type": "ambient", "color": 0.1, "up": [0, 0, 1]},
      {"type": "area", "center": [0, 2, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
       "color": [8, 8, 8]}
    ],
    "meshes": [
      {"name": "quad", "material": "e", "positions": [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0],
       "indices": [0, 1, 2, 0, 2, 3], "normals": [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1],
       "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]]},
      {"material": "c", "generate": {"kind": "grid", "triangles": 200, "seed": 3},
       "transform": {"translate": [0, -1, 0], "scale": 2}}
    ],
    "spheres": [{"center": [1, 2, 3], "radius": 0.5, "material": "g"}]
  })");
  EXPECT_EQ(scene.settings.width, 640);
  EXPECT_EQ(scene.settings.height, 320);
  EXPECT_EQ(scene.settings.spp, 8);
  EXPECT_EQ(scene.settings.max_depth, 7);
  EXPECT_EQ(scene.settings.integrator, "path");
  EXPECT_EQ(scene.settings.seed, 12345678901234u);

  EXPECT_EQ(scene.camera.target, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(scene.camera.vfov_deg, 30.0f);
  // The horizontal fov follows from the file's 2:1 resolution.
  EXPECT_NEAR(std::tan(radians(scene.camera.hfov_deg) / 2), 2.0f * std::tan(radians(30.0f) / 2),
              1e-5f);
  EXPECT_FLOAT_EQ(scene.camera.lens_radius, 0.05f);
  EXPECT_FLOAT_EQ(scene.camera.focal_distance, 4.5f);

  ASSERT_EQ(scene.materials.size(), 6u);
  EXPECT_EQ(scene.materials[0].reflectance, Rgb(0.25f));
  EXPECT_EQ(scene.materials[1].type, MaterialType::kMirror);
  EXPECT_EQ(scene.materials[2].type, MaterialType::kGlass);
  EXPECT_FLOAT_EQ(scene.materials[2].ior, 1.45f);
  EXPECT_FLOAT_EQ(scene.materials[2].roughness, 0.1f);
  EXPECT_EQ(scene.materials[3].type, MaterialType::kRefraction);
  EXPECT_EQ(scene.materials[4].type, MaterialType::kMicrofacet);
  EXPECT_FLOAT_EQ(scene.materials[4].alpha, 0.3f);
  EXPECT_EQ(scene.materials[4].k, Rgb(4.0f, 2.4f, 1.6f));
  EXPECT_TRUE(scene.materials[5].is_emissive());
  EXPECT_EQ(scene.materials[5].radiance, Rgb(5, 4, 3));

  ASSERT_EQ(scene.lights.size(), 5u);
  EXPECT_EQ(scene.lights[0].type, LightType::kPoint);
  EXPECT_EQ(scene.lights[0].name, "p");
  EXPECT_FLOAT_EQ(scene.lights[0].quadratic_attenuation, 0.5f);
  EXPECT_EQ(scene.lights[1].type, LightType::kSpot);
  EXPECT_EQ(scene.lights[1].direction, Vec3(0, -1, 0));
  EXPECT_FLOAT_EQ(scene.lights[1].falloff_angle_deg, 60.0f);
  EXPECT_EQ(scene.lights[2].type, LightType::kDirectional);
  EXPECT_EQ(scene.lights[3].type, LightType::kAmbient);
  EXPECT_EQ(scene.lights[3].up, Vec3(0, 0, 1));
  const Light& area = scene.lights[4];
  EXPECT_EQ(area.type, LightType::kArea);
  EXPECT_EQ(area.direction, Vec3(0, -1, 0));  // edge_u x edge_v
  EXPECT_EQ(area.edge_u, Vec3(1, 0, 0));

  ASSERT_EQ(scene.geometry.meshes.size(), 2u);
  const TriangleMesh& quad = scene.geometry.meshes[0];
  EXPECT_EQ(quad.triangle_count(), 2u);
  EXPECT_EQ(quad.material_id, 5u);
  ASSERT_EQ(quad.normals.size(), 6u);  // per corner
  ASSERT_EQ(quad.uvs.size(), 6u);
  EXPECT_EQ(quad.uvs[4], Vec2(1, 1));  // triangle 1, corner 1 is vertex 2
  const TriangleMesh& grid = scene.geometry.meshes[1];
  EXPECT_EQ(grid.name, "meshes[1]");
  EXPECT_EQ(grid.triangle_count(), 200u);
  EXPECT_EQ(grid.bounds().lower, Vec3(-2, -3, 0));
  EXPECT_EQ(grid.bounds().upper, Vec3(2, 1, 0));
  ASSERT_EQ(scene.geometry.spheres.size(), 1u);
  EXPECT_EQ(scene.geometry.spheres[0].material_id, 2u);
  EXPECT_NO_THROW(scene.validate());
}

TEST_F(ScenesJson, FovAxisAndDefaults) {
  json scene = base_scene();
  Scene s = load(scene.dump());
  EXPECT_FLOAT_EQ(s.camera.vfov_deg, 45.0f);  // vertical by default
  EXPECT_NEAR(std::tan(radians(s.camera.hfov_deg) / 2), 4.0f / 3.0f * std::tan(radians(22.5f)),
              1e-5f);
  EXPECT_EQ(s.camera.up, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(s.camera.focal_distance, 5.0f);  // the target's distance
  EXPECT_FALSE(s.settings.width.has_value());

  scene["camera"]["fov_axis"] = "horizontal";
  s = load(scene.dump());
  EXPECT_FLOAT_EQ(s.camera.hfov_deg, 45.0f);
  EXPECT_LT(s.camera.vfov_deg, 45.0f);
}

TEST_F(ScenesJson, TransformsMoveGeometryAndMirrorsKeepOrientation) {
  json scene = base_scene();
  scene["meshes"][0]["transform"] = {{"scale", {-1, 1, 1}}, {"translate", {10, 0, 0}}};
  const Scene s = load(scene.dump());
  const TriangleMesh& m = s.geometry.meshes[0];
  EXPECT_EQ(m.bounds().lower, Vec3(9, 0, 0));
  EXPECT_EQ(m.bounds().upper, Vec3(10, 1, 0));
  // The original triangle faced +z; mirrored in x it still does (the winding was flipped).
  const Vec3 n = glm::cross(m.positions[m.triangles[0].y] - m.positions[m.triangles[0].x],
                            m.positions[m.triangles[0].z] - m.positions[m.triangles[0].x]);
  EXPECT_GT(n.z, 0.0f);

  scene["meshes"][0]["transform"] = {{"matrix", {1, 0, 0, 5, 0, 1, 0, 6, 0, 0, 1, 7, 0, 0, 0, 1}}};
  EXPECT_EQ(load(scene.dump()).geometry.meshes[0].positions[0], Vec3(5, 6, 7));
  scene["meshes"][0]["transform"] = {{"rotate", {{"axis", {0, 0, 1}}, {"degrees", 90}}}};
  const Vec3 p = load(scene.dump()).geometry.meshes[0].positions[1];  // (1, 0, 0) turned to +y
  EXPECT_NEAR(p.x, 0.0f, 1e-6f);
  EXPECT_NEAR(p.y, 1.0f, 1e-6f);
}

TEST_F(ScenesJson, MalformedJsonGivesLineAndColumn) {
  const Error e = error_of("{\n  \"camera\": {\n    \"fov\": 40,,\n  }\n}\n");
  EXPECT_EQ(e.location().line, 3);
  EXPECT_NE(e.message().find("line 3, column 15"), std::string::npos) << e.what();
  EXPECT_NE(error_of("").message().find("malformed JSON"), std::string::npos);
  EXPECT_NE(error_of("{\"camera\": [1e999]}").message().find("1e999"), std::string::npos);
}

TEST_F(ScenesJson, SemanticErrorsCarryTheLine) {
  const Error e = error_of(R"({
  "camera": {"position": [0, 0, 5], "target": [0, 0, 0], "fov": 45},
  "materials": [
    {"name": "a", "type": "diffuse"},
    {"name": "b", "type": "diffuse",
     "reflectance": [0.5, 2, 0.5]}
  ]
})");
  EXPECT_EQ(e.location().element, "materials[1].reflectance[1]");
  EXPECT_EQ(e.location().line, 6);
  EXPECT_NE(
      std::string(e.what()).find("scene.json:6: materials[1].reflectance[1]: must be in [0, 1]"),
      std::string::npos)
      << e.what();
}

TEST_F(ScenesJson, WrongTypes) {
  json s = base_scene();
  s["camera"]["fov"] = "wide";
  expect_error(s, "camera.fov", "expected a number, got string");
  s = base_scene();
  s["materials"] = {{"name", "x"}};
  expect_error(s, "materials", "expected an array, got object");
  s = base_scene();
  s["camera"]["position"] = {0, 0};
  expect_error(s, "camera.position", "3 numbers");
  s = base_scene();
  s["render"] = {{"width", 480.5}};
  expect_error(s, "render.width", "expected an integer");
  s = base_scene();
  s["meshes"][0]["positions"][1] = {1, "0", 0};
  expect_error(s, "meshes[0].positions[1][1]", "expected a number, got string");
}

TEST_F(ScenesJson, MissingRequiredFields) {
  json s = base_scene();
  s["camera"].erase("fov");
  expect_error(s, "camera", "missing required field 'fov'");
  s = base_scene();
  s.erase("camera");
  expect_error(s, "", "missing required field 'camera'");
  s = base_scene();
  s["materials"][0].erase("name");
  expect_error(s, "materials[0]", "'name'");
  s = base_scene();
  s["meshes"][0].erase("indices");
  expect_error(s, "meshes[0]", "'indices'");
  s = base_scene();
  s["meshes"][0].erase("positions");
  expect_error(s, "meshes[0]", "exactly one of");
  s = base_scene();
  s["materials"][0] = {{"name", "e"}, {"type", "emission"}};
  expect_error(s, "materials[0]", "'radiance'");
}

TEST_F(ScenesJson, UnknownKeysAreRejectedWithTheValidOnes) {
  json s = base_scene();
  s["materials"][0]["relfectance"] = 0.5;
  const Error e = error_of_scene(s);
  EXPECT_EQ(e.location().element, "materials[0].relfectance");
  EXPECT_NE(e.message().find("did you mean 'reflectance'"), std::string::npos) << e.what();
  EXPECT_NE(e.message().find("valid keys: name, type, reflectance"), std::string::npos);
  s = base_scene();
  s["lightz"] = json::array();
  expect_error(s, "lightz", "valid keys: camera, render, materials, lights, meshes, spheres");
  s = base_scene();
  s["materials"][0]["ior"] = 1.5;  // a glass field on a diffuse material
  expect_error(s, "materials[0].ior", "unknown key 'ior'");
  s = base_scene();
  s["camera"]["fov_degrees"] = 40;
  expect_error(s, "camera.fov_degrees", "unknown key");
  s = base_scene();
  s["meshes"][0]["normals"] = json::array();
  s["meshes"][0].erase("positions");
  s["meshes"][0]["generate"] = {{"kind", "grid"}, {"triangles", 8}};
  expect_error(s, "meshes[0].indices", "unknown key 'indices'");
  s = base_scene();
  s["materials"][0] = {{"name", "x"}, {"tpye", "diffuse"}};
  expect_error(s, "materials[0].tpye", "did you mean 'type'");
}

TEST_F(ScenesJson, NumbersOutOfRange) {
  json s = base_scene();
  s["spheres"][0]["radius"] = -1;
  expect_error(s, "spheres[0].radius", "must be > 0");
  s["spheres"][0]["radius"] = 1e39;  // finite in JSON, not in a float
  expect_error(s, "spheres[0].radius", "not finite");
  for (const double fov : {0.0, 180.0, -5.0, 200.0}) {
    s = base_scene();
    s["camera"]["fov"] = fov;
    expect_error(s, "camera.fov", "must be in (0, 180)");
  }
  s = base_scene();
  s["meshes"][0]["indices"] = {{0, 1, 3}};
  expect_error(s, "meshes[0].indices[0][2]", "out of range");
  s["meshes"][0]["indices"] = {0, -1, 2};
  expect_error(s, "meshes[0].indices[1]", "out of range");
  s = base_scene();
  s["render"] = {{"spp", 0}};
  expect_error(s, "render.spp", "must be in [1,");
  s = base_scene();
  s["lights"] = {{{"type", "spot"},
                  {"position", {0, 0, 0}},
                  {"direction", {0, 0, 0}},
                  {"color", 1},
                  {"falloff_angle", 30}}};
  expect_error(s, "lights[0].direction", "non-zero length");
  s["lights"][0]["direction"] = {0, 0, -1};
  s["lights"][0]["falloff_angle"] = 181;
  expect_error(s, "lights[0].falloff_angle", "must be in (0, 180]");
  s = base_scene();
  s["lights"] = {{{"type", "area"},
                  {"center", {0, 0, 0}},
                  {"edge_u", {1, 0, 0}},
                  {"edge_v", {2, 0, 0}},
                  {"color", 1}}};
  expect_error(s, "lights[0]", "span no area");
  s = base_scene();
  s["meshes"][0]["transform"] = {{"scale", 0}};
  expect_error(s, "meshes[0].transform.scale", "must not be 0");
  s = base_scene();
  s["camera"]["target"] = {0, 0, 5};
  expect_error(s, "camera", "coincide");
  s = base_scene();
  s["materials"][0]["reflectance"] = {0.5, -0.1, 0.5};
  expect_error(s, "materials[0].reflectance[1]", "must be in [0, 1]");
}

TEST_F(ScenesJson, DanglingAndDuplicateMaterialNames) {
  json s = base_scene();
  s["meshes"][0]["material"] = "nope";
  expect_error(s, "meshes[0].material", "unknown material 'nope'; defined materials: white");
  s = base_scene();
  s["spheres"][0]["material"] = "chrome";
  expect_error(s, "spheres[0].material", "unknown material 'chrome'");
  s = base_scene();
  s["materials"].push_back({{"name", "white"}, {"type", "mirror"}});
  expect_error(s, "materials[1].name", "duplicate material name 'white'");
  s = base_scene();
  s["materials"][0]["type"] = "plastic";
  expect_error(s, "materials[0].type", "available: diffuse, mirror, glass");
  s = base_scene();
  s["lights"] = {{{"type", "laser"}}};
  expect_error(s, "lights[0].type", "available: point, spot");
}

TEST_F(ScenesJson, CameraTargetAliases) {
  json s = base_scene();
  s["camera"]["look_at"] = {0, 0, 0};
  expect_error(s, "camera", "not both");
  s["camera"].erase("look_at");
  s["camera"].erase("target");
  expect_error(s, "camera", "'target' (or 'look_at')");
}

TEST_F(ScenesJson, MissingAndCorruptMeshFiles) {
  json s = base_scene();
  s["meshes"][0] = {{"material", "white"}, {"file", "missing/bunny.obj"}};
  Error e = error_of_scene(s);
  EXPECT_EQ(e.location().element, "meshes[0].file");
  EXPECT_NE(e.message().find((dir_ / "missing/bunny.obj").string()), std::string::npos) << e.what();
  EXPECT_NE(e.message().find("not found"), std::string::npos) << e.what();

  test::write_text(dir_ / "broken.ply", "ply\nformat ascii 1.0\nelement vertex 3\ngarbage\n");
  s["meshes"][0]["file"] = "broken.ply";
  e = error_of_scene(s);
  EXPECT_EQ(e.location().element, "meshes[0].file");
  EXPECT_NE(e.message().find("broken.ply"), std::string::npos) << e.what();
}

TEST_F(ScenesJson, HostileInputFailsCleanly) {
  // Deep nesting: rejected by depth, not by a stack overflow.
  const Error deep =
      error_of("{\"camera\": " + std::string(200000, '[') + std::string(200000, ']') + "}");
  EXPECT_NE(deep.message().find("deeper than"), std::string::npos) << deep.what();
  EXPECT_EQ(deep.location().line, 1);

  // Huge generated meshes are refused before any memory is touched.
  json s = base_scene();
  s["meshes"][0] = {{"material", "white"},
                    {"generate", {{"kind", "soup"}, {"triangles", 60'000'000}}}};
  expect_error(s, "meshes[0].generate.triangles", "50000000");
  s["meshes"][0]["generate"]["triangles"] = 1e30;
  expect_error(s, "meshes[0].generate.triangles", "expected an integer");
  s["meshes"][0]["generate"] = {{"kind", "tetrahedra"}, {"triangles", 10}};
  expect_error(s, "meshes[0].generate.kind", "unknown generated mesh kind 'tetrahedra'");
  s["meshes"][0]["generate"] = {{"kind", "grid"}, {"triangles", 10}, {"seed", -3}};
  expect_error(s, "meshes[0].generate.seed", ">= 0");
}

TEST_F(ScenesJson, MaterialsNameTextures) {
  test::write_text(dir_ / "wood.png", "the loader only checks that the file exists");
  fs::create_directories(dir_ / "maps");
  test::write_text(dir_ / "maps" / "screen.png", "-");
  json s = base_scene();
  s["materials"] = json::parse(R"([
    {"name": "white", "type": "diffuse",
     "reflectance": {"texture": "wood.png", "color_space": "sRGB - Texture",
                     "scale": [0.9, 0.8, 0.7]}},
    {"name": "screen", "type": "emission",
     "radiance": {"texture": "maps/screen.png", "scale": 5}},
    {"name": "gold", "type": "microfacet", "alpha": 0.2, "reflectance": {"texture": "wood.png"}},
    {"name": "steel", "type": "microfacet", "reflectance": [0.6, 0.6, 0.6]},
    {"name": "chrome", "type": "mirror",
     "reflectance": {"texture": "wood.png", "color_space": "sRGB - Texture"}}
  ])");
  const Scene scene = load(s.dump(2));
  ASSERT_EQ(scene.materials.size(), 5u);
  ASSERT_EQ(scene.textures.size(), 3u);  // wood.png twice with the same space is one texture
  const Material& white = scene.materials[0];
  EXPECT_EQ(white.reflectance, Rgb(0.9f, 0.8f, 0.7f));
  EXPECT_EQ(white.reflectance_texture, 0u);
  EXPECT_EQ(scene.textures[0].file, dir_ / "wood.png");
  EXPECT_EQ(scene.textures[0].name, "wood.png");
  EXPECT_EQ(scene.textures[0].color_space, "sRGB - Texture");
  EXPECT_EQ(scene.textures[0].origin.element, "materials[0].reflectance.texture");
  EXPECT_GT(scene.textures[0].origin.line, 0);
  EXPECT_EQ(scene.materials[1].radiance, Rgb(5.0f));
  EXPECT_EQ(scene.materials[1].radiance_texture, 1u);
  EXPECT_EQ(scene.textures[1].file, dir_ / "maps" / "screen.png");
  EXPECT_EQ(scene.materials[2].reflectance_texture, 2u);
  EXPECT_EQ(scene.materials[2].reflectance, Rgb(1.0f));
  EXPECT_TRUE(scene.textures[2].color_space.empty());
  const Material& steel = scene.materials[3];
  EXPECT_EQ(steel.reflectance_texture, kNoTexture);
  const float n = steel.eta.r, k = steel.k.r;
  EXPECT_NEAR(((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 0.6f, 1e-5f);
  EXPECT_EQ(scene.materials[4].reflectance_texture, 0u);
}

TEST_F(ScenesJson, TextureMistakesAreErrors) {
  test::write_text(dir_ / "wood.png", "-");
  json s = base_scene();
  s["materials"][0]["reflectance"] = {{"texture", "nothere.png"}};
  expect_error(s, "materials[0].reflectance.texture", "texture file 'nothere.png' not found");
  s["materials"][0]["reflectance"] = {{"texture", "wood.png"}, {"colour_space", "sRGB"}};
  expect_error(s, "materials[0].reflectance.colour_space", "did you mean 'color_space'");
  s["materials"][0]["reflectance"] = {{"texture", "wood.png"}, {"scale", 2}};
  expect_error(s, "materials[0].reflectance.scale", "must be in [0, 1]");
  s["materials"][0]["reflectance"] = {{"texture", "wood.png"}, {"color_space", ""}};
  expect_error(s, "materials[0].reflectance.color_space", "empty");
  s["materials"][0]["reflectance"] = {{"scale", 0.5}};
  expect_error(s, "materials[0].reflectance", "missing required field 'texture'");
  s["materials"][0] = {
      {"name", "white"}, {"type", "microfacet"}, {"reflectance", 0.5}, {"eta", 1}, {"k", 1}};
  expect_error(s, "materials[0].reflectance", "not both");
  s["materials"][0] = {
      {"name", "white"}, {"type", "glass"}, {"transmittance", {{"texture", "wood.png"}}}};
  expect_error(s, "materials[0].transmittance", "expected a colour");
}

// docs/SCENE_FORMAT.md's textures example must stay loadable materials.
TEST_F(ScenesJson, DocumentedTexturesExampleLoads) {
  std::ifstream in(fs::path(PRISM_SOURCE_DIR) / "docs" / "SCENE_FORMAT.md");
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string text = doc.str();
  const size_t section = text.find("## Textures");
  ASSERT_NE(section, std::string::npos);
  const size_t begin = text.find("```json\n", section);
  const size_t end = text.find("```\n", begin + 8);
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  fs::create_directories(dir_ / "textures");
  for (const char* name : {"wood.png", "brass.jpg", "screen.exr"}) {
    test::write_text(dir_ / "textures" / name, "-");
  }
  const Scene scene =
      load("{\"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0], \"fov\": 45},\n" +
           text.substr(begin + 8, end - begin - 8) + "}");
  EXPECT_EQ(scene.materials.size(), 3u);
  EXPECT_EQ(scene.textures.size(), 3u);
}

// docs/SCENE_FORMAT.md's complete example must stay a loadable scene.
TEST_F(ScenesJson, DocumentedExampleLoads) {
  std::ifstream in(fs::path(PRISM_SOURCE_DIR) / "docs" / "SCENE_FORMAT.md");
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string text = doc.str();
  const size_t section = text.find("## A complete example");
  ASSERT_NE(section, std::string::npos);
  const size_t begin = text.find("```json\n", section);
  const size_t end = text.find("```\n", begin + 8);
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  fs::create_directories(dir_ / "models");
  test::write_text(dir_ / "models" / "bunny.ply",
                   "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 4\nproperty list uchar int vertex_indices\n"
                   "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const Scene scene = load(text.substr(begin + 8, end - begin - 8));
  EXPECT_EQ(scene.materials.size(), 6u);
  EXPECT_EQ(scene.lights.size(), 5u);
  EXPECT_EQ(scene.geometry.meshes.size(), 4u);
  EXPECT_EQ(scene.geometry.meshes[2].triangle_count(), 4u);
  EXPECT_EQ(scene.geometry.spheres.size(), 2u);
  EXPECT_NO_THROW(scene.validate());
}

}  // namespace
}  // namespace prism
