// Model files as whole scenes (scenes/model_loader.*, scenes/model/): every format, node
// transforms, the material mapping, textures, cameras, lights and the default lighting, and
// hostile files. The files are written by the tests (tests/support/model_test_files.h); FBX by
// Assimp's own exporter.

#include <gtest/gtest.h>

#include <assimp/scene.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "scenes/model/model_lights.h"
#include "scenes/model/model_materials.h"
#include "scenes/scene_loader.h"
#include "tests/support/model_test_files.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::Bytes;
using test::GltfBuilder;

const std::string kQuadObj = R"(mtllib quad.mtl
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
usemtl painted
f 1/1/1 2/2/1 3/3/1 4/4/1
)";

/// kQuadObj without its material library: Assimp's default material.
std::string replaced_mtllib() {
  std::string text = kQuadObj;
  text.erase(0, text.find('\n') + 1);
  text.erase(text.find("usemtl"), std::string("usemtl painted\n").size());
  return text;
}

/// The reflectance at normal incidence of a conductor eta + i k.
float normal_reflectance(float eta, float k) {
  return ((eta - 1) * (eta - 1) + k * k) / ((eta + 1) * (eta + 1) + k * k);
}

bool has_warning(const Scene& scene, const std::string& part) {
  return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                     [&](const std::string& w) { return w.find(part) != std::string::npos; });
}

const Light* find_light(const Scene& scene, LightType type) {
  for (const Light& l : scene.lights) {
    if (l.type == type) return &l;
  }
  return nullptr;
}

class ScenesModel : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::make_temp_dir("scenes_model"); }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  fs::path text_file(const std::string& name, const std::string& text) const {
    test::write_text(dir_ / name, text);
    return dir_ / name;
  }
  fs::path bytes_file(const std::string& name, const Bytes& bytes) const {
    test::write_bytes(dir_ / name, bytes);
    return dir_ / name;
  }
  Scene load(const fs::path& path, bool literal = false) const {
    return load_scene(path, SceneLoadOptions{.literal_camera = literal});
  }
  /// The error load() throws for `path` (fails the test when it loads).
  Error load_error(const fs::path& path, bool literal = false) const {
    try {
      load(path, literal);
    } catch (const Error& e) {
      return e;
    }
    ADD_FAILURE() << path << " loaded";
    return Error(ErrorKind::kInternal, "loaded");
  }

  fs::path dir_;
};

TEST_F(ScenesModel, ObjWithMtlAndTextureIsAScene) {
  text_file("quad.obj", kQuadObj);
  text_file("quad.mtl", "newmtl painted\nKd 0.8 0.6 0.4\nmap_Kd maps/checker.png\n");
  fs::create_directories(dir_ / "maps");
  bytes_file("maps/checker.png", test::png_checkerboard(2, 2, {255, 0, 0}, {0, 0, 255}));
  const Scene scene = load(dir_ / "quad.obj");
  EXPECT_EQ(scene.source, (dir_ / "quad.obj").string());
  ASSERT_EQ(scene.geometry.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.geometry.meshes[0];
  EXPECT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.uvs.size(), 6u);
  EXPECT_EQ(mesh.normals.size(), 6u);
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.name, "painted");
  EXPECT_EQ(m.type, MaterialType::kDiffuse);
  EXPECT_NEAR(m.reflectance.r, 0.8f, 1e-6f);
  EXPECT_NEAR(m.reflectance.b, 0.4f, 1e-6f);
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(m.reflectance_texture, 0u);
  EXPECT_EQ(scene.textures[0].file, dir_ / "maps/checker.png");
  EXPECT_FALSE(scene.textures[0].is_embedded());
  EXPECT_TRUE(scene.textures[0].color_space.empty());
}

TEST_F(ScenesModel, ExtensionsAreReadInAnyCase) {
  text_file("QUAD.OBJ", replaced_mtllib());
  const Scene scene = load(dir_ / "QUAD.OBJ");
  EXPECT_EQ(scene.geometry.triangle_count(), 2u);
}

TEST_F(ScenesModel, StlAndPlyGetGreyDiffuseAndTheDefaultLighting) {
  const fs::path stl = text_file("tri.stl", R"(solid t
facet normal 0 0 1
outer loop
vertex 0 0 0
vertex 1 0 0
vertex 0 1 0
endloop
endfacet
facet normal 0 0 1
outer loop
vertex 1 0 0
vertex 1 1 0
vertex 0 1 0
endloop
endfacet
endsolid t
)");
  const fs::path ply = text_file("tri.ply", R"(ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 1
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
1 1 0
0 1 0
4 0 1 2 3
)");
  for (const fs::path& path : {stl, ply}) {
    SCOPED_TRACE(path.string());
    const Scene scene = load(path);
    EXPECT_EQ(scene.geometry.triangle_count(), 2u);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].type, MaterialType::kDiffuse);
    EXPECT_EQ(scene.materials[0].reflectance, Rgb(model::kDefaultGrey));
    ASSERT_EQ(scene.lights.size(), 2u);
    const Light* sky = find_light(scene, LightType::kAmbient);
    const Light* key = find_light(scene, LightType::kDirectional);
    ASSERT_TRUE(sky && key);
    EXPECT_EQ(sky->color, Rgb(model::kDefaultSkyRadiance));
    EXPECT_EQ(sky->up, Vec3(0, 1, 0));
    EXPECT_EQ(key->color, Rgb(model::kDefaultKeyIrradiance));
    // From above, in front (+Z) and to the right (+X).
    EXPECT_LT(key->direction.y, 0.0f);
    EXPECT_LT(key->direction.z, 0.0f);
    EXPECT_LT(key->direction.x, 0.0f);
    EXPECT_TRUE(has_warning(scene, "default lighting"));
  }
}

TEST_F(ScenesModel, NodeTransformsArePerInstance) {
  GltfBuilder b;
  const int quad = b.add_quad_mesh(-1);
  b.add_node({{"name", "left"}, {"mesh", quad}, {"translation", {-2, 0, 0}}});
  b.add_node({{"name", "right"}, {"mesh", quad}, {"translation", {3, 0, 0}}, {"scale", {1, 2, 1}}});
  // A parent turning its child a quarter turn about +Y: the child's quad faces +X.
  const int child = b.add_node({{"name", "child"}, {"mesh", quad}, {"translation", {0, 0, 1}}},
                               /*root=*/false);
  b.add_node({{"name", "parent"},
              {"translation", {0, 5, 0}},
              {"rotation", {0, std::sin(M_PI / 4), 0, std::cos(M_PI / 4)}},
              {"children", {child}}});
  const Scene scene = load(text_file("nodes.gltf", b.gltf()));
  ASSERT_EQ(scene.geometry.meshes.size(), 3u);
  const auto bounds = [&](size_t i) { return scene.geometry.meshes[i].bounds(); };
  EXPECT_NEAR(bounds(0).lower.x, -3.0f, 1e-5f);
  EXPECT_NEAR(bounds(0).upper.x, -1.0f, 1e-5f);
  EXPECT_NEAR(bounds(1).lower.x, 2.0f, 1e-5f);
  EXPECT_NEAR(bounds(1).upper.x, 4.0f, 1e-5f);
  EXPECT_NEAR(bounds(1).lower.y, -2.0f, 1e-5f);
  EXPECT_NEAR(bounds(1).upper.y, 2.0f, 1e-5f);
  // child: z = 1 becomes x = 1 under the rotation, then y moves up by 5.
  EXPECT_NEAR(bounds(2).lower.x, 1.0f, 1e-5f);
  EXPECT_NEAR(bounds(2).upper.x, 1.0f, 1e-5f);
  EXPECT_NEAR(bounds(2).lower.y, 4.0f, 1e-5f);
  EXPECT_NEAR(bounds(2).upper.y, 6.0f, 1e-5f);
  const TriangleMesh& turned = scene.geometry.meshes[2];
  for (const Vec3& n : turned.normals) EXPECT_NEAR(n.x, 1.0f, 1e-5f);
  EXPECT_EQ(turned.name.rfind("child/", 0), 0u) << turned.name;
}

TEST_F(ScenesModel, MirroringNodesKeepFrontsOnTheirSide) {
  GltfBuilder b;
  const int quad = b.add_quad_mesh(-1);
  b.add_node({{"mesh", quad}, {"scale", {-1, 1, 1}}});
  const Scene scene = load(text_file("mirror.gltf", b.gltf()));
  ASSERT_EQ(scene.geometry.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.geometry.meshes[0];
  ASSERT_EQ(mesh.normals.size(), 6u);
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    const Vec3 winding = glm::cross(mesh.positions[tri.y] - mesh.positions[tri.x],
                                    mesh.positions[tri.z] - mesh.positions[tri.x]);
    EXPECT_GT(winding.z, 0.0f) << "triangle " << t;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mesh.normals[3 * t + size_t(c)].z, 1.0f, 1e-6f);
  }
}

TEST_F(ScenesModel, MaterialsMapToPrismsModels) {
  GltfBuilder b;
  const int paint =
      b.add_material("paint", {{"baseColorFactor", {0.8, 0.2, 0.1, 1}}, {"metallicFactor", 0.2}});
  const int gold = b.add_material(
      "gold",
      {{"baseColorFactor", {1.0, 0.78, 0.34, 1}}, {"metallicFactor", 1}, {"roughnessFactor", 0.5}});
  const int mirror = b.add_material(
      "polished",
      {{"baseColorFactor", {0.9, 0.9, 0.9, 1}}, {"metallicFactor", 0.9}, {"roughnessFactor", 0}});
  const int glass = b.add_material(
      "glass", {{"baseColorFactor", {0.9, 1, 0.95, 1}}, {"metallicFactor", 0}},
      {{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1}}}}}});
  const int lamp =
      b.add_material("lamp", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"metallicFactor", 0}},
                     {{"emissiveFactor", {1, 0.5, 0.25}}});
  b.doc["extensionsUsed"] = {"KHR_materials_transmission"};
  for (const int material : {paint, gold, mirror, glass, lamp}) {
    b.add_node({{"mesh", b.add_quad_mesh(material)}, {"translation", {3 * material, 0, 0}}});
  }
  const Scene scene = load(text_file("materials.gltf", b.gltf()));
  ASSERT_EQ(scene.materials.size(), 5u);
  const auto material = [&](const std::string& name) -> const Material& {
    for (const Material& m : scene.materials) {
      if (m.name == name) return m;
    }
    ADD_FAILURE() << "no material " << name;
    return scene.materials[0];
  };
  EXPECT_EQ(material("paint").type, MaterialType::kDiffuse);
  EXPECT_NEAR(material("paint").reflectance.g, 0.2f, 1e-6f);
  EXPECT_FALSE(material("paint").is_emissive());

  const Material& g = material("gold");
  EXPECT_EQ(g.type, MaterialType::kMicrofacet);
  EXPECT_NEAR(g.alpha, 0.25f, 1e-6f);  // roughness squared
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(normal_reflectance(g.eta[c], g.k[c]), std::min(g.reflectance[c], 0.999f), 1e-4f)
        << "channel " << c;
  }
  EXPECT_NEAR(g.reflectance.b, 0.34f, 1e-6f);
  EXPECT_NEAR(material("polished").alpha, model::kMinMetalAlpha, 1e-7f);

  const Material& t = material("glass");
  EXPECT_EQ(t.type, MaterialType::kGlass);
  EXPECT_NEAR(t.transmittance.g, 1.0f, 1e-6f);
  EXPECT_NEAR(t.transmittance.r, 0.9f, 1e-6f);
  EXPECT_NEAR(t.ior, 1.5f, 1e-6f);

  const Material& l = material("lamp");
  EXPECT_EQ(l.type, MaterialType::kDiffuse);  // emission on top of the surface
  EXPECT_TRUE(l.is_emissive());
  EXPECT_EQ(l.radiance, Rgb(1.0f, 0.5f, 0.25f));
  // The emissive quad lights the model: no default lighting.
  EXPECT_TRUE(scene.lights.empty());
  EXPECT_FALSE(has_warning(scene, "default lighting"));
}

TEST_F(ScenesModel, GlbEmbeddedTexturesTravelAsBytes) {
  GltfBuilder b;
  const Bytes png = test::png_checkerboard(2, 4, {255, 255, 255}, {0, 0, 0});
  const int texture = b.embed_image(png);
  const int m =
      b.add_material("checker", {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0}},
                     {{"emissiveFactor", {2, 2, 2}}, {"emissiveTexture", {{"index", texture}}}});
  b.add_node({{"mesh", b.add_quad_mesh(m)}});
  const Scene scene = load(bytes_file("embedded.glb", b.glb()));
  ASSERT_EQ(scene.textures.size(), 1u);  // one image, named twice
  const TextureSource& source = scene.textures[0];
  EXPECT_TRUE(source.is_embedded());
  EXPECT_EQ(source.bytes, png);
  EXPECT_NE(source.name.find("embedded.glb: embedded texture"), std::string::npos) << source.name;
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].reflectance_texture, 0u);
  EXPECT_EQ(scene.materials[0].radiance_texture, 0u);
  EXPECT_EQ(scene.materials[0].radiance, Rgb(2.0f));
  // Assimp reports glTF's uvs with v up: the quad's bottom-left corner is (0, 0).
  const TriangleMesh& mesh = scene.geometry.meshes[0];
  for (size_t c = 0; c < mesh.uvs.size(); ++c) {
    const Vec3 p = mesh.positions[mesh.triangles[c / 3][int(c % 3)]];
    EXPECT_NEAR(mesh.uvs[c].x, 0.5f * (p.x + 1.0f), 1e-6f);
    EXPECT_NEAR(mesh.uvs[c].y, 0.5f * (p.y + 1.0f), 1e-6f);
  }
}

TEST_F(ScenesModel, ExternalTexturesResolveBesideTheModel) {
  GltfBuilder b;
  const int texture = b.file_image("textures/wood%20grain.png");
  const int m = b.add_material("wood", {{"baseColorTexture", {{"index", texture}}}});
  b.add_node({{"mesh", b.add_quad_mesh(m)}});
  fs::create_directories(dir_ / "textures");
  bytes_file("textures/wood grain.png", test::png_rgb8(1, 1, {10, 20, 30}));
  const Scene scene = load(text_file("wood.gltf", b.gltf()));
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_TRUE(fs::equivalent(scene.textures[0].file, dir_ / "textures/wood grain.png"));
  // metallicFactor defaults to 1 in glTF: a textured metal.
  EXPECT_EQ(scene.materials[0].type, MaterialType::kMicrofacet);
  EXPECT_EQ(scene.materials[0].reflectance_texture, 0u);
}

TEST_F(ScenesModel, AMissingTextureIsAnErrorNamingIt) {
  GltfBuilder b;
  const int texture = b.file_image("nothere.png");
  const int m = b.add_material("lost", {{"baseColorTexture", {{"index", texture}}}});
  b.add_node({{"mesh", b.add_quad_mesh(m)}});
  const fs::path model = text_file("lost.gltf", b.gltf());
  const Error e = load_error(model);
  EXPECT_EQ(e.kind(), ErrorKind::kInput);
  EXPECT_EQ(e.exit_code(), 2);
  EXPECT_EQ(e.location().file, model.string());
  EXPECT_NE(std::string(e.what()).find("nothere.png"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("lost"), std::string::npos) << e.what();

  text_file("quad.obj", kQuadObj);
  text_file("quad.mtl", "newmtl painted\nmap_Kd C:\\Users\\me\\gone.png\n");
  const Error obj = load_error(dir_ / "quad.obj");
  EXPECT_NE(std::string(obj.what()).find("gone.png"), std::string::npos) << obj.what();
}

TEST_F(ScenesModel, TexturesMovedBesideTheModelAreFound) {
  text_file("quad.obj", kQuadObj);
  text_file("quad.mtl", "newmtl painted\nmap_Kd C:\\Users\\me\\art\\here.png\n");
  bytes_file("here.png", test::png_rgb8(1, 1, {1, 2, 3}));
  const Scene scene = load(dir_ / "quad.obj");
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].file, dir_ / "here.png");
}

TEST_F(ScenesModel, TheHomeworkFramingLooksFromTheFilesCamera) {
  GltfBuilder b;
  b.add_node({{"mesh", b.add_quad_mesh(-1)}, {"translation", {0, 1, 0}}});
  // A camera 5 units along +Z turned 90 degrees about +Y: it looks down -X.
  const double s = std::sin(M_PI / 4), c = std::cos(M_PI / 4);
  b.add_node({{"name", "cam"},
              {"camera", b.add_camera(0.6, 1.5, 0.05, 50)},
              {"translation", {0, 0, 5}},
              {"rotation", {0, s, 0, c}}});
  const fs::path model = text_file("camera.gltf", b.gltf());
  const Scene framed = load(model);
  const Camera& f = framed.camera;
  // The point one unit ahead, (-1, 0, 5), as a direction from the origin.
  const Vec3 expected_c = glm::normalize(Vec3(-1, 0, 5));
  const float r = 1.5f * glm::length(framed.geometry.bounds().diagonal());
  EXPECT_NEAR(glm::length(f.target - Vec3(0, 1, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(f.position - (f.target + r * expected_c)), 0.0f, 1e-4f);
  EXPECT_EQ(f.up, Vec3(0, 1, 0));
  // Assimp 5.2 reports glTF's horizontal fov as yfov x aspect.
  EXPECT_NEAR(f.hfov_deg, glm::degrees(0.9f), 1e-3f);

  const Scene literal = load(model, /*literal=*/true);
  const Camera& l = literal.camera;
  EXPECT_NEAR(glm::length(l.position - Vec3(0, 0, 5)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(l.target - Vec3(-1, 0, 5)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(l.up - Vec3(0, 1, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(l.hfov_deg, glm::degrees(0.9f), 1e-3f);
  EXPECT_NEAR(std::tan(radians(l.hfov_deg) / 2) / std::tan(radians(l.vfov_deg) / 2), 1.5f, 1e-4f);
  EXPECT_NEAR(l.znear, 0.05f, 1e-6f);
  EXPECT_NEAR(l.zfar, 50.0f, 1e-4f);
}

TEST_F(ScenesModel, WithoutACameraTheFramingLooksFromTheFrontAndAbove) {
  text_file("quad.obj", replaced_mtllib());
  const Scene scene = load(dir_ / "quad.obj");
  const Vec3 c = glm::normalize(scene.camera.position - scene.camera.target);
  EXPECT_NEAR(glm::length(c - glm::normalize(Vec3(0.3f, 0.5f, 1.0f))), 0.0f, 1e-5f);
  EXPECT_EQ(scene.camera.up, Vec3(0, 1, 0));
  EXPECT_NEAR(glm::length(scene.camera.target), 0.0f, 1e-6f);
  EXPECT_GT(scene.camera.zfar, glm::length(scene.camera.position));

  const Error e = load_error(dir_ / "quad.obj", /*literal=*/true);
  EXPECT_EQ(e.kind(), ErrorKind::kInput);
  EXPECT_NE(std::string(e.what()).find("no camera"), std::string::npos) << e.what();
  EXPECT_EQ(e.location().file, (dir_ / "quad.obj").string());
}

TEST_F(ScenesModel, TheFilesLightsReplaceTheDefaultLighting) {
  GltfBuilder b;
  b.add_node({{"mesh", b.add_quad_mesh(-1)}});
  const int point = b.add_light({{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 8}});
  const int spot =
      b.add_light({{"type", "spot"}, {"intensity", 2}, {"spot", {{"outerConeAngle", 0.5}}}});
  b.add_node({{"name", "bulb"},
              {"translation", {1, 2, 3}},
              {"extensions", {{"KHR_lights_punctual", {{"light", point}}}}}});
  // A spot at y = 4 turned to look down: -Z rotated -90 degrees about X.
  const double s = std::sin(-M_PI / 4), c = std::cos(-M_PI / 4);
  b.add_node({{"name", "spot"},
              {"translation", {0, 4, 0}},
              {"rotation", {s, 0, 0, c}},
              {"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
  const Scene scene = load(text_file("lit.gltf", b.gltf()));
  ASSERT_EQ(scene.lights.size(), 2u);
  const Light* bulb = find_light(scene, LightType::kPoint);
  ASSERT_NE(bulb, nullptr);
  EXPECT_NEAR(glm::length(bulb->position - Vec3(1, 2, 3)), 0.0f, 1e-5f);
  EXPECT_NEAR(bulb->color.r, 8.0f, 1e-5f);
  EXPECT_NEAR(bulb->color.b, 2.0f, 1e-5f);
  EXPECT_EQ(bulb->quadratic_attenuation + bulb->linear_attenuation > 0.0f, true);
  const Light* cone = find_light(scene, LightType::kSpot);
  ASSERT_NE(cone, nullptr);
  EXPECT_NEAR(glm::length(cone->direction - Vec3(0, -1, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(cone->falloff_angle_deg, glm::degrees(1.0f), 1e-3f);  // 2 x glTF's half angle
  EXPECT_FALSE(has_warning(scene, "default lighting"));
}

TEST_F(ScenesModel, FbxWrittenByAssimpLoads) {
  GltfBuilder b;
  const int m =
      b.add_material("paint", {{"baseColorFactor", {0.2, 0.4, 0.6, 1}}, {"metallicFactor", 0}});
  const int quad = b.add_quad_mesh(m);
  b.add_node({{"name", "a"}, {"mesh", quad}, {"translation", {-2, 0, 0}}});
  b.add_node({{"name", "b"}, {"mesh", quad}, {"translation", {2, 0, 0}}});
  const fs::path gltf = text_file("source.gltf", b.gltf());
  Assimp::Importer importer;
  const aiScene* source = importer.ReadFile(gltf.string(), 0);
  ASSERT_NE(source, nullptr) << importer.GetErrorString();
  // Assimp 5.2 reads back its ASCII FBX; its binary FBX 7.5 it cannot ("block offset is out of
  // range").
  Assimp::Exporter exporter;
  const fs::path fbx = dir_ / "model.fbx";
  if (exporter.Export(source, "fbxa", fbx.string()) != AI_SUCCESS) {
    GTEST_SKIP() << "this Assimp cannot write FBX: " << exporter.GetErrorString();
  }
  const Scene scene = load(fbx);
  ASSERT_EQ(scene.geometry.meshes.size(), 2u);
  EXPECT_EQ(scene.geometry.triangle_count(), 4u);
  const Bounds3 bounds = scene.geometry.bounds();
  EXPECT_NEAR(bounds.lower.x, -3.0f, 1e-4f);
  EXPECT_NEAR(bounds.upper.x, 3.0f, 1e-4f);
  ASSERT_FALSE(scene.materials.empty());
  EXPECT_EQ(scene.materials[0].type, MaterialType::kDiffuse);
  EXPECT_NEAR(scene.materials[0].reflectance.b, 0.6f, 1e-5f);
}

TEST_F(ScenesModel, HostileFilesAreOneLineInputErrors) {
  GltfBuilder b;
  b.add_node({{"mesh", b.add_quad_mesh(-1)}});
  Bytes truncated = b.glb();
  truncated.resize(truncated.size() / 2);
  json overrun = json::parse(b.gltf());
  overrun["accessors"][0]["count"] = 1u << 30;
  json cyclic = json::parse(b.gltf());
  cyclic["nodes"][0]["children"] = {0};
  Bytes noise(4096);
  for (size_t i = 0; i < noise.size(); ++i) noise[i] = (unsigned char)((i * 2654435761u) >> 13);
  const std::vector<std::pair<std::string, Bytes>> files = {
      {"empty.obj", {}},
      {"points.obj", Bytes{'v', ' ', '0', ' ', '0', ' ', '0', '\n'}},
      {"noise.obj", noise},
      {"noise.stl", noise},
      {"noise.ply", noise},
      {"noise.fbx", noise},
      {"noise.glb", noise},
      {"noise.gltf", noise},
      {"truncated.glb", truncated},
      {"bad.gltf", Bytes{'{', '"', 'a', 's'}},
  };
  std::vector<std::pair<std::string, std::string>> texts = {{"overrun.gltf", overrun.dump()},
                                                            {"cyclic.gltf", cyclic.dump()}};
  for (const auto& [name, text] : texts) bytes_file(name, Bytes(text.begin(), text.end()));
  for (const auto& [name, bytes] : files) bytes_file(name, bytes);
  std::vector<std::string> names;
  for (const auto& f : files) names.push_back(f.first);
  for (const auto& t : texts) names.push_back(t.first);
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const Error e = load_error(dir_ / name);
    EXPECT_EQ(e.kind(), ErrorKind::kInput);
    EXPECT_EQ(e.location().file, (dir_ / name).string());
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace prism
