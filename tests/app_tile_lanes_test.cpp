// core/app/tile_lanes.h: tiles rendered on threads of their own, each in a film of its own.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/app/tile_lanes.h"
#include "core/app/tile_messages.h"

namespace prism {
namespace {

/// Adds sample s of pixel (x, y) as the value x + y + s; waits for `gate` (when given) first.
class FakeRenderer : public TileRenderer {
 public:
  explicit FakeRenderer(const std::atomic<bool>* gate = nullptr) : gate_(gate) {}
  void render_tile(const Tile& tile, SampleRange range, Film& film) const override {
    ++started;
    while (gate_ && !gate_->load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (tile.begin.x < 0) throw std::runtime_error("bad tile");
    for (int y = tile.begin.y; y < tile.end.y; ++y) {
      for (int x = tile.begin.x; x < tile.end.x; ++x) {
        FilmPixel& state = film.pixel({x, y});
        for (uint32_t s = std::max(range.first, state.progress); s < range.last; ++s) {
          film.add_sample({x, y}, Rgb(float(x + y + int(s))));
        }
        state.progress = std::max(state.progress, range.last);
      }
    }
  }
  mutable std::atomic<int> started{0};

 private:
  const std::atomic<bool>* gate_;
};

TileJob job_for(const RenderSchedule& schedule, int index) {
  const Tile tile = schedule.tile(index);
  return TileJob{index, tile, Film(40, 30, PixelRect{tile.begin, tile.end})};
}

/// Takes finished jobs until `count` came back.
std::vector<TileJob> take(TileLanes& lanes, size_t count) {
  std::vector<TileJob> jobs;
  while (jobs.size() < count) {
    for (TileJob& job : lanes.take_finished()) jobs.push_back(std::move(job));
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return jobs;
}

TEST(AppTileLanes, TilesComeBackAsIfRenderedIntoOneFilm) {
  const RenderSchedule schedule(PixelRect{{0, 0}, {40, 30}}, SampleRange{0, 5}, 1);
  const FakeRenderer renderer;
  Film direct(40, 30);
  for (int t = 0; t < schedule.tile_count(); ++t) {
    renderer.render_tile(schedule.tile(t), schedule.samples(), direct);
  }
  TileLanes lanes(renderer, schedule.samples(), 3);
  EXPECT_EQ(lanes.lanes(), 3);
  for (int t = 0; t < schedule.tile_count(); ++t) lanes.push(job_for(schedule, t));
  Film gathered(40, 30);
  for (const TileJob& job : take(lanes, size_t(schedule.tile_count()))) {
    EXPECT_TRUE(job.rendered);
    set_tile_pixels(gathered, job.tile, tile_pixels(job.film, job.tile));
  }
  EXPECT_EQ(lanes.load(), 0u);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      EXPECT_EQ(std::memcmp(&gathered.pixel({x, y}), &direct.pixel({x, y}), sizeof(FilmPixel)), 0);
    }
  }
}

TEST(AppTileLanes, HaltGivesBackTheJobsThatHadNotStarted) {
  const RenderSchedule schedule(PixelRect{{0, 0}, {40, 30}}, SampleRange{0, 2}, 1);
  std::atomic<bool> gate{false};
  const FakeRenderer renderer(&gate);
  TileLanes lanes(renderer, schedule.samples(), 1);
  for (int t = 0; t < 3; ++t) lanes.push(job_for(schedule, t));
  while (renderer.started.load() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  lanes.halt();
  lanes.push(job_for(schedule, 3));  // after a halt: given back at once
  gate = true;
  int rendered = 0;
  for (const TileJob& job : take(lanes, 4)) rendered += job.rendered ? 1 : 0;
  EXPECT_EQ(rendered, 1);
  EXPECT_EQ(renderer.started.load(), 1);
}

TEST(AppTileLanes, ARenderErrorReachesTheOwner) {
  const RenderSchedule schedule(PixelRect{{0, 0}, {40, 30}}, SampleRange{0, 2}, 1);
  const FakeRenderer renderer;
  TileLanes lanes(renderer, schedule.samples(), 2);
  lanes.push(TileJob{0, Tile{{-1, 0}, {0, 1}}, Film(40, 30)});
  EXPECT_THROW(
      for (;;) {
        lanes.take_finished();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      },
      std::runtime_error);
}

}  // namespace
}  // namespace prism
