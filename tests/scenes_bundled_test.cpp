#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/scene.h"
#include "scenes/scene_loader.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

Scene load_bundled(const std::string& name) { return load_scene(bundled_scene_dir() / name); }

size_t count_emissive_meshes(const Scene& scene) {
  return std::count_if(
      scene.geometry.meshes.begin(), scene.geometry.meshes.end(),
      [&](const TriangleMesh& m) { return scene.materials[m.material_id].is_emissive(); });
}

/// Where `p` lands on the image in [-1, 1]^2 (x right, y up), as Camera::generate_ray maps it.
Vec2 project(const Camera& camera, const Vec3& p) {
  const Vec3 forward = glm::normalize(camera.target - camera.position);
  const Vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const Vec3 up = glm::cross(right, forward);
  const Vec3 d = p - camera.position;
  const float depth = glm::dot(d, forward);
  return {glm::dot(d, right) / depth / std::tan(radians(camera.hfov_deg) / 2),
          glm::dot(d, up) / depth / std::tan(radians(camera.vfov_deg) / 2)};
}

/// Checks shared by the Cornell boxes: 480x360, the box framed, walls facing in, light down.
void expect_cornell_box(const Scene& scene) {
  EXPECT_EQ(scene.settings.width, 480);
  EXPECT_EQ(scene.settings.height, 360);
  EXPECT_EQ(count_emissive_meshes(scene), 1u);
  EXPECT_TRUE(scene.lights.empty());  // the emissive quad is the light
  // Geometry apart from the light quad and the contents: the 2 x 1.5 x 2 box.
  const Bounds3 box = scene.geometry.bounds();
  EXPECT_EQ(box.lower, Vec3(-1, 0, -1));
  EXPECT_EQ(box.upper, Vec3(1, 1.5f, 1));
  // Every corner of the box is in the picture, and the open front fills most of it.
  float widest = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner{i & 1 ? box.upper.x : box.lower.x, i & 2 ? box.upper.y : box.lower.y,
                      i & 4 ? box.upper.z : box.lower.z};
    const Vec2 at = project(scene.camera, corner);
    EXPECT_LT(std::abs(at.x), 1.0f) << "corner " << i;
    EXPECT_LT(std::abs(at.y), 1.0f) << "corner " << i;
    widest = std::max(widest, std::abs(at.x));
  }
  EXPECT_GT(widest, 0.8f);
  // The red wall is on the left of the image, the blue one on the right.
  for (const TriangleMesh& m : scene.geometry.meshes) {
    const Material& mat = scene.materials[m.material_id];
    const Vec3 centre = m.bounds().center();
    const Vec3 box_centre = box.center();
    for (const auto& t : m.triangles) {
      const Vec3 n =
          glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
      if (mat.is_emissive()) {
        EXPECT_LT(n.y, 0.0f) << m.name << " should emit downwards";
      } else if (m.name.find("wall") != std::string::npos || m.name == "floor" ||
                 m.name == "ceiling") {
        EXPECT_GT(glm::dot(n, box_centre - centre), 0.0f) << m.name << " should face into the box";
      }
    }
    if (m.name == "left_wall") {
      EXPECT_GT(mat.reflectance.r, 2 * mat.reflectance.b);
      EXPECT_LT(project(scene.camera, centre).x, 0.0f);
    }
    if (m.name == "right_wall") {
      EXPECT_GT(mat.reflectance.b, 2 * mat.reflectance.r);
      EXPECT_GT(project(scene.camera, centre).x, 0.0f);
    }
  }
}

TEST(ScenesBundled, DefaultSceneIsTheCornellBoxWithSpheres) {
  EXPECT_EQ(default_scene_path().filename(), "cornell_spheres.json");
  EXPECT_TRUE(fs::exists(default_scene_path()));
}

TEST(ScenesBundled, CornellEmpty) {
  const Scene scene = load_bundled("cornell_empty.json");
  EXPECT_EQ(scene.geometry.meshes.size(), 6u);
  EXPECT_EQ(scene.geometry.triangle_count(), 12u);
  EXPECT_TRUE(scene.geometry.spheres.empty());
  expect_cornell_box(scene);
}

TEST(ScenesBundled, CornellSpheres) {
  const Scene scene = load_bundled("cornell_spheres.json");
  EXPECT_EQ(scene.geometry.triangle_count(), 12u);
  ASSERT_EQ(scene.geometry.spheres.size(), 2u);
  std::vector<MaterialType> kinds;
  for (const Sphere& s : scene.geometry.spheres) {
    kinds.push_back(scene.materials[s.material_id].type);
    EXPECT_NEAR(s.center.y, s.radius, 1e-6f) << "spheres rest on the floor";
  }
  EXPECT_EQ(kinds, (std::vector<MaterialType>{MaterialType::kMirror, MaterialType::kGlass}));
  expect_cornell_box(scene);
}

TEST(ScenesBundled, CornellMesh) {
  const Scene scene = load_bundled("cornell_mesh.json");
  ASSERT_EQ(scene.geometry.meshes.size(), 7u);
  const TriangleMesh& blob = scene.geometry.meshes.back();
  EXPECT_GT(blob.triangle_count(), 15000u);
  EXPECT_LT(blob.triangle_count(), 25000u);
  // Inside the box, resting just above the floor.
  const Bounds3 b = blob.bounds();
  EXPECT_GT(b.lower.y, 0.0f);
  EXPECT_LT(b.lower.y, 0.2f);
  EXPECT_GT(b.lower.x, -1.0f);
  EXPECT_LT(b.upper.x, 1.0f);
  expect_cornell_box(scene);
}

TEST(ScenesBundled, EveryBundledSceneLoads) {
  size_t count = 0;
  for (const auto& entry : fs::directory_iterator(bundled_scene_dir())) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_NO_THROW(load_scene(entry.path())) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 3u);
}

}  // namespace
}  // namespace prism
