#include "scenes/model/model_view.h"

#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "core/error.h"
#include "core/strings.h"
#include "scenes/collada/camera_framing.h"

namespace prism::model {
namespace {

Vec3 axis_vector(int32_t axis, int32_t sign) {
  Vec3 v(0.0f);
  v[axis] = sign < 0 ? -1.0f : 1.0f;
  return v;
}

Error camera_error(const std::filesystem::path& file, const std::string& message) {
  return Error(ErrorKind::kInput, message, {file.string(), 0, "camera"});
}

/// The point one unit in front of the camera, and its frame, in world space.
struct CameraFrame {
  Vec3 position, ahead, forward, up;
};

CameraFrame camera_frame(const aiCamera& camera, const NodeTransforms& transforms, bool gltf) {
  const auto it = transforms.find(camera.mName.C_Str());
  const Mat4 m = it != transforms.end() ? it->second : Mat4(1.0f);
  // Assimp 5.2's glTF importer copies the camera node's translation into mPosition as well,
  // though the node's transform already places the camera: counted once here.
  const Vec3 position =
      gltf ? Vec3(0.0f) : Vec3(camera.mPosition.x, camera.mPosition.y, camera.mPosition.z);
  const Vec3 look(camera.mLookAt.x, camera.mLookAt.y, camera.mLookAt.z);
  const Vec3 up(camera.mUp.x, camera.mUp.y, camera.mUp.z);
  const float look_length = glm::length(look);
  CameraFrame frame;
  frame.position = Vec3(m * Vec4(position, 1.0f));
  frame.ahead =
      look_length > 0.0f ? Vec3(m * Vec4(position + look / look_length, 1.0f)) : frame.position;
  frame.forward = Vec3(m * Vec4(look, 0.0f));
  frame.up = Vec3(m * Vec4(up, 0.0f));
  return frame;
}

/// The optics of the file's camera, or nothing when it has none Assimp could describe.
std::optional<collada::CameraOptics> camera_optics(const aiCamera& camera) {
  const double hfov = glm::degrees(double(camera.mHorizontalFOV));
  if (camera.mOrthographicWidth > 0.0f || !(hfov > 0.0 && hfov < 180.0)) return std::nullopt;
  const double aspect =
      camera.mAspect > 0.0f && std::isfinite(camera.mAspect) ? double(camera.mAspect) : 4.0 / 3.0;
  collada::CameraOptics optics;
  optics.hfov_deg = hfov;
  optics.vfov_deg = 2.0 * glm::degrees(std::atan(std::tan(glm::radians(hfov) * 0.5) / aspect));
  if (camera.mClipPlaneNear > 0.0f && std::isfinite(camera.mClipPlaneNear)) {
    optics.znear = camera.mClipPlaneNear;
  }
  if (camera.mClipPlaneFar > optics.znear.value_or(0.0) && std::isfinite(camera.mClipPlaneFar)) {
    optics.zfar = camera.mClipPlaneFar;
  }
  return optics;
}

}  // namespace

ModelAxes model_axes(const aiScene& scene) {
  ModelAxes axes;
  int32_t up_axis = 1, up_sign = 1;
  if (scene.mMetaData == nullptr || !scene.mMetaData->Get("UpAxis", up_axis) || up_axis < 0 ||
      up_axis > 2) {
    return axes;
  }
  scene.mMetaData->Get("UpAxisSign", up_sign);
  axes.up = axis_vector(up_axis, up_sign);
  // Y up: the front is +Z; Z (or X) up: the front is -Y (or +Z), as Blender's front view.
  axes.front = up_axis == 2 ? Vec3(0.0f, -1.0f, 0.0f) : Vec3(0.0f, 0.0f, 1.0f);
  if (up_axis == 1 && up_sign < 0) axes.front = Vec3(0.0f, 0.0f, -1.0f);
  axes.right = glm::cross(axes.up, axes.front);
  return axes;
}

Vec3 default_view_direction(const ModelAxes& axes) {
  return glm::normalize(axes.front + 0.5f * axes.up + 0.3f * axes.right);
}

Camera model_camera(const aiScene& scene, const NodeTransforms& transforms, const Bounds3& bounds,
                    const ModelAxes& axes, bool literal, const std::filesystem::path& file) {
  const aiCamera* camera = scene.mNumCameras > 0 ? scene.mCameras[0] : nullptr;
  const std::string ext = lower_case_extension(file);
  const bool gltf = ext == ".gltf" || ext == ".glb";
  if (!literal) {
    collada::CameraOptics optics;
    DVec3 c(default_view_direction(axes));
    if (camera != nullptr) {
      optics = camera_optics(*camera).value_or(collada::CameraOptics{});
      // The homework's rule: the point ahead of the camera as a direction from the origin.
      const DVec3 ahead(camera_frame(*camera, transforms, gltf).ahead);
      const double length = glm::length(ahead);
      if (length > 1e-12 && std::isfinite(length)) c = ahead / length;
    }
    // The file's clip planes are for its own camera position, not the framed one (Assimp also
    // reports a near plane of 0.1 for files that give none): near enough for any model size.
    optics.znear.reset();
    optics.zfar.reset();
    Camera framed = collada::frame_homework(optics, bounds, c, axes.up);
    framed.znear = std::min(framed.znear, 1e-3f * glm::length(framed.position - framed.target));
    return framed;
  }
  if (camera == nullptr) {
    throw camera_error(file, "--literal-camera: the file has no camera");
  }
  const std::optional<collada::CameraOptics> optics = camera_optics(*camera);
  if (!optics) {
    throw camera_error(file, camera->mOrthographicWidth > 0.0f
                                 ? "orthographic cameras are not supported"
                                 : "the camera's horizontal field of view is not in (0, 180) "
                                   "degrees");
  }
  const CameraFrame frame = camera_frame(*camera, transforms, gltf);
  const float forward_length = glm::length(frame.forward), up_length = glm::length(frame.up);
  if (!(forward_length > 0.0f) || !(up_length > 0.0f) || !std::isfinite(forward_length) ||
      !std::isfinite(up_length) || !is_finite(frame.position) ||
      glm::length(glm::cross(frame.forward / forward_length, frame.up / up_length)) < 1e-6f) {
    throw camera_error(file, "the camera's transform collapses its frame");
  }
  Camera out;
  out.position = frame.position;
  out.target = frame.position + frame.forward / forward_length;
  out.up = frame.up / up_length;
  out.hfov_deg = float(optics->hfov_deg);
  out.vfov_deg = float(optics->vfov_deg);
  if (optics->znear) out.znear = float(*optics->znear);
  if (optics->zfar) out.zfar = float(*optics->zfar);
  return out;
}

}  // namespace prism::model
