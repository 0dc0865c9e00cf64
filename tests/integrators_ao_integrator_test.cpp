// The ambient occlusion integrator (integrators/ao_integrator): open where nothing occludes,
// darker in the corners of a closed box.
#include <gtest/gtest.h>

#include "tests/support/integrators_test_scenes.h"

namespace prism {
namespace {

using test::TestRender;

TEST(IntegratorsAoIntegrator, AmbientOcclusion) {
  // A lone floor: nothing occludes, so every hit pixel is fully open.
  Scene scene;
  test::add_material(scene, MaterialType::kDiffuse, Rgb(0.5f), "floor");
  scene.geometry.meshes.push_back(
      test::quad("floor", {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, 0));
  scene.camera.position = Vec3(0.0f, 1.0f, 2.0f);
  scene.camera.target = Vec3(0.0f);
  scene.geometry.finalize();
  TestRender settings;
  settings.spp = 4;
  ParamSet params;
  params.set("ao.samples", "4");
  const Image open = test::render_scene(scene, "ao", params, settings);
  for (int y = 0; y < open.height; ++y) {
    for (int x = 0; x < open.width; ++x) EXPECT_LE(open.at(x, y, 0), 1.0f);
  }
  // The centre looks at the middle of the floor; a corner at the sky.
  EXPECT_EQ(open.at(open.width / 2, open.height / 2, 0), 1.0f);
  EXPECT_EQ(open.at(0, 0, 0), 0.0f);
  // Inside the closed Cornell box, corners are occluded.
  const Image box = test::render_scene(test::cornell_box(), "ao", params, settings);
  const test::ImageMean m = test::image_mean(box, 0);
  EXPECT_GT(m.mean, 0.1);
  EXPECT_LT(m.mean, 1.0);
}

}  // namespace
}  // namespace prism
