#pragma once

#include "integrators/bsdf/bsdf.h"

namespace prism {

/// Perfect specular reflection with a constant reflectance (no Fresnel term).
class MirrorBsdf final : public Bsdf {
 public:
  explicit MirrorBsdf(const Rgb& reflectance) : reflectance_(reflectance) {}
  Rgb eval(const Vec3&, const Vec3&) const override { return Rgb(0.0f); }
  std::optional<BsdfSample> sample(const Vec3& wo, float u_lobe, Vec2 u) const override;
  float pdf(const Vec3&, const Vec3&) const override { return 0.0f; }
  uint32_t lobes() const override { return kLobeReflection | kLobeSpecular; }
  bool reads_lobe_sample() const override { return false; }
  Rgb albedo() const override { return reflectance_; }

 private:
  Rgb reflectance_;
};

}  // namespace prism
