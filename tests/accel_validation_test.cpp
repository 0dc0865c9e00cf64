// The validation tools: ray sets and their hex-float form, the double-precision oracle, and the
// classifier of disagreements (which must call real bugs HARD and rounding AMBIGUOUS or TIE).

#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "accel/validation/double_oracle.h"
#include "accel/validation/hit_comparison.h"
#include "accel/validation/ray_sets.h"
#include "core/error.h"

namespace prism {
namespace {

uint32_t bits(float x) { return std::bit_cast<uint32_t>(x); }

Ray ray(Vec3 origin, Vec3 direction, float tmin = 0.0f, float tmax = kInfinity) {
  Ray r;
  r.origin = origin;
  r.direction = direction;
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

/// Two triangles sharing the edge x = y in the plane z = 2 (a unit quad), a copy of the first
/// in a second mesh (coplanar duplicate), and a sphere of radius 1 at (5, 0, 2).
SceneGeometry quad_scene() {
  SceneGeometry g;
  TriangleMesh quad;
  quad.positions = {{0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  quad.finalize();
  g.meshes.push_back(quad);
  TriangleMesh copy;
  copy.positions = {{0, 0, 2}, {1, 0, 2}, {1, 1, 2}};
  copy.triangles = {{0, 1, 2}};
  copy.finalize();
  g.meshes.push_back(copy);
  g.spheres.push_back({Vec3(5, 0, 2), 1.0f, 0});
  return g;
}

Hit hit_on(float t, uint32_t geom, uint32_t prim) { return Hit{t, 0.25f, 0.25f, geom, prim}; }

TEST(AccelRaySets, FormatRoundTripsExactly) {
  for (const Ray& r : {ray({0.1f, -0.0f, 1e-30f}, {3.0f, -1e20f, 0.7f}, 0.0f, kInfinity),
                       ray({-5, 6, 7}, {0, 0, 1}, 1e-7f, 12345.678f)}) {
    const std::string text = format_ray(r);
    const auto back = parse_ray(text);
    ASSERT_TRUE(back) << text;
    EXPECT_EQ(bits(back->origin.x), bits(r.origin.x));
    EXPECT_EQ(bits(back->origin.y), bits(r.origin.y));
    EXPECT_EQ(bits(back->origin.z), bits(r.origin.z));
    EXPECT_EQ(bits(back->direction.y), bits(r.direction.y));
    EXPECT_EQ(bits(back->tmin), bits(r.tmin));
    EXPECT_EQ(bits(back->tmax), bits(r.tmax));
  }
  EXPECT_NE(format_ray(ray({0.1f, 0, 0}, {0, 0, 1})).find("0x1.99999ap-4"), std::string::npos);
  EXPECT_FALSE(parse_ray("origin=(1, 2) direction=(0, 0, 1) tmin=0 tmax=1"));
  EXPECT_FALSE(parse_ray(format_ray(ray({0, 0, 0}, {0, 0, 1})) + " trailing"));
}

TEST(AccelRaySets, RandomRaysAreDeterministicAndWellFormed) {
  const Bounds3 box{Vec3(-2, 0, 1), Vec3(3, 1, 4)};
  const auto a = random_rays(box, 5000, 7);
  const auto b = random_rays(box, 5000, 7);
  const auto c = random_rays(box, 5000, 8);
  ASSERT_EQ(a.size(), 5000u);
  size_t finite_tmax = 0, positive_tmin = 0, inside = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(format_ray(a[i]), format_ray(b[i]));
    EXPECT_TRUE(is_finite(a[i].origin) && is_finite(a[i].direction));
    EXPECT_NE(a[i].direction, Vec3(0.0f));
    EXPECT_LE(a[i].tmin, a[i].tmax);
    finite_tmax += std::isfinite(a[i].tmax);
    positive_tmin += a[i].tmin > 0.0f;
    inside += glm::all(glm::greaterThanEqual(a[i].origin, box.lower)) &&
              glm::all(glm::lessThanEqual(a[i].origin, box.upper));
  }
  EXPECT_NE(format_ray(a[0]), format_ray(c[0]));
  EXPECT_GT(finite_tmax, 500u);
  EXPECT_GT(positive_tmin, 500u);
  EXPECT_GT(inside, 2000u);
  EXPECT_EQ(random_rays(Bounds3{}, 10, 1).size(), 10u);  // empty bounds still work
}

TEST(AccelRaySets, FeatureRaysAimAtVerticesAndEdges) {
  const SceneGeometry g = quad_scene();
  const auto rays = feature_rays(g, 3000, 1);
  ASSERT_EQ(rays.size(), 3000u);
  size_t at_vertex = 0, at_sphere = 0;
  for (const Ray& r : rays) {
    const Vec3 target = r.origin + r.direction;  // t = 1 at the target
    if (std::abs(target.z - 2.0f) < 1e-5f &&
        std::abs(glm::length(target - Vec3(5, 0, 2)) - 1) > 1e-4f) {
      const bool corner = (std::abs(target.x) < 1e-5f || std::abs(target.x - 1) < 1e-5f) &&
                          (std::abs(target.y) < 1e-5f || std::abs(target.y - 1) < 1e-5f);
      at_vertex += corner;
    }
    at_sphere += std::abs(glm::length(target - Vec3(5, 0, 2)) - 1.0f) < 1e-4f;
  }
  EXPECT_GT(at_vertex, 500u);
  EXPECT_GT(at_sphere, 100u);
  EXPECT_TRUE(feature_rays(SceneGeometry{}, 10, 1).empty());
}

TEST(AccelOracle, ClosestFollowsTheTieRule) {
  const SceneGeometry g = quad_scene();
  const DoubleOracle oracle(g);
  const auto h = oracle.closest(ray({0.75f, 0.25f, 0}, {0, 0, 1}));
  ASSERT_TRUE(h);
  EXPECT_EQ(h->t, 2.0);
  EXPECT_EQ(h->geom_id, 0u);  // the duplicate in mesh 1 ties and loses
  EXPECT_EQ(h->prim_id, 0u);
  const auto s = oracle.closest(ray({5, 0, -5}, {0, 0, 1}));
  ASSERT_TRUE(s);
  EXPECT_EQ(s->geom_id, 2u);
  EXPECT_DOUBLE_EQ(s->t, 6.0);
  EXPECT_FALSE(oracle.closest(ray({0.5f, 0.5f, 0}, {0, 0, -1})));
  EXPECT_FALSE(oracle.closest(ray({0.5f, 0.5f, 0}, {0, 0, 1}, 0.0f, 1.5f)));
  EXPECT_FALSE(oracle.closest(ray({0.5f, 0.5f, 0}, {NAN, 0, 1})));
}

TEST(AccelOracle, ProbeMeasuresEdgeDistanceAndGrazing) {
  const SceneGeometry g = quad_scene();
  const DoubleOracle oracle(g);
  const PrimitiveProbe inside = oracle.probe(ray({0.75f, 0.25f, 0}, {0, 0, 1}), 0, 0);
  EXPECT_TRUE(inside.hit);
  EXPECT_DOUBLE_EQ(inside.t, 2.0);
  EXPECT_NEAR(inside.boundary_distance, 0.25, 1e-7);  // to the edges y = 0 and x = 1
  EXPECT_FALSE(inside.grazes());
  const PrimitiveProbe diagonal = oracle.probe(ray({0.5f, 0.5f, 0}, {0, 0, 1}), 0, 1);
  EXPECT_TRUE(diagonal.grazes());
  const PrimitiveProbe outside = oracle.probe(ray({0.5f, -0.1f, 0}, {0, 0, 1}), 0, 0);
  EXPECT_FALSE(outside.hit);
  EXPECT_NEAR(outside.boundary_distance, 0.1, 1e-6);
  EXPECT_FALSE(outside.grazes());
  const PrimitiveProbe silhouette = oracle.probe(ray({6, -5, 2}, {0, 1, 0}), 2, 0);
  EXPECT_TRUE(silhouette.grazes());
  EXPECT_GT(silhouette.t_tolerance, 1e-4);  // tangent: t is ill-conditioned
  const PrimitiveProbe at_end = oracle.probe(ray({0.75f, 0.25f, 0}, {0, 0, 1}, 0.0f, 2.0f), 0, 0);
  EXPECT_TRUE(at_end.near_interval_end(ray({0.75f, 0.25f, 0}, {0, 0, 1}, 0.0f, 2.0f)));
  EXPECT_THROW(oracle.probe(ray({0, 0, 0}, {0, 0, 1}), 5, 0), Error);
}

TEST(AccelHitComparison, ExactRule) {
  const std::optional<Hit> a = hit_on(2.0f, 0, 1);
  EXPECT_EQ(compare_exact(std::nullopt, std::nullopt).agreement, HitAgreement::kSame);
  EXPECT_EQ(compare_exact(a, a).agreement, HitAgreement::kSame);
  EXPECT_EQ(compare_exact(a, std::nullopt).agreement, HitAgreement::kHard);
  EXPECT_EQ(compare_exact(a, hit_on(std::nextafter(2.0f, 3.0f), 0, 1)).agreement,
            HitAgreement::kHard);
  EXPECT_EQ(compare_exact(a, hit_on(2.0f, 0, 2)).agreement, HitAgreement::kTie);
  Hit other_uv = *a;
  other_uv.u = 0.5f;
  EXPECT_EQ(compare_exact(a, other_uv).agreement, HitAgreement::kHard);
}

TEST(AccelHitComparison, TolerantRuleSeparatesTiesRoundingAndBugs) {
  const SceneGeometry g = quad_scene();
  const DoubleOracle oracle(g);
  const Ray interior = ray({0.75f, 0.25f, 0}, {0, 0, 1});
  const Ray diagonal = ray({0.5f, 0.5f, 0}, {0, 0, 1});
  const auto verdict = [&](const Ray& r, std::optional<Hit> a, std::optional<Hit> b) {
    return compare_tolerant(r, a, b, oracle).agreement;
  };
  // Same primitive: t within 1e-4 max(1, t) is the same answer; far off is a bug.
  EXPECT_EQ(verdict(interior, hit_on(2.0f, 0, 0), hit_on(2.0001f, 0, 0)), HitAgreement::kSame);
  EXPECT_EQ(verdict(interior, hit_on(2.0f, 0, 0), hit_on(2.1f, 0, 0)), HitAgreement::kHard);
  // A coplanar duplicate and a shared edge are ties.
  EXPECT_EQ(verdict(interior, hit_on(2.0f, 0, 0), hit_on(2.0f, 1, 0)), HitAgreement::kTie);
  EXPECT_EQ(verdict(diagonal, hit_on(2.0f, 0, 0), hit_on(2.0f, 0, 1)), HitAgreement::kTie);
  // The other triangle of the quad, away from the shared edge, is a bug.
  EXPECT_EQ(verdict(interior, hit_on(2.0f, 0, 0), hit_on(2.0f, 0, 1)), HitAgreement::kHard);
  // Missing a solid hit is a bug; missing at the edge of the quad is rounding.
  EXPECT_EQ(verdict(interior, hit_on(2.0f, 0, 0), std::nullopt), HitAgreement::kHard);
  EXPECT_EQ(verdict(ray({1.0f, 0.5f, 0}, {0, 0, 1}), hit_on(2.0f, 0, 0), std::nullopt),
            HitAgreement::kAmbiguous);
  // A hit the oracle does not see, away from any edge, is a bug.
  EXPECT_EQ(verdict(ray({0.5f, -0.5f, 0}, {0, 0, 1}), std::nullopt, hit_on(2.0f, 0, 0)),
            HitAgreement::kHard);
  // At exactly tmax, in or out is rounding.
  EXPECT_EQ(
      verdict(ray({0.75f, 0.25f, 0}, {0, 0, 1}, 0.0f, 2.0f), hit_on(2.0f, 0, 0), std::nullopt),
      HitAgreement::kAmbiguous);
  // Grazing the sphere's silhouette: rounding; through its middle: a bug.
  EXPECT_EQ(verdict(ray({6, -5, 2}, {0, 1, 0}), hit_on(5.0f, 2, 0), std::nullopt),
            HitAgreement::kAmbiguous);
  EXPECT_EQ(verdict(ray({5, -5, 2}, {0, 1, 0}), hit_on(4.0f, 2, 0), std::nullopt),
            HitAgreement::kHard);
  // The sphere returned where the quad is nearer and solidly hit: a bug.
  EXPECT_EQ(verdict(ray({0.2f, 0.25f, 1.9f}, {1, 0, 0.2f}), hit_on(0.5f, 0, 0), hit_on(4.1f, 2, 0)),
            HitAgreement::kHard);
}

TEST(AccelHitComparison, TallyKeepsTheFirstReasonOfEachKind) {
  AgreementTally tally;
  tally.add({HitAgreement::kSame, ""}, "r0");
  tally.add({HitAgreement::kHard, "first"}, "r1");
  tally.add({HitAgreement::kHard, "second"}, "r2");
  tally.add({HitAgreement::kTie, "tie"}, "r3");
  EXPECT_EQ(tally.total(), 4u);
  EXPECT_EQ(tally.hard, 2u);
  EXPECT_NE(tally.first_hard.find("first"), std::string::npos);
  EXPECT_NE(tally.first_hard.find("r1"), std::string::npos);
  EXPECT_EQ(tally.summary(), "same=1 tie=1 ambiguous=0 hard=2");
}

}  // namespace
}  // namespace prism
