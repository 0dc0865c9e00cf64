#include "integrators/debug_integrators.h"

namespace prism {
namespace {

/// A colour of the first hit alone; what colour is decided by `Shade`.
template <typename Shade>
class FirstHitEstimator final : public PixelEstimator {
 public:
  explicit FirstHitEstimator(const RenderContext& context) : context_(context) {}

  Rgb li(const Ray& ray, Sampler&, AovSample& aovs) const override {
    const std::optional<Hit> hit = context_.accel.intersect(ray);
    if (!hit) return Rgb(0.0f);
    const SurfaceInteraction si = context_.scene.surface_at(ray, *hit);
    aovs = hit_aovs(context_.scene, ray, *hit, si);
    return Shade{}(ray, *hit, si);
  }
  bool escaping_rays_are_black() const override { return true; }

 private:
  const RenderContext& context_;
};

struct ShadeNormal {
  Rgb operator()(const Ray&, const Hit&, const SurfaceInteraction& si) const {
    return 0.5f * si.shading_normal + Vec3(0.5f);
  }
};

struct ShadeDepth {
  Rgb operator()(const Ray& ray, const Hit& hit, const SurfaceInteraction&) const {
    // t is measured in units of |direction|; report a true distance.
    return Rgb(hit.t * glm::length(ray.direction));
  }
};

}  // namespace

std::unique_ptr<PixelEstimator> NormalsIntegrator::prepare(const RenderContext& context) const {
  return std::make_unique<FirstHitEstimator<ShadeNormal>>(context);
}

std::unique_ptr<PixelEstimator> DepthIntegrator::prepare(const RenderContext& context) const {
  return std::make_unique<FirstHitEstimator<ShadeDepth>>(context);
}

}  // namespace prism
