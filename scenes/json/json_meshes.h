#pragma once

// The `meshes` entries of a JSON scene (inline, file, generated) and their transforms.

#include <cstdint>
#include <filesystem>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/scene_geometry.h"
#include "scenes/json/json_document.h"

namespace prism::json {

/// Largest `generate.triangles` a scene may ask for (documented in docs/SCENE_FORMAT.md): about
/// 1.5 GB of mesh, so that a typo of a few zeros is an error rather than an out-of-memory.
inline constexpr int64_t kMaxGeneratedTriangles = 50'000'000;

/// Material names of a scene and their indices into Scene::materials.
class MaterialNames {
 public:
  /// Records `name` as material `id`; fails at `where` if the name is empty or taken.
  void add(const std::string& name, uint32_t id, const JsonNode& where);
  /// The id of the material named by the string `reference`; fails naming the missing material
  /// and listing the defined ones.
  uint32_t resolve(const JsonNode& reference) const;

 private:
  std::unordered_map<std::string, uint32_t> ids_;
  std::vector<std::string> names_;  ///< in definition order, for messages
};

/// Reads one `meshes[i]` object. `default_name` names it when it has no "name"; relative
/// `file` paths resolve against `base_dir`.
TriangleMesh read_mesh(const JsonNode& node, const MaterialNames& materials,
                       const std::filesystem::path& base_dir, const std::string& default_name);

/// Reads a `transform` object (translate, rotate, scale, or matrix) as a 4x4 affine matrix.
Mat4 read_transform(const JsonNode& node);

/// Applies an invertible affine `m` to positions and normals; mirrors flip the winding so that
/// faces keep their orientation.
void transform_mesh(const Mat4& m, TriangleMesh& mesh);

}  // namespace prism::json
