#pragma once

// A 3-vector in the low lanes of one 128-bit vector register, for the per-component arithmetic
// of hot scalar code (Scene::surface_at()'s error bounds). GCC compiles glm's Vec3 arithmetic to
// one scalar instruction per component and glm::abs() to a compare and a branch per component,
// and its superword vectoriser then shuffles the scalars in and out of vector registers; the
// same arithmetic on Lanes3 is one instruction per operation (docs/PERFORMANCE.md, "surface_at
// in vector lanes"). Every operation is the scalar code's IEEE operation on each lane, so results
// are the same bit for bit (except that the absolute value of -0 is +0). GCC and Clang vector
// extensions: portable to every target either compiler has.

#include <cstdint>

#include "core/math.h"

namespace prism {

/// x, y, z in lanes 0-2; lane 3 is 0 from lanes_of(Vec3) and ignored.
using Lanes3 = float __attribute__((vector_size(16)));

inline Lanes3 lanes_of(const Vec3& v) { return Lanes3{v.x, v.y, v.z, 0.0f}; }
/// s in every lane.
inline Lanes3 lanes_of(float s) { return Lanes3{s, s, s, s}; }
inline Vec3 vec3_of(Lanes3 v) { return Vec3(v[0], v[1], v[2]); }

/// |v| per lane: the sign bits cleared.
inline Lanes3 abs_components(Lanes3 v) {
  using Bits = uint32_t __attribute__((vector_size(16)));
  return reinterpret_cast<Lanes3>(reinterpret_cast<Bits>(v) & 0x7fffffffu);
}
/// Per lane, as glm::min(): b < a ? b : a.
inline Lanes3 component_min(Lanes3 a, Lanes3 b) { return b < a ? b : a; }
/// Per lane, as glm::max() and std::max(): a < b ? b : a.
inline Lanes3 component_max(Lanes3 a, Lanes3 b) { return a < b ? b : a; }
/// The largest of lanes 0-2, as max_component(const Vec3&).
inline float max_component(Lanes3 v) { return glm::max(v[0], glm::max(v[1], v[2])); }

}  // namespace prism
