#pragma once

#include "integrators/bsdf/bsdf.h"

namespace prism {

/// Lambertian reflection R / pi on the side of wo; cosine-weighted sampling.
class DiffuseBsdf final : public Bsdf {
 public:
  explicit DiffuseBsdf(const Rgb& reflectance) : reflectance_(reflectance) {}
  Rgb eval(const Vec3& wo, const Vec3& wi) const override;
  std::optional<BsdfSample> sample(const Vec3& wo, float u_lobe, Vec2 u) const override;
  float pdf(const Vec3& wo, const Vec3& wi) const override;
  uint32_t lobes() const override { return kLobeReflection | kLobeDiffuse; }
  bool reads_lobe_sample() const override { return false; }
  Rgb albedo() const override { return reflectance_; }

 private:
  Rgb reflectance_;
};

}  // namespace prism
