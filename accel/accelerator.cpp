#include "accel/accelerator.h"

#include "core/timing.h"

namespace prism {

void Accelerator::build(const SceneGeometry& geometry) {
  geometry_ = nullptr;
  build_ms_ = time_ms([&] {
    geometry.validate();
    build_structure(geometry);
  });
  geometry_ = &geometry;
}

void Accelerator::intersect(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const {
  PRISM_CHECK(rays.size() == hits.size());
  for (size_t i = 0; i < rays.size(); ++i) hits[i] = intersect(rays[i]);
}

AccelStats Accelerator::stats() const {
  AccelStats stats = structure_stats();
  stats.build_ms = build_ms_;
  return stats;
}

}  // namespace prism
