// The Accelerator contract (accel/accelerator.h), run on every backend of the registry on tiny
// hand-made scenes whose answers are known exactly.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "accel/accelerator.h"
#include "core/error.h"
#include "core/scene_geometry.h"
#include "tests/support/accel_test_geometry.h"

namespace prism {
namespace {

using test::mesh_of;
using test::one_triangle;
using test::ray;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

class AccelAccelerator : public ::testing::TestWithParam<std::string> {
 protected:
  /// A backend of this test's kind built on `geometry` (kept alive by the fixture).
  const Accelerator& build(SceneGeometry geometry, const ParamSet& params = {}) {
    geometry_ = std::make_unique<SceneGeometry>(std::move(geometry));
    accel_ = accelerator_registry().create(GetParam(), params);
    accel_->build(*geometry_);
    return *accel_;
  }
  /// intersect() after checking that occluded() agrees with it.
  std::optional<Hit> query(const Ray& r) {
    const std::optional<Hit> hit = accel_->intersect(r);
    EXPECT_EQ(accel_->occluded(r), hit.has_value());
    return hit;
  }

  std::unique_ptr<SceneGeometry> geometry_;
  std::unique_ptr<Accelerator> accel_;
};

TEST_P(AccelAccelerator, TriangleHitHasEmbreeBarycentrics) {
  build(one_triangle());
  const auto hit = query(ray({0, 0, 0}, {-0.5f, 0.25f, 2.0f}));
  ASSERT_TRUE(hit);
  EXPECT_FLOAT_EQ(hit->t, 1.0f);
  // p = (1-u-v) p0 + u p1 + v p2 = (-0.5, 0.25, 2)  ->  u = 0.25, v = 0.625
  EXPECT_NEAR(hit->u, 0.25f, 1e-6f);
  EXPECT_NEAR(hit->v, 0.625f, 1e-6f);
  EXPECT_EQ(hit->geom_id, 0u);
  EXPECT_EQ(hit->prim_id, 0u);
}

TEST_P(AccelAccelerator, BothFacesAreHit) {
  build(one_triangle());
  const auto front = query(ray({-0.5f, -0.5f, 0}, {0, 0, 1}));
  const auto back = query(ray({-0.5f, -0.5f, 5}, {0, 0, -1}));
  ASSERT_TRUE(front);
  ASSERT_TRUE(back);
  EXPECT_EQ(front->t, 2.0f);
  EXPECT_EQ(back->t, 3.0f);
}

TEST_P(AccelAccelerator, DirectionNeedNotBeUnit) {
  build(one_triangle());
  const auto hit = query(ray({-0.5f, -0.5f, 0}, {0, 0, 4}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 0.5f);
}

TEST_P(AccelAccelerator, IntervalIsClosed) {
  build(one_triangle());
  const Vec3 o(-0.5f, -0.5f, 0), d(0, 0, 1);
  EXPECT_TRUE(query(ray(o, d, 2.0f, kInfinity)));
  EXPECT_TRUE(query(ray(o, d, 0.0f, 2.0f)));
  EXPECT_TRUE(query(ray(o, d, 2.0f, 2.0f)));
  EXPECT_FALSE(query(ray(o, d, std::nextafter(2.0f, 3.0f), kInfinity)));
  EXPECT_FALSE(query(ray(o, d, 0.0f, std::nextafter(2.0f, 0.0f))));
  EXPECT_FALSE(query(ray(o, d, 3.0f, 1.0f)));  // empty interval
  // A negative tmin counts as 0: nothing behind the origin.
  EXPECT_FALSE(query(ray({-0.5f, -0.5f, 3}, d, -5.0f, kInfinity)));
}

TEST_P(AccelAccelerator, Misses) {
  build(one_triangle());
  EXPECT_FALSE(query(ray({0, 0, 0}, {0, 0, -1})));                     // pointing away
  EXPECT_FALSE(query(ray({0.6f, 0.6f, 0}, {0, 0, 1})));                // beside the hypotenuse
  EXPECT_FALSE(query(ray({0, 0, 2}, {1, 0, 0}, 0.5f)));                // in the plane
  EXPECT_FALSE(query(ray({-0.5f, -0.5f, 0}, {0, 0, 1}, 0.0f, 1.0f)));  // ends before it
}

TEST_P(AccelAccelerator, SpheresFromOutsideAndInside) {
  SceneGeometry g;
  g.spheres.push_back({Vec3(0, 0, 5), 1.0f, 0});
  g.spheres.push_back({Vec3(10, 0, 0), 2.0f, 0});
  build(std::move(g));
  const auto outside = query(ray({0, 0, 0}, {0, 0, 1}));
  ASSERT_TRUE(outside);
  EXPECT_FLOAT_EQ(outside->t, 4.0f);
  EXPECT_EQ(outside->geom_id, 0u);  // no meshes: spheres have geom id 0
  EXPECT_EQ(outside->prim_id, 0u);
  EXPECT_NEAR(outside->v, 1.0f, 1e-3f);  // the south pole: theta = pi

  const auto inside = query(ray({10, 0, 0}, {0, -1, 0}));
  ASSERT_TRUE(inside);
  EXPECT_FLOAT_EQ(inside->t, 2.0f);  // the far root: the near one is behind the origin
  EXPECT_EQ(inside->prim_id, 1u);
  EXPECT_NEAR(inside->u, 0.75f, 1e-6f);  // phi = -pi/2 + 2pi
  EXPECT_NEAR(inside->v, 0.5f, 1e-6f);   // on the equator

  EXPECT_FALSE(query(ray({0, 0, 0}, {0, 1, 0})));
  EXPECT_FALSE(query(ray({0, 0, 0}, {0, 0, 1}, 0.0f, 3.9f)));
  EXPECT_FALSE(query(ray({0, 1.0001f, 0}, {0, 0, 1})));  // passes just outside the silhouette
}

TEST_P(AccelAccelerator, FoldedSliversAreOrderedAsInDoublePrecision) {
  // Two slivers of an architectural mesh (edges 1.36 long, 0.0006 wide) folded along their
  // shared edge, and a ray that meets both near the edge: in double precision B is hit at
  // t = 0.1861639, A at 0.1862026. A float t off by 5e-5 used to return A.
  SceneGeometry g;
  g.meshes.push_back(mesh_of({{0x1.3c411ap-4f, 0x1.570ef2p-1f, 0x1.a1d50cp-4f},
                              {0x1.3c411ap-4f, -0x1.6046dp-1f, 0x1.a1d4dp-4f},
                              {0x1.39d676p-4f, -0x1.6046dp-1f, 0x1.a14b8cp-4f},
                              {0x1.3bb7d6p-4f, 0x1.570ef2p-1f, 0x1.a43ca8p-4f}},
                             {{0, 1, 2}, {1, 0, 3}}));
  build(std::move(g));
  const auto hit = query(ray({0x1.7b50ep-3f, -0x1.0ab0b8p-2f, 0x1.868a6ep-3f},
                             {-0x1.290af4p-1f, 0x1.524934p-1f, -0x1.e7bd1p-2f}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->prim_id, 1u) << "t = " << hit->t;
  EXPECT_NEAR(hit->t, 0.1861639, 2e-7);
}

TEST_P(AccelAccelerator, GeomIdsFollowMeshesThenSpheres) {
  SceneGeometry g;
  g.meshes.push_back(mesh_of({{-1, -1, 8}, {1, -1, 8}, {0, 1, 8}}, {{0, 1, 2}}));
  g.meshes.push_back(mesh_of({}, {}));  // an empty mesh keeps its id
  g.meshes.push_back(
      mesh_of({{-1, -1, 4}, {1, -1, 4}, {0, 1, 4}, {5, 5, 5}}, {{3, 3, 3}, {0, 1, 2}}));
  g.spheres.push_back({Vec3(0, 0, 6), 0.5f, 0});
  build(std::move(g));
  const auto near = query(ray({0, 0, 0}, {0, 0, 1}));
  ASSERT_TRUE(near);
  EXPECT_EQ(near->geom_id, 2u);
  EXPECT_EQ(near->prim_id, 1u);
  const auto sphere = query(ray({0, 0, 0}, {0, 0, 1}, 4.5f));
  ASSERT_TRUE(sphere);
  EXPECT_EQ(sphere->geom_id, 3u);
  EXPECT_EQ(sphere->prim_id, 0u);
  EXPECT_FLOAT_EQ(sphere->t, 5.5f);
  const auto far = query(ray({0, 0, 0}, {0, 0, 1}, 6.6f));
  ASSERT_TRUE(far);
  EXPECT_EQ(far->geom_id, 0u);
}

TEST_P(AccelAccelerator, ClosestOfManyAlongTheRay) {
  SceneGeometry g;
  std::vector<Vec3> p;
  std::vector<glm::uvec3> t;
  for (int i = 0; i < 50; ++i) {
    // Shuffled depths so that the closest is not the first or last primitive.
    const float z = float((i * 37 + 20) % 50 + 1);
    const uint32_t b = uint32_t(p.size());
    p.insert(p.end(), {{-1, -1, z}, {1, -1, z}, {0, 1, z}});
    t.push_back({b, b + 1, b + 2});
  }
  g.meshes.push_back(mesh_of(p, t));
  build(std::move(g));
  const auto hit = query(ray({0, 0, 0}, {0, 0, 1}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 1.0f);
  EXPECT_EQ(hit->prim_id, 40u);  // (40 * 37 + 20) % 50 == 0
  const auto later = query(ray({0, 0, 0}, {0, 0, 1}, 20.5f));
  ASSERT_TRUE(later);
  EXPECT_EQ(later->t, 21.0f);
}

TEST_P(AccelAccelerator, NonFiniteRaysMissWithoutCrashing) {
  SceneGeometry g = one_triangle();
  g.spheres.push_back({Vec3(0, 0, 5), 1.0f, 0});
  build(std::move(g));
  const float inf = kInfinity;
  for (const Ray& r :
       {ray({0, 0, 0}, {kNaN, 0, 1}), ray({0, 0, 0}, {0, 0, kNaN}), ray({kNaN, 0, 0}, {0, 0, 1}),
        ray({0, 0, -inf}, {0, 0, 1}), ray({0, 0, 0}, {0, 0, inf}), ray({0, 0, 0}, {inf, 0, 0}),
        ray({0, 0, 0}, {-inf, inf, inf}), ray({0, 0, 0}, {0, 0, 0}),
        ray({0, 0, 0}, {0, 0, 1}, kNaN), ray({0, 0, 0}, {0, 0, 1}, 0.0f, kNaN),
        ray({0, 0, 0}, {0, 0, 1}, inf, inf)}) {
    EXPECT_FALSE(accel_->intersect(r));
    EXPECT_FALSE(accel_->occluded(r));
  }
}

TEST_P(AccelAccelerator, EmptySceneMissesEverything) {
  build(SceneGeometry{});
  EXPECT_FALSE(query(ray({0, 0, 0}, {0, 0, 1})));
  EXPECT_FALSE(query(ray({1, 2, 3}, {-1, 0.5f, 0.25f}, 1.0f, 2.0f)));
  EXPECT_EQ(accel_->stats().nodes, 0u);
  EXPECT_EQ(accel_->stats().leaves, 0u);
}

TEST_P(AccelAccelerator, DegenerateTrianglesAreNeverHit) {
  SceneGeometry g;
  // Collinear corners, a repeated corner and a point in front of a proper triangle at z = 2.
  g.meshes.push_back(mesh_of(
      {{-1, 0, 1}, {0, 0, 1}, {1, 0, 1}, {-1, -1, 2}, {1, -1, 2}, {0, 1, 2}, {0.25f, 0.25f, 1.5f}},
      {{0, 1, 2}, {0, 0, 1}, {6, 6, 6}, {3, 4, 5}}));
  build(std::move(g));
  for (const Vec3& target : {Vec3(-0.25f, 0, 1), Vec3(0, 0, 1), Vec3(0.25f, 0.25f, 1.5f)}) {
    const auto hit = query(ray({target.x, target.y, 0}, {0, 0, 1}));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->prim_id, 3u);
    EXPECT_EQ(hit->t, 2.0f);
  }
}

TEST_P(AccelAccelerator, StatsAreFilled) {
  SceneGeometry g;
  std::vector<Vec3> p;
  std::vector<glm::uvec3> t;
  for (int i = 0; i < 100; ++i) {
    const float x = float(i);
    const uint32_t b = uint32_t(p.size());
    p.insert(p.end(), {{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}});
    t.push_back({b, b + 1, b + 2});
  }
  g.meshes.push_back(mesh_of(p, t));
  g.spheres.push_back({Vec3(0, 0, 5), 1.0f, 0});
  build(std::move(g));
  const AccelStats s = accel_->stats();
  EXPECT_GE(s.build_ms, 0.0);
  if (GetParam() == "embree") {
    EXPECT_GT(s.bytes, 0u);  // Embree exposes its memory, not its nodes
  } else {
    EXPECT_GE(s.nodes, 1u);
    EXPECT_GE(s.leaves, 1u);
    EXPECT_GT(s.sah_cost, 0.0);
  }
  if (GetParam() == "bvh") {
    EXPECT_LE(s.nodes, 2 * s.leaves - 1);  // every interior node has two or more children
    EXPECT_GT(s.max_depth, 0u);
    EXPECT_GT(s.bytes, 0u);
    EXPECT_LT(s.sah_cost, 101.0);  // better than testing everything
  }
}

TEST_P(AccelAccelerator, BatchedIntersectMatchesSingle) {
  build(one_triangle());
  const std::vector<Ray> rays = {ray({-0.5f, -0.5f, 0}, {0, 0, 1}), ray({5, 5, 0}, {0, 0, 1}),
                                 ray({0, 0, 0}, {-0.5f, 0.25f, 2.0f})};
  std::vector<std::optional<Hit>> hits(rays.size());
  accel_->intersect(rays, hits);
  for (size_t i = 0; i < rays.size(); ++i) {
    const auto single = accel_->intersect(rays[i]);
    ASSERT_EQ(hits[i].has_value(), single.has_value());
    if (single) {
      EXPECT_EQ(hits[i]->t, single->t);
    }
  }
}

TEST_P(AccelAccelerator, RejectsBrokenGeometry) {
  SceneGeometry g;
  g.meshes.push_back(mesh_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 7}}));
  const auto accel = accelerator_registry().create(GetParam(), {});
  try {
    accel->build(g);
    FAIL() << "an index out of range must be rejected";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInput);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, AccelAccelerator, ::testing::Values("brute", "bvh", "embree"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace prism
