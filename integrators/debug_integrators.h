#pragma once

#include "integrators/integrator.h"

namespace prism {

/// Normal shading: the shading normal n of the first hit as the colour
/// 0.5 * n + 0.5 (world space); black where the ray escapes.
class NormalsIntegrator final : public PixelIntegrator {
 public:
  std::string_view name() const override { return "normals"; }

 protected:
  std::unique_ptr<PixelEstimator> prepare(const RenderContext& context) const override;
};

/// Distance from the ray origin to the first hit, in scene units, as grey; 0 where the ray
/// escapes.
class DepthIntegrator final : public PixelIntegrator {
 public:
  std::string_view name() const override { return "depth"; }

 protected:
  std::unique_ptr<PixelEstimator> prepare(const RenderContext& context) const override;
};

}  // namespace prism
