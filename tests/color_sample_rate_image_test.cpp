// The adaptive sampler's "sample rate" picture (color/sample_rate_image): the colour map from
// few samples (blue) to many (red), and nothing for an image without sample counts. The file an
// adaptive render writes is tested end to end in app_render_test.cpp.

#include <gtest/gtest.h>

#include "color/sample_rate_image.h"
#include "core/image.h"

namespace prism {
namespace {

TEST(ColorSampleRateImage, MapsFewSamplesToBlueAndManyToRed) {
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

TEST(ColorSampleRateImage, NothingWithoutASampleCountChannel) {
  Image beauty;
  beauty.width = beauty.height = 1;
  beauty.channel_names = {"R", "G", "B"};
  beauty.pixels = {1, 1, 1};
  EXPECT_FALSE(make_sample_rate_image(beauty).has_value());
}

}  // namespace
}  // namespace prism
