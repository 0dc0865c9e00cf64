#pragma once

#include <cstddef>
#include <string>

#include "core/scene.h"
#include "scenes/mesh_generator.h"

namespace prism {

/// A generated mesh of `kind` with about `count` triangles (generate_mesh(), seed 1) inside a
/// closed box three times its size, so that bounce rays hit something, with a camera looking
/// at it and a point light. Validated. For `prism bench`, `prism validate` and tests.
Scene make_generated_scene(GeneratedMeshKind kind, size_t count);

/// The scene a SCENE argument of `prism bench` or `prism validate` names: a scene file
/// (load_scene()), or a generated scene "gen:KIND:COUNT" where COUNT may end in k or M
/// (gen:soup:100k). `name` receives a short label ("soup_100k", "CBbunny"). Throws
/// Error(kUsage) on a malformed gen: spec, Error(kInput) on a bad file.
Scene load_scene_or_generated(const std::string& spec, std::string& name);

}  // namespace prism
