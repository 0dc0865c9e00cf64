#pragma once

#include <filesystem>
#include <string>

#include "core/scene.h"
#include "scenes/scene_loader.h"

namespace prism {

/// Whether load_model() reads files with this extension (lower case, with the dot): .obj,
/// .ply, .stl, .gltf, .glb, .fbx.
bool is_model_extension(const std::string& extension);

/// Loads a model file through Assimp as a whole scene (docs/SCENE_FORMAT.md, "Model files"):
/// every mesh instance of its node tree with the node transforms applied (model/model_geometry.h),
/// its materials mapped to prism's with their base-colour and emission textures (from files
/// beside it or embedded; model/model_materials.h), its lights, and a camera: the homework
/// framing, or with options.literal_camera the file's own (model/model_view.h). A model
/// without lights or emissive surfaces gets the default lighting (model/model_lights.h), and a
/// warning says so. Throws Error(kInput) naming the file, in one line, when the extension is
/// not one of is_model_extension()'s, the file is not a regular file, Assimp cannot read it
/// (its message included), it holds no triangle, a texture it names is missing, or it breaks
/// the limits of model/model_geometry.h; Error(kResource) when memory runs out.
Scene load_model(const std::filesystem::path& path, const SceneLoadOptions& options);

}  // namespace prism
