// The debug integrators (integrators/debug_integrators): the shading normal as a colour and
// the depth along the camera ray.
#include <gtest/gtest.h>

#include "tests/support/integrators_test_scenes.h"

namespace prism {
namespace {

using test::TestRender;

/// A unit sphere 3 units in front of the camera, nothing else.
Scene one_sphere() {
  Scene scene;
  test::add_material(scene, MaterialType::kDiffuse, Rgb(0.25f, 0.5f, 0.75f), "paint");
  scene.geometry.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  scene.camera.position = Vec3(0.0f, 0.0f, 4.0f);
  scene.camera.target = Vec3(0.0f);
  scene.camera.hfov_deg = scene.camera.vfov_deg = 40.0f;
  scene.geometry.finalize();
  return scene;
}

TEST(IntegratorsDebugIntegrators, NormalsAndDepthOfASphere) {
  const Scene scene = one_sphere();
  TestRender settings;
  settings.width = settings.height = 15;  // odd: the centre pixel looks straight at the sphere
  settings.spp = 1;
  settings.sampler = "jittered";  // spp 1: one stratum, the sample at random in it
  const Image normals = test::render_scene(scene, "normals", settings);
  const Image depth = test::render_scene(scene, "depth", settings);
  // Centre: n = (0, 0, 1) -> colour (0.5, 0.5, 1); depth 3.
  EXPECT_NEAR(normals.at(7, 7, 0), 0.5f, 0.05f);
  EXPECT_NEAR(normals.at(7, 7, 1), 0.5f, 0.05f);
  EXPECT_NEAR(normals.at(7, 7, 2), 1.0f, 0.01f);
  EXPECT_NEAR(depth.at(7, 7, 0), 3.0f, 0.02f);
  // Corners miss: black, depth 0.
  EXPECT_EQ(normals.at(0, 0, 0), 0.0f);
  EXPECT_EQ(depth.at(0, 0, 0), 0.0f);
  // Every hit pixel: a unit normal on the camera's side, depth in [3, 4].
  for (int y = 0; y < normals.height; ++y) {
    for (int x = 0; x < normals.width; ++x) {
      if (depth.at(x, y, 0) == 0.0f) continue;
      const Vec3 n =
          2.0f * Vec3(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2)) - Vec3(1.0f);
      EXPECT_NEAR(glm::length(n), 1.0f, 1e-3f);
      EXPECT_GT(n.z, 0.0f);
      EXPECT_GE(depth.at(x, y, 0), 3.0f - 1e-4f);
      EXPECT_LE(depth.at(x, y, 0), 4.0f);
    }
  }
}

}  // namespace
}  // namespace prism
