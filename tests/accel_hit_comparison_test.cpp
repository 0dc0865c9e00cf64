// The classifier of disagreements between two backends (accel/validation/hit_comparison): the
// exact rule, the tolerant rule (which must call real bugs HARD and rounding AMBIGUOUS or TIE),
// and the tally.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "accel/validation/double_oracle.h"
#include "accel/validation/hit_comparison.h"
#include "tests/support/accel_test_geometry.h"

namespace prism {
namespace {

using test::quad_scene;
using test::ray;

Hit hit_on(float t, uint32_t geom, uint32_t prim) { return Hit{t, 0.25f, 0.25f, geom, prim}; }

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
