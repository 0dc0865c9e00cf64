#include "integrators/direct_integrator.h"

#include <cmath>

namespace prism {
namespace {

class DirectEstimator final : public PixelEstimator {
 public:
  DirectEstimator(const RenderContext& context, const LightTransportSettings& settings)
      : context_(context),
        settings_(settings),
        shading_(context.scene, settings.bsdf, settings.lights, texture_filter_of(context)) {}

  Rgb li(const Ray& ray, Sampler& sampler, AovSample& aovs) const override;
  /// An escaping ray sees the infinite lights only.
  bool escaping_rays_are_black() const override {
    return shading_.lights.infinite_lights().empty();
  }

 private:
  const RenderContext& context_;
  const LightTransportSettings settings_;
  const ShadingContext shading_;
};

Rgb DirectEstimator::li(const Ray& ray, Sampler& sampler, AovSample& aovs) const {
  const std::optional<Hit> hit = context_.accel.intersect(ray);
  if (!hit) return shading_.lights.le_escaped(glm::normalize(ray.direction));
  const SurfaceInteraction si = context_.scene.surface_at(ray, *hit);
  BsdfStorage bsdf_storage;
  const Bsdf& bsdf = shading_.bsdf_at(si, bsdf_storage);
  aovs.albedo = bsdf.albedo();
  aovs.normal = si.shading_normal;
  aovs.depth = hit->t * glm::length(ray.direction);

  Rgb radiance = emitted_radiance(si, ray, shading_);
  if (bsdf.is_black()) return radiance;
  const ShadingPoint sp(si, ray, bsdf);
  if (bsdf.is_delta()) {
    const float u_lobe = sp.lobe_sample(sampler);
    const std::optional<BsdfSample> bs = sp.sample(u_lobe, sampler.get_2d());
    if (!bs) return radiance;
    const Ray next = sp.spawn(bs->wi);
    const std::optional<Hit> next_hit = context_.accel.intersect(next);
    const Rgb le =
        next_hit ? emitted_radiance(context_.scene.surface_at(next, *next_hit), next, shading_)
                 : shading_.lights.le_escaped(bs->wi);
    return radiance + bs->f * std::abs(glm::dot(bs->wi, si.shading_normal)) * le / bs->pdf;
  }
  if (settings_.hemisphere) {
    return radiance +
           estimate_direct_hemisphere(sp, sampler, context_, shading_, settings_.light_samples);
  }
  return radiance +
         estimate_direct_lights(sp, sampler, context_, shading_, settings_.light_samples);
}

}  // namespace

DirectIntegrator::DirectIntegrator(const ParamSet& params) : settings_("direct", params) {}

std::unique_ptr<PixelEstimator> DirectIntegrator::prepare(const RenderContext& context) const {
  return std::make_unique<DirectEstimator>(context, settings_);
}

}  // namespace prism
