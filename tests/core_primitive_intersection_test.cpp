// core/primitive_intersection.h: the watertight ray/triangle test and the ray/sphere test
// shared by the backends, against hand computations. offset_ray_origin (core/scene.h) is tested
// in core_spawn_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "core/primitive_intersection.h"

namespace prism {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Ray make_ray(Vec3 origin, Vec3 direction, float tmin = 0.0f, float tmax = kInf) {
  Ray r;
  r.origin = origin;
  r.direction = direction;
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

std::optional<PrimitiveHit> triangle_hit(const Ray& ray, Vec3 p0, Vec3 p1, Vec3 p2) {
  return intersect_triangle(WatertightRay(ray), p0, p1, p2);
}

Vec3 barycentric_point(Vec3 p0, Vec3 p1, Vec3 p2, float u, float v) {
  return (1.0f - u - v) * p0 + u * p1 + v * p2;
}

Vec3 random_point(std::mt19937& rng, float extent) {
  std::uniform_real_distribution<float> u(-extent, extent);
  const float x = u(rng), y = u(rng), z = u(rng);
  return Vec3(x, y, z);
}

// The right triangle (0,0,3), (2,0,3), (0,2,3) in the plane z = 3.
const Vec3 kP0(0.0f, 0.0f, 3.0f), kP1(2.0f, 0.0f, 3.0f), kP2(0.0f, 2.0f, 3.0f);

TEST(CorePrimitiveIntersection, TriangleHitHasHandComputedTAndBarycentrics) {
  // (0.5, 0.25, 3) = (1-u-v) p0 + u p1 + v p2 with u = 0.5/2, v = 0.25/2.
  const auto hit = triangle_hit(make_ray({0.5f, 0.25f, 0.0f}, {0, 0, 1}), kP0, kP1, kP2);
  ASSERT_TRUE(hit);
  EXPECT_FLOAT_EQ(hit->t, 3.0f);
  EXPECT_FLOAT_EQ(hit->u, 0.25f);
  EXPECT_FLOAT_EQ(hit->v, 0.125f);

  // The centroid of (1,0,0), (0,1,0), (0,0,1) from the origin: t is in units of |direction|.
  const Vec3 a(1, 0, 0), b(0, 1, 0), c(0, 0, 1);
  const auto unit = triangle_hit(make_ray(Vec3(0.0f), Vec3(1.0f)), a, b, c);
  ASSERT_TRUE(unit);
  EXPECT_NEAR(unit->t, 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(unit->u, 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(unit->v, 1.0f / 3.0f, 1e-6f);
  const auto doubled = triangle_hit(make_ray(Vec3(0.0f), Vec3(2.0f)), a, b, c);
  ASSERT_TRUE(doubled);
  EXPECT_NEAR(doubled->t, 1.0f / 6.0f, 1e-6f);

  // Near the vertices, u and v say which: p1 is u = 1, p2 is v = 1.
  const auto near_p1 = triangle_hit(make_ray({1.9f, 0.05f, 0.0f}, {0, 0, 1}), kP0, kP1, kP2);
  ASSERT_TRUE(near_p1);
  EXPECT_NEAR(near_p1->u, 0.95f, 1e-6f);
  EXPECT_NEAR(near_p1->v, 0.025f, 1e-6f);
  const auto near_p2 = triangle_hit(make_ray({0.05f, 1.9f, 0.0f}, {0, 0, 1}), kP0, kP1, kP2);
  ASSERT_TRUE(near_p2);
  EXPECT_NEAR(near_p2->u, 0.025f, 1e-6f);
  EXPECT_NEAR(near_p2->v, 0.95f, 1e-6f);
}

TEST(CorePrimitiveIntersection, RandomTrianglesHitAtTheChosenBarycentrics) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int tested = 0;
  while (tested < 2000) {
    const Vec3 p0 = random_point(rng, 5.0f), p1 = random_point(rng, 5.0f),
               p2 = random_point(rng, 5.0f);
    const Vec3 n = glm::cross(p1 - p0, p2 - p0);
    if (glm::length(n) < 1.0f) continue;
    // A point with every barycentric coordinate at least 0.02.
    float u = unit(rng), v = unit(rng);
    if (u + v > 1.0f) {
      u = 1.0f - u;
      v = 1.0f - v;
    }
    if (std::min({u, v, 1.0f - u - v}) < 0.02f) continue;
    const Vec3 target = barycentric_point(p0, p1, p2, u, v);
    const Vec3 origin = random_point(rng, 10.0f);
    const float scale = 0.5f + 1.5f * unit(rng);
    const Vec3 direction = (target - origin) * scale;
    // Skip grazing rays, whose t is ill-conditioned.
    if (std::abs(glm::dot(glm::normalize(direction), glm::normalize(n))) < 0.1f) continue;
    ++tested;
    const auto hit = triangle_hit(make_ray(origin, direction), p0, p1, p2);
    ASSERT_TRUE(hit) << "triangle " << tested;
    EXPECT_NEAR(hit->t, 1.0f / scale, 1e-4f / scale);
    EXPECT_NEAR(hit->u, u, 1e-4f);
    EXPECT_NEAR(hit->v, v, 1e-4f);
  }
}

TEST(CorePrimitiveIntersection, RaysOutsideTheTriangleMiss) {
  for (const Vec3 xy : {Vec3(1.5f, 1.5f, 0), Vec3(-0.1f, 0.5f, 0), Vec3(0.5f, -0.1f, 0),
                        Vec3(2.1f, 0.0f, 0), Vec3(1.01f, 1.01f, 0), Vec3(-1, -1, 0)}) {
    EXPECT_FALSE(triangle_hit(make_ray(xy, {0, 0, 1}), kP0, kP1, kP2)) << xy.x << "," << xy.y;
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-2.0f, 3.0f);
  int tested = 0;
  while (tested < 2000) {
    const Vec3 p0 = random_point(rng, 5.0f), p1 = random_point(rng, 5.0f),
               p2 = random_point(rng, 5.0f);
    const Vec3 n = glm::cross(p1 - p0, p2 - p0);
    if (glm::length(n) < 1.0f) continue;
    const float u = unit(rng), v = unit(rng);
    if (std::min({u, v, 1.0f - u - v}) > -0.02f) continue;  // inside or close to an edge
    const Vec3 target = barycentric_point(p0, p1, p2, u, v);
    const Vec3 origin = random_point(rng, 10.0f);
    if (std::abs(glm::dot(glm::normalize(target - origin), glm::normalize(n))) < 0.1f) continue;
    ++tested;
    EXPECT_FALSE(triangle_hit(make_ray(origin, target - origin), p0, p1, p2))
        << "u " << u << " v " << v;
  }
}

TEST(CorePrimitiveIntersection, BothFacesOfATriangleCount) {
  // From below (+z) and from above (-z), and with the winding reversed (u and v swap roles).
  const Ray up = make_ray({0.5f, 0.25f, 0.0f}, {0, 0, 1});
  const Ray down = make_ray({0.5f, 0.25f, 6.0f}, {0, 0, -1});
  for (const Ray& ray : {up, down}) {
    const auto hit = triangle_hit(ray, kP0, kP1, kP2);
    ASSERT_TRUE(hit);
    EXPECT_FLOAT_EQ(hit->t, 3.0f);
    EXPECT_FLOAT_EQ(hit->u, 0.25f);
    EXPECT_FLOAT_EQ(hit->v, 0.125f);
    const auto reversed = triangle_hit(ray, kP0, kP2, kP1);
    ASSERT_TRUE(reversed);
    EXPECT_FLOAT_EQ(reversed->t, 3.0f);
    EXPECT_FLOAT_EQ(reversed->u, 0.125f);
    EXPECT_FLOAT_EQ(reversed->v, 0.25f);
  }
}

TEST(CorePrimitiveIntersection, TriangleIntervalIsClosed) {
  const Vec3 origin(0.5f, 0.25f, 0.0f), dir(0, 0, 1);
  const auto free_hit = triangle_hit(make_ray(origin, dir), kP0, kP1, kP2);
  ASSERT_TRUE(free_hit);
  const float t = free_hit->t;
  EXPECT_FLOAT_EQ(t, 3.0f);
  const float above = std::nextafter(t, kInf), below = std::nextafter(t, 0.0f);
  EXPECT_TRUE(triangle_hit(make_ray(origin, dir, t, kInf), kP0, kP1, kP2));
  EXPECT_TRUE(triangle_hit(make_ray(origin, dir, 0.0f, t), kP0, kP1, kP2));
  EXPECT_TRUE(triangle_hit(make_ray(origin, dir, t, t), kP0, kP1, kP2));
  EXPECT_FALSE(triangle_hit(make_ray(origin, dir, above, kInf), kP0, kP1, kP2));
  EXPECT_FALSE(triangle_hit(make_ray(origin, dir, 0.0f, below), kP0, kP1, kP2));
  // Behind the origin: outside [0, inf), inside [-10, inf).
  const Vec3 past(0.5f, 0.25f, 5.0f);
  EXPECT_FALSE(triangle_hit(make_ray(past, dir), kP0, kP1, kP2));
  const auto behind = triangle_hit(make_ray(past, dir, -10.0f, kInf), kP0, kP1, kP2);
  ASSERT_TRUE(behind);
  EXPECT_FLOAT_EQ(behind->t, -2.0f);
}

/// Counts rays from random origins through points near the segment a-b (offset across it by
/// `offsets` times `across`) that hit none of `triangles`.
int misses_near_segment(const std::vector<std::array<Vec3, 3>>& triangles, Vec3 a, Vec3 b,
                        Vec3 across, uint32_t seed, int rays) {
  const std::vector<float> offsets{0.0f, 1e-7f, -1e-7f, 1e-6f, -1e-6f};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int misses = 0;
  for (int i = 0; i < rays; ++i) {
    // Away from the segment's ends, where the offsets could leave the covered region.
    const float s = 0.01f + 0.98f * unit(rng);
    const Vec3 on_edge = a + s * (b - a);
    Vec3 origin = random_point(rng, 10.0f);
    origin.z = -10.0f + unit(rng);  // below the (roughly z = 5) surface
    for (const float offset : offsets) {
      const Vec3 target = on_edge + offset * across;
      const Ray ray = make_ray(origin, target - origin);
      bool any = false;
      for (const auto& t : triangles) any = any || triangle_hit(ray, t[0], t[1], t[2]).has_value();
      misses += !any;
    }
  }
  return misses;
}

TEST(CorePrimitiveIntersection, RaysThroughASharedEdgeHitAtLeastOneTriangle) {
  // A non-planar quad a-b-c-d split along a-c, both triangles wound the same way.
  const Vec3 a(-1.0f, -1.1f, 5.0f), b(1.3f, -0.7f, 5.2f), c(0.9f, 1.1f, 4.7f), d(-1.2f, 0.8f, 5.1f);
  const std::vector<std::array<Vec3, 3>> quad{{a, b, c}, {a, c, d}};
  const Vec3 across = glm::normalize(glm::cross(c - a, Vec3(0, 0, 1)));
  EXPECT_EQ(misses_near_segment(quad, a, c, across, 21, 4000), 0);

  // Away from the edge, exactly one triangle is hit, the one on that side.
  const Vec3 mid = 0.5f * (a + c);
  const Vec3 origin(0.1f, 0.2f, -5.0f);
  const Ray to_b_side = make_ray(origin, mid + 0.05f * glm::normalize(b - mid) - origin);
  EXPECT_TRUE(triangle_hit(to_b_side, a, b, c));
  EXPECT_FALSE(triangle_hit(to_b_side, a, c, d));
  const Ray to_d_side = make_ray(origin, mid + 0.05f * glm::normalize(d - mid) - origin);
  EXPECT_FALSE(triangle_hit(to_d_side, a, b, c));
  EXPECT_TRUE(triangle_hit(to_d_side, a, c, d));
}

TEST(CorePrimitiveIntersection, AxisAlignedRaysExactlyOnAnEdgeHitAtLeastOneTriangle) {
  // The edge x = 0 of two triangles in z = 5: the edge functions are exactly zero.
  const Vec3 top(0.0f, 1.0f, 5.0f), bottom(0.0f, -1.0f, 5.0f), left(-1.0f, 0.0f, 5.0f),
      right(1.0f, 0.0f, 5.0f);
  int misses = 0;
  for (int i = 1; i < 100; ++i) {
    const float y = -1.0f + 2.0f * float(i) / 100.0f;
    for (const float dz : {1.0f, -1.0f}) {
      const Ray ray = make_ray({0.0f, y, dz > 0 ? 0.0f : 10.0f}, {0.0f, 0.0f, dz});
      const bool any =
          triangle_hit(ray, bottom, right, top) || triangle_hit(ray, bottom, top, left);
      misses += !any;
    }
  }
  EXPECT_EQ(misses, 0);
  // The shared vertices, along each axis direction that sees them.
  for (const Vec3 vertex : {top, bottom}) {
    const Ray ray = make_ray(vertex - Vec3(0, 0, 5), {0, 0, 1});
    EXPECT_TRUE(triangle_hit(ray, bottom, right, top) || triangle_hit(ray, bottom, top, left));
  }
}

TEST(CorePrimitiveIntersection, RaysThroughASharedVertexHitAtLeastOneTriangle) {
  // A closed fan of 7 triangles around an inexact centre; rays aim at the centre and along the
  // spokes.
  const Vec3 centre(0.1f, 0.2f, 5.0f);
  std::vector<Vec3> ring;
  for (int k = 0; k < 7; ++k) {
    const float phi = 2.0f * kPi * float(k) / 7.0f + 0.3f;
    ring.push_back(centre + Vec3(std::cos(phi), std::sin(phi), 0.2f * std::sin(3.0f * phi)));
  }
  std::vector<std::array<Vec3, 3>> fan;
  for (int k = 0; k < 7; ++k) fan.push_back({centre, ring[k], ring[(k + 1) % 7]});

  std::mt19937 rng(5);
  int misses = 0;
  for (int i = 0; i < 2000; ++i) {
    Vec3 origin = random_point(rng, 10.0f);
    origin.z = -5.0f;
    const Ray ray = make_ray(origin, centre - origin);
    bool any = false;
    for (const auto& t : fan) any = any || triangle_hit(ray, t[0], t[1], t[2]).has_value();
    misses += !any;
  }
  EXPECT_EQ(misses, 0);
  for (int k = 0; k < 7; ++k) {
    const Vec3 spoke = ring[k] - centre;
    const Vec3 across = glm::normalize(glm::cross(spoke, Vec3(0, 0, 1)));
    EXPECT_EQ(misses_near_segment(fan, centre, ring[k], across, 100 + k, 300), 0) << "spoke " << k;
  }
}

TEST(CorePrimitiveIntersection, DegenerateTrianglesAreNeverHit) {
  // Repeated corners: the determinant is exactly zero from any direction.
  const std::vector<std::array<Vec3, 3>> repeated{
      {Vec3(0, 0, 3), Vec3(0, 0, 3), Vec3(1, 0, 3)},
      {Vec3(0.3f, -0.2f, 2.5f), Vec3(1.7f, 0.4f, 3.1f), Vec3(1.7f, 0.4f, 3.1f)},
      {Vec3(1, 1, 3), Vec3(1, 1, 3), Vec3(1, 1, 3)},
      {Vec3(0.1f, 0.3f, 1.7f), Vec3(0.1f, 0.3f, 1.7f), Vec3(0.1f, 0.3f, 1.7f)},
  };
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int hits = 0, rays = 0;
  for (const auto& t : repeated) {
    for (int i = 0; i < 500; ++i) {
      // Through a point of the degenerate triangle, from anywhere.
      float u = unit(rng), v = unit(rng);
      if (u + v > 1.0f) {
        u = 1.0f - u;
        v = 1.0f - v;
      }
      const Vec3 target = barycentric_point(t[0], t[1], t[2], u, v);
      const Vec3 origin = random_point(rng, 10.0f);
      hits += triangle_hit(make_ray(origin, target - origin), t[0], t[1], t[2]).has_value();
      ++rays;
    }
  }
  // Distinct collinear corners, along the axes and from anywhere: the shear rounds the projected
  // corners off their common line, but the test rejects a triangle whose cross product is zero.
  const std::vector<std::array<Vec3, 3>> collinear{
      {Vec3(0, 0, 3), Vec3(1, 1, 3), Vec3(2, 2, 3)},
      {Vec3(0, 0, 3), Vec3(2, 2, 3), Vec3(1, 1, 3)},
      {Vec3(0, 0, 2), Vec3(1, 1, 3), Vec3(2, 2, 4)},
  };
  for (const auto& t : collinear) {
    for (int i = 0; i <= 16; ++i) {
      const Vec3 target = t[0] + (float(i) / 8.0f) * (t[1] - t[0]);
      for (const Vec3 dir : {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, -1)}) {
        hits += triangle_hit(make_ray(target - 5.0f * dir, dir), t[0], t[1], t[2]).has_value();
        ++rays;
      }
    }
    for (int i = 0; i < 2000; ++i) {
      const Vec3 target = t[0] + unit(rng) * (t[2] - t[0]);
      const Vec3 origin = random_point(rng, 10.0f);
      hits += triangle_hit(make_ray(origin, target - origin), t[0], t[1], t[2]).has_value();
      ++rays;
    }
  }
  EXPECT_EQ(hits, 0) << "of " << rays;
}

TEST(CorePrimitiveIntersection, RaysParallelToTheTriangleMiss) {
  // In the plane, through the triangle's interior, and beside the plane.
  EXPECT_FALSE(triangle_hit(make_ray({-1.0f, 0.25f, 3.0f}, {1, 0, 0}), kP0, kP1, kP2));
  EXPECT_FALSE(triangle_hit(make_ray({0.5f, 0.25f, 3.0f}, {1, 1, 0}), kP0, kP1, kP2));
  EXPECT_FALSE(triangle_hit(make_ray({-1.0f, 0.25f, 2.9f}, {1, 0, 0}), kP0, kP1, kP2));
  EXPECT_FALSE(triangle_hit(make_ray({0.2f, -1.0f, 3.1f}, {0, 1, 0}), kP0, kP1, kP2));
  // The tilted triangle x + y + z = 1 and a ray along its plane.
  const Vec3 a(1, 0, 0), b(0, 1, 0), c(0, 0, 1);
  EXPECT_FALSE(triangle_hit(make_ray({1.0f, -1.0f, 1.0f}, {-1, 1, 0}), a, b, c));
}

// The sphere of radius 1 about (0, 0, 5).
const Vec3 kCentre(0.0f, 0.0f, 5.0f);

TEST(CorePrimitiveIntersection, SphereFromOutsideGivesTheNearRoot) {
  const auto hit = intersect_sphere(make_ray(Vec3(0.0f), {0, 0, 1}), kCentre, 1.0f);
  ASSERT_TRUE(hit);
  EXPECT_FLOAT_EQ(hit->t, 4.0f);
  // The south pole (0, 0, -1) about the centre: theta = pi.
  EXPECT_FLOAT_EQ(hit->v, 1.0f);
  // t in units of |direction|.
  const auto doubled = intersect_sphere(make_ray(Vec3(0.0f), {0, 0, 2}), kCentre, 1.0f);
  ASSERT_TRUE(doubled);
  EXPECT_FLOAT_EQ(doubled->t, 2.0f);
  // Off axis: x = 0.6 enters at z = 5 - 0.8.
  const auto off = intersect_sphere(make_ray({0.6f, 0.0f, 0.0f}, {0, 0, 1}), kCentre, 1.0f);
  ASSERT_TRUE(off);
  EXPECT_NEAR(off->t, 4.2f, 1e-5f);
  // From the side: the hit (0, -1, 0) about the centre has phi = 3pi/2, theta = pi/2.
  const auto side = intersect_sphere(make_ray({0.0f, -5.0f, 5.0f}, {0, 1, 0}), kCentre, 1.0f);
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->t, 4.0f, 1e-6f);
  EXPECT_NEAR(side->u, 0.75f, 1e-6f);
  EXPECT_NEAR(side->v, 0.5f, 1e-6f);
  // And (1, 0, 0): phi = 0; (0, 1, 0): phi = pi/2.
  const auto east = intersect_sphere(make_ray({5.0f, 0.0f, 5.0f}, {-1, 0, 0}), kCentre, 1.0f);
  ASSERT_TRUE(east);
  EXPECT_NEAR(east->u, 0.0f, 1e-6f);
  const auto north = intersect_sphere(make_ray({0.0f, 5.0f, 5.0f}, {0, -1, 0}), kCentre, 1.0f);
  ASSERT_TRUE(north);
  EXPECT_NEAR(north->u, 0.25f, 1e-6f);
  EXPECT_NEAR(north->v, 0.5f, 1e-6f);
}

TEST(CorePrimitiveIntersection, SphereFromInsideGivesTheFarRoot) {
  const auto centre_hit = intersect_sphere(make_ray(kCentre, {0, 0, 1}), kCentre, 1.0f);
  ASSERT_TRUE(centre_hit);
  EXPECT_FLOAT_EQ(centre_hit->t, 1.0f);
  EXPECT_NEAR(centre_hit->v, 0.0f, 1e-6f);  // the north pole
  const auto inner = intersect_sphere(make_ray({0.0f, 0.0f, 5.5f}, {0, 0, -1}), kCentre, 1.0f);
  ASSERT_TRUE(inner);
  EXPECT_FLOAT_EQ(inner->t, 1.5f);
  EXPECT_NEAR(inner->v, 1.0f, 1e-6f);
}

TEST(CorePrimitiveIntersection, SphereRespectsTheClosedInterval) {
  const Vec3 o(0.0f), d(0, 0, 1);
  // The near root is excluded: the far one is taken.
  const auto far = intersect_sphere(make_ray(o, d, 4.5f, kInf), kCentre, 1.0f);
  ASSERT_TRUE(far);
  EXPECT_FLOAT_EQ(far->t, 6.0f);
  EXPECT_FALSE(intersect_sphere(make_ray(o, d, 0.0f, 3.9f), kCentre, 1.0f));
  EXPECT_FALSE(intersect_sphere(make_ray(o, d, 6.1f, kInf), kCentre, 1.0f));
  EXPECT_FALSE(intersect_sphere(make_ray(o, d, 4.1f, 5.9f), kCentre, 1.0f));
  // The ends count.
  const auto at_tmin = intersect_sphere(make_ray(o, d, 4.0f, kInf), kCentre, 1.0f);
  ASSERT_TRUE(at_tmin);
  EXPECT_FLOAT_EQ(at_tmin->t, 4.0f);
  const auto at_tmax = intersect_sphere(make_ray(o, d, 0.0f, 4.0f), kCentre, 1.0f);
  ASSERT_TRUE(at_tmax);
  EXPECT_FLOAT_EQ(at_tmax->t, 4.0f);
  const auto far_at_tmax = intersect_sphere(make_ray(o, d, 4.5f, 6.0f), kCentre, 1.0f);
  ASSERT_TRUE(far_at_tmax);
  EXPECT_FLOAT_EQ(far_at_tmax->t, 6.0f);
  EXPECT_FALSE(intersect_sphere(make_ray(o, d, 4.5f, std::nextafter(6.0f, 0.0f)), kCentre, 1.0f));
  // A sphere behind the ray.
  EXPECT_FALSE(intersect_sphere(make_ray(o, -d), kCentre, 1.0f));
}

TEST(CorePrimitiveIntersection, SphereGrazingRays) {
  // Just inside the silhouette: two close roots about t = 5.
  const auto inside = intersect_sphere(make_ray({0.999f, 0.0f, 0.0f}, {0, 0, 1}), kCentre, 1.0f);
  ASSERT_TRUE(inside);
  EXPECT_NEAR(inside->t, 5.0f - std::sqrt(1.0f - 0.999f * 0.999f), 1e-4f);
  EXPECT_LT(inside->t, 5.0f);
  // Exactly tangent (the discriminant is exactly zero): touches at t = 5.
  const auto tangent = intersect_sphere(make_ray({1.0f, 0.0f, 0.0f}, {0, 0, 1}), kCentre, 1.0f);
  ASSERT_TRUE(tangent);
  EXPECT_FLOAT_EQ(tangent->t, 5.0f);
  // Just outside.
  EXPECT_FALSE(intersect_sphere(make_ray({1.001f, 0.0f, 0.0f}, {0, 0, 1}), kCentre, 1.0f));
  EXPECT_FALSE(intersect_sphere(make_ray({0.8f, 0.8f, 0.0f}, {0, 0, 1}), kCentre, 1.0f));
}

TEST(CorePrimitiveIntersection, SmallDistantSphereIsHitAccurately) {
  // A sphere 1e4 away: the textbook discriminant b^2 - 4ac would lose the answer to cancellation.
  const Vec3 centre(0.0f, 0.0f, 1e4f);
  const float radius = 0.01f;
  for (const float x : {0.0f, 0.005f, 0.0099f}) {
    SCOPED_TRACE(x);
    const Ray ray = make_ray({x, 0.0f, 0.0f}, {0, 0, 1});
    const auto hit = intersect_sphere(ray, centre, radius);
    ASSERT_TRUE(hit);
    // The hit point lies on the sphere (to float precision at 1e4, ~1e-3).
    EXPECT_NEAR(glm::length(ray.at(hit->t) - centre), radius, 2e-3f);
    EXPECT_LE(hit->t, 1e4f);
  }
  EXPECT_FALSE(intersect_sphere(make_ray({0.0101f, 0.0f, 0.0f}, {0, 0, 1}), centre, radius));
}

TEST(CorePrimitiveIntersection, ObliqueRaysAtADistantSphereAgreeWithDouble) {
  // Rays from around the origin toward points near a small sphere 1e4 away, in no axis's
  // direction: hit or miss and t as a double-precision solution says, away from the silhouette.
  const DVec3 centre(3e3, -4e3, 8.5e3);
  const double radius = 0.5;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int hits = 0, misses = 0;
  for (int i = 0; i < 2000; ++i) {
    const DVec3 origin(unit(rng), unit(rng), unit(rng));
    const DVec3 aim = centre + 1.5 * radius * DVec3(unit(rng), unit(rng), unit(rng));
    const Vec3 direction(glm::normalize(aim - origin));
    const Vec3 o(origin);
    // The exact line of the float ray, solved in double.
    const DVec3 d(direction), f = DVec3(o) - centre;
    const double a = glm::dot(d, d), half_b = glm::dot(f, d);
    const double distance2 = glm::dot(glm::cross(f, d), glm::cross(f, d)) / a;
    const auto hit = intersect_sphere(make_ray(o, direction), Vec3(centre), float(radius));
    // Within 1% of the radius of the silhouette either way is too close to call in float.
    if (std::abs(std::sqrt(distance2) - radius) < 0.01 * radius) continue;
    if (distance2 > radius * radius) {
      EXPECT_FALSE(hit) << i;
      ++misses;
      continue;
    }
    ASSERT_TRUE(hit) << i;
    const double t = (-half_b - std::sqrt(radius * radius - distance2) * std::sqrt(a)) / a;
    // A few float roundings of t (its ulp here is about 1e-3).
    EXPECT_NEAR(hit->t, t, 8.0 * t * 0x1p-24) << i;
    ++hits;
  }
  EXPECT_GT(hits, 200);
  EXPECT_GT(misses, 200);
}

TEST(CorePrimitiveIntersection, SphereUvAreTheAnglesOfTheHitPoint) {
  // u = phi / 2pi in [0, 1), v = theta / pi, against libm in double, all around the sphere.
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 toward = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
    const Vec3 origin = kCentre + 3.0f * toward;
    const Vec3 aim = kCentre + 0.5f * Vec3(unit(rng), unit(rng), unit(rng));
    const Ray ray = make_ray(origin, glm::normalize(aim - origin));
    const auto hit = intersect_sphere(ray, kCentre, 1.0f);
    ASSERT_TRUE(hit) << i;
    const DVec3 local = DVec3(ray.at(hit->t)) - DVec3(kCentre);
    double phi = std::atan2(local.y, local.x);
    if (phi < 0.0) phi += 2.0 * M_PI;
    const double theta = std::acos(std::clamp(local.z / glm::length(local), -1.0, 1.0));
    EXPECT_GE(hit->u, 0.0f);
    EXPECT_LE(hit->u, 1.0f);
    // Where phi wraps (y just below 0 about x > 0), 1 and 0 are the same place.
    const double du = std::abs(hit->u - phi / (2.0 * M_PI));
    EXPECT_LT(std::min(du, 1.0 - du), 1e-6) << i;
    EXPECT_NEAR(hit->v, theta / M_PI, 1e-6) << i;
  }
}

}  // namespace
}  // namespace prism
