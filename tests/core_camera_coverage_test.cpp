// core/camera_coverage: which pixels' camera rays may reach a box. Conservative (no pixel
// outside the rectangle has a ray that reaches the box), useful (a box in the middle of the
// view leaves the border out) and safe where it cannot tell (lens, box behind the camera).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/camera_coverage.h"

namespace prism {
namespace {

/// Whether `ray` meets `box` at some t in [tmin, tmax], in double (slab test).
bool ray_meets_box(const Ray& ray, const Bounds3& box) {
  double t0 = ray.tmin, t1 = ray.tmax;
  for (int a = 0; a < 3; ++a) {
    const double o = ray.origin[a], d = ray.direction[a];
    if (d == 0.0) {
      if (o < box.lower[a] || o > box.upper[a]) return false;
      continue;
    }
    double n = (box.lower[a] - o) / d, f = (box.upper[a] - o) / d;
    if (n > f) std::swap(n, f);
    t0 = std::max(t0, n);
    t1 = std::min(t1, f);
    if (t0 > t1) return false;
  }
  return true;
}

Camera pinhole(Vec3 position, Vec3 target, float hfov, float vfov) {
  return Camera{.position = position, .target = target, .hfov_deg = hfov, .vfov_deg = vfov};
}

TEST(CoreCameraCoverage, NoRayOfAPixelOutsideTheRectangleMeetsTheBox) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  constexpr int kWidth = 48, kHeight = 36;
  // Sample positions inside a pixel: its corners and edges included (the largest float below 1).
  const float offsets[] = {0.0f, 0.25f, 0.5f, 0.75f, 0.99999994f};
  int cases_with_border = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Vec3 centre(u(rng) * 3.0f, u(rng) * 3.0f, u(rng) * 3.0f - 8.0f);
    const Vec3 half(0.2f + 0.8f * std::abs(u(rng)), 0.2f + 0.8f * std::abs(u(rng)),
                    0.2f + 0.8f * std::abs(u(rng)));
    const Bounds3 box{centre - half, centre + half};
    Camera camera = pinhole(Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), -10.0f),
                            30.0f + 40.0f * std::abs(u(rng)), 25.0f + 40.0f * std::abs(u(rng)));
    camera.up = glm::normalize(Vec3(u(rng) * 0.3f, 1.0f, 0.0f));
    const PixelRect seeing = pixels_seeing_bounds(camera, box, kWidth, kHeight);
    ASSERT_TRUE((PixelRect{{0, 0}, {kWidth, kHeight}}).contains(seeing));
    if (seeing.pixel_count() < size_t(kWidth * kHeight)) ++cases_with_border;
    const CameraRayGenerator rays(camera);
    int pixels_meeting = 0;
    PixelRect met{{kWidth, kHeight}, {0, 0}};  // the pixels with a ray meeting the box
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        for (const float ox : offsets) {
          for (const float oy : offsets) {
            const Vec2 film((float(x) + ox) / float(kWidth), (float(y) + oy) / float(kHeight));
            const bool meets = ray_meets_box(rays.generate_ray(film), box);
            if (meets) {
              ++pixels_meeting;
              met.begin = glm::min(met.begin, glm::ivec2(x, y));
              met.end = glm::max(met.end, glm::ivec2(x + 1, y + 1));
            }
            ASSERT_TRUE(!meets || seeing.contains(glm::ivec2(x, y)))
                << "trial " << trial << " pixel " << x << ", " << y;
          }
        }
      }
    }
    // Useful: the rectangle is not far larger than what the rays meet (one pixel of margin,
    // one of rounding to whole pixels, one of the sample grid).
    if (pixels_meeting > 0 && seeing.pixel_count() < size_t(kWidth * kHeight)) {
      EXPECT_GE(seeing.begin.x, met.begin.x - 3) << "trial " << trial;
      EXPECT_GE(seeing.begin.y, met.begin.y - 3) << "trial " << trial;
      EXPECT_LE(seeing.end.x, met.end.x + 3) << "trial " << trial;
      EXPECT_LE(seeing.end.y, met.end.y + 3) << "trial " << trial;
    }
  }
  // Most random views leave part of the frame out, so the check above had pixels to check.
  EXPECT_GT(cases_with_border, 30);
}

TEST(CoreCameraCoverage, ABoxInTheMiddleLeavesTheBorderOut) {
  const Camera camera = pinhole(Vec3(0.0f, 0.0f, 10.0f), Vec3(0.0f), 40.0f, 30.0f);
  const Bounds3 box{Vec3(-1.0f), Vec3(1.0f)};
  const PixelRect seeing = pixels_seeing_bounds(camera, box, 480, 360);
  // The box's front face (z = 1, 9 away) spans tan^-1(1 / 9) of the half-angles' tangents:
  // 1 / 9 / tan(20 deg) = 0.305 of the half width, about 73 pixels each side of the centre.
  EXPECT_NEAR(seeing.begin.x, 240 - 73, 3);
  EXPECT_NEAR(seeing.end.x, 240 + 73, 3);
  EXPECT_TRUE(seeing.contains(glm::ivec2(240, 180)));
  EXPECT_FALSE(seeing.contains(glm::ivec2(10, 10)));
  EXPECT_FALSE(seeing.contains(glm::ivec2(470, 350)));
}

TEST(CoreCameraCoverage, TheWholeImageWhereItCannotTell) {
  const Bounds3 box{Vec3(-1.0f), Vec3(1.0f)};
  const PixelRect whole{{0, 0}, {64, 32}};
  Camera lens = pinhole(Vec3(0.0f, 0.0f, 10.0f), Vec3(0.0f), 40.0f, 30.0f);
  lens.lens_radius = 0.1f;
  lens.focal_distance = 10.0f;
  const PixelRect with_lens = pixels_seeing_bounds(lens, box, 64, 32);
  EXPECT_EQ(with_lens.begin, whole.begin);
  EXPECT_EQ(with_lens.end, whole.end);
  // The camera inside the box, and a box reaching behind the camera.
  for (const Vec3 position : {Vec3(0.0f), Vec3(0.0f, 0.0f, 1.5f)}) {
    const Camera camera = pinhole(position, Vec3(0.0f, 0.0f, -5.0f), 40.0f, 30.0f);
    const Bounds3 deep{Vec3(-1.0f, -1.0f, -3.0f), Vec3(1.0f, 1.0f, 2.0f)};
    const PixelRect seeing = pixels_seeing_bounds(camera, deep, 64, 32);
    EXPECT_EQ(seeing.begin, whole.begin);
    EXPECT_EQ(seeing.end, whole.end);
  }
  // Non-finite bounds: everything.
  const Bounds3 huge{Vec3(-kInfinity), Vec3(1.0f)};
  const Camera camera = pinhole(Vec3(0.0f, 0.0f, 10.0f), Vec3(0.0f), 40.0f, 30.0f);
  EXPECT_EQ(pixels_seeing_bounds(camera, huge, 64, 32).pixel_count(), whole.pixel_count());
  // Nothing to see: no pixel.
  EXPECT_TRUE(pixels_seeing_bounds(camera, Bounds3{}, 64, 32).empty());
}

}  // namespace
}  // namespace prism
