#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "core/film.h"
#include "core/progress.h"
#include "core/render_schedule.h"
#include "integrators/integrator.h"

namespace prism {

/// Why a render ended.
enum class RenderEnd {
  kComplete,   ///< every pass of the schedule is in the film
  kTimeLimit,  ///< --time-limit: stopped at a pass boundary
  kSignal,     ///< SIGINT or SIGTERM: stopped after the tiles in flight
};

/// How render_progressively() runs and when it stops.
struct ProgressiveOptions {
  /// Seconds of rendering this run may spend (0: no limit). A pass is never cut: the run stops
  /// before a pass that, at the mean pass time so far, would end past the limit, and finishes
  /// the pass it is in when the limit passes. At least one pass runs.
  double time_limit_seconds = 0.0;
  /// Set (to the signal number) by the signal handler: no tile starts once it is non-zero.
  const std::atomic<int>* stop_signal = nullptr;
  /// Called between passes, with every thread idle and the film consistent, once
  /// checkpoint_interval_seconds have passed since the start or the last call (not after the
  /// last pass). May throw; the render then stops with that error.
  std::function<void(const Film&)> checkpoint;
  double checkpoint_interval_seconds = 60.0;
  /// Advanced by the samples (pixels x samples of a unit) rendered; may be null.
  ProgressReporter* progress = nullptr;
};

/// What render_progressively() did.
struct ProgressiveResult {
  RenderEnd end = RenderEnd::kComplete;
  int passes_complete = 0;  ///< passes every tile has finished (the film's, not this run's)
  double seconds = 0.0;     ///< wall time of this run
};

/// The samples of `schedule` not yet in `film` (per the pixels' progress), units in schedule
/// order: pass by pass, the tiles of a pass in parallel. Stops early as `options` say; the film
/// is then consistent at tile granularity, so another call continues where this one stopped and
/// ends with the same bits as an uninterrupted render.
ProgressiveResult render_progressively(const TileRenderer& renderer, const RenderSchedule& schedule,
                                       Film& film, const ProgressiveOptions& options);

/// Passes every tile of `schedule` has finished in `film` (from the pixels' progress).
int passes_complete(const RenderSchedule& schedule, const Film& film);

/// Samples (pixels x samples) of `schedule` still to take in `film`, for progress totals.
uint64_t samples_remaining(const RenderSchedule& schedule, const Film& film);

}  // namespace prism
