// The double-precision oracle of the validation tools (accel/validation/double_oracle): the
// closest hit under the tie rule, and the probe that measures how close a ray is to an edge.

#include <gtest/gtest.h>

#include <cmath>

#include "accel/validation/double_oracle.h"
#include "core/error.h"
#include "tests/support/accel_test_geometry.h"

namespace prism {
namespace {

using test::quad_scene;
using test::ray;

TEST(AccelDoubleOracle, ClosestFollowsTheTieRule) {
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

TEST(AccelDoubleOracle, ProbeMeasuresEdgeDistanceAndGrazing) {
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

}  // namespace
}  // namespace prism
