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

}  // namespace prism
