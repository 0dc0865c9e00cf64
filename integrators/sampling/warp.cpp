#include "integrators/sampling/warp.h"

#include "core/angles.h"

namespace prism {

namespace {

/// {cos x, sin x} for |x| <= pi / 4, where the concentric map needs them: Taylor polynomials to
/// x^10 and x^9, whose truncation error there (below 3e-8 and 3e-9) is under float's rounding.
/// About a third of the cost of libm's sincosf, which must reduce any argument.
Vec2 cos_sin_quarter_turn(float x) {
  const float x2 = x * x;
  const float s =
      x * (1.0f + x2 * (-1.0f / 6.0f +
                        x2 * (1.0f / 120.0f + x2 * (-1.0f / 5040.0f + x2 * (1.0f / 362880.0f)))));
  const float c =
      1.0f +
      x2 * (-0.5f + x2 * (1.0f / 24.0f + x2 * (-1.0f / 720.0f + x2 * (1.0f / 40320.0f +
                                                                      x2 * (-1.0f / 3628800.0f)))));
  return {c, s};
}

/// Shirley and Chiu's concentric map of u in [0,1)^2 to the unit disk, with the point's signed
/// radius (its distance from the centre, up to sign), which the map knows before the point: the
/// angle is pi / 4 * o.y / o.x from the x axis in the wedges around it (radius o.x), pi / 2 -
/// pi / 4 * o.x / o.y in those around the y axis (radius o.y; the cosine and sine are then the
/// sine and cosine of pi / 4 * o.x / o.y). The wedge is chosen by selects, not a branch: it
/// depends on the sample value alone, which the processor cannot predict.
struct ConcentricPoint {
  Vec2 point;
  float radius;
};

ConcentricPoint concentric_map(Vec2 u) {
  const Vec2 o = 2.0f * u - Vec2(1.0f);
  const bool around_x = std::abs(o.x) > std::abs(o.y);
  const float radius = around_x ? o.x : o.y;
  const float across = around_x ? o.y : o.x;
  if (radius == 0.0f) return {Vec2(0.0f), 0.0f};  // the centre: o.x = o.y = 0
  const Vec2 cs = cos_sin_quarter_turn((kPi / 4.0f) * (across / radius));
  return {radius * (around_x ? cs : Vec2(cs.y, cs.x)), radius};
}

}  // namespace

Vec2 square_to_uniform_disk(Vec2 u) { return concentric_map(u).point; }

Vec3 square_to_cosine_hemisphere(Vec2 u) {
  // The height from the radius, not from the point's coordinates: its square root then runs
  // beside the division and the polynomials instead of after them.
  const ConcentricPoint c = concentric_map(u);
  return {c.point.x, c.point.y, safe_sqrt(1.0f - c.radius * c.radius)};
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

float triangle_solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const float la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const float numerator = std::abs(glm::dot(a, glm::cross(b, c)));
  const float denominator =
      la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  const float omega = 2.0f * atan2_nonnegative_y(numerator, denominator);
  return std::isfinite(omega) && omega > 0.0f ? omega : 0.0f;
}

std::optional<Vec3> sample_spherical_triangle(const Vec3& a, const Vec3& b, const Vec3& c,
                                              float solid_angle, Vec2 u) {
  // Arvo's notation: alpha is the angle of the spherical triangle at a, and cos(c) the cosine
  // of the arc from a to b. A sub-triangle (a, b, c') of area u.x * solid_angle is found
  // first, then a point on the arc from b to c', with the cosine of its distance to b uniform.
  const Vec3 n_ab = glm::cross(a, b), n_ac = glm::cross(a, c);
  const float l_ab = glm::length(n_ab), l_ac = glm::length(n_ac);
  if (!(l_ab > 0.0f) || !(l_ac > 0.0f)) return std::nullopt;
  const float cos_alpha = std::clamp(glm::dot(n_ab, n_ac) / (l_ab * l_ac), -1.0f, 1.0f);
  const float sin_alpha = safe_sqrt(1.0f - cos_alpha * cos_alpha);
  // s and t are the sine and cosine of phi = u.x * solid_angle - alpha, by the angle
  // difference formulas: alpha's own are known, so one sincos instead of acos, sin and cos.
  const float area_sample = u.x * solid_angle;
  const float sin_area = std::sin(area_sample), cos_area = std::cos(area_sample);
  const float s = sin_area * cos_alpha - cos_area * sin_alpha;
  const float t = cos_area * cos_alpha + sin_area * sin_alpha;
  const float uu = t - cos_alpha;
  const float vv = s + sin_alpha * glm::dot(a, b);
  const float q = ((vv * t - uu * s) * cos_alpha - vv) / ((vv * s + uu * t) * sin_alpha);
  if (!std::isfinite(q)) return std::nullopt;
  const float cos_bp = std::clamp(q, -1.0f, 1.0f);
  const Vec3 c_perp = c - glm::dot(c, a) * a;
  const float l_c_perp = glm::length(c_perp);
  if (!(l_c_perp > 0.0f)) return std::nullopt;
  const Vec3 c_prime = cos_bp * a + (safe_sqrt(1.0f - cos_bp * cos_bp) / l_c_perp) * c_perp;
  const float z = 1.0f - u.y * (1.0f - glm::dot(c_prime, b));
  const Vec3 cp_perp = c_prime - glm::dot(c_prime, b) * b;
  const float l_cp_perp = glm::length(cp_perp);
  if (!(l_cp_perp > 0.0f)) return b;
  const Vec3 w = z * b + (safe_sqrt(1.0f - z * z) / l_cp_perp) * cp_perp;
  const float lw = glm::length(w);
  if (!(lw > 0.0f) || !std::isfinite(lw)) return std::nullopt;
  return w * (1.0f / lw);
}

}  // namespace prism
