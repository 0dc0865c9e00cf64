#pragma once

#include <optional>
#include <string_view>

#include "accel/accelerator.h"

namespace prism {

/// The reference backend: tests every triangle and sphere for every ray with core's primitive
/// tests, and orders hits by comes_before() (exact ties go to the lowest geom_id, then prim_id).
/// O(primitives) per ray: for tests and validation, not for rendering.
/// Parameters: none. stats() describes it as one leaf holding every primitive.
class BruteAccelerator final : public Accelerator {
 public:
  explicit BruteAccelerator(const ParamSet& params);

  std::string_view name() const override { return "brute"; }
  /// Validates `geometry` (throws Error(kInput)) and keeps a reference to it.
  void build(const SceneGeometry& geometry) override;
  std::optional<Hit> intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override;
  AccelStats stats() const override { return stats_; }

 private:
  const SceneGeometry* geometry_ = nullptr;
  AccelStats stats_;
};

}  // namespace prism
