#pragma once

#include <optional>
#include <string_view>

#include "accel/accelerator.h"
#include "accel/bvh/bvh2.h"
#include "accel/bvh/median_split_builder.h"

namespace prism {

/// The handwritten backend: a binary BVH over all triangles and spheres (one tree; a leaf
/// entry is a (geom_id, prim_id) reference), built by the median-split builder and traversed
/// nearer child first. Results equal brute force bit for bit (see bvh2_intersect()).
/// Parameters: bvh.max_leaf_size (integer in [1, 255], default 4).
class BvhAccelerator final : public Accelerator {
 public:
  /// Reads the parameters; throws Error(kUsage) on a bad value.
  explicit BvhAccelerator(const ParamSet& params);

  std::string_view name() const override { return "bvh"; }
  /// Validates `geometry` (throws Error(kInput)), builds the tree and keeps a reference to
  /// `geometry`.
  void build(const SceneGeometry& geometry) override;
  std::optional<Hit> intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override;
  /// nodes, leaves, max_depth, bytes (nodes + primitive references), SAH cost, build time.
  AccelStats stats() const override { return stats_; }

  /// The tree, for tests and tools.
  const Bvh2& tree() const { return bvh_; }

 private:
  MedianSplitOptions options_;
  const SceneGeometry* geometry_ = nullptr;
  Bvh2 bvh_;
  AccelStats stats_;
};

}  // namespace prism
