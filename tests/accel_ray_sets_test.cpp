// The validation ray sets (accel/validation/ray_sets): the exact hex-float text form, and the
// random and feature rays (aimed at vertices, edges and sphere silhouettes).

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <string>

#include "accel/validation/ray_sets.h"
#include "tests/support/accel_test_geometry.h"

namespace prism {
namespace {

using test::quad_scene;
using test::ray;

uint32_t bits(float x) { return std::bit_cast<uint32_t>(x); }

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

}  // namespace
}  // namespace prism
