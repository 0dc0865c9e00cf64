#include "integrators/debug_integrators.h"

namespace prism {

Rgb NormalsIntegrator::li(const Ray& ray, Sampler& sampler, const RenderContext& context) const {
  const std::optional<Hit> hit = context.accel.intersect(ray);
  if (!hit) return Rgb(0.0f);
  const SurfaceInteraction si = context.scene.surface_at(ray, *hit);
  return 0.5f * si.shading_normal + Vec3(0.5f);
}

Rgb DepthIntegrator::li(const Ray& ray, Sampler& sampler, const RenderContext& context) const {
  const std::optional<Hit> hit = context.accel.intersect(ray);
  if (!hit) return Rgb(0.0f);
  // t is measured in units of |direction|; report a true distance.
  return Rgb(hit->t * glm::length(ray.direction));
}

}  // namespace prism
