#pragma once

// Vector math for the whole project: GLM types under project names.
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
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

/// |v| per component, each by clearing its sign bit. glm::abs() computes `x >= 0 ? x : -x`,
/// which GCC compiles to a compare and a branch per component; on the signs of surface points
/// and normals those branches mispredict. The same values, except that -0 gives +0.
inline Vec3 abs_components(const Vec3& v) {
  return Vec3(std::abs(v.x), std::abs(v.y), std::abs(v.z));
}

/// Largest component of v.
inline float max_component(const Vec3& v) { return glm::max(v.x, glm::max(v.y, v.z)); }
/// Index (0, 1, 2) of the largest component of v.
inline int max_dimension(const Vec3& v) {
  return (v.x >= v.y && v.x >= v.z) ? 0 : (v.y >= v.z ? 1 : 2);
}

/// std::nextafter(x, +infinity) without the libm call (the hot path of every spawned ray):
/// the same value for every x, NaN, infinities and both zeros included.
inline float next_float_up(float x) {
  if (!(x < kInfinity)) return x;  // +infinity and NaN stay
  if (x == 0.0f) return std::numeric_limits<float>::denorm_min();
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  return std::bit_cast<float>(x > 0.0f ? bits + 1u : bits - 1u);
}

/// std::nextafter(x, -infinity) without the libm call; see next_float_up().
inline float next_float_down(float x) {
  if (!(x > -kInfinity)) return x;  // -infinity and NaN stay
  if (x == 0.0f) return -std::numeric_limits<float>::denorm_min();
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  return std::bit_cast<float>(x > 0.0f ? bits - 1u : bits + 1u);
}

}  // namespace prism
