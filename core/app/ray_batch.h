#pragma once

// Ray queries over arrays, in parallel: what the Python module's Accelerator.intersect() and
// occluded() run once NumPy has handed over its buffers. Plain C++, so that tests can check them
// against Accelerator::intersect() and occluded() ray by ray.

#include <cstdint>
#include <span>

#include "accel/accelerator.h"
#include "core/ray.h"

namespace prism {

/// `size` rays as flat arrays: origins and directions hold 3 floats per ray (x, y, z); tmin and
/// tmax hold either one value for every ray or one per ray.
struct RayBatch {
  std::span<const float> origins;
  std::span<const float> directions;
  std::span<const float> tmin;
  std::span<const float> tmax;
  size_t size = 0;

  /// Throws Error(kInternal) unless the spans have the sizes above.
  void check() const;
  /// Ray i, exactly as the arrays give it (Accelerator's queries apply prepare_query()).
  Ray ray(size_t i) const {
    const float* o = origins.data() + 3 * i;
    const float* d = directions.data() + 3 * i;
    return Ray{.origin = Vec3(o[0], o[1], o[2]),
               .tmin = tmin[tmin.size() == 1 ? 0 : i],
               .direction = Vec3(d[0], d[1], d[2]),
               .tmax = tmax[tmax.size() == 1 ? 0 : i]};
  }
};

/// Where intersect_batch() writes, one entry per ray. A miss has t = +infinity, u = v = 0,
/// geom_id = prim_id = -1 and hit = false; a hit has Hit's values and hit = true.
struct HitArrays {
  std::span<float> t;
  std::span<float> u;
  std::span<float> v;
  std::span<int64_t> geom_id;
  std::span<int64_t> prim_id;
  std::span<bool> hit;
};

/// accel.intersect(batch.ray(i)) for every ray, in parallel on prism's loops (core/parallel.h;
/// a ThreadLimit alive around the call limits them). accel must be built; the spans of `hits`
/// must hold batch.size entries (Error(kInternal) otherwise).
void intersect_batch(const Accelerator& accel, const RayBatch& batch, const HitArrays& hits);

/// accel.occluded(batch.ray(i)) into occluded[i] for every ray, in parallel likewise.
void occluded_batch(const Accelerator& accel, const RayBatch& batch, std::span<bool> occluded);

}  // namespace prism
