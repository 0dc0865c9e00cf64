#include "integrators/bsdf/microfacet_distribution.h"

#include <algorithm>
#include <cmath>

#include "integrators/sampling/warp.h"

namespace prism {

MicrofacetDistribution::MicrofacetDistribution(MicrofacetModel model, float alpha)
    // Below ~1e-3 the peak of D overflows float; such surfaces are mirrors in all but name.
    : model_(model), alpha_(std::max(alpha, 1e-3f)) {}

float MicrofacetDistribution::d(const Vec3& h) const {
  const float cos2 = h.z * h.z;
  if (h.z <= 0.0f || cos2 <= 0.0f) return 0.0f;
  const float tan2 = std::max(0.0f, 1.0f - cos2) / cos2;
  const float a2 = alpha_ * alpha_;
  const float cos4 = cos2 * cos2;
  if (model_ == MicrofacetModel::kBeckmann) {
    return std::exp(-tan2 / a2) / (kPi * a2 * cos4);
  }
  const float denom = a2 + tan2;
  return a2 / (kPi * cos4 * denom * denom);
}

float MicrofacetDistribution::lambda(const Vec3& w) const {
  const float cos2 = w.z * w.z;
  const float sin2 = std::max(0.0f, 1.0f - cos2);
  if (sin2 == 0.0f) return 0.0f;
  if (cos2 == 0.0f) return kInfinity;
  const float tan_theta = std::sqrt(sin2 / cos2);
  if (model_ == MicrofacetModel::kBeckmann) {
    const float a = 1.0f / (alpha_ * tan_theta);
    // Exact Beckmann Lambda; the erf form loses all digits for large a, where Lambda -> 0.
    if (a > 8.0f) return 0.0f;
    return 0.5f * (std::erf(a) - 1.0f) + std::exp(-a * a) / (2.0f * a * std::sqrt(kPi));
  }
  const float at = alpha_ * tan_theta;
  return 0.5f * (std::sqrt(1.0f + at * at) - 1.0f);
}

Vec3 MicrofacetDistribution::sample_h(Vec2 u) const {
  const float a2 = alpha_ * alpha_;
  float tan2;
  if (model_ == MicrofacetModel::kBeckmann) {
    tan2 = -a2 * std::log1p(-u.x);  // u.x < 1, so log1p(-u.x) is finite
  } else {
    tan2 = a2 * u.x / (1.0f - u.x);
  }
  const float cos_theta = 1.0f / std::sqrt(1.0f + tan2);
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  const float phi = 2.0f * kPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

}  // namespace prism
