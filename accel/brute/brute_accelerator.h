#pragma once

#include <optional>
#include <string_view>

#include "accel/accelerator.h"

namespace prism {

/// The reference backend: tests every triangle and sphere for every ray with core's primitive
/// tests, and orders hits by comes_before() (exact ties go to the lowest geom_id, then prim_id).
/// O(primitives) per ray: for tests and validation, not for rendering.
/// Parameters: none. Its statistics describe it as one leaf holding every primitive.
class BruteAccelerator final : public Accelerator {
 public:
  explicit BruteAccelerator(const ParamSet& params);

  std::string_view name() const override { return "brute"; }

 protected:
  void build_structure(const SceneGeometry& geometry) override;
  std::optional<Hit> intersect_prepared(const Ray& ray) const override;
  bool occluded_prepared(const Ray& ray) const override;
  AccelStats structure_stats() const override { return stats_; }

 private:
  AccelStats stats_;
};

}  // namespace prism
