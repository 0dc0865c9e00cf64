#include "integrators/bsdf/glass_bsdf.h"

#include "integrators/bsdf/fresnel.h"

namespace prism {
namespace {

/// The refracted direction of wo through the boundary, with the relative index crossed.
bool refract_local(const Vec3& wo, float ior, Vec3* wi, float* eta) {
  const bool entering = wo.z > 0.0f;
  *eta = entering ? ior : 1.0f / ior;
  const Vec3 n(0.0f, 0.0f, entering ? 1.0f : -1.0f);
  return refract(wo, n, *eta, wi);
}

}  // namespace

std::optional<BsdfSample> GlassBsdf::sample(const Vec3& wo, float u_lobe, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  const float fresnel = fresnel_dielectric(wo.z, ior_);
  BsdfSample s;
  if (u_lobe < fresnel) {
    s.wi = reflect_z(wo);
    s.pdf = fresnel;
    s.f = reflectance_ * (fresnel / abs_cos_theta(s.wi));
    s.lobe = kLobeReflection | kLobeSpecular;
    return s;
  }
  float eta = 1.0f;
  if (!refract_local(wo, ior_, &s.wi, &eta) || s.wi.z == 0.0f) return std::nullopt;
  s.pdf = 1.0f - fresnel;
  s.f = transmittance_ * ((1.0f - fresnel) / (abs_cos_theta(s.wi) * eta * eta));
  s.lobe = kLobeTransmission | kLobeSpecular;
  s.eta = eta;
  return s;
}

std::optional<BsdfSample> RefractionBsdf::sample(const Vec3& wo, float u_lobe, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  BsdfSample s;
  float eta = 1.0f;
  if (!refract_local(wo, ior_, &s.wi, &eta) || s.wi.z == 0.0f) return std::nullopt;
  s.pdf = 1.0f;
  s.f = transmittance_ / (abs_cos_theta(s.wi) * eta * eta);
  s.lobe = kLobeTransmission | kLobeSpecular;
  s.eta = eta;
  return s;
}

}  // namespace prism
