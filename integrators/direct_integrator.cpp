#include "integrators/direct_integrator.h"

#include <cmath>

#include "integrators/sampling/warp.h"

namespace prism {

DirectIntegrator::DirectIntegrator(const ParamSet& params)
    : LightTransportIntegrator("direct", params) {}

Rgb DirectIntegrator::li(const Ray& ray, Sampler& sampler, const RenderContext& context) const {
  AovSample aovs;
  return li_aov(ray, sampler, context, aovs);
}

Rgb DirectIntegrator::li_aov(const Ray& ray, Sampler& sampler, const RenderContext& context,
                             AovSample& aovs) const {
  const ShadingContext& shading = this->shading();
  const std::optional<Hit> hit = context.accel.intersect(ray);
  if (!hit) return shading.lights.le_escaped(glm::normalize(ray.direction));
  const SurfaceInteraction si = context.scene.surface_at(ray, *hit);
  const Bsdf& bsdf = *shading.bsdfs[si.material_id];
  aovs.albedo = bsdf.albedo();
  aovs.normal = si.shading_normal;
  aovs.depth = hit->t * glm::length(ray.direction);

  Rgb radiance = emitted_radiance(si, ray, shading);
  if (bsdf.is_black()) return radiance;
  const ShadingPoint sp(si, ray, bsdf);
  if (bsdf.is_delta()) {
    const float u_lobe = sampler.get_1d();
    const std::optional<BsdfSample> bs = sp.sample(u_lobe, sampler.get_2d());
    if (!bs) return radiance;
    const Ray next = sp.spawn(bs->wi);
    const std::optional<Hit> next_hit = context.accel.intersect(next);
    const Rgb le = next_hit
                       ? emitted_radiance(context.scene.surface_at(next, *next_hit), next, shading)
                       : shading.lights.le_escaped(bs->wi);
    return radiance + bs->f * std::abs(glm::dot(bs->wi, si.shading_normal)) * le / bs->pdf;
  }
  if (context.hemisphere_sampling) {
    return radiance + estimate_direct_hemisphere(sp, sampler, context, shading);
  }
  return radiance + estimate_direct_lights(sp, sampler, context, shading);
}

AoIntegrator::AoIntegrator(const ParamSet& params)
    : max_distance_(float(params.get_float("ao.max_distance", 0.0, 0.0, 1e30))),
      samples_(int(params.get_int("ao.samples", 1, 1, 1 << 16))) {}

void AoIntegrator::begin_render(const RenderContext& context) const {
  reach_ = max_distance_;
  if (!(reach_ > 0.0f)) {
    const Bounds3 b = context.scene.geometry.bounds();
    reach_ = b.empty() ? 1.0f : 0.1f * glm::length(b.diagonal());
  }
}

Rgb AoIntegrator::li(const Ray& ray, Sampler& sampler, const RenderContext& context) const {
  AovSample aovs;
  return li_aov(ray, sampler, context, aovs);
}

Rgb AoIntegrator::li_aov(const Ray& ray, Sampler& sampler, const RenderContext& context,
                         AovSample& aovs) const {
  const std::optional<Hit> hit = context.accel.intersect(ray);
  if (!hit) return Rgb(0.0f);
  const SurfaceInteraction si = context.scene.surface_at(ray, *hit);
  aovs.albedo = material_albedo(context.scene.materials[si.material_id]);
  aovs.normal = si.shading_normal;
  aovs.depth = hit->t * glm::length(ray.direction);
  // The hemisphere on the side the camera sees.
  const Vec3 wo = -glm::normalize(ray.direction);
  Vec3 n = si.shading_normal;
  if (glm::dot(n, wo) < 0.0f) n = -n;
  const Frame frame = Frame::from_z(n);
  int open = 0;
  for (int i = 0; i < samples_; ++i) {
    const Vec3 wi = glm::normalize(frame.to_world(square_to_cosine_hemisphere(sampler.get_2d())));
    if (glm::dot(wi, si.geometric_normal) * glm::dot(wo, si.geometric_normal) <= 0.0f) continue;
    Ray r;
    r.origin = offset_ray_origin(si.position, si.geometric_normal, wi);
    r.direction = wi;
    r.tmax = reach_;
    if (!context.accel.occluded(r)) ++open;
  }
  return Rgb(float(open) / float(samples_));
}

}  // namespace prism
