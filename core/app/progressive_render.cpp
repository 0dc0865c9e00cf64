#include "core/app/progressive_render.h"

#include <algorithm>
#include <chrono>

#include "core/parallel.h"
#include "core/timing.h"

namespace prism {
namespace {

using Clock = std::chrono::steady_clock;

/// How far tile `t` of the schedule got: every pixel of a tile shares its progress.
uint32_t tile_progress(const RenderSchedule& schedule, const Film& film, int t) {
  return film.pixel(schedule.tile(t).begin).progress;
}

bool signalled(const ProgressiveOptions& options) {
  return options.stop_signal != nullptr && options.stop_signal->load() != 0;
}

}  // namespace

int passes_complete(const RenderSchedule& schedule, const Film& film) {
  uint32_t least = schedule.samples().last;
  for (int t = 0; t < schedule.tile_count(); ++t) {
    least = std::min(least, tile_progress(schedule, film, t));
  }
  // A tile that reached the end of a pass has finished it.
  if (least >= schedule.samples().last) return schedule.pass_count();
  if (least <= schedule.samples().first) return 0;
  return schedule.pass_of_sample(least);
}

uint64_t samples_remaining(const RenderSchedule& schedule, const Film& film) {
  uint64_t remaining = 0;
  for (int t = 0; t < schedule.tile_count(); ++t) {
    const Tile tile = schedule.tile(t);
    const uint32_t done = std::max(tile_progress(schedule, film, t), schedule.samples().first);
    const uint64_t pixels = uint64_t(tile.end.x - tile.begin.x) * (tile.end.y - tile.begin.y);
    remaining += pixels * (schedule.samples().last - std::min(done, schedule.samples().last));
  }
  return remaining;
}

ProgressiveResult render_progressively(const TileRenderer& renderer, const RenderSchedule& schedule,
                                       Film& film, const ProgressiveOptions& options) {
  const Clock::time_point start = Clock::now();
  Clock::time_point last_checkpoint = start;
  ProgressiveResult result;
  int passes_run = 0;
  for (int pass = passes_complete(schedule, film); pass < schedule.pass_count(); ++pass) {
    if (signalled(options)) {
      result.end = RenderEnd::kSignal;
      break;
    }
    const double elapsed = seconds_since(start);
    if (options.time_limit_seconds > 0.0 && passes_run > 0 &&
        elapsed + elapsed / passes_run > options.time_limit_seconds) {
      result.end = RenderEnd::kTimeLimit;
      break;
    }
    const SampleRange range = schedule.pass(pass);
    parallel_for_indices(size_t(schedule.tile_count()), [&](size_t t) {
      if (signalled(options)) return;
      if (tile_progress(schedule, film, int(t)) >= range.last) return;  // resumed past it
      const Tile tile = schedule.tile(int(t));
      renderer.render_tile(tile, range, film);
      if (options.progress) {
        options.progress->update(uint64_t(tile.end.x - tile.begin.x) * (tile.end.y - tile.begin.y) *
                                 range.count());
      }
    });
    if (signalled(options)) {
      result.end = RenderEnd::kSignal;
      break;
    }
    ++passes_run;
    const bool last = pass + 1 == schedule.pass_count();
    if (options.checkpoint && !last &&
        seconds_since(last_checkpoint) >= options.checkpoint_interval_seconds) {
      options.checkpoint(film);
      last_checkpoint = Clock::now();
    }
  }
  result.passes_complete = passes_complete(schedule, film);
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace prism
