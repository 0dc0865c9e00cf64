#include "integrators/bsdf/mirror_bsdf.h"

namespace prism {

std::optional<BsdfSample> MirrorBsdf::sample(const Vec3& wo, float u_lobe, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  BsdfSample s;
  s.wi = reflect_z(wo);
  s.f = reflectance_ / abs_cos_theta(s.wi);
  s.pdf = 1.0f;
  s.lobe = kLobeReflection | kLobeSpecular;
  return s;
}

}  // namespace prism
