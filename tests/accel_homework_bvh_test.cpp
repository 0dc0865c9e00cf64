// The homework's median-split BVH (accel/bvh/homework/): tree invariants, degenerate inputs,
// parameters, and exact agreement with brute force on small scenes.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "accel/accelerator.h"
#include "accel/brute/brute_accelerator.h"
#include "accel/bvh/homework/homework_bvh.h"
#include "accel/bvh/homework/homework_bvh_accelerator.h"
#include "accel/bvh/homework/homework_bvh_builder.h"
#include "accel/primitive_query.h"
#include "accel/validation/hit_comparison.h"
#include "accel/validation/ray_sets.h"

namespace prism {
namespace {

/// Triangles with corners at pseudo-random points of [-1, 1]^3 (a fixed LCG) plus a few
/// spheres, in two meshes.
SceneGeometry small_scene(int triangles) {
  uint32_t state = 12345;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) * 0x1p-23f - 1.0f;
  };
  SceneGeometry g;
  for (int m = 0; m < 2; ++m) {
    TriangleMesh mesh;
    for (int i = 0; i < triangles / 2; ++i) {
      const Vec3 c(next(), next(), next());
      const uint32_t b = uint32_t(mesh.positions.size());
      for (int k = 0; k < 3; ++k) mesh.positions.push_back(c + 0.2f * Vec3(next(), next(), next()));
      mesh.triangles.push_back({b, b + 1, b + 2});
    }
    mesh.finalize();
    g.meshes.push_back(std::move(mesh));
  }
  for (int i = 0; i < 5; ++i) g.spheres.push_back({Vec3(next(), next(), next()), 0.15f, 0});
  return g;
}

TEST(AccelHomeworkBvh, TreeInvariantsHoldForEveryLeafSize) {
  const SceneGeometry g = small_scene(400);
  for (uint32_t leaf : {1u, 2u, 3u, 4u, 16u, 255u}) {
    const auto prims = gather_homework_primitives(g);
    const HomeworkBvh bvh = build_homework_bvh(prims, HomeworkBvhOptions{leaf});
    EXPECT_NO_THROW(check_homework_bvh(bvh, prims)) << "leaf size " << leaf;
    for (const HomeworkBvhNode& n : bvh.nodes) {
      if (n.is_leaf()) {
        EXPECT_LE(n.count, leaf);
      }
    }
    const AccelStats s = homework_bvh_stats(bvh);
    EXPECT_EQ(s.nodes, bvh.nodes.size());
    EXPECT_EQ(s.nodes, 2 * s.leaves - 1);
    EXPECT_EQ(s.bytes,
              bvh.nodes.size() * sizeof(HomeworkBvhNode) + prims.size() * sizeof(PrimitiveId));
    // Median splits halve the count: depth is at most ceil(log2(n / leaf)) + 1.
    EXPECT_LE(double(s.max_depth), std::ceil(std::log2(double(prims.size()) / leaf)) + 1.0);
  }
}

TEST(AccelHomeworkBvh, CheckCatchesABrokenTree) {
  const SceneGeometry g = small_scene(40);
  const auto prims = gather_homework_primitives(g);
  HomeworkBvh bvh = build_homework_bvh(prims, {});
  ASSERT_NO_THROW(check_homework_bvh(bvh, prims));
  HomeworkBvh shrunk = bvh;
  shrunk.nodes.back().upper -= Vec3(0.5f);
  EXPECT_THROW(check_homework_bvh(shrunk, prims), Error);
  HomeworkBvh repeated = bvh;
  repeated.prims[1] = repeated.prims[0];
  EXPECT_THROW(check_homework_bvh(repeated, prims), Error);
}

TEST(AccelHomeworkBvh, MillionIdenticalTrianglesBuildShallowAndTieToTheFirst) {
  SceneGeometry g;
  TriangleMesh mesh;
  mesh.positions = {{-1, -1, 3}, {1, -1, 3}, {0, 1, 3}};
  mesh.triangles.assign(1'000'000, glm::uvec3(0, 1, 2));
  mesh.finalize();
  g.meshes.push_back(std::move(mesh));
  HomeworkBvhAccelerator bvh(ParamSet{});
  bvh.build(g);
  const AccelStats s = bvh.stats();
  EXPECT_LE(s.max_depth, 20u);  // ceil(log2(1e6 / 4)) = 18
  EXPECT_EQ(s.leaves, (s.nodes + 1) / 2);
  Ray r;
  r.direction = {0, 0, 1};
  const auto hit = bvh.intersect(r);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 3.0f);
  EXPECT_EQ(hit->prim_id, 0u);  // every triangle ties: the lowest prim_id wins
  EXPECT_TRUE(bvh.occluded(r));
  r.origin = {5, 5, 0};
  EXPECT_FALSE(bvh.intersect(r));
}

TEST(AccelHomeworkBvh, CoincidentPrimitivesOfBothKindsTieByIds) {
  SceneGeometry g;
  for (int m = 0; m < 3; ++m) {
    TriangleMesh mesh;
    mesh.positions = {{-1, -1, 1}, {1, -1, 1}, {0, 1, 1}};
    mesh.triangles.assign(7, glm::uvec3(0, 1, 2));
    mesh.finalize();
    g.meshes.push_back(std::move(mesh));
  }
  // Spheres touching the plane z = 1 at the ray's hit point: equal t as well.
  for (int i = 0; i < 9; ++i) g.spheres.push_back({Vec3(0, 0, 1.5f), 0.5f, 0});
  BruteAccelerator brute(ParamSet{});
  brute.build(g);
  for (int leaf : {1, 2, 4}) {
    ParamSet params;
    params.set("bvh.max_leaf_size", std::to_string(leaf));
    HomeworkBvhAccelerator bvh(params);
    bvh.build(g);
    Ray r;
    r.direction = {0, 0, 1};
    const auto hit = bvh.intersect(r);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->geom_id, 0u);
    EXPECT_EQ(hit->prim_id, 0u);
    // Past the triangles: the spheres' far roots coincide too; the first sphere wins.
    r.tmin = 1.5f;
    const auto sphere = bvh.intersect(r);
    ASSERT_TRUE(sphere);
    EXPECT_EQ(sphere->geom_id, 3u);
    EXPECT_EQ(sphere->prim_id, 0u);
    EXPECT_EQ(compare_exact(sphere, brute.intersect(r)).agreement, HitAgreement::kSame);
  }
}

TEST(AccelHomeworkBvh, EqualsBruteBitForBitOnRandomRays) {
  const SceneGeometry g = small_scene(600);
  BruteAccelerator brute(ParamSet{});
  brute.build(g);
  const std::vector<Ray> rays = random_rays(g.bounds(), 4000, 3);
  const std::vector<Ray> features = feature_rays(g, 2000, 3);
  for (int leaf : {1, 4, 9}) {
    ParamSet params;
    params.set("bvh.max_leaf_size", std::to_string(leaf));
    HomeworkBvhAccelerator bvh(params);
    bvh.build(g);
    size_t hits = 0;
    for (const auto* set : {&rays, &features}) {
      for (const Ray& r : *set) {
        const auto expected = brute.intersect(r);
        const auto got = bvh.intersect(r);
        hits += expected.has_value();
        ASSERT_EQ(compare_exact(got, expected).agreement, HitAgreement::kSame)
            << compare_exact(got, expected).reason << "\n  ray: " << format_ray(r);
        ASSERT_EQ(bvh.occluded(r), expected.has_value()) << format_ray(r);
      }
    }
    EXPECT_GT(hits, 1000u);  // the rays exercise the tree
  }
}

}  // namespace
}  // namespace prism
