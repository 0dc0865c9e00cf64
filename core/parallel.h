#pragma once

#include <functional>
#include <memory>

#include <tbb/global_control.h>

#include "core/math.h"

namespace prism {

/// A rectangle of pixels [begin, end).
struct Tile {
  glm::ivec2 begin;
  glm::ivec2 end;
};

/// Calls body(tile) for every tile of a width x height image, in parallel on oneTBB.
/// Each pixel belongs to exactly one tile; tiles may run in any order on any thread.
void parallel_for_tiles(int width, int height, int tile_size,
                        const std::function<void(const Tile&)>& body);

/// Calls body(i) for every i in [0, count) in parallel, one index per task (for items of work
/// large enough to balance one by one, such as image tiles).
void parallel_for_indices(size_t count, const std::function<void(size_t)>& body);

/// Calls body(begin, end) over chunks of [0, count) in parallel.
void parallel_for_range(size_t count, const std::function<void(size_t, size_t)>& body);

/// Limits oneTBB (and so Embree, which uses it) to `threads` worker threads while alive;
/// threads <= 0 means all hardware threads.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;
  /// The number of threads in effect.
  int threads() const { return threads_; }

 private:
  std::unique_ptr<tbb::global_control> control_;
  int threads_;
};

}  // namespace prism
