#include "scenes/scene_loader.h"

#include <algorithm>
#include <cctype>

#include "core/error.h"
#include "core/strings.h"
#include "scenes/collada_loader.h"
#include "scenes/json_scene_loader.h"
#include "scenes/model_loader.h"

namespace prism {

Scene load_scene(const std::filesystem::path& path, const SceneLoadOptions& options) {
  const ErrorLocation where{path.string(), 0, {}};
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw Error(ErrorKind::kInput, "scene file not found", where);
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(ErrorKind::kInput, "scene path is a directory, not a file", where);
  }
  const std::string ext = lower_case_extension(path);
  Scene scene;
  if (ext == ".dae") {
    scene = load_collada(path, options);
  } else if (ext == ".json") {
    scene = load_json_scene(path);
  } else if (is_model_extension(ext)) {
    scene = load_model(path, options);
  } else {
    throw Error(ErrorKind::kInput,
                "unknown scene format '" + ext +
                    "'; supported: .dae (CS184 COLLADA), .json (prism), and model files .obj, "
                    ".ply, .stl, .gltf, .glb, .fbx",
                where);
  }
  scene.source = path.string();
  try {
    scene.validate();
  } catch (const Error& e) {
    ErrorLocation located = e.location();
    if (located.file.empty()) located.file = path.string();
    throw Error(e.kind(), e.message(), located);
  }
  scene.geometry.finalize();
  return scene;
}

std::filesystem::path bundled_scene_dir() {
  return std::filesystem::path(PRISM_SOURCE_DIR) / "scenes" / "data";
}

std::filesystem::path default_scene_path() { return bundled_scene_dir() / "cornell_spheres.json"; }

}  // namespace prism
