#include "integrators/bsdf/fresnel.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "integrators/bsdf/bsdf.h"

namespace prism {

bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3* wt) {
  const float cos_i = glm::dot(n, wi);
  const float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
  const float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  *wt = -wi / eta + (cos_i / eta - cos_t) * n;
  return true;
}

float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, -1.0f, 1.0f);
  if (cos_i < 0.0f) {
    eta = 1.0f / eta;
    cos_i = -cos_i;
  }
  const float sin2_i = 1.0f - cos_i * cos_i;
  const float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
  const float r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parallel * r_parallel + r_perpendicular * r_perpendicular);
}

namespace {

float fresnel_complex(float cos_i, std::complex<float> eta) {
  using C = std::complex<float>;
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_i = 1.0f - cos_i * cos_i;
  const C sin2_t = C(sin2_i) / (eta * eta);
  const C cos_t = std::sqrt(C(1.0f) - sin2_t);
  const C r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const C r_perpendicular = (C(cos_i) - eta * cos_t) / (C(cos_i) + eta * cos_t);
  return std::min(1.0f, 0.5f * (std::norm(r_parallel) + std::norm(r_perpendicular)));
}

}  // namespace

Rgb fresnel_conductor(float cos_i, const Rgb& eta, const Rgb& k) {
  return {fresnel_complex(cos_i, {eta.r, k.r}), fresnel_complex(cos_i, {eta.g, k.g}),
          fresnel_complex(cos_i, {eta.b, k.b})};
}

}  // namespace prism
