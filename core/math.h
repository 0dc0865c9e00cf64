#pragma once

// Vector math for the whole project: GLM types under project names.
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>

namespace prism {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using DVec3 = glm::dvec3;
using Mat4 = glm::mat4;
using DMat4 = glm::dmat4;
using Rgb = glm::vec3;  ///< linear RGB in the working colour space

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

inline float radians(float degrees) { return degrees * (kPi / 180.0f); }
inline float degrees(float radians) { return radians * (180.0f / kPi); }

inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Largest component of v.
inline float max_component(const Vec3& v) { return glm::max(v.x, glm::max(v.y, v.z)); }
/// Index (0, 1, 2) of the largest component of v.
inline int max_dimension(const Vec3& v) {
  return (v.x >= v.y && v.x >= v.z) ? 0 : (v.y >= v.z ? 1 : 2);
}

}  // namespace prism
