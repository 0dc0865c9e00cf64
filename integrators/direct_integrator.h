#pragma once

#include "integrators/light_transport.h"

namespace prism {

/// Zero bounce plus one bounce (the homework's direct illumination): emission seen directly,
/// plus light reflected once, estimated by light importance sampling (default; every light,
/// RenderContext::light_samples samples per non-delta light) or by uniform hemisphere sampling
/// (RenderContext::hemisphere_sampling). At a purely specular surface the one bounce follows
/// the specular direction instead, so mirrors show the lights they reflect.
class DirectIntegrator final : public LightTransportIntegrator {
 public:
  explicit DirectIntegrator(const ParamSet& params);
  std::string_view name() const override { return "direct"; }

 protected:
  Rgb li(const Ray& ray, Sampler& sampler, const RenderContext& context) const override;
  Rgb li_aov(const Ray& ray, Sampler& sampler, const RenderContext& context,
             AovSample& aovs) const override;
};

/// Ambient occlusion: the fraction of a cosine-weighted hemisphere at the first hit that is
/// open within `ao.max_distance` (default: a tenth of the scene's bounding-box diagonal), from
/// `ao.samples` rays (default 1). Black where the camera ray escapes.
class AoIntegrator final : public PixelIntegrator {
 public:
  explicit AoIntegrator(const ParamSet& params);
  std::string_view name() const override { return "ao"; }

 protected:
  Rgb li(const Ray& ray, Sampler& sampler, const RenderContext& context) const override;
  Rgb li_aov(const Ray& ray, Sampler& sampler, const RenderContext& context,
             AovSample& aovs) const override;
  void begin_render(const RenderContext& context) const override;

 private:
  float max_distance_;  ///< <= 0: the default fraction of the scene size
  int samples_;
  mutable float reach_ = 1.0f;  ///< the occlusion distance of the current render
};

}  // namespace prism
