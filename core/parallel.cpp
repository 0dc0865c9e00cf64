#include "core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

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

void parallel_for_range(size_t count, const std::function<void(size_t, size_t)>& body) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count),
                    [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
}

ThreadLimit::ThreadLimit(int threads) {
  const int hardware = tbb::info::default_concurrency();
  threads_ = threads > 0 ? threads : hardware;
  control_ =
      std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads_);
}

ThreadLimit::~ThreadLimit() = default;

}  // namespace prism
