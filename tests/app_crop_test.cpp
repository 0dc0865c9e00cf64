// --crop end to end (`prism render`): the EXR holds the crop as its data window inside the full
// image's display window, and its pixels are the full render's, bit for bit in every channel,
// whatever the crop's place (on or off the tile grid, at the image's edges, one pixel), the
// pass size and the thread count; on a bundled scene and a CS184 scene.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "color/image_output.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/image_compare.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSpheres = fs::path(PRISM_SOURCE_DIR) / "scenes" / "data" / "cornell_spheres.json";

/// Renders `scene` whole and cropped to each of `crops` (X0 Y0 X1 Y1, with `crop_args` added)
/// and expects every crop to be the full render's pixels, placed where they belong.
void expect_crops_are_the_full_renders_pixels(
    const fs::path& scene, const std::vector<std::string>& args,
    const std::vector<std::pair<std::array<int, 4>, std::vector<std::string>>>& crops) {
  TestDirs dirs("crop");
  const Image full = render_small_float_exr(scene, dirs.out / "full.exr", args).image;
  ASSERT_EQ(full.width, 64);
  ASSERT_EQ(full.height, 48);
  for (const auto& [crop, crop_args] : crops) {
    const auto [x0, y0, x1, y1] = crop;
    const std::string name = std::to_string(x0) + " " + std::to_string(y0) + " " +
                             std::to_string(x1) + " " + std::to_string(y1);
    SCOPED_TRACE("--crop " + name);
    std::vector<std::string> all = args;
    all.push_back("--crop");
    for (int v : crop) all.push_back(std::to_string(v));
    all.insert(all.end(), crop_args.begin(), crop_args.end());
    const ImageFileContents file = render_small_float_exr(
        scene, dirs.out / ("crop_" + std::to_string(x0) + "_" + std::to_string(y0) + ".exr"), all);
    EXPECT_EQ(file.attribute("prism:crop"), name);
    // The data window at the crop, inside the full display window.
    EXPECT_EQ(file.image.x, x0);
    EXPECT_EQ(file.image.y, y0);
    EXPECT_EQ(file.image.width, x1 - x0);
    EXPECT_EQ(file.image.height, y1 - y0);
    EXPECT_EQ(file.image.full_width, 64);
    EXPECT_EQ(file.image.full_height, 48);
    EXPECT_TRUE(same_bits_in(file.image, full));
  }
}

TEST(AppCrop, BundledSceneCropsAreTheFullRendersPixels) {
  expect_crops_are_the_full_renders_pixels(
      kSpheres, {"-s", "8"},
      {
          {{13, 7, 45, 38}, {}},                                   // off the tile grid
          {{16, 16, 32, 32}, {"-t", "1"}},                         // one tile of the grid
          {{0, 0, 64, 1}, {"--pass-samples", "3"}},                // the top row
          {{48, 30, 64, 48}, {"--pass-samples", "8"}},             // the bottom-right corner
          {{31, 23, 32, 24}, {"-t", "1", "--pass-samples", "1"}},  // one pixel
      });
}

TEST(AppCrop, Cs184SceneCropsAreTheFullRendersPixels) {
  PRISM_REQUIRE_CS184(scene, "CBspheres_lambertian.dae");
  expect_crops_are_the_full_renders_pixels(scene, {"-s", "8", "-m", "3"},
                                           {
                                               {{5, 3, 41, 29}, {"-t", "1"}},
                                               {{40, 20, 64, 48}, {"--pass-samples", "3"}},
                                           });
}

TEST(AppCrop, AdaptiveSamplingCropsAreTheFullRendersPixels) {
  // Adaptive sampling decides per pixel from that pixel's samples: a crop stops the same pixels
  // after the same samples.
  expect_crops_are_the_full_renders_pixels(kSpheres, {"-s", "32", "-a", "4", "0.05"},
                                           {{{13, 7, 45, 38}, {"--pass-samples", "3"}}});
}

}  // namespace
}  // namespace prism::test
