#pragma once

#include <optional>

#include <pugixml.hpp>

#include "core/bounds.h"
#include "core/camera.h"
#include "core/math.h"
#include "scenes/collada/document.h"
#include "scenes/collada/transforms.h"

namespace prism::collada {

/// The optics of a COLLADA <camera>: full fields of view in degrees and clip distances.
struct CameraOptics {
  double hfov_deg = 49.13434;  ///< Blender's default 35 mm lens, the one every shipped file uses
  double vfov_deg = 2.0 * glm::degrees(std::atan(std::tan(glm::radians(49.13434 / 2.0)) * 0.75));
  std::optional<double> znear, zfar;
};

/// Reads optics/technique_common/perspective of the <camera> named by `instance` (an
/// <instance_camera>): xfov is the horizontal fov; without yfov the vertical one follows from
/// aspect_ratio (4/3, the homework's 480 x 360, when that is absent too); with only yfov the
/// horizontal one follows the same way. Throws Error(kInput) on an orthographic camera, on no
/// fov at all, on a fov outside (0, 180) or on bad clip distances.
CameraOptics parse_camera(const Document& doc, pugi::xml_node instance);

/// Where the homework's viewer puts the camera: c = normalize(M * (0, 0, -1, 1)), the point one
/// unit in front of the camera node taken as a direction from the world origin. Like the
/// homework, it reads only M's top three rows (no division by w), so a camera <matrix> short of
/// its bottom row frames as it does there. Falls back to kDefaultViewDirection when that point
/// is the origin.
DVec3 homework_view_direction(const DMat4& camera_world);

/// View direction used when a file has no camera: from the -Y side looking along +Y, which is
/// Blender's "front" view and the direction of the CBbunny camera.
inline constexpr DVec3 kDefaultViewDirection{0.0, -1.0, 0.0};

/// The homework framing: target = centre of `bounds` (all geometry), r = 1.5 x its diagonal
/// length (1 for an empty or single-point box), position = target + r c, up = `up` (for
/// COLLADA +Z, the world up, see transforms.h; model files pass their own). A direction
/// (anti)parallel to up is tilted 0.01 rad toward -Y (toward +Z when up is along Y), as the
/// homework's viewer clamps its polar angle away from the pole. zfar grows to r + diagonal if
/// needed, so the framed scene is never clipped.
Camera frame_homework(const CameraOptics& optics, const Bounds3& bounds, DVec3 c,
                      Vec3 up = kWorldUp);

/// The file's camera as it is: at M's origin, looking down M's -Z, with M's +Y as up.
/// Throws Error(kInput) at `instance` when M collapses those axes.
Camera literal_camera(const Document& doc, pugi::xml_node instance, const CameraOptics& optics,
                      const DMat4& camera_world);

}  // namespace prism::collada
