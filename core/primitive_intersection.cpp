#include "core/primitive_intersection.h"

#include <cmath>
#include <utility>

#include "core/angles.h"

namespace prism {

WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin), tmin(ray.tmin), tmax(ray.tmax) {
  const Vec3 abs_dir = abs_components(ray.direction);
  kz = max_dimension(abs_dir);
  kx = (kz + 1) % 3;
  ky = (kx + 1) % 3;
  // Keep the winding of the permuted frame right-handed so edge-function signs are consistent.
  if (ray.direction[kz] < 0.0f) std::swap(kx, ky);
  shear_z = 1.0f / ray.direction[kz];
  shear_x = -ray.direction[kx] * shear_z;
  shear_y = -ray.direction[ky] * shear_z;
}

namespace {

/// The same operations in the same order everywhere (the SIMD kernels repeat them), so every
/// caller gets the same bits.
ShearedTriangle shear(const WatertightRay& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 a = p0 - ray.origin;
  const Vec3 b = p1 - ray.origin;
  const Vec3 c = p2 - ray.origin;
  ShearedTriangle s;
  s.az = a[ray.kz];
  s.bz = b[ray.kz];
  s.cz = c[ray.kz];
  s.ax = a[ray.kx] + ray.shear_x * s.az;
  s.ay = a[ray.ky] + ray.shear_y * s.az;
  s.bx = b[ray.kx] + ray.shear_x * s.bz;
  s.by = b[ray.ky] + ray.shear_y * s.bz;
  s.cx = c[ray.kx] + ray.shear_x * s.cz;
  s.cy = c[ray.ky] + ray.shear_y * s.cz;
  return s;
}

}  // namespace

bool is_degenerate_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const DVec3 e1 = DVec3(p1) - DVec3(p0);
  const DVec3 e2 = DVec3(p2) - DVec3(p0);
  return glm::cross(e1, e2) == DVec3(0.0);
}

std::optional<PrimitiveHit> sheared_triangle_hit(const WatertightRay& ray,
                                                 const ShearedTriangle& s) {
  // Float products of the edge functions cancel badly on long thin triangles seen along their
  // length, and t interpolates vertex depths that differ by the whole length with them: a float
  // t can be off by 1e-4 relative and put the farther of two nearby slivers first. In double the
  // products of floats are exact, so each edge function is rounded once.
  const double e0 = double(s.bx) * double(s.cy) - double(s.by) * double(s.cx);
  const double e1 = double(s.cx) * double(s.ay) - double(s.cy) * double(s.ax);
  const double e2 = double(s.ax) * double(s.by) - double(s.ay) * double(s.bx);
  const double det = e0 + e1 + e2;
  if (det == 0.0) return std::nullopt;
  const double t_scaled =
      (e0 * double(s.az) + e1 * double(s.bz) + e2 * double(s.cz)) * double(ray.shear_z);
  const double inv_det = 1.0 / det;
  const float t = static_cast<float>(t_scaled * inv_det);
  if (!(t >= ray.tmin && t <= ray.tmax)) return std::nullopt;
  return PrimitiveHit{t, static_cast<float>(e1 * inv_det), static_cast<float>(e2 * inv_det)};
}

std::optional<PrimitiveHit> triangle_hit_parameters(const WatertightRay& ray, const Vec3& p0,
                                                    const Vec3& p1, const Vec3& p2) {
  const std::optional<PrimitiveHit> hit = sheared_triangle_hit(ray, shear(ray, p0, p1, p2));
  // Checked last: most candidates fail the interval first.
  if (!hit || is_degenerate_triangle(p0, p1, p2)) return std::nullopt;
  return hit;
}

std::optional<PrimitiveHit> intersect_triangle(const WatertightRay& ray, const Vec3& p0,
                                               const Vec3& p1, const Vec3& p2) {
  const ShearedTriangle s = shear(ray, p0, p1, p2);
  float e0 = s.bx * s.cy - s.by * s.cx;
  float e1 = s.cx * s.ay - s.cy * s.ax;
  float e2 = s.ax * s.by - s.ay * s.bx;
  // Exactly zero edge functions are recomputed in double so that rays through edges and vertices
  // are classified consistently for neighbouring triangles.
  if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
    e0 = static_cast<float>(double(s.bx) * double(s.cy) - double(s.by) * double(s.cx));
    e1 = static_cast<float>(double(s.cx) * double(s.ay) - double(s.cy) * double(s.ax));
    e2 = static_cast<float>(double(s.ax) * double(s.by) - double(s.ay) * double(s.bx));
  }
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) {
    return std::nullopt;
  }
  if (e0 + e1 + e2 == 0.0f) return std::nullopt;
  return triangle_hit_parameters(ray, p0, p1, p2);
}

namespace sphere_test {
#include "core/sphere_test_body.h"
}  // namespace sphere_test

std::optional<float> intersect_sphere_t(const Ray& ray, const Vec3& center, float radius) {
  float t;
  if (!sphere_test::sphere_hit_t(ray, center, radius, t)) return std::nullopt;
  return t;
}

Vec2 sphere_hit_uv(const Ray& ray, float t, const Vec3& center) {
  const Vec3 local = ray.at(t) - center;
  // phi = atan2(y, x) in [0, 2 pi), theta = the angle from +z, by the polynomial atan2 (libm's
  // atan2f and acosf cost 2% of a render of CBspheres).
  const float half_turn = atan2_nonnegative_y(std::abs(local.y), local.x);
  const float phi = local.y < 0.0f ? 2.0f * kPi - half_turn : half_turn;
  const float theta =
      atan2_nonnegative_y(std::sqrt(local.x * local.x + local.y * local.y), local.z);
  return {phi / (2.0f * kPi), theta / kPi};
}

std::optional<PrimitiveHit> intersect_sphere(const Ray& ray, const Vec3& center, float radius) {
  const std::optional<float> t = intersect_sphere_t(ray, center, radius);
  if (!t) return std::nullopt;
  const Vec2 uv = sphere_hit_uv(ray, *t, center);
  return PrimitiveHit{*t, uv.x, uv.y};
}

}  // namespace prism
