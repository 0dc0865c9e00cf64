#pragma once

#include "integrators/bsdf/bsdf.h"

namespace prism {

/// Smooth dielectric: specular reflection weighted by the exact Fresnel reflectance F and
/// specular refraction weighted by 1 - F (all reflection under total internal reflection),
/// chosen with probabilities F and 1 - F. Local +z is outside (index 1), -z inside (index ior).
/// `reflectance` and `transmittance` tint the two lobes.
class GlassBsdf final : public Bsdf {
 public:
  GlassBsdf(const Rgb& reflectance, const Rgb& transmittance, float ior)
      : Bsdf(kLobeReflection | kLobeTransmission | kLobeSpecular, true),
        reflectance_(reflectance),
        transmittance_(transmittance),
        ior_(ior) {}
  Rgb eval(const Vec3&, const Vec3&) const override { return Rgb(0.0f); }
  std::optional<BsdfSample> sample(const Vec3& wo, float u_lobe, Vec2 u) const override;
  float pdf(const Vec3&, const Vec3&) const override { return 0.0f; }
  Rgb albedo() const override { return transmittance_; }

 private:
  Rgb reflectance_;
  Rgb transmittance_;
  float ior_;
};

/// Specular refraction only: no reflected lobe and no Fresnel
/// weighting (everything is transmitted, tinted by `transmittance`); total internal reflection
/// absorbs. Same frame convention as GlassBsdf.
class RefractionBsdf final : public Bsdf {
 public:
  RefractionBsdf(const Rgb& transmittance, float ior)
      : Bsdf(kLobeTransmission | kLobeSpecular, false), transmittance_(transmittance), ior_(ior) {}
  Rgb eval(const Vec3&, const Vec3&) const override { return Rgb(0.0f); }
  std::optional<BsdfSample> sample(const Vec3& wo, float u_lobe, Vec2 u) const override;
  float pdf(const Vec3&, const Vec3&) const override { return 0.0f; }
  Rgb albedo() const override { return transmittance_; }

 private:
  Rgb transmittance_;
  float ior_;
};

}  // namespace prism
