#pragma once

#include <optional>
#include <string_view>

#include "accel/accelerator.h"
#include "accel/bvh/homework/homework_bvh.h"
#include "accel/bvh/homework/homework_bvh_builder.h"

namespace prism {

/// The homework's BVH as a backend (`--accel bvh --set bvh.split=median --set
/// bvh.layout=bvh2`): one binary tree over all triangles and spheres whose leaves hold
/// (geom_id, prim_id) ids, built by build_homework_bvh() and traversed nearer child first, one
/// scalar primitive test at a time. Hits equal brute force's bit for bit
/// (homework_bvh_intersect()). Parameters: bvh.max_leaf_size (integer in [1, 255], default 4).
class HomeworkBvhAccelerator final : public Accelerator {
 public:
  /// Reads the parameters; throws Error(kUsage) on a bad value.
  explicit HomeworkBvhAccelerator(const ParamSet& params);

  std::string_view name() const override { return "bvh"; }

  /// The tree, for tests and tools.
  const HomeworkBvh& tree() const { return bvh_; }

 protected:
  void build_structure(const SceneGeometry& geometry) override;
  std::optional<Hit> intersect_prepared(const Ray& ray) const override;
  bool occluded_prepared(const Ray& ray) const override;
  /// nodes, leaves, max_depth, bytes (nodes + primitive ids), SAH cost.
  AccelStats structure_stats() const override { return stats_; }

 private:
  HomeworkBvhOptions options_;
  HomeworkBvh bvh_;
  AccelStats stats_;
};

}  // namespace prism
