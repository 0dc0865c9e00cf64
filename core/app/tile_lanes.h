#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "core/film.h"
#include "core/render_schedule.h"
#include "integrators/integrator.h"

namespace prism {

/// One tile of a schedule to render with all the samples of the schedule's range, in a film of
/// its own whose window is the tile (holding the tile's earlier state when resumed).
struct TileJob {
  int index = 0;
  Tile tile;
  Film film;
  bool rendered = false;  ///< set when the lanes rendered it; false for a job given back unstarted
};

/// Renders tiles on threads of its own while the thread that owns it (under MPI the main
/// thread, the only one that talks to other ranks) hands out and collects them. Jobs start in
/// the order they are pushed. Each job's film is its own, so the renders never touch a shared
/// film: the owner copies finished tiles where they belong. All methods are for the owner's
/// thread.
class TileLanes {
 public:
  /// `lanes` threads (at least 1) rendering with `renderer` the samples `samples` of each tile.
  TileLanes(const TileRenderer& renderer, SampleRange samples, int lanes);
  /// Halts, and waits for the tiles being rendered.
  ~TileLanes();
  TileLanes(const TileLanes&) = delete;
  TileLanes& operator=(const TileLanes&) = delete;

  int lanes() const { return int(threads_.size()); }
  void push(TileJob job);
  /// The jobs finished since the last call, rendered, and after halt() the jobs that had not
  /// started, unrendered. Rethrows the first exception a lane's rendering threw.
  std::vector<TileJob> take_finished();
  /// No job starts any more; those being rendered finish.
  void halt();
  /// Jobs pushed and not yet taken back by take_finished().
  size_t load() const;

 private:
  void run_lane();

  const TileRenderer& renderer_;
  SampleRange samples_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<TileJob> queue_;
  std::vector<TileJob> finished_;
  size_t load_ = 0;
  bool halted_ = false;
  bool closing_ = false;
  std::exception_ptr error_;
  std::vector<std::thread> threads_;
};

}  // namespace prism
