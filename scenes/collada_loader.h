#pragma once

#include <filesystem>

#include "core/scene.h"
#include "scenes/scene_loader.h"

namespace prism {

/// Loads a CS184 COLLADA 1.4.1 file with the "CGL" profile, as ../shared/docs/cs184-collada.md
/// describes it: node hierarchy and transforms, polylist/triangles with normals and uvs, CGL
/// spheres, all CGL materials, all light types, and the homework's camera framing unless
/// options.literal_camera. Throws Error(kInput) naming file, line and element on bad input.
Scene load_collada(const std::filesystem::path& path, const SceneLoadOptions& options);

}  // namespace prism
