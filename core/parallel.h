#pragma once

#include <cstddef>
#include <functional>
#include <memory>

#include "core/math.h"

// Every parallel loop of prism goes through this header (and core/parallel_reduce.h), never
// through a threading library directly. Two implementations, chosen when configuring:
// - oneTBB (the default);
// - plain std::thread (-DPRISM_PARALLEL=threads, which defines PRISM_PARALLEL_THREADS): what
//   ThreadSanitizer builds use, since Debian's oneTBB is not instrumented and TSan cannot see
//   its synchronisation (docs/RELIABILITY.md).
// Both give the same results: the bodies write disjoint data, and reductions are exact.

namespace prism {

/// A rectangle of pixels [begin, end).
struct Tile {
  glm::ivec2 begin;
  glm::ivec2 end;
};

/// Calls body(tile) for every tile of a width x height image, in parallel.
/// Each pixel belongs to exactly one tile; tiles may run in any order on any thread.
void parallel_for_tiles(int width, int height, int tile_size,
                        const std::function<void(const Tile&)>& body);

/// Calls body(i) for every i in [0, count) in parallel, one index per task (for items of work
/// large enough to balance one by one, such as image tiles).
void parallel_for_indices(size_t count, const std::function<void(size_t)>& body);

/// Calls body(begin, end) over disjoint chunks covering [0, count), in parallel. A chunk holds
/// at most about `grain` indices under oneTBB (its blocked_range grain: chunks of grain/2 to
/// grain when count is large); 1 lets the library choose. The std::thread implementation may
/// make chunks larger than grain, never smaller.
void parallel_for_range(size_t count, const std::function<void(size_t, size_t)>& body,
                        size_t grain = 1);

/// Runs a() and b(), possibly at the same time on two threads, and returns when both have
/// returned. Nested calls (recursive builders) are bounded: under std::thread, b runs on the
/// calling thread and a on a new thread only while the thread limit leaves room, inline
/// otherwise. An exception from either is rethrown here once both are done.
void parallel_invoke(const std::function<void()>& a, const std::function<void()>& b);

/// Runs body() once beside the caller and returns at once. Under oneTBB body is a task of the
/// current arena that a worker takes when it is free: loops started meanwhile run with one
/// thread fewer until body returns, never with more threads than the limit (ThreadLimit). The
/// std::thread implementation runs body on the calling thread before returning. body must not
/// throw; the caller learns that it has run by its own means (and must not end the process
/// while it runs).
void run_beside(std::function<void()> body);

/// Limits the threads of every parallel loop (and of oneTBB, which Embree uses) to `threads`
/// while alive; threads <= 0 means all hardware threads. When several are alive the smallest
/// limit holds (oneTBB's global_control rule).
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;
  /// The number of threads in effect.
  int threads() const { return threads_; }

 private:
  struct State;
  std::unique_ptr<State> state_;
  int threads_;
};

/// A fixed number of threads for the parallel loops started inside execute(), whatever the
/// machine: `prism bench` measures each thread count in its own arena. Under oneTBB this is a
/// tbb::task_arena, whose workers stay warm between calls.
class ThreadArena {
 public:
  /// threads >= 1.
  explicit ThreadArena(int threads);
  ~ThreadArena();
  ThreadArena(const ThreadArena&) = delete;
  ThreadArena& operator=(const ThreadArena&) = delete;

  int threads() const { return threads_; }
  /// Runs body() on the calling thread; the parallel loops it starts use at most threads()
  /// threads (the calling thread included).
  void execute(const std::function<void()>& body);

 private:
  struct State;
  std::unique_ptr<State> state_;
  int threads_;
};

}  // namespace prism
