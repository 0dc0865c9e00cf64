#include "core/app/ray_batch.h"

#include <limits>
#include <optional>

#include "core/parallel.h"

namespace prism {

void RayBatch::check() const {
  PRISM_CHECK(origins.size() == 3 * size && directions.size() == 3 * size);
  PRISM_CHECK(tmin.size() == 1 || tmin.size() == size);
  PRISM_CHECK(tmax.size() == 1 || tmax.size() == size);
}

void intersect_batch(const Accelerator& accel, const RayBatch& batch, const HitArrays& hits) {
  batch.check();
  const size_t n = batch.size;
  PRISM_CHECK(hits.t.size() == n && hits.u.size() == n && hits.v.size() == n);
  PRISM_CHECK(hits.geom_id.size() == n && hits.prim_id.size() == n && hits.hit.size() == n);
  parallel_for_range(n, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const std::optional<Hit> hit = accel.intersect(batch.ray(i));
      hits.hit[i] = hit.has_value();
      hits.t[i] = hit ? hit->t : std::numeric_limits<float>::infinity();
      hits.u[i] = hit ? hit->u : 0.0f;
      hits.v[i] = hit ? hit->v : 0.0f;
      hits.geom_id[i] = hit ? int64_t(hit->geom_id) : -1;
      hits.prim_id[i] = hit ? int64_t(hit->prim_id) : -1;
    }
  });
}

void occluded_batch(const Accelerator& accel, const RayBatch& batch, std::span<bool> occluded) {
  batch.check();
  PRISM_CHECK(occluded.size() == batch.size);
  parallel_for_range(batch.size, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) occluded[i] = accel.occluded(batch.ray(i));
  });
}

}  // namespace prism
