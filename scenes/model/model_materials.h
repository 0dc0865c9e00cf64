#pragma once

// Materials of a model file read by Assimp, mapped to prism's (docs/SCENE_FORMAT.md, "Model
// files").

#include <cstdint>
#include <filesystem>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/scene.h"

struct aiScene;

namespace prism::model {

/// Smallest Beckmann alpha a metal gets (roughness 0 would be a mirror the microfacet model
/// cannot sample well).
inline constexpr float kMinMetalAlpha = 0.01f;
/// Metallic factors from this value up make a conductor; below it, a diffuse surface.
inline constexpr float kMetallicThreshold = 0.5f;
/// Reflectance of the grey diffuse material of files without materials (STL, PLY, and OBJ
/// without a material library, whose meshes Assimp gives its "DefaultMaterial").
inline constexpr float kDefaultGrey = 0.5f;

/// The materials of `scene` (read from `file`), converted as meshes ask for them, so that the
/// scene holds only materials some mesh uses: appended to scene.materials, their textures to
/// scene.textures, notes to scene.warnings.
class ModelMaterials {
 public:
  ModelMaterials(const aiScene& scene, const std::filesystem::path& file, Scene& out);

  /// Index in Scene::materials of Assimp material `index`, converting it on first use. Throws
  /// Error(kInput) naming the file and material when a texture it names is missing (an
  /// external file not found, an embedded one the file does not have).
  uint32_t index_of(unsigned index);

 private:
  Material convert(unsigned index);
  /// The index in Scene::textures of the texture `path` a material names.
  uint32_t texture(const std::string& path, const std::string& material);

  const aiScene& scene_;
  std::filesystem::path file_;
  Scene& out_;
  std::unordered_map<unsigned, uint32_t> converted_;
  bool gltf_;           ///< glTF's alpha mode decides whether opacity means transparency
  bool has_materials_;  ///< false for formats that carry none (STL, PLY)
};

}  // namespace prism::model
