#pragma once

#include <cstddef>
#include <cstring>

#include "core/lanes3.h"
#include "core/math.h"

namespace prism {

/// A ray origin + t * direction, valid for t in the closed interval [tmin, tmax].
/// direction need not be normalized; t is measured in units of |direction|.
struct Ray {
  Vec3 origin{0.0f};
  float tmin = 0.0f;
  Vec3 direction{0.0f, 0.0f, 1.0f};
  float tmax = kInfinity;

  Vec3 at(float t) const { return origin + t * direction; }
};

/// The ray origin + t * direction for t in [tmin, tmax], written as two 16-byte vectors
/// {origin, tmin} and {direction, tmax}: the halves the wide BVH's set-up loads. Rays built
/// at every vertex (spawn_ray(), camera rays) are built so: a vector load of a ray written field
/// by field waits until those stores reach the cache, as a load that spans several stores cannot
/// take its value from them (store-to-load forwarding).
inline Ray build_ray(const Vec3& origin, const Vec3& direction, float tmin, float tmax) {
  static_assert(offsetof(Ray, tmin) == offsetof(Ray, origin) + 3 * sizeof(float) &&
                offsetof(Ray, direction) == offsetof(Ray, origin) + 4 * sizeof(float) &&
                offsetof(Ray, tmax) == offsetof(Ray, direction) + 3 * sizeof(float) &&
                sizeof(Ray) == 8 * sizeof(float));
  const Lanes3 origin_and_tmin = {origin.x, origin.y, origin.z, tmin};
  const Lanes3 direction_and_tmax = {direction.x, direction.y, direction.z, tmax};
  Ray ray;
  std::memcpy(reinterpret_cast<char*>(&ray) + offsetof(Ray, origin), &origin_and_tmin, 16);
  std::memcpy(reinterpret_cast<char*>(&ray) + offsetof(Ray, direction), &direction_and_tmax, 16);
  return ray;
}

/// The wide BVH's box padding (docs/RELIABILITY.md, "Geometric robustness"): its slab test never
/// rejects a primitive the watertight triangle test or the sphere test would hit, because every
/// box is entered wherever the ray passes within, on every axis,
///     kBoxOriginPaddingUlps u |o| + kBoxCoordinatePaddingUlps u |b| + kBoxSizePaddingUlps u s
/// of it (u = 2^-24, |.| the largest coordinate magnitude): o is the ray's origin, b the box (the
/// tests' rounding grows with the vertices' and the origin's coordinates, the slab test's with
/// the origin's), s the largest extent of a primitive under the box (a triangle's box, a sphere's
/// diameter; the edge functions' rounding grows with it). The collapse widens each stored box by
/// its two terms; the per-ray set-up adds the origin's. So a box near the world origin is
/// padded by its own coordinates and primitives, not by the scene's extent, and
/// Scene::surface_at() starts a ray leaving an axis-aligned triangle beyond its own flat box's
/// padding: a ray leaving a floor does not enter the floor's leaf again.
inline constexpr float kBoxOriginPaddingUlps = 32.0f;
inline constexpr float kBoxCoordinatePaddingUlps = 16.0f;
inline constexpr float kBoxSizePaddingUlps = 24.0f;

}  // namespace prism
