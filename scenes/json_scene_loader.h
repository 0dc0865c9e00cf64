#pragma once

#include <filesystem>

#include "core/scene.h"

namespace prism {

/// Loads prism's native JSON scene format (docs/SCENE_FORMAT.md). Relative mesh paths resolve
/// against the scene file's folder. Throws Error(kInput) naming file, line and JSON path.
Scene load_json_scene(const std::filesystem::path& path);

}  // namespace prism
