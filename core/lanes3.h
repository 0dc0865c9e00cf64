#pragma once

// A 3-vector in the low lanes of one 128-bit vector register, for the per-component arithmetic
// of hot scalar code (the hit rebuild, Scene::surface_at()). GCC compiles glm's Vec3 arithmetic to
// one scalar instruction per component and glm::abs() to a compare and a branch per component,
// and its superword vectoriser then shuffles the scalars in and out of vector registers; the
// same arithmetic on Lanes3 is one instruction per operation (docs/PERFORMANCE.md, "surface_at
// in vector lanes"). Every operation is the scalar code's IEEE operation on each lane, so results
// are the same bit for bit (except that the absolute value of -0 is +0). GCC and Clang vector
// extensions: portable to every target either compiler has.

#include <cmath>
#include <cstdint>
#if defined(__SSE__)
#include <immintrin.h>
#endif

#include "core/math.h"

namespace prism {

/// x, y, z in lanes 0-2; lane 3 is 0 from lanes_of(Vec3) and ignored.
using Lanes3 = float __attribute__((vector_size(16)));

inline Lanes3 lanes_of(const Vec3& v) { return Lanes3{v.x, v.y, v.z, 0.0f}; }
/// s in every lane.
inline Lanes3 lanes_of(float s) { return Lanes3{s, s, s, s}; }
inline Vec3 vec3_of(Lanes3 v) { return Vec3(v[0], v[1], v[2]); }

/// The same in double precision: four doubles, converted to and from Lanes3 with
/// __builtin_convertvector() (exactly, and rounded to float). Locals only: without AVX, a
/// function that took or returned one would change the ABI (GCC's -Wpsabi).
using DoubleLanes3 = double __attribute__((vector_size(32)));

/// |v| per lane: the sign bits cleared.
inline Lanes3 abs_components(Lanes3 v) {
  using Bits = uint32_t __attribute__((vector_size(16)));
  return reinterpret_cast<Lanes3>(reinterpret_cast<Bits>(v) & 0x7fffffffu);
}
/// Per lane, as glm::min(): b < a ? b : a.
inline Lanes3 component_min(Lanes3 a, Lanes3 b) { return b < a ? b : a; }
/// Per lane, as glm::max() and std::max(): a < b ? b : a.
inline Lanes3 component_max(Lanes3 a, Lanes3 b) { return a < b ? b : a; }
/// As glm::dot(): (x x' + y y') + z z'.
inline float dot(Lanes3 a, Lanes3 b) {
  const Lanes3 products = a * b;
  return (products[0] + products[1]) + products[2];
}
/// As glm::cross(): lane 0 is a.y b.z - b.y a.z, and so on.
inline Lanes3 cross(Lanes3 a, Lanes3 b) {
  const Lanes3 a_yzx = __builtin_shufflevector(a, a, 1, 2, 0, 3);
  const Lanes3 b_yzx = __builtin_shufflevector(b, b, 1, 2, 0, 3);
  const Lanes3 a_zxy = __builtin_shufflevector(a, a, 2, 0, 1, 3);
  const Lanes3 b_zxy = __builtin_shufflevector(b, b, 2, 0, 1, 3);
  return a_yzx * b_zxy - b_yzx * a_zxy;
}

/// The square root of every lane (all four): one instruction where SSE has it.
inline Lanes3 square_roots(Lanes3 v) {
#if defined(__SSE__)
  return reinterpret_cast<Lanes3>(_mm_sqrt_ps(reinterpret_cast<__m128>(v)));
#else
  return Lanes3{std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3])};
#endif
}

/// The largest of lanes 0-2, as max_component(const Vec3&).
inline float max_component(Lanes3 v) { return glm::max(v[0], glm::max(v[1], v[2])); }

}  // namespace prism
