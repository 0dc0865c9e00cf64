// core/camera.h: the primary rays of the pinhole and thin-lens camera, fit_to_aspect, and
// validate(), against hand-derived frames and angles.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/error.h"

namespace prism {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

float angle_deg(Vec3 a, Vec3 b) {
  return degrees(
      std::acos(glm::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)));
}

/// Distance from `p` to the line of `ray`.
float distance_to_line(const Ray& ray, Vec3 p) {
  const Vec3 d = glm::normalize(ray.direction);
  const Vec3 w = p - ray.origin;
  return glm::length(w - glm::dot(w, d) * d);
}

void expect_vec_near(Vec3 a, Vec3 b, float tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance) << "x";
  EXPECT_NEAR(a.y, b.y, tolerance) << "y";
  EXPECT_NEAR(a.z, b.z, tolerance) << "z";
}

/// A camera at an arbitrary place looking at an arbitrary point.
Camera oblique_camera() {
  Camera c;
  c.position = Vec3(1.0f, 2.0f, 3.0f);
  c.target = Vec3(-2.0f, 0.5f, 7.0f);
  c.up = Vec3(0.0f, 1.0f, 0.0f);
  c.hfov_deg = 60.0f;
  c.vfov_deg = 40.0f;
  return c;
}

TEST(CoreCamera, CentreRayPointsAtTheTarget) {
  for (const Camera& camera : {Camera{}, oblique_camera()}) {
    const Ray ray = camera.generate_ray(Vec2(0.5f));
    expect_vec_near(ray.origin, camera.position, 1e-6f);
    EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-6f);
    expect_vec_near(ray.direction, glm::normalize(camera.target - camera.position), 1e-6f);
    EXPECT_LT(distance_to_line(ray, camera.target), 1e-5f);
  }
}

TEST(CoreCamera, DefaultCameraLooksDownMinusZWithXRightAndYUp) {
  // From (0, 0, 5) towards the origin with y up, the image's right is +x and its top is +y.
  const Camera camera;
  const Ray right = camera.generate_ray(Vec2(1.0f, 0.5f));
  const Ray left = camera.generate_ray(Vec2(0.0f, 0.5f));
  const Ray top = camera.generate_ray(Vec2(0.5f, 0.0f));
  const Ray bottom = camera.generate_ray(Vec2(0.5f, 1.0f));
  const float tan_h = std::tan(radians(50.0f / 2.0f));
  const float tan_v = std::tan(radians(37.5f / 2.0f));
  // Direction (x, y, -1) normalised.
  expect_vec_near(right.direction, glm::normalize(Vec3(tan_h, 0.0f, -1.0f)), 1e-6f);
  expect_vec_near(left.direction, glm::normalize(Vec3(-tan_h, 0.0f, -1.0f)), 1e-6f);
  expect_vec_near(top.direction, glm::normalize(Vec3(0.0f, tan_v, -1.0f)), 1e-6f);
  expect_vec_near(bottom.direction, glm::normalize(Vec3(0.0f, -tan_v, -1.0f)), 1e-6f);
  // The top-left corner, and a point a quarter of the way in: the film is linear in tangent
  // space (a flat image plane), not in angle.
  const Ray corner = camera.generate_ray(Vec2(0.0f, 0.0f));
  expect_vec_near(corner.direction, glm::normalize(Vec3(-tan_h, tan_v, -1.0f)), 1e-6f);
  const Ray quarter = camera.generate_ray(Vec2(0.75f, 0.25f));
  expect_vec_near(quarter.direction, glm::normalize(Vec3(0.5f * tan_h, 0.5f * tan_v, -1.0f)),
                  1e-6f);
}

TEST(CoreCamera, EdgesSpanTheFieldsOfView) {
  const Camera camera = oblique_camera();
  const Vec3 forward = glm::normalize(camera.target - camera.position);
  const Ray left = camera.generate_ray(Vec2(0.0f, 0.5f));
  const Ray right = camera.generate_ray(Vec2(1.0f, 0.5f));
  const Ray top = camera.generate_ray(Vec2(0.5f, 0.0f));
  const Ray bottom = camera.generate_ray(Vec2(0.5f, 1.0f));
  EXPECT_NEAR(angle_deg(left.direction, right.direction), camera.hfov_deg, 1e-3f);
  EXPECT_NEAR(angle_deg(top.direction, bottom.direction), camera.vfov_deg, 1e-3f);
  EXPECT_NEAR(angle_deg(left.direction, forward), camera.hfov_deg / 2.0f, 1e-3f);
  EXPECT_NEAR(angle_deg(top.direction, forward), camera.vfov_deg / 2.0f, 1e-3f);
  // The top of the image is towards up; left and right are symmetric about the up plane.
  EXPECT_GT(glm::dot(top.direction, camera.up), 0.0f);
  EXPECT_LT(glm::dot(bottom.direction, camera.up), 0.0f);
  EXPECT_NEAR(glm::dot(left.direction, camera.up), glm::dot(right.direction, camera.up), 1e-6f);
}

TEST(CoreCamera, ImageRightFollowsTheRightHandRule) {
  // Looking along +x with z up, the image's right is -y and its top +z.
  Camera camera;
  camera.position = Vec3(0.0f);
  camera.target = Vec3(10.0f, 0.0f, 0.0f);
  camera.up = Vec3(0.0f, 0.0f, 1.0f);
  camera.hfov_deg = 90.0f;
  camera.vfov_deg = 90.0f;
  expect_vec_near(camera.generate_ray(Vec2(1.0f, 0.5f)).direction,
                  glm::normalize(Vec3(1.0f, -1.0f, 0.0f)), 1e-6f);
  expect_vec_near(camera.generate_ray(Vec2(0.5f, 0.0f)).direction,
                  glm::normalize(Vec3(1.0f, 0.0f, 1.0f)), 1e-6f);
}

TEST(CoreCamera, OnlyThePartOfUpAcrossTheViewMatters) {
  // up need not be unit length nor perpendicular to the view direction.
  Camera a;
  Camera b;
  b.up = Vec3(0.0f, 3.0f, 0.0f);
  Camera c;
  c.up = Vec3(0.0f, 1.0f, 1.0f);  // view is -z: the z part is along it
  for (const Vec2 film : {Vec2(0.1f, 0.2f), Vec2(0.9f, 0.6f), Vec2(0.0f, 1.0f)}) {
    expect_vec_near(b.generate_ray(film).direction, a.generate_ray(film).direction, 1e-6f);
    expect_vec_near(c.generate_ray(film).direction, a.generate_ray(film).direction, 1e-6f);
  }
}

TEST(CoreCamera, RayIntervalBoundsTheViewAxisDistance) {
  Camera camera = oblique_camera();
  camera.znear = 0.5f;
  camera.zfar = 100.0f;
  const Vec3 forward = glm::normalize(camera.target - camera.position);
  for (const Vec2 film : {Vec2(0.5f), Vec2(0.0f, 0.0f), Vec2(1.0f, 0.3f), Vec2(0.2f, 1.0f)}) {
    const Ray ray = camera.generate_ray(film);
    EXPECT_NEAR(glm::dot(ray.at(ray.tmin) - camera.position, forward), 0.5f, 1e-5f);
    EXPECT_NEAR(glm::dot(ray.at(ray.tmax) - camera.position, forward), 100.0f, 1e-3f);
    // Off-axis rays travel further than the view-axis distance.
    EXPECT_GE(ray.tmin, 0.5f * (1.0f - 1e-6f));
  }
  const Ray corner = camera.generate_ray(Vec2(0.0f, 0.0f));
  const float tan_h = std::tan(radians(30.0f)), tan_v = std::tan(radians(20.0f));
  EXPECT_NEAR(corner.tmin, 0.5f * std::sqrt(1.0f + tan_h * tan_h + tan_v * tan_v), 1e-5f);
}

TEST(CoreCamera, FitToAspectWidensTheHorizontalFieldForWideImages) {
  Camera camera;  // hfov 50, vfov 37.5: tan ratio 1.3735
  camera.fit_to_aspect(2.0f);
  EXPECT_FLOAT_EQ(camera.vfov_deg, 37.5f);
  EXPECT_NEAR(camera.hfov_deg, degrees(2.0f * std::atan(2.0f * std::tan(radians(18.75f)))), 1e-4f);
  EXPECT_GT(camera.hfov_deg, 50.0f);
  EXPECT_NEAR(std::tan(radians(camera.hfov_deg) / 2) / std::tan(radians(camera.vfov_deg) / 2), 2.0f,
              1e-5f);
}

TEST(CoreCamera, FitToAspectWidensTheVerticalFieldForTallImages) {
  for (const float aspect : {1.0f, 0.5f, 4.0f / 3.0f}) {
    SCOPED_TRACE(aspect);
    Camera camera;
    camera.fit_to_aspect(aspect);
    EXPECT_FLOAT_EQ(camera.hfov_deg, 50.0f);
    EXPECT_GT(camera.vfov_deg, 37.5f);
    EXPECT_NEAR(camera.vfov_deg, degrees(2.0f * std::atan(std::tan(radians(25.0f)) / aspect)),
                1e-4f);
  }
}

TEST(CoreCamera, FitToAspectNeverNarrowsAndIsIdempotent) {
  for (const float aspect : {0.25f, 0.75f, 1.0f, 1.3735f, 1.5f, 16.0f / 9.0f, 3.0f}) {
    SCOPED_TRACE(aspect);
    Camera camera = oblique_camera();
    camera.fit_to_aspect(aspect);
    EXPECT_GE(camera.hfov_deg, 60.0f);
    EXPECT_GE(camera.vfov_deg, 40.0f);
    // Exactly one of them moved (or neither, within rounding, at the matching aspect).
    EXPECT_TRUE(camera.hfov_deg == 60.0f || camera.vfov_deg == 40.0f);
    EXPECT_NEAR(std::tan(radians(camera.hfov_deg) / 2) / std::tan(radians(camera.vfov_deg) / 2),
                aspect, 1e-5f * aspect);
    const Camera once = camera;
    camera.fit_to_aspect(aspect);
    EXPECT_NEAR(camera.hfov_deg, once.hfov_deg, 1e-3f);
    EXPECT_NEAR(camera.vfov_deg, once.vfov_deg, 1e-3f);
  }
}

TEST(CoreCamera, ThinLensRaysConvergeOnThePlaneInFocus) {
  Camera camera = oblique_camera();
  camera.lens_radius = 0.2f;
  camera.focal_distance = 3.0f;
  Camera pinhole = camera;
  pinhole.lens_radius = 0.0f;
  const Vec3 forward = glm::normalize(camera.target - camera.position);
  /// The point of `ray` at view-axis distance `depth` from the camera.
  const auto at_depth = [&](const Ray& ray, float depth) {
    const float start = glm::dot(ray.origin - camera.position, forward);
    return ray.at((depth - start) / glm::dot(ray.direction, forward));
  };

  for (const Vec2 film : {Vec2(0.5f), Vec2(0.1f, 0.8f), Vec2(0.95f, 0.05f)}) {
    SCOPED_TRACE(testing::Message() << film.x << "," << film.y);
    const Vec3 in_focus = at_depth(pinhole.generate_ray(film), 3.0f);
    float origin_spread = 0.0f, far_spread = 0.0f;
    const Vec3 far_centre = at_depth(pinhole.generate_ray(film), 6.0f);
    for (int i = 0; i < 5; ++i) {
      for (int j = 0; j < 8; ++j) {
        const Vec2 lens((i + 0.5f) / 5.0f, j / 8.0f);
        const Ray ray = camera.generate_ray(film, lens);
        EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-5f);
        // The origin lies on the lens: the disk of lens_radius across the view axis.
        const Vec3 offset = ray.origin - camera.position;
        EXPECT_NEAR(glm::dot(offset, forward), 0.0f, 1e-5f);
        EXPECT_LE(glm::length(offset), 0.2f + 1e-5f);
        origin_spread = std::max(origin_spread, glm::length(offset));
        // Every lens ray passes through the pinhole ray's point at the focal distance...
        expect_vec_near(at_depth(ray, 3.0f), in_focus, 1e-5f);
        // ...and not through its point elsewhere.
        far_spread = std::max(far_spread, glm::length(at_depth(ray, 6.0f) - far_centre));
        // tmin still bounds the view-axis distance.
        EXPECT_NEAR(glm::dot(ray.at(ray.tmin) - camera.position, forward), camera.znear, 1e-5f);
      }
    }
    EXPECT_GT(origin_spread, 0.15f);
    EXPECT_GT(far_spread, 0.1f);
  }
}

TEST(CoreCamera, LensSamplesCoverTheApertureUniformly) {
  // A stratified grid of lens samples: the share of ray origins within half the radius is the
  // share of the area, 1/4, and each half of the disk gets half of them.
  Camera camera = oblique_camera();
  camera.lens_radius = 0.5f;
  camera.focal_distance = 2.0f;
  const Vec3 forward = glm::normalize(camera.target - camera.position);
  const Vec3 right = glm::normalize(glm::cross(forward, camera.up));
  constexpr int kGrid = 64;
  int inner = 0, right_half = 0;
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const Vec2 lens((i + 0.5f) / kGrid, (j + 0.5f) / kGrid);
      const Vec3 offset = camera.generate_ray(Vec2(0.3f, 0.6f), lens).origin - camera.position;
      ASSERT_LE(glm::length(offset), 0.5f + 1e-5f);
      inner += glm::length(offset) < 0.25f;
      right_half += glm::dot(offset, right) > 0.0f;
    }
  }
  EXPECT_NEAR(double(inner) / (kGrid * kGrid), 0.25, 0.01);
  EXPECT_NEAR(double(right_half) / (kGrid * kGrid), 0.5, 0.01);
}

TEST(CoreCamera, PinholeIgnoresTheLensSample) {
  const Camera camera = oblique_camera();
  const Ray a = camera.generate_ray(Vec2(0.3f, 0.6f));
  for (const Vec2 lens : {Vec2(0.0f), Vec2(0.9f, 0.1f), Vec2(0.37f, 0.99f)}) {
    const Ray b = camera.generate_ray(Vec2(0.3f, 0.6f), lens);
    EXPECT_EQ(b.origin, a.origin);
    EXPECT_EQ(b.direction, a.direction);
    EXPECT_EQ(b.tmin, a.tmin);
    EXPECT_EQ(b.tmax, a.tmax);
  }
}

/// The ErrorKind that validate() throws for `camera`, or "none".
std::string validation_result(const Camera& camera) {
  try {
    camera.validate();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("camera"), std::string::npos) << e.what();
    return e.kind() == ErrorKind::kInput ? "kInput" : "other kind";
  }
  return "none";
}

TEST(CoreCamera, ProjectInvertsGenerateRay) {
  Camera c = oblique_camera();
  c.znear = 0.5f;
  c.zfar = 40.0f;
  const CameraRayGenerator camera(c);
  for (const Vec2 film : {Vec2(0.5f), Vec2(0.1f, 0.9f), Vec2(0.97f, 0.02f), Vec2(0.3f, 0.6f)}) {
    const Ray ray = camera.generate_ray(film);
    const float t = 7.0f;
    const std::optional<FilmProjection> seen = camera.project(ray.origin + t * ray.direction);
    ASSERT_TRUE(seen.has_value());
    EXPECT_NEAR(seen->film.x, film.x, 1e-5f);
    EXPECT_NEAR(seen->film.y, film.y, 1e-5f);
    EXPECT_NEAR(seen->distance, t, 1e-4f);
    expect_vec_near(seen->to_camera, -ray.direction, 1e-5f);
    const Vec3 forward = glm::normalize(c.target - c.position);
    EXPECT_NEAR(seen->cos_view, glm::dot(ray.direction, forward), 1e-6f);
    // The camera ray starts at the near point: its tmin is the near plane.
    expect_vec_near(seen->near_point, ray.origin + ray.tmin * ray.direction, 1e-5f);
  }
  // Behind the camera, off the film, nearer than znear, beyond zfar: not seen.
  const Vec3 forward = glm::normalize(c.target - c.position);
  EXPECT_FALSE(camera.project(c.position - 3.0f * forward).has_value());
  EXPECT_FALSE(camera.project(c.position + forward + 5.0f * Vec3(0.0f, 1.0f, 0.0f)).has_value());
  EXPECT_FALSE(camera.project(c.position + 0.4f * forward).has_value());
  EXPECT_FALSE(camera.project(c.position + 41.0f * forward).has_value());
  // The film's area on the plane at depth 1, per pixel.
  const float tan_h = std::tan(radians(30.0f)), tan_v = std::tan(radians(20.0f));
  EXPECT_NEAR(camera.pixel_area(40, 20), (2.0f * tan_h / 40.0f) * (2.0f * tan_v / 20.0f), 1e-9f);
}

TEST(CoreCamera, ValidateAcceptsOrdinaryCameras) {
  EXPECT_EQ(validation_result(Camera{}), "none");
  EXPECT_EQ(validation_result(oblique_camera()), "none");
  Camera lens = oblique_camera();
  lens.lens_radius = 0.1f;
  lens.focal_distance = 4.0f;
  EXPECT_EQ(validation_result(lens), "none");
  Camera wide;
  wide.hfov_deg = 179.0f;
  wide.vfov_deg = 0.5f;
  EXPECT_EQ(validation_result(wide), "none");
}

TEST(CoreCamera, ValidateRejectsDegenerateCameras) {
  const auto changed = [](auto change) {
    Camera c;
    change(c);
    return validation_result(c);
  };
  EXPECT_EQ(changed([](Camera& c) { c.target = c.position; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.up = Vec3(0.0f, 0.0f, 1.0f); }), "kInput");   // along view
  EXPECT_EQ(changed([](Camera& c) { c.up = Vec3(0.0f, 0.0f, -3.0f); }), "kInput");  // opposite
  EXPECT_EQ(changed([](Camera& c) { c.up = Vec3(0.0f); }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.hfov_deg = 0.0f; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.vfov_deg = 0.0f; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.hfov_deg = -10.0f; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.hfov_deg = 180.0f; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.vfov_deg = 200.0f; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.hfov_deg = kNaN; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.vfov_deg = kInf; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.position.x = kNaN; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.target.y = kInf; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.up.z = -kInf; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.lens_radius = kNaN; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) { c.lens_radius = -0.1f; }), "kInput");
  EXPECT_EQ(changed([](Camera& c) {
              c.lens_radius = 0.1f;
              c.focal_distance = kInf;
            }),
            "kInput");
  EXPECT_EQ(changed([](Camera& c) {
              c.lens_radius = 0.1f;
              c.focal_distance = 0.0f;
            }),
            "kInput");
}

}  // namespace
}  // namespace prism
