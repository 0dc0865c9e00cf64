#pragma once

#include "core/math.h"

namespace prism {

/// Axis-aligned box. Default-constructed boxes are empty (lower > upper) and absorb any point.
struct Bounds3 {
  Vec3 lower{kInfinity};
  Vec3 upper{-kInfinity};

  bool empty() const { return lower.x > upper.x || lower.y > upper.y || lower.z > upper.z; }
  void extend(const Vec3& p) {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  void extend(const Bounds3& b) {
    lower = glm::min(lower, b.lower);
    upper = glm::max(upper, b.upper);
  }
  Vec3 center() const { return 0.5f * (lower + upper); }
  Vec3 diagonal() const { return upper - lower; }
  /// Surface area; 0 for an empty box.
  float area() const {
    if (empty()) return 0.0f;
    const Vec3 d = diagonal();
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
  }
};

}  // namespace prism
