#pragma once

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

/// How far the wide BVH pads every box, in units of 2^-24 times the larger of the ray origin's and
/// the scene's largest coordinate magnitude (accel/bvh/wide_kernel_common.h): the slab test then
/// never rejects a triangle the watertight test would hit. Scene::surface_at() moves the origins
/// of rays leaving large flat triangles past it where that is cheap (docs/RELIABILITY.md).
inline constexpr float kBoxPaddingUlps = 32.0f;

}  // namespace prism
