// Both accelerators give statistically identical images: per-pixel tests of the difference of
// means against the estimated variances, with the false-discovery rate controlled by
// Benjamini-Hochberg.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scenes/scene_loader.h"
#include "tests/support/integrators_test_scenes.h"
#include "tests/support/statistics.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

using test::benjamini_hochberg;
using test::normal_two_sided_p;

using test::TestRender;

/// Renders `scene` with bvh and with embree (different seeds) and expects no pixel to differ
/// significantly at false-discovery rate 1%.
void expect_backends_agree(const Scene& scene, const std::string& integrator, TestRender settings) {
  settings.accelerator = "bvh";
  settings.seed = 1;
  const Image a = test::render_scene(scene, integrator, settings);
  settings.accelerator = "embree";
  settings.seed = 2;
  const Image b = test::render_scene(scene, integrator, settings);
  ASSERT_EQ(a.width, b.width);
  std::vector<double> p_values;
  double sum_a = 0.0, sum_b = 0.0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double d = double(a.at(x, y, c)) - b.at(x, y, c);
        const double v =
            double(a.at(x, y, Film::kVarianceChannel + c)) + b.at(x, y, Film::kVarianceChannel + c);
        sum_a += a.at(x, y, c);
        sum_b += b.at(x, y, c);
        // No variance on either side (black, or a noiseless estimate): must match exactly
        // up to float rounding.
        if (v <= 0.0) {
          p_values.push_back(
              std::abs(d) <= 1e-5 * std::max(1.0, std::abs(double(a.at(x, y, c)))) ? 1.0 : 0.0);
          continue;
        }
        p_values.push_back(normal_two_sided_p(d / std::sqrt(v)));
      }
    }
  }
  const std::vector<bool> rejected = benjamini_hochberg(p_values, 0.01);
  size_t count = 0, first = rejected.size();
  for (size_t i = 0; i < rejected.size(); ++i) {
    if (rejected[i]) {
      ++count;
      first = std::min(first, i);
    }
  }
  EXPECT_EQ(count, 0u) << count << " of " << rejected.size()
                       << " pixel channels differ; first: pixel " << (first / 3) % a.width << ","
                       << (first / 3) / a.width << " channel " << first % 3;
  EXPECT_GT(sum_a, 0.0);
  EXPECT_GT(sum_b, 0.0);
}

TEST(IntegratorsBackend, CornellWithSpheresBvhAndEmbreeAgree) {
  const Scene scene = test::cornell_box({.spheres = true, .sphere_material = MaterialType::kGlass});
  TestRender settings;
  settings.width = settings.height = 32;
  settings.spp = 64;
  settings.max_depth = 5;
  expect_backends_agree(scene, "path", settings);
}

TEST(IntegratorsBackend, Cs184SpheresLambertianBvhAndEmbreeAgree) {
  PRISM_REQUIRE_CS184(path, "CBspheres_lambertian.dae");
  const Scene scene = load_scene(path);
  TestRender settings;
  settings.width = 40;
  settings.height = 30;
  settings.spp = 64;
  settings.max_depth = 4;
  expect_backends_agree(scene, "path", settings);
}

TEST(IntegratorsBackend, Cs184BunnyBvhAndEmbreeAgree) {
  PRISM_REQUIRE_CS184(path, "CBbunny.dae");
  const Scene scene = load_scene(path);
  TestRender settings;
  settings.width = 40;
  settings.height = 30;
  settings.spp = 32;
  settings.light_samples = 2;
  settings.max_depth = 3;
  expect_backends_agree(scene, "path", settings);
}

TEST(IntegratorsBackend, Cs184ScenesRenderWithoutNonFiniteSamples) {
  const std::vector<std::string> names = test::cs184_scene_names();
  if (names.empty()) GTEST_SKIP() << "../shared/scenes/cs184 absent";
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const Scene scene = load_scene(*test::cs184_scene(name));
    TestRender settings;
    settings.width = 16;
    settings.height = 12;
    settings.spp = 4;
    settings.max_depth = 4;
    // render_scene() fails the test on any NaN or infinite sample.
    const Image image = test::render_scene(scene, "path", settings);
    double sum = 0.0;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) sum += image.at(x, y, 1);
    }
    EXPECT_GT(sum, 0.0) << "a black image";
  }
}

}  // namespace
}  // namespace prism
