#pragma once

// A render split across the ranks of an MPI run (`mpirun -np N prism render ...`). The unit of
// work is one tile of the schedule with every sample of its range still to take (tile-major:
// adaptive sampling state stays with one rank, and each pixel's state crosses the network
// once). Rank 0 coordinates and renders: its main thread hands tiles out on request, in
// schedule order, to its own TileLanes and to the workers, and copies every tile that comes
// back into the film whole; a worker keeps one request in flight while it renders, so that it
// never waits for work. A tile that already has samples (a resumed render) travels with its
// pixels' states. The film only ever holds whole tiles (finished, or as they were when handed
// out), so a checkpoint can be written from it at any time without stopping the workers, and
// integer sums make the result the single-process film bit for bit. docs/PRODUCTION.md ("MPI")
// describes it for users.

#include <atomic>
#include <cstdint>
#include <functional>

#include "core/app/mpi_channel.h"
#include "core/app/progressive_render.h"
#include "core/film.h"
#include "core/progress.h"
#include "core/render_schedule.h"
#include "integrators/integrator.h"

namespace prism {

/// How rank 0 runs a distributed render.
struct DistributedOptions {
  int lanes = 1;  ///< rendering threads on rank 0
  /// Rank 0's stop signal: no tile is handed out once it is non-zero; the workers are told to
  /// stop and give back the tiles they have not started. A worker's own stop signal stops the
  /// whole render the same way.
  const std::atomic<int>* stop_signal = nullptr;
  /// Called with the film every checkpoint_interval_seconds (not after the last tile). May
  /// throw: the render then fails with that error.
  std::function<void(const Film&)> checkpoint;
  double checkpoint_interval_seconds = 60.0;
  ProgressReporter* progress = nullptr;  ///< advanced as tiles come back; may be null
};

/// What coordinate_render() did.
struct DistributedResult {
  ProgressiveResult run;         ///< end (kComplete or kSignal), passes complete, seconds
  int signal = 0;                ///< the stop signal when run.end is kSignal
  uint64_t bytes_exchanged = 0;  ///< message bytes rank 0 sent and received (all traffic)
};

/// Rank 0: renders the tiles of `schedule` not yet complete in `film` with the workers (ranks 1
/// to N-1, each in serve_render()) and returns when each has returned every tile it was given
/// and said it is done. A worker that dies leaves this waiting (its launcher ends the job).
DistributedResult coordinate_render(const TileRenderer& renderer, const RenderSchedule& schedule,
                                    Film& film, MpiChannel& channel,
                                    const DistributedOptions& options);

/// Rank 0, after writing the outputs: every worker exits with `exit_code`.
void finish_workers(MpiChannel& channel, int exit_code);

/// Ranks 1 to N-1: renders the tiles rank 0 hands out, with `lanes` threads, into films of
/// width x height, until rank 0 says the render is over; returns the exit code it sent.
/// `stop_signal` (this process's) stops it as DistributedOptions::stop_signal says.
int serve_render(const TileRenderer& renderer, const RenderSchedule& schedule, int width,
                 int height, MpiChannel& channel, int lanes, const std::atomic<int>* stop_signal);

}  // namespace prism
