#pragma once

#include <filesystem>
#include <string>

#include "core/scene.h"

namespace prism {

/// How a scene file is turned into a Scene.
struct SceneLoadOptions {
  /// COLLADA and model files: use the file's camera as it is instead of the CS184 homework
  /// framing (an error for a model file without a camera).
  bool literal_camera = false;
};

/// Loads a scene by extension, in any case: .dae (CS184 COLLADA), .json (prism's native
/// format), or a model file through Assimp (.obj, .ply, .stl, .gltf, .glb, .fbx: load_model()).
/// Throws Error(kInput) with file, line and element on malformed input; the returned scene has
/// passed Scene::validate() and SceneGeometry::finalize().
Scene load_scene(const std::filesystem::path& path, const SceneLoadOptions& options = {});

/// The scene rendered when no SCENE is given: the bundled Cornell box with two spheres
/// (scenes/data/cornell_spheres.json, located next to the source tree or installed data).
std::filesystem::path default_scene_path();

/// Directory of the scenes the project ships (scenes/data).
std::filesystem::path bundled_scene_dir();

}  // namespace prism
