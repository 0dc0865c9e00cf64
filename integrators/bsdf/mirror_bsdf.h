#pragma once

#include "integrators/bsdf/bsdf.h"

namespace prism {

/// Perfect specular reflection with a constant reflectance (no Fresnel term).
class MirrorBsdf final : public Bsdf {
 public:
  explicit MirrorBsdf(const Rgb& reflectance)
      : Bsdf(kLobeReflection | kLobeSpecular, false), reflectance_(reflectance) {}
  Rgb eval(const Vec3&, const Vec3&) const override { return Rgb(0.0f); }
  std::optional<BsdfSample> sample(const Vec3& wo, float u_lobe, Vec2 u) const override;
  float pdf(const Vec3&, const Vec3&) const override { return 0.0f; }
  Rgb albedo() const override { return reflectance_; }

 private:
  Rgb reflectance_;
};

}  // namespace prism
