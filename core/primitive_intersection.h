#pragma once

// The ray-primitive tests shared by every backend that does its own traversal (brute, bvh) and
// by Embree's user geometry for spheres, so backends can differ only in traversal.

#include <optional>

#include "core/math.h"
#include "core/ray.h"

namespace prism {

/// Parametric hit on one primitive: t along the ray, (u, v) as Hit defines them.
struct PrimitiveHit {
  float t, u, v;
};

/// Per-ray constants of the watertight triangle test (Woop, Benthin, Wald 2013): the axis
/// permutation that makes the direction's largest component z, and the shear that maps the
/// direction to +z.
struct WatertightRay {
  explicit WatertightRay(const Ray& ray);
  /// Fields to be filled by a caller that computed them with the same operations (the SIMD
  /// kernels' per-ray setup).
  WatertightRay() = default;

  Vec3 origin;
  int kx, ky, kz;
  float shear_x, shear_y, shear_z;
  float tmin, tmax;
};

/// Watertight ray/triangle test: a ray through a shared edge or vertex hits at least one of the
/// triangles sharing it. Both faces count; a triangle whose vertices are collinear or coincide
/// is never hit. Returns the hit with t in [tmin, tmax], u, v in Embree's convention
/// (p = (1-u-v) p0 + u p1 + v p2), or nothing. The hit decision uses the float edge functions
/// (exact zeros re-decided in double); t, u, v come from triangle_hit_parameters().
std::optional<PrimitiveHit> intersect_triangle(const WatertightRay& ray, const Vec3& p0,
                                               const Vec3& p1, const Vec3& p2);

/// The vertices relative to the ray origin in the ray's sheared frame, as intersect_triangle()
/// computes them: (x, y) across the ray, z along its permuted axis.
struct ShearedTriangle {
  float ax, ay, az, bx, by, bz, cx, cy, cz;
};

/// t, u, v of a sheared triangle (see triangle_hit_parameters()), without the degenerate-triangle
/// check: nothing when the double determinant is zero or t is outside [ray.tmin, ray.tmax].
std::optional<PrimitiveHit> sheared_triangle_hit(const WatertightRay& ray,
                                                 const ShearedTriangle& s);

/// Whether the triangle's vertices are collinear or coincide, exactly (its cross product in
/// double is zero): such a triangle has no area and is never hit.
bool is_degenerate_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2);

/// The second half of intersect_triangle(), for callers that made the hit decision themselves
/// with the same float operations (the SIMD kernels): t, u, v from the edge functions evaluated
/// in double precision on the float sheared vertices, so that t is accurate even on long slivers
/// seen along their length; nothing when the triangle is degenerate, the double determinant is
/// zero or t is outside [tmin, tmax].
std::optional<PrimitiveHit> triangle_hit_parameters(const WatertightRay& ray, const Vec3& p0,
                                                    const Vec3& p1, const Vec3& p2);

/// Ray/sphere test: the nearest root of |o + t d - c| = r with t in [tmin, tmax] (the far root
/// when the near one is outside the interval). u = phi / 2pi, v = theta / pi of the hit point
/// about the centre (z is the pole axis).
std::optional<PrimitiveHit> intersect_sphere(const Ray& ray, const Vec3& center, float radius);
/// The t of intersect_sphere() alone (what any-hit queries need): no trigonometry for u, v.
std::optional<float> intersect_sphere_t(const Ray& ray, const Vec3& center, float radius);
/// The u, v intersect_sphere() reports for its hit at `t` on a sphere about `center` (the angles
/// of the hit point's direction from it, whatever the radius).
Vec2 sphere_hit_uv(const Ray& ray, float t, const Vec3& center);

}  // namespace prism
