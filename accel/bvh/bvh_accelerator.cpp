#include "accel/bvh/bvh_accelerator.h"

#include <chrono>

#include "accel/bvh/bvh2_traversal.h"
#include "accel/primitive_ref.h"
#include "accel/ray_query.h"
#include "core/error.h"

namespace prism {

BvhAccelerator::BvhAccelerator(const ParamSet& params) {
  options_.max_leaf_size = static_cast<uint32_t>(params.get_int("bvh.max_leaf_size", 4, 1, 255));
}

void BvhAccelerator::build(const SceneGeometry& geometry) {
  const auto start = std::chrono::steady_clock::now();
  geometry.validate();
  geometry_ = &geometry;
  bvh_ = build_median_split(gather_build_primitives(geometry), options_);
  PRISM_CHECK(bvh_.max_depth <= kBvh2MaxDepth);
  stats_ = bvh2_stats(bvh_);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::optional<Hit> BvhAccelerator::intersect(const Ray& ray) const {
  PRISM_CHECK(geometry_ != nullptr);
  const std::optional<Ray> prepared = prepare_query(ray);
  if (!prepared) return std::nullopt;
  return bvh2_intersect(bvh_, *geometry_, *prepared);
}

bool BvhAccelerator::occluded(const Ray& ray) const {
  PRISM_CHECK(geometry_ != nullptr);
  const std::optional<Ray> prepared = prepare_query(ray);
  if (!prepared) return false;
  return bvh2_occluded(bvh_, *geometry_, *prepared);
}

}  // namespace prism
