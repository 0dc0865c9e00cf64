// The adaptive sampler's "sample rate" picture: the colour map, and the file an adaptive render
// writes beside its output.

#include <gtest/gtest.h>

#include "color/image_output.h"
#include "color/sample_rate_image.h"
#include "scenes/scene_loader.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

TEST(AppSampleRate, MapsFewSamplesToBlueAndManyToRed) {
  Image counts;
  counts.width = 3;
  counts.height = 1;
  counts.channel_names = {"R", "G", "B", "sampleCount.Y"};
  counts.pixels = {0, 0, 0, 8, 0, 0, 0, 32, 0, 0, 0, 64};
  const auto rate = make_sample_rate_image(counts);
  ASSERT_TRUE(rate.has_value());
  ASSERT_EQ(rate->channels(), 3);
  EXPECT_GT(rate->at(0, 0, 2), rate->at(0, 0, 0));  // 1/8 of the maximum: blue
  EXPECT_GT(rate->at(1, 0, 1), 0.9f);               // half: green
  EXPECT_GT(rate->at(2, 0, 0), rate->at(2, 0, 1));  // the maximum: (dark) red
  EXPECT_FLOAT_EQ(rate->at(2, 0, 2), 0.0f);
}

TEST(AppSampleRate, NothingWithoutASampleCountChannel) {
  Image beauty;
  beauty.width = beauty.height = 1;
  beauty.channel_names = {"R", "G", "B"};
  beauty.pixels = {1, 1, 1};
  EXPECT_FALSE(make_sample_rate_image(beauty).has_value());
}

TEST(AppSampleRate, AdaptiveRenderWritesTheRatePictureBesideItsOutput) {
  const auto dir = test::make_temp_dir("sample_rate");
  const auto scene = (bundled_scene_dir() / "cornell_spheres.json").string();
  const auto result =
      test::run_prism({"render", scene, "--resolution", "24", "18", "--spp", "64", "-a", "8",
                       "0.05", "--quiet", "--output", (dir / "a.exr").string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto rate = read_image_file(dir / "a_rate.png");
  EXPECT_EQ(rate.image.width, 24);
  EXPECT_EQ(rate.image.height, 18);
  const auto exr = read_image_file(dir / "a.exr");
  double total = 0;
  const auto& names = exr.image.channel_names;
  const int channel = int(std::find(names.begin(), names.end(), "sampleCount.Y") - names.begin());
  ASSERT_LT(channel, exr.image.channels());
  for (int y = 0; y < 18; ++y) {
    for (int x = 0; x < 24; ++x) total += exr.image.at(x, y, channel);
  }
  EXPECT_LT(total, 24.0 * 18 * 64);  // some pixels converged before 64 samples
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace prism
