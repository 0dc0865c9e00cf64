#pragma once

#include "core/math.h"

namespace prism {

/// Isotropic microfacet normal distributions with Smith shadowing-masking.
enum class MicrofacetModel { kBeckmann, kGgx };

/// A normal distribution D of roughness alpha over the upper hemisphere (local frame), with
/// Smith's height-correlated G and sampling of D(h) cos(theta_h).
class MicrofacetDistribution {
 public:
  MicrofacetDistribution(MicrofacetModel model, float alpha);

  /// D(h) for a unit h in the local frame (0 for h.z <= 0); integrates D(h) h.z to 1.
  float d(const Vec3& h) const;
  /// Smith's Lambda(w) of this distribution.
  float lambda(const Vec3& w) const;
  /// Height-correlated masking-shadowing 1 / (1 + Lambda(wo) + Lambda(wi)).
  float g(const Vec3& wo, const Vec3& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }
  /// A microfacet normal h (h.z > 0) with density pdf_h(h) = D(h) h.z from u in [0,1)^2.
  Vec3 sample_h(Vec2 u) const;
  float pdf_h(const Vec3& h) const { return d(h) * std::max(0.0f, h.z); }
  float alpha() const { return alpha_; }
  MicrofacetModel model() const { return model_; }

 private:
  MicrofacetModel model_;
  float alpha_;
};

}  // namespace prism
