#include "core/primitive_intersection.h"

#include <cmath>
#include <utility>

namespace prism {

WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin), tmin(ray.tmin), tmax(ray.tmax) {
  const Vec3 abs_dir = glm::abs(ray.direction);
  kz = max_dimension(abs_dir);
  kx = (kz + 1) % 3;
  ky = (kx + 1) % 3;
  // Keep the winding of the permuted frame right-handed so edge-function signs are consistent.
  if (ray.direction[kz] < 0.0f) std::swap(kx, ky);
  shear_z = 1.0f / ray.direction[kz];
  shear_x = -ray.direction[kx] * shear_z;
  shear_y = -ray.direction[ky] * shear_z;
}

std::optional<PrimitiveHit> intersect_triangle(const WatertightRay& ray, const Vec3& p0,
                                               const Vec3& p1, const Vec3& p2) {
  const Vec3 a = p0 - ray.origin;
  const Vec3 b = p1 - ray.origin;
  const Vec3 c = p2 - ray.origin;
  const float az = a[ray.kz], bz = b[ray.kz], cz = c[ray.kz];
  const float ax = a[ray.kx] + ray.shear_x * az;
  const float ay = a[ray.ky] + ray.shear_y * az;
  const float bx = b[ray.kx] + ray.shear_x * bz;
  const float by = b[ray.ky] + ray.shear_y * bz;
  const float cx = c[ray.kx] + ray.shear_x * cz;
  const float cy = c[ray.ky] + ray.shear_y * cz;

  float e0 = bx * cy - by * cx;
  float e1 = cx * ay - cy * ax;
  float e2 = ax * by - ay * bx;
  // Exactly zero edge functions are recomputed in double so that rays through edges and vertices
  // are classified consistently for neighbouring triangles.
  if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
    e0 = static_cast<float>(double(bx) * double(cy) - double(by) * double(cx));
    e1 = static_cast<float>(double(cx) * double(ay) - double(cy) * double(ax));
    e2 = static_cast<float>(double(ax) * double(by) - double(ay) * double(bx));
  }
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) {
    return std::nullopt;
  }
  const float det = e0 + e1 + e2;
  if (det == 0.0f) return std::nullopt;

  const float t_scaled = (e0 * az + e1 * bz + e2 * cz) * ray.shear_z;
  const float inv_det = 1.0f / det;
  const float t = t_scaled * inv_det;
  if (!(t >= ray.tmin && t <= ray.tmax)) return std::nullopt;
  return PrimitiveHit{t, e1 * inv_det, e2 * inv_det};
}

std::optional<PrimitiveHit> intersect_sphere(const Ray& ray, const Vec3& center, float radius) {
  const Vec3 f = ray.origin - center;
  const Vec3& d = ray.direction;
  const float a = glm::dot(d, d);
  const float half_b = glm::dot(f, d);
  const float c = glm::dot(f, f) - radius * radius;
  // Discriminant in the form that does not cancel for distant spheres (Ray Tracing Gems, ch. 7).
  const Vec3 l = f - (half_b / a) * d;
  const float disc = a * (radius * radius - glm::dot(l, l));
  if (!(disc >= 0.0f)) return std::nullopt;
  const float q = -half_b - std::copysign(std::sqrt(disc), half_b);
  float t0 = c / q;
  float t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  float t;
  if (t0 >= ray.tmin && t0 <= ray.tmax) {
    t = t0;
  } else if (t1 >= ray.tmin && t1 <= ray.tmax) {
    t = t1;
  } else {
    return std::nullopt;
  }
  const Vec3 local = ray.at(t) - center;
  float phi = std::atan2(local.y, local.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  const float cos_theta = glm::clamp(local.z / radius, -1.0f, 1.0f);
  return PrimitiveHit{t, phi / (2.0f * kPi), std::acos(cos_theta) / kPi};
}

}  // namespace prism
