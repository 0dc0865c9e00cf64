// The oneTBB implementation of core/parallel.h (the default; -DPRISM_PARALLEL=tbb).
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include "core/parallel.h"

#ifdef PRISM_PARALLEL_THREADS
#error "core/parallel_tbb.cpp is the oneTBB implementation: build core/parallel_threads.cpp"
#endif

namespace prism {

void parallel_for_tiles(int width, int height, int tile_size,
                        const std::function<void(const Tile&)>& body) {
  const int tiles_x = (width + tile_size - 1) / tile_size;
  const int tiles_y = (height + tile_size - 1) / tile_size;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, tiles_x * tiles_y, 1), [&](const tbb::blocked_range<int>& range) {
        for (int i = range.begin(); i != range.end(); ++i) {
          const glm::ivec2 begin{(i % tiles_x) * tile_size, (i / tiles_x) * tile_size};
          const glm::ivec2 end = glm::min(begin + tile_size, glm::ivec2(width, height));
          body(Tile{begin, end});
        }
      });
}

void parallel_for_indices(size_t count, const std::function<void(size_t)>& body) {
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, count, 1),
      [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) body(i);
      },
      tbb::simple_partitioner());
}

void parallel_for_range(size_t count, const std::function<void(size_t, size_t)>& body,
                        size_t grain) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, grain),
                    [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
}

void parallel_invoke(const std::function<void()>& a, const std::function<void()>& b) {
  tbb::parallel_invoke(a, b);
}

void run_beside(std::function<void()> body) { tbb::this_task_arena::enqueue(std::move(body)); }

struct ThreadLimit::State {
  explicit State(int threads) : control(tbb::global_control::max_allowed_parallelism, threads) {}
  tbb::global_control control;
};

ThreadLimit::ThreadLimit(int threads) {
  const int hardware = tbb::info::default_concurrency();
  threads_ = threads > 0 ? threads : hardware;
  state_ = std::make_unique<State>(threads_);
}

ThreadLimit::~ThreadLimit() = default;

struct ThreadArena::State {
  explicit State(int threads) : arena(threads) {}
  tbb::task_arena arena;
};

ThreadArena::ThreadArena(int threads)
    : state_(std::make_unique<State>(threads)), threads_(threads) {}

ThreadArena::~ThreadArena() = default;

void ThreadArena::execute(const std::function<void()>& body) { state_->arena.execute(body); }

}  // namespace prism
