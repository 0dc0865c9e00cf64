#pragma once

#include "integrators/light_transport.h"

namespace prism {

/// Unidirectional path tracing with next-event estimation. Parameters (prefix "path."):
/// - mis (default true): light sampling and BSDF sampling combined by multiple importance
///   sampling (power heuristic), lights chosen by power, light_samples NEE samples per vertex;
///   false reproduces the homework's estimator: at every vertex the one-bounce estimate of
///   every light (or by hemisphere sampling with -H), emission found by BSDF-sampled rays
///   counted only after specular bounces.
/// - accumulate (default true): the sum of bounces 0..max_depth; false gives only bounce
///   max_depth (light that scattered exactly max_depth times).
/// - rr (default true), rr_depth (default 3, or 1 with rr_probability), rr_probability
///   (default 0: continuation probability from the path throughput; in (0,1]: that fixed
///   continuation probability, as the homework does).
/// - microfacet: beckmann (default) or ggx.
class PathIntegrator final : public LightTransportIntegrator {
 public:
  explicit PathIntegrator(const ParamSet& params);
  std::string_view name() const override { return "path"; }

 protected:
  Rgb li(const Ray& ray, Sampler& sampler, const RenderContext& context) const override;
  Rgb li_aov(const Ray& ray, Sampler& sampler, const RenderContext& context,
             AovSample& aovs) const override;

 private:
  /// Light arriving at `sp` from one light chosen by power, MIS-weighted against BSDF
  /// sampling; averaged over context.light_samples samples.
  Rgb sample_lights_mis(const ShadingPoint& sp, Sampler& sampler, const RenderContext& context,
                        const ShadingContext& shading) const;

  bool mis_;
  bool accumulate_;
  bool russian_roulette_;
  int rr_depth_;
  float rr_probability_;
};

}  // namespace prism
