#pragma once

#include "integrators/bsdf/bsdf.h"
#include "integrators/sampling/warp.h"

namespace prism {

/// Lambertian reflection R / pi on the side of wo; cosine-weighted sampling. Its functions are
/// defined here, and the class is final, so that a caller holding a DiffuseBsdf (as_diffuse())
/// has them inline.
class DiffuseBsdf final : public Bsdf {
 public:
  explicit DiffuseBsdf(const Rgb& reflectance)
      : Bsdf(kLobeReflection | kLobeDiffuse, false, Kind::kDiffuse), reflectance_(reflectance) {}

  Rgb eval(const Vec3& wo, const Vec3& wi) const override {
    return same_hemisphere(wo, wi) ? reflectance_ * kInvPi : Rgb(0.0f);
  }
  std::optional<BsdfSample> sample(const Vec3& wo, float /*u_lobe*/, Vec2 u) const override {
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
  float pdf(const Vec3& wo, const Vec3& wi) const override {
    return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(std::abs(wi.z)) : 0.0f;
  }
  Rgb albedo() const override { return reflectance_; }

 private:
  Rgb reflectance_;
};

/// `bsdf` as the Lambertian BSDF when it is one, else null: no virtual call, no type_info.
inline const DiffuseBsdf* as_diffuse(const Bsdf& bsdf) {
  return bsdf.kind() == Bsdf::Kind::kDiffuse ? static_cast<const DiffuseBsdf*>(&bsdf) : nullptr;
}

}  // namespace prism
