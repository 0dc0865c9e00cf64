#include "integrators/ao_integrator.h"

#include "integrators/sampling/frame.h"
#include "integrators/sampling/warp.h"

namespace prism {
namespace {

class AoEstimator final : public PixelEstimator {
 public:
  /// `reach`: the occlusion distance.
  AoEstimator(const RenderContext& context, int samples, float reach)
      : context_(context), samples_(samples), reach_(reach) {}

  Rgb li(const Ray& ray, Sampler& sampler, AovSample& aovs) const override;
  bool escaping_rays_are_black() const override { return true; }

 private:
  const RenderContext& context_;
  const int samples_;
  const float reach_;
};

Rgb AoEstimator::li(const Ray& ray, Sampler& sampler, AovSample& aovs) const {
  const std::optional<Hit> hit = context_.accel.intersect(ray);
  if (!hit) return Rgb(0.0f);
  const SurfaceInteraction si = context_.scene.surface_at(ray, *hit);
  aovs = hit_aovs(context_.scene, ray, *hit, si);
  // The hemisphere on the side the camera sees.
  const Vec3 wo = -glm::normalize(ray.direction);
  Vec3 n = si.shading_normal;
  if (glm::dot(n, wo) < 0.0f) n = -n;
  const Frame frame = Frame::from_z(n);
  int open = 0;
  for (int i = 0; i < samples_; ++i) {
    const Vec3 wi = glm::normalize(frame.to_world(square_to_cosine_hemisphere(sampler.get_2d())));
    if (glm::dot(wi, si.geometric_normal) * glm::dot(wo, si.geometric_normal) <= 0.0f) continue;
    Ray r = spawn_ray(si, wi);
    r.tmax = reach_;
    if (!context_.accel.occluded(r)) ++open;
  }
  return Rgb(float(open) / float(samples_));
}

}  // namespace

AoIntegrator::AoIntegrator(const ParamSet& params)
    : max_distance_(float(params.get_float("ao.max_distance", 0.0, 0.0, 1e30))),
      samples_(int(params.get_int("ao.samples", 1, 1, 1 << 16))) {}

std::unique_ptr<PixelEstimator> AoIntegrator::prepare(const RenderContext& context) const {
  float reach = max_distance_;
  if (!(reach > 0.0f)) {
    const Bounds3 b = context.scene.geometry.bounds();
    reach = b.empty() ? 1.0f : 0.1f * glm::length(b.diagonal());
  }
  return std::make_unique<AoEstimator>(context, samples_, reach);
}

}  // namespace prism
