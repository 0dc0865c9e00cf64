#pragma once

#include "integrators/integrator.h"

namespace prism {

/// Ambient occlusion: the fraction of a cosine-weighted hemisphere at the first hit that is
/// open within `ao.max_distance` (default: a tenth of the scene's bounding-box diagonal), from
/// `ao.samples` rays (default 1). Black where the camera ray escapes.
class AoIntegrator final : public PixelIntegrator {
 public:
  explicit AoIntegrator(const ParamSet& params);
  std::string_view name() const override { return "ao"; }

 protected:
  std::unique_ptr<PixelEstimator> prepare(const RenderContext& context) const override;

 private:
  float max_distance_;  ///< <= 0: the default fraction of the scene size
  int samples_;
};

}  // namespace prism
