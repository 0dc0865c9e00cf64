// core/lanes3.h: the 3-vector in vector lanes that Scene::surface_at() computes with gives glm's
// Vec3 results bit for bit (its callers' images must not change with it), on random values of
// every magnitude and sign, zeros included.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/lanes3.h"
#include "core/scene_geometry.h"

namespace prism {
namespace {

uint32_t bits_of(float x) { return std::bit_cast<uint32_t>(x); }

void expect_same_bits(const Vec3& lanes, const Vec3& glm_result, const char* what) {
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(bits_of(lanes[k]), bits_of(glm_result[k])) << what << " component " << k;
  }
}

/// Random finite floats: mostly of everyday magnitudes, some tiny or huge, some zeros of
/// either sign.
std::vector<Vec3> random_vectors(size_t count) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-40, 40);
  std::vector<Vec3> out;
  for (size_t i = 0; i < count; ++i) {
    Vec3 v;
    for (int k = 0; k < 3; ++k) {
      const int kind = int(rng() % 8);
      v[k] = kind == 0   ? 0.0f
             : kind == 1 ? -0.0f
                         : unit(rng) * std::ldexp(1.0f, kind == 2 ? exponent(rng) : 0);
    }
    out.push_back(v);
  }
  return out;
}

TEST(CoreLanes3, ArithmeticIsGlmsBitForBit) {
  const std::vector<Vec3> v = random_vectors(30000);
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    const Vec3 &a = v[i], &b = v[i + 1], &c = v[i + 2];
    const Lanes3 la = lanes_of(a), lb = lanes_of(b), lc = lanes_of(c);
    expect_same_bits(vec3_of(cross(la, lb)), glm::cross(a, b), "cross");
    ASSERT_EQ(bits_of(dot(la, lb)), bits_of(glm::dot(a, b))) << "dot";
    expect_same_bits(vec3_of(component_min(la, lb)), glm::min(a, b), "min");
    expect_same_bits(vec3_of(component_max(la, lb)), glm::max(a, b), "max");
    ASSERT_EQ(bits_of(max_component(la)), bits_of(max_component(a))) << "max_component";
    expect_same_bits(vec3_of(triangle_extent(la, lb, lc)),
                     glm::max(a, glm::max(b, c)) - glm::min(a, glm::min(b, c)), "extent");
    expect_same_bits(vec3_of(lanes_of(a.x) * lb + lc / lanes_of(2.5f)), a.x * b + c / 2.5f,
                     "scaled sum");
    // The absolute value is glm's except for the sign of a zero.
    const Vec3 abs_glm = glm::abs(a) + Vec3(0.0f);  // -0 + 0 = +0
    expect_same_bits(vec3_of(abs_components(la)), abs_glm, "abs");
    expect_same_bits(abs_components(a), abs_glm, "abs of Vec3");
  }
}

TEST(CoreLanes3, DoubleLanesRoundLikeGlmsDoubleVectors) {
  const std::vector<Vec3> v = random_vectors(30000);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> barycentric(0.0f, 1.0f);
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    const Vec3 &a = v[i], &b = v[i + 1], &c = v[i + 2];
    const double u = barycentric(rng), w = barycentric(rng);
    const DVec3 d0(a);
    const Vec3 expected(d0 + u * (DVec3(b) - d0) + w * (DVec3(c) - d0));
    const DoubleLanes3 da = __builtin_convertvector(lanes_of(a), DoubleLanes3);
    const DoubleLanes3 db = __builtin_convertvector(lanes_of(b), DoubleLanes3);
    const DoubleLanes3 dc = __builtin_convertvector(lanes_of(c), DoubleLanes3);
    const Lanes3 point = __builtin_convertvector(da + u * (db - da) + w * (dc - da), Lanes3);
    expect_same_bits(vec3_of(point), expected, "point");
  }
}

TEST(CoreLanes3, SquareRootsAreStdSqrtInEveryLane) {
  const std::vector<Vec3> v = random_vectors(3000);
  for (size_t i = 0; i + 1 < v.size(); ++i) {
    const Lanes3 x = abs_components(Lanes3{v[i].x, v[i].y, v[i].z, v[i + 1].x});
    const Lanes3 r = square_roots(x);
    for (int k = 0; k < 4; ++k) ASSERT_EQ(bits_of(r[k]), bits_of(std::sqrt(x[k]))) << "lane " << k;
  }
}

}  // namespace
}  // namespace prism
