#pragma once

#include "integrators/bsdf/bsdf.h"
#include "integrators/bsdf/microfacet_distribution.h"

namespace prism {

/// Rough conductor: f = F(wo.h) G(wo, wi) D(h) /
/// (4 |cos_o| |cos_i|) with conductor Fresnel of complex index eta + i k, reflecting on the side
/// of wo. Sampling draws h from D(h) cos(theta_h) and reflects wo about it.
class MicrofacetBsdf final : public Bsdf {
 public:
  MicrofacetBsdf(const Rgb& eta, const Rgb& k, float alpha, MicrofacetModel model);
  Rgb eval(const Vec3& wo, const Vec3& wi) const override;
  std::optional<BsdfSample> sample(const Vec3& wo, float u_lobe, Vec2 u) const override;
  float pdf(const Vec3& wo, const Vec3& wi) const override;
  Rgb albedo() const override { return normal_reflectance_; }

 private:
  Rgb eta_, k_;
  MicrofacetDistribution distribution_;
  Rgb normal_reflectance_;
};

}  // namespace prism
