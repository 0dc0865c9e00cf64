#pragma once

#include <optional>

#include "core/math.h"
#include "core/ray.h"

namespace prism {

/// Pinhole or thin-lens perspective camera in world space.
struct Camera {
  Vec3 position{0.0f, 0.0f, 5.0f};
  Vec3 target{0.0f};  ///< a point the camera looks at
  Vec3 up{0.0f, 1.0f, 0.0f};
  float hfov_deg = 50.0f;       ///< full horizontal field of view
  float vfov_deg = 37.5f;       ///< full vertical field of view
  float znear = 0.01f;          ///< rays start at this distance along the view axis
  float zfar = 1e30f;           ///< and end at this one
  float lens_radius = 0.0f;     ///< 0 for a pinhole
  float focal_distance = 1.0f;  ///< distance of the plane in focus (thin lens only)

  /// Widens (never narrows) one field of view so that tan(hfov/2) / tan(vfov/2) == aspect
  /// (width / height of the output image).
  void fit_to_aspect(float aspect);

  /// Throws Error(kInput) if the camera is degenerate (position == target, up parallel to the
  /// view direction, fov outside (0, 180), non-finite values).
  void validate() const;

  /// Whether generate_ray() reads its `lens` sample (a thin lens, lens_radius > 0); a pinhole
  /// camera's sampler dimensions for it can be skipped.
  bool uses_lens() const { return lens_radius > 0.0f; }

  /// The primary ray through film position `film` in [0,1]^2 ((0,0) is the top-left corner of
  /// the image, x to the right, y down), using `lens` in [0,1)^2 when uses_lens().
  /// The direction is unit length; tmin/tmax bound the view-axis distance to [znear, zfar].
  Ray generate_ray(Vec2 film, Vec2 lens = Vec2(0.5f)) const;
};

/// Where a pinhole camera sees a point, from CameraRayGenerator::project().
struct FilmProjection {
  Vec2 film{0.0f};        ///< film position in [0,1)^2, as generate_ray() takes it
  Vec3 to_camera{0.0f};   ///< unit, from the point toward the camera
  float distance = 0.0f;  ///< from the point to the camera
  float cos_view = 0.0f;  ///< cosine between the camera's ray to the point and the view axis
  Vec3 near_point{0.0f};  ///< where that ray starts: its point at view depth znear
};

/// Camera::generate_ray() with the terms that depend only on the camera (its basis, the
/// tangents of the half fields of view) computed once, for render loops: the same rays, bit
/// for bit, without two tan() calls and three normalisations per ray. Copies the camera.
class CameraRayGenerator {
 public:
  explicit CameraRayGenerator(const Camera& camera);
  /// Camera::generate_ray(film, lens) of the camera given to the constructor.
  Ray generate_ray(Vec2 film, Vec2 lens = Vec2(0.5f)) const;
  /// Where a pinhole camera (lens_radius 0) sees `p`: the inverse of generate_ray(). Nothing
  /// when p is behind the camera, off the film, or at a view depth outside [znear, zfar].
  std::optional<FilmProjection> project(const Vec3& p) const;
  /// The area of one pixel of a width x height image on the plane at view depth 1, over which
  /// generate_ray() spreads a pixel's rays uniformly.
  float pixel_area(int width, int height) const {
    return (2.0f * tan_h_ / float(width)) * (2.0f * tan_v_ / float(height));
  }

 private:
  Camera camera_;
  Vec3 forward_, right_, true_up_;
  float tan_h_, tan_v_;
};

}  // namespace prism
