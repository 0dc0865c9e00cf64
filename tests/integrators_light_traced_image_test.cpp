// LightTracedImage (integrators/light_traced_image.h): which sample indices it traces and keeps,
// and that an index traced again gives the same image.
#include <gtest/gtest.h>

#include <map>
#include <mutex>
#include <vector>

#include "integrators/light_traced_image.h"

namespace prism {
namespace {

constexpr int kWidth = 8;
constexpr int kHeight = 4;
constexpr uint32_t kPaths = 300;  // two chunks of LightTracedImage::kChunkPaths

/// A tracer whose splats are a function of (sample index, path), counting the paths it traced
/// per sample index.
struct CountingTracer {
  std::mutex mutex;
  std::map<uint32_t, uint32_t> paths_traced;

  LightTracedImage::TraceFunction function() {
    return [this](uint32_t sample, uint32_t first, uint32_t last, std::vector<Splat>& splats,
                  std::vector<CausticVertex>&) {
      for (uint32_t path = first; path < last; ++path) {
        splats.push_back(Splat{.pixel = (sample * 7 + path) % uint32_t(kWidth * kHeight),
                               .path = path,
                               .radiance = Rgb(float(sample + 1), float(path % 5), 0.25f)});
      }
      const std::lock_guard<std::mutex> lock(mutex);
      paths_traced[sample] += last - first;
    };
  }
  uint32_t times_traced(uint32_t sample) {
    const std::lock_guard<std::mutex> lock(mutex);
    return paths_traced[sample] / kPaths;
  }
};

std::vector<Rgb> pixels_of(const LightTracedSample& image) {
  std::vector<Rgb> pixels;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) pixels.push_back(image.at({x, y}));
  }
  return pixels;
}

TEST(IntegratorsLightTracedImage, TracesEachIndexOnceWhileCallersUseThemAllAtOnce) {
  // A tile handed every sample of its pixels (MPI's schedule) uses all of them at once.
  CountingTracer tracer;
  const LightTracedImage images(tracer.function(), kPaths, kWidth, kHeight);
  for (int tile = 0; tile < 3; ++tile) {
    for (uint32_t s = 0; s < 4; ++s) images.sample(s, 4);
  }
  for (uint32_t s = 0; s < 4; ++s) EXPECT_EQ(tracer.times_traced(s), 1u) << s;
}

TEST(IntegratorsLightTracedImage, KeepsOnlyWhatCallersUseAtOnceAndRetracesTheSameBits) {
  // One sample per pass: a pass's image is dropped once the next pass asks for its own.
  CountingTracer tracer;
  const LightTracedImage images(tracer.function(), kPaths, kWidth, kHeight);
  const std::vector<Rgb> first = pixels_of(*images.sample(0, 1));
  images.sample(0, 1);
  EXPECT_EQ(tracer.times_traced(0), 1u);  // still cached within its pass
  images.sample(1, 1);
  const std::vector<Rgb> again = pixels_of(*images.sample(0, 1));
  EXPECT_EQ(tracer.times_traced(0), 2u);
  EXPECT_EQ(tracer.times_traced(1), 1u);
  EXPECT_EQ(first, again);
  // Pixel 3 sums the splats of sample 0's paths 3, 35, 67, ...
  Rgb expected(0.0f);
  for (uint32_t path = 3; path < kPaths; path += kWidth * kHeight) {
    expected += Rgb(1.0f, float(path % 5), 0.25f);
  }
  EXPECT_EQ(first[3], expected);
}

TEST(IntegratorsLightTracedImage, TheLargestUseAtOnceSoFarHolds) {
  CountingTracer tracer;
  const LightTracedImage images(tracer.function(), kPaths, kWidth, kHeight);
  images.sample(0, 2);
  images.sample(1, 1);
  images.sample(0, 1);  // two are kept: 0 is still there
  EXPECT_EQ(tracer.times_traced(0), 1u);
  images.sample(2, 1);  // the oldest traced, 0, makes room
  images.sample(1, 1);
  EXPECT_EQ(tracer.times_traced(1), 1u);
  images.sample(0, 1);
  EXPECT_EQ(tracer.times_traced(0), 2u);
}

TEST(IntegratorsLightTracedImage, LookupsAlongARowAgreeWithLookupsOfOnePixel) {
  // A sparse image with empty rows, a full row and scattered pixels.
  std::vector<Splat> splats;
  uint32_t path = 0;
  for (uint32_t pixel : {0u, 3u, 4u, 7u, 17u, 18u, 19u, 20u, 21u, 22u, 23u, 30u}) {
    splats.push_back({.pixel = pixel, .path = path++, .radiance = Rgb(float(pixel) + 1.0f)});
  }
  const LightTracedSample image(splats, {}, kWidth, kHeight, path);
  // Left to right along each row (the tile loop's order), from any first column.
  for (int first_x = 0; first_x < kWidth; ++first_x) {
    LightTracedSample::RowPosition position;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = first_x; x < kWidth; ++x) {
        EXPECT_EQ(image.at_in_row({x, y}, position), image.at({x, y})) << x << " " << y;
      }
    }
  }
  // Any other order too: a pixel left of the previous one is searched for again.
  LightTracedSample::RowPosition position;
  for (const glm::ivec2 pixel : {glm::ivec2{7, 0}, glm::ivec2{3, 0}, glm::ivec2{4, 0},
                                 glm::ivec2{1, 2}, glm::ivec2{6, 3}, glm::ivec2{0, 0}}) {
    EXPECT_EQ(image.at_in_row(pixel, position), image.at(pixel)) << pixel.x << " " << pixel.y;
  }
  EXPECT_EQ(image.at({7, 0}), Rgb(8.0f));
  EXPECT_EQ(image.at({5, 0}), Rgb(0.0f));
}

TEST(IntegratorsLightTracedImage, ARunOfARowIsEmptyExactlyWhenNoPixelOfItReceivedAnything) {
  // Rows 0 and 2 with scattered pixels, row 1 empty, row 3 full but for its ends.
  std::vector<Splat> splats;
  uint32_t path = 0;
  for (uint32_t pixel : {0u, 3u, 4u, 7u, 18u, 22u, 25u, 26u, 27u, 28u, 29u, 30u}) {
    splats.push_back({.pixel = pixel, .path = path++, .radiance = Rgb(1.0f)});
  }
  const LightTracedSample image(splats, {}, kWidth, kHeight, path);
  // Every run [x0, x1) of every row against a look at each of its pixels.
  for (int y = 0; y < kHeight; ++y) {
    for (int x0 = 0; x0 < kWidth; ++x0) {
      for (int x1 = x0 + 1; x1 <= kWidth; ++x1) {
        bool empty = true;
        for (int x = x0; x < x1; ++x) empty = empty && image.at({x, y}) == Rgb(0.0f);
        EXPECT_EQ(image.row_is_empty(y, x0, x1), empty) << y << ": " << x0 << " " << x1;
      }
    }
  }
  EXPECT_TRUE(image.row_is_empty(1, 0, kWidth));
  EXPECT_FALSE(image.row_is_empty(3, 0, kWidth));
  EXPECT_TRUE(image.row_is_empty(0, 5, 7));
  // An image without splats.
  const LightTracedSample nothing({}, {}, kWidth, kHeight, 1);
  for (int y = 0; y < kHeight; ++y) EXPECT_TRUE(nothing.row_is_empty(y, 0, kWidth)) << y;
}

}  // namespace
}  // namespace prism
