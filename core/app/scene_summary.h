#pragma once

// What a scene holds, counted once for `prism info` (which prints it) and the Python module's
// prism.load_scene() / prism.info() (which return it as a dict).

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/bounds.h"
#include "core/camera.h"
#include "core/scene.h"

namespace prism {

/// A total and a count per name ("diffuse" 2, "emission" 1), names in first-seen order.
struct CountByName {
  size_t total = 0;
  std::vector<std::pair<std::string, size_t>> counts;

  /// "3 (diffuse 2, emission 1)"; just "0" when empty.
  std::string to_string() const;
};

/// The counts, bounds, camera and settings `prism info` reports on a scene.
struct SceneSummary {
  std::string source;
  size_t triangles = 0;
  size_t meshes = 0;
  size_t spheres = 0;
  size_t emissive_meshes = 0;         ///< meshes whose material emits
  CountByName lights;                 ///< by light type
  CountByName materials;              ///< by material type
  std::vector<std::string> textures;  ///< texture names, in the scene's order
  Bounds3 bounds;                     ///< of every primitive; empty() for a scene without any
  Camera camera;                      ///< as the file gives it (before the render fits its aspect)
  SceneRenderSettings settings;
};

SceneSummary summarize_scene(const Scene& scene);

}  // namespace prism
