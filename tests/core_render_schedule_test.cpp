// core/render_schedule.h: the units of a render (tiles x passes, pass-major) cover every sample
// of every pixel of the window exactly once, tiles are clipped to the window, passes split the
// sample range with a shorter last pass, and pass_of_sample() inverts pass().
#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "core/render_schedule.h"

namespace prism {
namespace {

struct Case {
  PixelRect window;
  SampleRange samples;
  uint32_t pass_samples;
  int tile_size;
};

/// Windows at the origin and inside an image, tile-aligned or not, one pixel wide, sample
/// ranges from 0 or from the middle, pass sizes dividing the range or not, larger than it.
const std::vector<Case> kCases = {
    {{{0, 0}, {64, 48}}, {0, 16}, 1, 16},  {{{0, 0}, {64, 48}}, {0, 16}, 16, 16},
    {{{0, 0}, {37, 21}}, {0, 10}, 3, 16},  {{{5, 7}, {43, 30}}, {4, 13}, 4, 16},
    {{{13, 2}, {14, 40}}, {0, 5}, 2, 8},   {{{3, 3}, {20, 4}}, {7, 8}, 1, 4},
    {{{0, 0}, {17, 17}}, {0, 9}, 100, 16}, {{{100, 50}, {131, 83}}, {2, 31}, 7, 10},
    {{{0, 0}, {1, 1}}, {0, 1}, 1, 16},
};

std::string describe(const Case& c) {
  return "window (" + std::to_string(c.window.begin.x) + ", " + std::to_string(c.window.begin.y) +
         ")-(" + std::to_string(c.window.end.x) + ", " + std::to_string(c.window.end.y) +
         ") samples [" + std::to_string(c.samples.first) + ", " + std::to_string(c.samples.last) +
         ") pass " + std::to_string(c.pass_samples) + " tile " + std::to_string(c.tile_size);
}

uint32_t ceil_div(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

TEST(CoreRenderSchedule, UnitsCoverEveryPixelSampleExactlyOnce) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(describe(c));
    const RenderSchedule schedule(c.window, c.samples, c.pass_samples, c.tile_size);
    // How many times each (pixel, sample) of the window is covered, from the units in order.
    const int w = c.window.width(), h = c.window.height();
    const uint32_t n = c.samples.count();
    std::vector<int> covered(size_t(w) * size_t(h) * n, 0);
    size_t outside = 0;
    for (size_t u = 0; u < schedule.unit_count(); ++u) {
      const Tile tile = schedule.tile(int(u % size_t(schedule.tile_count())));
      const SampleRange pass = schedule.pass(int(u / size_t(schedule.tile_count())));
      for (int y = tile.begin.y; y < tile.end.y; ++y) {
        for (int x = tile.begin.x; x < tile.end.x; ++x) {
          for (uint32_t s = pass.first; s < pass.last; ++s) {
            if (!c.window.contains(glm::ivec2(x, y)) || s < c.samples.first ||
                s >= c.samples.last) {
              ++outside;
              continue;
            }
            const size_t i =
                (size_t(y - c.window.begin.y) * size_t(w) + size_t(x - c.window.begin.x)) * n +
                (s - c.samples.first);
            ++covered[i];
          }
        }
      }
    }
    EXPECT_EQ(outside, 0u) << "units reach outside the window or the sample range";
    size_t wrong = 0;
    for (int v : covered) wrong += v != 1;
    EXPECT_EQ(wrong, 0u) << "(pixel, sample) pairs not covered exactly once";
  }
}

TEST(CoreRenderSchedule, TilesAreClippedToTheWindowInRowOrder) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(describe(c));
    const RenderSchedule schedule(c.window, c.samples, c.pass_samples, c.tile_size);
    const int tiles_x = (c.window.width() + c.tile_size - 1) / c.tile_size;
    const int tiles_y = (c.window.height() + c.tile_size - 1) / c.tile_size;
    ASSERT_EQ(schedule.tile_count(), tiles_x * tiles_y);
    for (int t = 0; t < schedule.tile_count(); ++t) {
      const Tile tile = schedule.tile(t);
      // Tile rows top to bottom, left to right in a row, each starting on the tile grid of the
      // window and clipped to it.
      const glm::ivec2 begin = c.window.begin + glm::ivec2(t % tiles_x, t / tiles_x) * c.tile_size;
      EXPECT_EQ(tile.begin, begin) << "tile " << t;
      EXPECT_EQ(tile.end, glm::min(begin + glm::ivec2(c.tile_size), c.window.end)) << "tile " << t;
      EXPECT_TRUE(c.window.contains(PixelRect{tile.begin, tile.end})) << "tile " << t;
      EXPECT_GT(tile.end.x, tile.begin.x) << "tile " << t;
      EXPECT_GT(tile.end.y, tile.begin.y) << "tile " << t;
    }
  }
}

TEST(CoreRenderSchedule, PassesSplitTheSampleRangeWithAShorterLastPass) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(describe(c));
    const RenderSchedule schedule(c.window, c.samples, c.pass_samples, c.tile_size);
    EXPECT_EQ(schedule.window(), c.window);
    EXPECT_EQ(schedule.samples(), c.samples);
    EXPECT_EQ(schedule.pass_samples(), c.pass_samples);
    ASSERT_EQ(schedule.pass_count(), int(ceil_div(c.samples.count(), c.pass_samples)));
    EXPECT_EQ(schedule.unit_count(), size_t(schedule.tile_count()) * size_t(schedule.pass_count()));
    uint32_t next = c.samples.first;
    for (int p = 0; p < schedule.pass_count(); ++p) {
      const SampleRange pass = schedule.pass(p);
      EXPECT_EQ(pass.first, next) << "pass " << p;
      const bool last = p + 1 == schedule.pass_count();
      if (last) {
        EXPECT_EQ(pass.last, c.samples.last);
        EXPECT_GE(pass.count(), 1u);
        EXPECT_LE(pass.count(), c.pass_samples);
      } else {
        EXPECT_EQ(pass.count(), c.pass_samples) << "pass " << p;
      }
      next = pass.last;
    }
    EXPECT_EQ(next, c.samples.last);
  }
}

TEST(CoreRenderSchedule, PassOfSampleIsThePassHoldingIt) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(describe(c));
    const RenderSchedule schedule(c.window, c.samples, c.pass_samples, c.tile_size);
    for (int p = 0; p < schedule.pass_count(); ++p) {
      const SampleRange pass = schedule.pass(p);
      for (uint32_t s = pass.first; s < pass.last; ++s) {
        EXPECT_EQ(schedule.pass_of_sample(s), p) << "sample " << s;
      }
    }
    // The end of the range and beyond: past the last pass; before the range: the first.
    EXPECT_EQ(schedule.pass_of_sample(c.samples.last), schedule.pass_count());
    EXPECT_EQ(schedule.pass_of_sample(c.samples.last + 1000), schedule.pass_count());
    if (c.samples.first > 0) {
      EXPECT_EQ(schedule.pass_of_sample(c.samples.first - 1), 0);
    }
  }
}

TEST(CoreRenderSchedule, AWorkedExample) {
  // 40 x 20 pixels at 12 samples in passes of 5: 3 x 2 tiles (the last column 8 wide, the
  // bottom row 4 high) and passes [0, 5), [5, 10), [10, 12): 18 units.
  const RenderSchedule schedule({{0, 0}, {40, 20}}, {0, 12}, 5);
  EXPECT_EQ(schedule.tile_count(), 3 * 2);
  EXPECT_EQ(schedule.pass_count(), 3);
  EXPECT_EQ(schedule.pass(0), (SampleRange{0, 5}));
  EXPECT_EQ(schedule.pass(1), (SampleRange{5, 10}));
  EXPECT_EQ(schedule.pass(2), (SampleRange{10, 12}));
  EXPECT_EQ(schedule.unit_count(), 18u);
  EXPECT_EQ(schedule.tile(4).begin, glm::ivec2(16, 16));
  EXPECT_EQ(schedule.tile(5).begin, glm::ivec2(32, 16));
  EXPECT_EQ(schedule.tile(5).end, glm::ivec2(40, 20));
  EXPECT_EQ(schedule.tile(2).end, glm::ivec2(40, 16));
}

TEST(CoreRenderSchedule, RejectsWhatCannotBeScheduled) {
  EXPECT_THROW(RenderSchedule({{0, 0}, {0, 4}}, {0, 4}, 1), Error);     // empty window
  EXPECT_THROW(RenderSchedule({{0, 0}, {4, 4}}, {0, 4}, 0), Error);     // no samples per pass
  EXPECT_THROW(RenderSchedule({{0, 0}, {4, 4}}, {0, 4}, 1, 0), Error);  // no tile size
  EXPECT_THROW(RenderSchedule({{0, 0}, {4, 4}}, {5, 4}, 1), Error);     // last before first
  const RenderSchedule schedule({{0, 0}, {4, 4}}, {0, 4}, 1);
  EXPECT_THROW(schedule.tile(1), Error);
  EXPECT_THROW(schedule.tile(-1), Error);
  EXPECT_THROW(schedule.pass(4), Error);
}

TEST(CoreRenderSchedule, AnEmptySampleRangeHasNoPasses) {
  const RenderSchedule schedule({{0, 0}, {8, 8}}, {3, 3}, 2);
  EXPECT_EQ(schedule.pass_count(), 0);
  EXPECT_EQ(schedule.unit_count(), 0u);
  EXPECT_EQ(schedule.pass_of_sample(3), 0);
}

}  // namespace
}  // namespace prism
