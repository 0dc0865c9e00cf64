#include "integrators/sampling/warp.h"

namespace prism {

Vec2 square_to_uniform_disk(Vec2 u) {
  const Vec2 o = 2.0f * u - Vec2(1.0f);
  if (o.x == 0.0f && o.y == 0.0f) return Vec2(0.0f);
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = (kPi / 4.0f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = kPi / 2.0f - (kPi / 4.0f) * (o.x / o.y);
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

Vec3 square_to_cosine_hemisphere(Vec2 u) {
  const Vec2 d = square_to_uniform_disk(u);
  return {d.x, d.y, safe_sqrt(1.0f - d.x * d.x - d.y * d.y)};
}

Vec3 square_to_uniform_hemisphere(Vec2 u) {
  const float z = u.x;
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 square_to_uniform_sphere(Vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec2 square_to_uniform_triangle(Vec2 u) {
  const float s = std::sqrt(u.x);
  return {1.0f - s, u.y * s};
}

float power_heuristic(float nf, float f_pdf, float ng, float g_pdf) {
  if (std::isinf(f_pdf)) return 1.0f;
  const float f = nf * f_pdf;
  const float g = ng * g_pdf;
  if (f == 0.0f) return 0.0f;
  // Ratio form: stays finite when the squares would overflow.
  const float r = g / f;
  return 1.0f / (1.0f + r * r);
}

}  // namespace prism
