#include "accel/bvh/homework/homework_bvh_accelerator.h"

#include "accel/bvh/homework/homework_bvh_traversal.h"
#include "core/error.h"

namespace prism {

HomeworkBvhAccelerator::HomeworkBvhAccelerator(const ParamSet& params) {
  options_.max_leaf_size = static_cast<uint32_t>(params.get_int("bvh.max_leaf_size", 4, 1, 255));
}

void HomeworkBvhAccelerator::build_structure(const SceneGeometry& geometry) {
  bvh_ = build_homework_bvh(gather_homework_primitives(geometry), options_);
  PRISM_CHECK(bvh_.max_depth <= kHomeworkBvhMaxDepth);
  stats_ = homework_bvh_stats(bvh_);
}

std::optional<Hit> HomeworkBvhAccelerator::intersect_prepared(const Ray& ray) const {
  return homework_bvh_intersect(bvh_, geometry(), ray);
}

bool HomeworkBvhAccelerator::occluded_prepared(const Ray& ray) const {
  return homework_bvh_occluded(bvh_, geometry(), ray);
}

}  // namespace prism
