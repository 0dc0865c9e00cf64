#pragma once

// parallel_reduce, apart from core/parallel.h because under oneTBB it is a template over
// tbb::parallel_reduce, whose header is heavy: only the files that reduce include it.

#include <algorithm>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "core/parallel.h"

#ifndef PRISM_PARALLEL_THREADS
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#endif

namespace prism {

#ifdef PRISM_PARALLEL_THREADS
namespace parallel_detail {

/// How the std::thread implementation cuts [0, count) for a loop of grain `grain`: chunk c is
/// [c * size, min(count, (c + 1) * size)), c < chunks.
struct Chunks {
  size_t size = 0;
  size_t chunks = 0;
};
Chunks chunks_of(size_t count, size_t grain);

/// Calls body(c) once for every c in [0, chunks), in parallel within the thread limit;
/// rethrows the first exception once every started call has returned.
void run_chunks(size_t chunks, const std::function<void(size_t)>& body);

}  // namespace parallel_detail
#endif

/// Reduces [begin, end) in parallel: the range is cut into chunks of about `grain` indices
/// (as parallel_for_range), body(chunk_begin, chunk_end, value) folds one chunk into `value`
/// (which starts as `identity`) and returns it, and join(a, b) merges two partial values.
/// Chunks are folded and joined in an order and grouping that vary from run to run under
/// oneTBB, so the result must not depend on them: bounds, bins and integer counts, not
/// floating-point sums.
template <typename T, typename Body, typename Join>
T parallel_reduce(size_t begin, size_t end, size_t grain, const T& identity, const Body& body,
                  const Join& join) {
#ifdef PRISM_PARALLEL_THREADS
  if (end <= begin) return identity;
  const parallel_detail::Chunks cut = parallel_detail::chunks_of(end - begin, grain);
  std::vector<T> partial(cut.chunks, identity);
  parallel_detail::run_chunks(cut.chunks, [&](size_t c) {
    const size_t first = begin + c * cut.size;
    partial[c] = body(first, std::min(end, first + cut.size), std::move(partial[c]));
  });
  T result = identity;
  for (const T& p : partial) result = join(std::move(result), p);
  return result;
#else
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(begin, end, grain), identity,
      [&](const tbb::blocked_range<size_t>& r, T value) {
        return body(r.begin(), r.end(), std::move(value));
      },
      join);
#endif
}

}  // namespace prism
