#include "core/camera.h"

#include <cmath>

#include "core/error.h"

namespace prism {

void Camera::fit_to_aspect(float aspect) {
  const float tan_h = std::tan(radians(hfov_deg) * 0.5f);
  const float tan_v = std::tan(radians(vfov_deg) * 0.5f);
  if (tan_h / tan_v < aspect) {
    hfov_deg = degrees(2.0f * std::atan(tan_v * aspect));
  } else {
    vfov_deg = degrees(2.0f * std::atan(tan_h / aspect));
  }
}

void Camera::validate() const {
  const ErrorLocation where{{}, 0, "camera"};
  if (!is_finite(position) || !is_finite(target) || !is_finite(up)) {
    throw Error(ErrorKind::kInput, "camera position, target and up must be finite", where);
  }
  const Vec3 view = target - position;
  if (glm::length(view) == 0.0f) {
    throw Error(ErrorKind::kInput, "camera position and target coincide", where);
  }
  if (glm::length(glm::cross(glm::normalize(view), up)) < 1e-6f) {
    throw Error(ErrorKind::kInput, "camera up vector is parallel to the view direction", where);
  }
  if (!(hfov_deg > 0.0f && hfov_deg < 180.0f && vfov_deg > 0.0f && vfov_deg < 180.0f)) {
    throw Error(ErrorKind::kInput, "field of view must be between 0 and 180 degrees", where);
  }
  if (!(lens_radius >= 0.0f) || !(focal_distance > 0.0f) || !std::isfinite(lens_radius) ||
      !std::isfinite(focal_distance)) {
    throw Error(ErrorKind::kInput, "lens radius must be >= 0 and focal distance > 0", where);
  }
}

Ray Camera::generate_ray(Vec2 film, Vec2 lens) const {
  return CameraRayGenerator(*this).generate_ray(film, lens);
}

CameraRayGenerator::CameraRayGenerator(const Camera& camera)
    : camera_(camera),
      forward_(glm::normalize(camera.target - camera.position)),
      right_(glm::normalize(glm::cross(forward_, camera.up))),
      true_up_(glm::cross(right_, forward_)),
      tan_h_(std::tan(radians(camera.hfov_deg) * 0.5f)),
      tan_v_(std::tan(radians(camera.vfov_deg) * 0.5f)) {}

Ray CameraRayGenerator::generate_ray(Vec2 film, Vec2 lens) const {
  const float sx = (2.0f * film.x - 1.0f) * tan_h_;
  const float sy = (1.0f - 2.0f * film.y) * tan_v_;
  // Direction in camera space has view-axis component 1, so t along it is view depth.
  const Vec3 camera_dir{sx, sy, 1.0f};
  Vec3 origin_cam{0.0f};
  Vec3 dir_cam = camera_dir;
  if (camera_.uses_lens()) {
    // Uniform disk sample by polar mapping; refocus through the plane at focal_distance.
    const float r = camera_.lens_radius * std::sqrt(lens.x);
    const float phi = 2.0f * kPi * lens.y;
    origin_cam = Vec3(r * std::cos(phi), r * std::sin(phi), 0.0f);
    dir_cam = camera_dir * camera_.focal_distance - origin_cam;
  }
  const float length = glm::length(dir_cam);
  const float depth_per_t = dir_cam.z / length;
  return build_ray(camera_.position + origin_cam.x * right_ + origin_cam.y * true_up_,
                   glm::normalize(dir_cam.x * right_ + dir_cam.y * true_up_ + dir_cam.z * forward_),
                   camera_.znear / depth_per_t, camera_.zfar / depth_per_t);
}

std::optional<FilmProjection> CameraRayGenerator::project(const Vec3& p) const {
  const Vec3 d = p - camera_.position;
  const float depth = glm::dot(d, forward_);
  if (!(depth >= camera_.znear) || !(depth <= camera_.zfar)) return std::nullopt;
  // Inverse of generate_ray(): the direction's camera-space components over its view depth.
  const Vec2 film(0.5f * (glm::dot(d, right_) / depth / tan_h_ + 1.0f),
                  0.5f * (1.0f - glm::dot(d, true_up_) / depth / tan_v_));
  if (!(film.x >= 0.0f && film.x < 1.0f && film.y >= 0.0f && film.y < 1.0f)) return std::nullopt;
  FilmProjection f;
  f.film = film;
  f.distance = glm::length(d);
  if (!(f.distance > 0.0f)) return std::nullopt;
  f.to_camera = -d / f.distance;
  f.cos_view = depth / f.distance;
  f.near_point = camera_.position + d * (camera_.znear / depth);
  return f;
}

}  // namespace prism
