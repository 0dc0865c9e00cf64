#include "scenes/model/model_geometry.h"

#include <assimp/scene.h>

#include <limits>
#include <utility>
#include <vector>

#include "scenes/json/json_meshes.h"

namespace prism::model {
namespace {

/// Assimp's row-major matrix as glm's column-major one.
Mat4 to_mat4(const aiMatrix4x4& m) {
  Mat4 out;
  const float rows[4][4] = {{m.a1, m.a2, m.a3, m.a4},
                            {m.b1, m.b2, m.b3, m.b4},
                            {m.c1, m.c2, m.c3, m.c4},
                            {m.d1, m.d2, m.d3, m.d4}};
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) out[col][row] = rows[row][col];
  }
  return out;
}

size_t count_triangles(const aiMesh& mesh) {
  size_t n = 0;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) n += mesh.mFaces[f].mNumIndices == 3 ? 1 : 0;
  return n;
}

/// The mesh in its own frame: positions, triangles, per-corner normals and uvs.
TriangleMesh local_mesh(const aiMesh& in) {
  TriangleMesh out;
  out.positions.reserve(size_t(in.mNumVertices) + 1);  // +1: Embree's padding (finalize())
  for (unsigned i = 0; i < in.mNumVertices; ++i) {
    const aiVector3D& p = in.mVertices[i];
    out.positions.emplace_back(p.x, p.y, p.z);
  }
  const bool normals = in.HasNormals(), uvs = in.HasTextureCoords(0);
  const size_t triangles = count_triangles(in);
  out.triangles.reserve(triangles);
  if (normals) out.normals.reserve(3 * triangles);
  if (uvs) out.uvs.reserve(3 * triangles);
  for (unsigned f = 0; f < in.mNumFaces; ++f) {
    const aiFace& face = in.mFaces[f];
    // SortByPType removed points and lines; anything else that is not a triangle is skipped.
    if (face.mNumIndices != 3) continue;
    const unsigned* idx = face.mIndices;
    out.triangles.emplace_back(idx[0], idx[1], idx[2]);
    for (int c = 0; c < 3; ++c) {
      if (normals) {
        const aiVector3D& n = in.mNormals[idx[c]];
        out.normals.emplace_back(n.x, n.y, n.z);
      }
      if (uvs) {
        const aiVector3D& t = in.mTextureCoords[0][idx[c]];
        out.uvs.emplace_back(t.x, t.y);
      }
    }
  }
  return out;
}

}  // namespace

NodeTransforms append_model_meshes(const aiScene& scene,
                                   const std::function<uint32_t(const aiMesh&)>& material_of,
                                   const ErrorLocation& where, SceneGeometry& geometry) {
  NodeTransforms transforms;
  if (scene.mRootNode == nullptr) return transforms;
  uint64_t total = 0;
  uint64_t visits = 0;
  // Depth first, children in file order: a stack of (node, parent's world transform).
  std::vector<std::pair<const aiNode*, Mat4>> stack = {{scene.mRootNode, Mat4(1.0f)}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (++visits > kMaxModelNodes) {
      throw Error(ErrorKind::kInput,
                  "the model's node tree has more than " + std::to_string(kMaxModelNodes) +
                      " nodes (or a cycle)",
                  where);
    }
    const Mat4 world = parent * to_mat4(node->mTransformation);
    transforms.emplace(node->mName.C_Str(), world);
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      if (node->mMeshes[i] >= scene.mNumMeshes) continue;  // ValidateDataStructure rejects it
      const aiMesh& mesh = *scene.mMeshes[node->mMeshes[i]];
      if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
      total += count_triangles(mesh);
      if (total > kMaxModelTriangles) {
        throw Error(ErrorKind::kInput,
                    "the model holds more than " + std::to_string(kMaxModelTriangles) +
                        " triangles once its instances are expanded",
                    where);
      }
      TriangleMesh instance = local_mesh(mesh);
      if (instance.triangles.empty()) continue;
      json::transform_mesh(world, instance);
      for (const Vec3& p : instance.positions) {
        if (!is_finite(p)) {
          throw Error(ErrorKind::kInput,
                      "a vertex of mesh '" + std::string(mesh.mName.C_Str()) + "' in node '" +
                          node->mName.C_Str() + "' is not finite once transformed",
                      where);
        }
      }
      instance.name = std::string(node->mName.C_Str()) + "/" + mesh.mName.C_Str();
      instance.material_id = material_of(mesh);
      geometry.meshes.push_back(std::move(instance));
    }
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      if (node->mChildren[c] != nullptr) stack.emplace_back(node->mChildren[c], world);
    }
  }
  return transforms;
}

}  // namespace prism::model
