// Spherical rectangles (integrators/sampling/spherical_rectangle.h): the solid angle against
// the rectangle's two triangles, chi-square goodness of fit of the sampled directions against
// the uniform density 1 / solid angle, and the sampled points on the rectangle.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

#include "integrators/sampling/spherical_rectangle.h"
#include "integrators/sampling/warp.h"
#include "tests/support/chi_square.h"

namespace prism {
namespace {

// One chi-square test per reference point of SamplingIsUniformInSolidAngle.
const double kSignificance = test::sidak_significance(0.01, 5);

/// A rectangle of `size` on the plane of normal (0.2, 0.3, 1), its x edge turned by `turn`.
Rectangle tilted_rectangle(const Vec3& corner, Vec2 size, float turn) {
  const Vec3 n = glm::normalize(Vec3(0.2f, 0.3f, 1.0f));
  const Vec3 a = glm::normalize(glm::cross(n, Vec3(1.0f, 0.0f, 0.0f)));
  const Vec3 b = glm::cross(n, a);
  const Vec3 x = std::cos(turn) * a + std::sin(turn) * b;
  const Vec3 y = glm::cross(n, x);
  const std::optional<Rectangle> r =
      rectangle_from_corner(corner, corner + size.x * x, corner + size.y * y);
  EXPECT_TRUE(r);
  return *r;
}

/// Whether the ray from `p` along `w` meets the rectangle.
bool hits(const Rectangle& r, const Vec3& p, const Vec3& w) {
  const float along = glm::dot(w, r.normal);
  if (along == 0.0f) return false;
  const float t = glm::dot(r.corner - p, r.normal) / along;
  if (!(t > 0.0f)) return false;
  const Vec3 q = p + t * w - r.corner;
  const float x = glm::dot(q, r.unit_x), y = glm::dot(q, r.unit_y);
  return x >= 0.0f && x <= r.length_x && y >= 0.0f && y <= r.length_y;
}

float two_triangles_solid_angle(const Rectangle& r, const Vec3& p) {
  const Vec3 a = r.corner - p;
  const Vec3 b = a + r.length_x * r.unit_x;
  const Vec3 c = b + r.length_y * r.unit_y;
  const Vec3 d = a + r.length_y * r.unit_y;
  return triangle_solid_angle(a, b, c) + triangle_solid_angle(a, c, d);
}

TEST(IntegratorsSphericalRectangle, RectanglesAreOnlyOrthogonalCorners) {
  EXPECT_TRUE(rectangle_from_corner(Vec3(1.0f), Vec3(2.0f, 1.0f, 1.0f), Vec3(1.0f, 1.0f, 3.0f)));
  EXPECT_FALSE(rectangle_from_corner(Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.01f, 1.0f, 0.0f)));
  EXPECT_FALSE(rectangle_from_corner(Vec3(0.0f), Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f)));
  const std::optional<Rectangle> r =
      rectangle_from_corner(Vec3(0.0f), Vec3(0.0f, 2.0f, 0.0f), Vec3(0.5f, 0.0f, 0.0f));
  ASSERT_TRUE(r);
  EXPECT_FLOAT_EQ(r->area(), 1.0f);
  EXPECT_NEAR(glm::dot(r->normal, Vec3(0.0f, 0.0f, -1.0f)), 1.0f, 1e-6f);
}

TEST(IntegratorsSphericalRectangle, SolidAngleIsTheTwoTrianglesSum) {
  // Reference points on both sides, over the rectangle and beside it, near and far.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  const Rectangle r = tilted_rectangle(Vec3(-0.4f, -0.3f, 0.2f), Vec2(0.8f, 0.6f), 0.7f);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
    const float expected = two_triangles_solid_angle(r, p);
    const float omega = SphericalRectangle(r, p).solid_angle();
    EXPECT_NEAR(omega, expected, 1e-6f + 1e-5f * expected) << p.x << " " << p.y << " " << p.z;
    ++checked;
  }
  EXPECT_EQ(checked, 2000);
  // Centred above a w x h rectangle at distance d: 4 asin(w h / sqrt((w^2 + 4 d^2) (h^2 + 4 d^2))).
  const Rectangle flat = *rectangle_from_corner(Vec3(-0.6f, -0.35f, 0.0f), Vec3(0.6f, -0.35f, 0.0f),
                                                Vec3(-0.6f, 0.35f, 0.0f));
  const float w = 1.2f, h = 0.7f, d = 0.4f;
  EXPECT_NEAR(SphericalRectangle(flat, Vec3(0.0f, 0.0f, -d)).solid_angle(),
              4.0f * std::asin(w * h / std::sqrt((w * w + 4 * d * d) * (h * h + 4 * d * d))),
              1e-5f);
  EXPECT_EQ(SphericalRectangle(flat, Vec3(5.0f, 1.0f, 0.0f)).solid_angle(), 0.0f);  // its plane
}

TEST(IntegratorsSphericalRectangle, SamplingIsUniformInSolidAngle) {
  const Rectangle r = tilted_rectangle(Vec3(-0.4f, -0.3f, 1.0f), Vec2(0.8f, 0.6f), 0.3f);
  const Vec3 centre = r.point_at(Vec2(0.5f));
  // Over the middle, beside it, behind its plane, nearly in its plane (close to 2 pi), and far
  // enough that the directions fill a few cells only.
  for (const Vec3& p : {centre - r.normal, centre + 1.2f * r.unit_x - 0.5f * r.normal,
                        centre + 0.3f * r.unit_y + 0.8f * r.normal, centre - 0.01f * r.normal,
                        centre - 4.0f * r.normal}) {
    const SphericalRectangle sr(r, p);
    const float omega = sr.solid_angle();
    ASSERT_GT(omega, 0.0f);
    const test::DirectionSampler sampler = [&](float, Vec2 u) -> std::optional<Vec3> {
      const std::optional<Vec3> q = sr.sample(u);
      if (!q) return std::nullopt;
      return glm::normalize(*q - p);
    };
    const test::DirectionPdf pdf = [&](const Vec3& w) -> double {
      return hits(r, p, w) ? 1.0 / omega : 0.0;
    };
    test::DirectionalChiSquareOptions options;
    options.theta_bins = 40;
    options.phi_bins = 80;
    const test::ChiSquareResult result = test::directional_chi_square(sampler, pdf, options);
    EXPECT_EQ(result.impossible_observations, 0u) << omega;
    EXPECT_GT(result.p_value, kSignificance)
        << result.summary() << " at " << p.x << " " << p.y << " " << p.z;
  }
}

TEST(IntegratorsSphericalRectangle, SamplesLieOnTheRectangle) {
  const Rectangle r = tilted_rectangle(Vec3(2.0f, -1.0f, 3.0f), Vec2(1.5f, 0.25f), 1.1f);
  const Vec3 p(2.5f, -0.5f, 2.2f);
  const SphericalRectangle sr(r, p);
  int missing = 0;
  for (int i = 0; i < 4096; ++i) {
    const Vec2 u((float(i % 64) + 0.5f) / 64.0f, (float(i / 64) + 0.5f) / 64.0f);
    const std::optional<Vec3> q = sr.sample(u);
    if (!q) {
      ++missing;
      continue;
    }
    const Vec3 local = *q - r.corner;
    EXPECT_NEAR(glm::dot(local, r.normal), 0.0f, 1e-5f);
    EXPECT_GE(glm::dot(local, r.unit_x), -1e-5f);
    EXPECT_LE(glm::dot(local, r.unit_x), r.length_x + 1e-5f);
    EXPECT_GE(glm::dot(local, r.unit_y), -1e-5f);
    EXPECT_LE(glm::dot(local, r.unit_y), r.length_y + 1e-5f);
  }
  EXPECT_EQ(missing, 0);
  // The corners of u's square map to the rectangle's corners.
  const Vec3 c00 = *sr.sample(Vec2(0.0f, 0.0f));
  EXPECT_LT(glm::length(c00 - r.corner), 1e-4f);
}

}  // namespace
}  // namespace prism
