#include "integrators/bsdf/diffuse_bsdf.h"

#include "integrators/sampling/warp.h"

namespace prism {

Rgb DiffuseBsdf::eval(const Vec3& wo, const Vec3& wi) const {
  return same_hemisphere(wo, wi) ? reflectance_ * kInvPi : Rgb(0.0f);
}

std::optional<BsdfSample> DiffuseBsdf::sample(const Vec3& wo, float u_lobe, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  Vec3 wi = square_to_cosine_hemisphere(u);
  if (wo.z < 0.0f) wi.z = -wi.z;
  const float p = cosine_hemisphere_pdf(std::abs(wi.z));
  if (p <= 0.0f) return std::nullopt;
  BsdfSample s;
  s.f = reflectance_ * kInvPi;
  s.wi = wi;
  s.pdf = p;
  s.lobe = kLobeReflection | kLobeDiffuse;
  return s;
}

float DiffuseBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(std::abs(wi.z)) : 0.0f;
}

}  // namespace prism
