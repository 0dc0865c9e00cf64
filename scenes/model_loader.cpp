#include "scenes/model_loader.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <exception>
#include <new>

#include "core/error.h"
#include "core/strings.h"
#include "scenes/mesh_file_loader.h"
#include "scenes/model/model_geometry.h"
#include "scenes/model/model_lights.h"
#include "scenes/model/model_materials.h"
#include "scenes/model/model_view.h"

namespace prism {
namespace {

/// The file read by Assimp: triangles only (polygons fan-triangulated, points and lines
/// dropped), identical vertices shared, the data structure validated.
const aiScene* import_model(Assimp::Importer& importer, const std::filesystem::path& path,
                            const ErrorLocation& where) {
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_SortByPType | aiProcess_ValidateDataStructure;
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path.string(), flags);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(ErrorKind::kInput, std::string("cannot read model file: ") + e.what(), where);
  }
  if (scene == nullptr) {
    std::string message = importer.GetErrorString();
    // Assimp's messages may span lines; the error is one line.
    for (char& c : message) {
      if (c == '\n' || c == '\r') c = ' ';
    }
    throw Error(ErrorKind::kInput, "cannot read model file: " + message, where);
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene->mNumMeshes == 0) {
    throw Error(ErrorKind::kInput, "model file contains no meshes", where);
  }
  return scene;
}

}  // namespace

bool is_model_extension(const std::string& extension) {
  for (const char* e : {".obj", ".ply", ".stl", ".gltf", ".glb", ".fbx"}) {
    if (extension == e) return true;
  }
  return false;
}

Scene load_model(const std::filesystem::path& path, const SceneLoadOptions& options) {
  const ErrorLocation where{path.string(), 0, {}};
  const std::string ext = lower_case_extension(path);
  if (!is_model_extension(ext)) {
    throw Error(ErrorKind::kInput,
                "unsupported model file extension '" + ext +
                    "'; supported: .obj, .ply, .stl, .gltf, .glb, .fbx",
                where);
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(ErrorKind::kInput, "model path is not a regular file", where);
  }
  try {
    if (ext == ".ply") check_ply_structure(path, where);
    Assimp::Importer importer;
    const aiScene& in = *import_model(importer, path, where);
    Scene scene;
    scene.source = path.string();
    model::ModelMaterials materials(in, path, scene);
    const model::NodeTransforms transforms = model::append_model_meshes(
        in, [&](const aiMesh& mesh) { return materials.index_of(mesh.mMaterialIndex); }, where,
        scene.geometry);
    if (scene.geometry.triangle_count() == 0) {
      throw Error(ErrorKind::kInput, "model file contains no triangles", where);
    }
    for (const TriangleMesh& mesh : scene.geometry.meshes) {
      const Material& m = scene.materials[mesh.material_id];
      if (m.is_textured() && mesh.uvs.empty()) {
        scene.warnings.push_back(path.string() + ": mesh '" + mesh.name +
                                 "' has no texture coordinates; the texture of its material '" +
                                 m.name +
                                 "' is looked up at each triangle's barycentric "
                                 "coordinates");
      }
    }
    const model::ModelAxes axes = model::model_axes(in);
    scene.lights = model::model_lights(in, transforms, axes, path, scene.warnings);
    scene.camera = model::model_camera(in, transforms, scene.geometry.bounds(), axes,
                                       options.literal_camera, path);
    if (!model::has_lighting(scene)) model::add_default_lighting(scene, axes, path);
    return scene;
  } catch (const std::bad_alloc&) {
    throw Error(ErrorKind::kResource, "out of memory while reading the model file", where);
  }
}

}  // namespace prism
