#include "scenes/collada/camera_framing.h"

#include <algorithm>
#include <cmath>

#include "scenes/collada/transforms.h"

namespace prism::collada {
namespace {

double fov_from(double fov_deg, double ratio) {
  return 2.0 * glm::degrees(std::atan(std::tan(glm::radians(fov_deg) * 0.5) * ratio));
}

void apply_clip(const CameraOptics& optics, Camera& camera) {
  if (optics.znear) camera.znear = static_cast<float>(*optics.znear);
  if (optics.zfar) camera.zfar = static_cast<float>(*optics.zfar);
}

}  // namespace

CameraOptics parse_camera(const Document& doc, pugi::xml_node instance) {
  const pugi::xml_node camera = doc.resolve(instance, "url", "camera");
  const pugi::xml_node common =
      doc.require_child(doc.require_child(camera, "optics"), "technique_common");
  const pugi::xml_node perspective = common.child("perspective");
  if (!perspective) {
    if (common.child("orthographic")) doc.fail(common, "orthographic cameras are not supported");
    doc.fail(common, "missing <perspective>");
  }
  const auto read = [&](const char* name) -> std::optional<double> {
    const pugi::xml_node e = perspective.child(name);
    if (!e) return std::nullopt;
    return doc.scalar(e);
  };
  const auto fov = [&](const char* name) -> std::optional<double> {
    const std::optional<double> v = read(name);
    if (v && !(*v > 0.0 && *v < 180.0)) {
      doc.fail(perspective.child(name), std::string(name) + " must be in (0, 180) degrees");
    }
    return v;
  };
  const std::optional<double> xfov = fov("xfov"), yfov = fov("yfov");
  const double aspect = read("aspect_ratio").value_or(4.0 / 3.0);
  if (!(aspect > 0.0)) doc.fail(perspective.child("aspect_ratio"), "aspect_ratio must be > 0");
  CameraOptics optics;
  if (xfov && yfov) {
    optics.hfov_deg = *xfov;
    optics.vfov_deg = *yfov;
  } else if (xfov) {
    optics.hfov_deg = *xfov;
    optics.vfov_deg = fov_from(*xfov, 1.0 / aspect);
  } else if (yfov) {
    optics.vfov_deg = *yfov;
    optics.hfov_deg = fov_from(*yfov, aspect);
  } else {
    doc.fail(perspective, "needs xfov or yfov");
  }
  if (!(optics.hfov_deg < 180.0)) {
    doc.fail(perspective, "yfov and aspect_ratio give a horizontal fov of 180 degrees or more");
  }
  optics.znear = read("znear");
  optics.zfar = read("zfar");
  if (optics.znear && !(*optics.znear >= 0.0)) {
    doc.fail(perspective.child("znear"), "znear must be >= 0");
  }
  if (optics.zfar && !(*optics.zfar > optics.znear.value_or(0.0))) {
    doc.fail(perspective.child("zfar"), "zfar must be greater than znear");
  }
  return optics;
}

DVec3 homework_view_direction(const DMat4& camera_world) {
  // The homework's Vector4D::to3D(): x, y, z of M (0, 0, -1, 1), w dropped.
  const DVec3 p(camera_world * glm::dvec4(0.0, 0.0, -1.0, 1.0));
  const double length = glm::length(p);
  if (!(length > 1e-12) || !std::isfinite(length)) return kDefaultViewDirection;
  return p / length;
}

Camera frame_homework(const CameraOptics& optics, const Bounds3& bounds, DVec3 c, Vec3 up_axis) {
  const DVec3 up(up_axis);
  if (glm::length(glm::cross(c, up)) < 1e-4) {
    const DVec3 tilt = std::abs(up.y) > 0.9 ? DVec3(0.0, 0.0, 1.0) : DVec3(0.0, -1.0, 0.0);
    c = glm::normalize(c + 0.01 * tilt);
  }
  DVec3 target(0.0);
  double diagonal = 0.0;
  if (!bounds.empty()) {
    target = 0.5 * (DVec3(bounds.lower) + DVec3(bounds.upper));
    diagonal = glm::length(DVec3(bounds.upper) - DVec3(bounds.lower));
  }
  const double r = diagonal > 0.0 ? 1.5 * diagonal : 1.0;
  Camera camera;
  camera.target = Vec3(target);
  camera.position = Vec3(target + r * c);
  camera.up = up_axis;
  camera.hfov_deg = static_cast<float>(optics.hfov_deg);
  camera.vfov_deg = static_cast<float>(optics.vfov_deg);
  apply_clip(optics, camera);
  camera.zfar = std::max(camera.zfar, static_cast<float>(r + diagonal));
  return camera;
}

Camera literal_camera(const Document& doc, pugi::xml_node instance, const CameraOptics& optics,
                      const DMat4& camera_world) {
  const DVec3 position = transform_point(camera_world, DVec3(0.0));
  const DVec3 forward = transform_vector(camera_world, DVec3(0, 0, -1));
  const DVec3 up = transform_vector(camera_world, DVec3(0, 1, 0));
  const double forward_length = glm::length(forward), up_length = glm::length(up);
  if (!(forward_length > 0.0) || !(up_length > 0.0) || !std::isfinite(forward_length) ||
      !std::isfinite(up_length) || !is_finite(Vec3(position))) {
    doc.fail(instance, "the camera node's transform collapses or overflows its frame");
  }
  Camera camera;
  camera.position = Vec3(position);
  camera.target = Vec3(position + forward / forward_length);
  camera.up = Vec3(up / up_length);
  camera.hfov_deg = static_cast<float>(optics.hfov_deg);
  camera.vfov_deg = static_cast<float>(optics.vfov_deg);
  apply_clip(optics, camera);
  return camera;
}

}  // namespace prism::collada
