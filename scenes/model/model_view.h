#pragma once

// The camera of a model file: the homework framing by default, the file's camera with
// --literal-camera (docs/SCENE_FORMAT.md, "Model files").

#include <filesystem>

#include "core/bounds.h"
#include "core/camera.h"
#include "core/math.h"
#include "scenes/model/model_geometry.h"

struct aiScene;

namespace prism::model {

/// The model's own axes: up, the side it faces the viewer with (front) and right =
/// cross(up, front). +Y up and +Z front (glTF's convention, and Assimp's) unless the file's
/// metadata says otherwise (FBX's UpAxis and UpAxisSign: a Z-up file faces -Y, as Blender's
/// front view shows it).
struct ModelAxes {
  Vec3 up{0.0f, 1.0f, 0.0f};
  Vec3 front{0.0f, 0.0f, 1.0f};
  Vec3 right{1.0f, 0.0f, 0.0f};
};
ModelAxes model_axes(const aiScene& scene);

/// Where the homework framing looks from when a model has no camera: front + 0.5 up + 0.3
/// right, normalised (a little above and to the right of the front, about 25 degrees up).
Vec3 default_view_direction(const ModelAxes& axes);

/// The camera of a model with geometry `bounds`. Default: the homework framing
/// (collada::frame_homework(), up = axes.up) from the direction c = normalize(M p), p the
/// point one unit in front of the file's first camera in its node's frame and M the node's
/// world transform (the COLLADA rule), with that camera's fields of view and clip planes; from
/// default_view_direction() with Blender's default lens (as for COLLADA) when the file has no
/// camera. `literal`: the file's first camera as it is (position, look-at direction and up
/// through its node's transform; Assimp's horizontal field of view, taken as the full angle,
/// and aspect ratio, 4:3 when the file has none). Throws Error(kInput) naming `file` when
/// `literal` and the file has no camera, or its camera is degenerate (a field of view outside
/// (0, 180) degrees, a transform that collapses its frame).
Camera model_camera(const aiScene& scene, const NodeTransforms& transforms, const Bounds3& bounds,
                    const ModelAxes& axes, bool literal, const std::filesystem::path& file);

}  // namespace prism::model
