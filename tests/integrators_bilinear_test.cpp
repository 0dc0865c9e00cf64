// Bilinear warps (integrators/sampling/bilinear.h) and the corner weights rectangular emitters
// use them with (solid_angle_corners()): the inverse CDF of the linear density, the density
// of the bilinear map against its Jacobian, and the weights against cos / distance^2.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "integrators/sampling/bilinear.h"
#include "integrators/sampling/spherical_rectangle.h"

namespace prism {
namespace {

/// The CDF of the density proportional to (1 - x) a + x b on [0, 1].
double linear_cdf(double x, double a, double b) {
  return (a * x + 0.5 * (b - a) * x * x) / (0.5 * (a + b));
}

TEST(IntegratorsBilinear, SampleLinearInvertsItsCdf) {
  const double weights[][2] = {{1.0, 1.0},  {0.0, 1.0},   {1.0, 0.0},   {0.2, 5.0},
                               {7.0, 0.01}, {1e-6f, 3.0}, {2.0, 2.0001}};
  for (const auto& w : weights) {
    for (int i = 0; i <= 1000; ++i) {
      const float u = std::min(float(i) / 1000.0f, 0x1.fffffep-1f);
      const float x = sample_linear(u, float(w[0]), float(w[1]));
      ASSERT_GE(x, 0.0f);
      ASSERT_LT(x, 1.0f);
      EXPECT_NEAR(linear_cdf(x, w[0], w[1]), u, 2e-6) << "a " << w[0] << " b " << w[1];
    }
  }
}

/// |det| of the Jacobian of sample_bilinear() at u, by central differences.
double bilinear_jacobian(Vec2 u, const BilinearCorners& w) {
  const float h = 1e-3f;
  const Vec2 dx =
      (sample_bilinear(u + Vec2(h, 0.0f), w) - sample_bilinear(u - Vec2(h, 0.0f), w)) / (2.0f * h);
  const Vec2 dy =
      (sample_bilinear(u + Vec2(0.0f, h), w) - sample_bilinear(u - Vec2(0.0f, h), w)) / (2.0f * h);
  return std::abs(double(dx.x) * dy.y - double(dx.y) * dy.x);
}

TEST(IntegratorsBilinear, DensityIsTheInverseOfTheMapsJacobian) {
  // A map from the unit square onto itself has density 1 / |det J|: the density that
  // bilinear_pdf() reports must be the one sample_bilinear() draws from.
  const BilinearCorners corners[] = {{1.0f, 1.0f, 1.0f, 1.0f},
                                     {1.0f, 2.0f, 3.0f, 4.0f},
                                     {0.05f, 1.0f, 1.0f, 8.0f},
                                     {5.0f, 0.3f, 0.2f, 0.1f},
                                     {0.0f, 1.0f, 1.0f, 0.0f}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.01f, 0.99f);
  for (const BilinearCorners& w : corners) {
    for (int i = 0; i < 200; ++i) {
      const Vec2 u(uniform(rng), uniform(rng));
      const Vec2 p = sample_bilinear(u, w);
      const double pdf = bilinear_pdf(p, w);
      ASSERT_GT(pdf, 0.0);
      EXPECT_NEAR(pdf * bilinear_jacobian(u, w), 1.0, 2e-2)
          << "corners " << w[0] << " " << w[1] << " " << w[2] << " " << w[3] << " at " << u.x << " "
          << u.y;
    }
  }
}

TEST(IntegratorsBilinear, DensityIntegratesToOne) {
  const BilinearCorners w = {0.1f, 2.0f, 0.7f, 4.0f};
  const int n = 400;
  double sum = 0.0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      sum += bilinear_pdf(Vec2((x + 0.5f) / n, (y + 0.5f) / n), w);
    }
  }
  EXPECT_NEAR(sum / (n * n), 1.0, 1e-4);
  // Zero weights everywhere: no density (callers fall back before they get there).
  EXPECT_EQ(bilinear_pdf(Vec2(0.5f), BilinearCorners{0.0f, 0.0f, 0.0f, 0.0f}), 0.0f);
}

TEST(IntegratorsBilinear, SolidAngleCornersFollowCosOverDistanceSquared) {
  const std::optional<Rectangle> r = rectangle_from_corner(
      Vec3(-0.5f, 2.0f, -0.25f), Vec3(0.5f, 2.0f, -0.25f), Vec3(-0.5f, 2.0f, 0.25f));
  ASSERT_TRUE(r);
  for (const Vec3& p : {Vec3(0.0f), Vec3(1.5f, 1.2f, 0.3f), Vec3(-0.4f, 1.99f, -0.2f)}) {
    const BilinearCorners w = solid_angle_corners(*r, p);
    const Vec3 corners[4] = {r->point_at({0, 0}), r->point_at({1, 0}), r->point_at({0, 1}),
                             r->point_at({1, 1})};
    // cos / d^2 = |distance to the plane| / d^3: the same ratio to the weight at every corner.
    double ratio[4];
    for (int i = 0; i < 4; ++i) {
      const Vec3 d = corners[i] - p;
      const double distance = glm::length(d);
      const double cos = std::abs(glm::dot(d, r->normal)) / distance;
      ratio[i] = (cos / (distance * distance)) / w[i];
    }
    for (int i = 1; i < 4; ++i) EXPECT_NEAR(ratio[i] / ratio[0], 1.0, 1e-5);
  }
  // At a corner the weights are not finite: equal ones instead.
  const BilinearCorners at_corner = solid_angle_corners(*r, r->corner);
  for (float v : at_corner) EXPECT_EQ(v, 1.0f);
}

TEST(IntegratorsBilinear, ExtentOfInvertsPointAt) {
  const std::optional<Rectangle> r =
      rectangle_from_corner(Vec3(1.0f, 0.0f, 0.0f), Vec3(1.0f, 2.0f, 0.0f), Vec3(1.0f, 0.0f, 3.0f));
  ASSERT_TRUE(r);
  for (const Vec2 u : {Vec2(0.0f), Vec2(0.25f, 0.75f), Vec2(0.999f, 0.5f)}) {
    const Vec2 back = r->extent_of(r->point_at(u));
    EXPECT_NEAR(back.x, u.x, 1e-6f);
    EXPECT_NEAR(back.y, u.y, 1e-6f);
  }
  EXPECT_EQ(r->extent_of(Vec3(1.0f, -5.0f, 9.0f)), Vec2(0.0f, 1.0f));  // clamped
}

}  // namespace
}  // namespace prism
