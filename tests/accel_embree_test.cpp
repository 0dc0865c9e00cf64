// The Embree backend (accel/embree/): its quality and robustness variants, and the vertex
// padding Embree needs.

#include <gtest/gtest.h>

#include <utility>

#include "accel/accelerator.h"
#include "core/error.h"
#include "core/param_set.h"
#include "core/scene_geometry.h"
#include "tests/support/accel_test_geometry.h"

namespace prism {
namespace {

using test::one_triangle;
using test::ray;

TEST(AccelEmbree, RobustAndQualityVariantsAgreeOnSimpleHits) {
  SceneGeometry g = one_triangle();
  g.spheres.push_back({Vec3(0, 0, 5), 1.0f, 0});
  for (const char* quality : {"low", "medium", "high"}) {
    for (const char* robust : {"false", "true"}) {
      ParamSet params;
      params.set("embree.quality", quality);
      params.set("embree.robust", robust);
      const auto accel = accelerator_registry().create("embree", params);
      accel->build(g);
      const auto hit = accel->intersect(ray({-0.5f, -0.5f, 0}, {0, 0, 1}));
      ASSERT_TRUE(hit) << quality << " " << robust;
      EXPECT_EQ(hit->t, 2.0f);
      const auto sphere = accel->intersect(ray({0, 0, 0}, {0, 0, 1}, 2.5f));
      ASSERT_TRUE(sphere);
      EXPECT_EQ(sphere->t, 4.0f);
    }
  }
}

TEST(AccelEmbree, MissingVertexPaddingIsAnInternalError) {
  SceneGeometry g;
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.positions.shrink_to_fit();
  m.triangles = {{0, 1, 2}};
  if (m.positions.capacity() > m.positions.size()) GTEST_SKIP() << "shrink_to_fit kept capacity";
  g.meshes.push_back(std::move(m));
  const auto accel = accelerator_registry().create("embree", {});
  try {
    accel->build(g);
    FAIL() << "expected the padding check to fail";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInternal);
  }
}

}  // namespace
}  // namespace prism
