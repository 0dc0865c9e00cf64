#pragma once

#include <cmath>

#include "core/math.h"

namespace prism {

/// An orthonormal basis (s, t, n): the local shading frame in which BSDFs work, with n the
/// local +z axis.
struct Frame {
  Vec3 s{1, 0, 0};
  Vec3 t{0, 1, 0};
  Vec3 n{0, 0, 1};

  /// A frame whose z axis is the unit vector `n`; continuous except where n.z changes sign
  /// (Duff et al., "Building an Orthonormal Basis, Revisited", 2017).
  static Frame from_z(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    Frame f;
    f.s = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.t = Vec3(b, sign + n.y * n.y * a, -n.y);
    f.n = n;
    return f;
  }
  Vec3 to_local(const Vec3& v) const { return {glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)}; }
  Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace prism
