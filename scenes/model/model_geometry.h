#pragma once

// The node tree of a model file read by Assimp: world transforms and mesh instances.

#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>

#include "core/error.h"
#include "core/math.h"
#include "core/scene_geometry.h"

struct aiScene;
struct aiMesh;

namespace prism::model {

/// Most triangles a model may have once its instances are expanded (about 3.6 GB of mesh), so
/// that a small hostile file that instantiates a large mesh many times is an error, not an
/// out-of-memory.
inline constexpr uint64_t kMaxModelTriangles = 100'000'000;

/// Most nodes a model's tree may have (a cyclic tree from a hostile file stops here too).
inline constexpr uint64_t kMaxModelNodes = 10'000'000;

/// World transforms of the named nodes (the first node of each name), which cameras and lights
/// refer to.
using NodeTransforms = std::unordered_map<std::string, Mat4>;

/// Walks the node tree of `scene` depth first, iteratively (a deep tree cannot overflow the
/// stack), and appends one TriangleMesh per (node, mesh) instance to `geometry`: the node's
/// world transform applied to positions, to per-corner normals by the inverse transpose
/// (renormalised), with the winding reversed under a mirroring transform so fronts stay on
/// their side; per-corner uvs of texture coordinate set 0 when the mesh has them; only
/// triangles. The mesh is named "<node>/<mesh>", its material_id is `material_of(mesh)`.
/// Returns the transforms of every named node. Throws Error(kInput) at `where` when the
/// instances hold more than kMaxModelTriangles triangles, the tree more than kMaxModelNodes
/// nodes, or a vertex is not finite once transformed.
NodeTransforms append_model_meshes(const aiScene& scene,
                                   const std::function<uint32_t(const aiMesh&)>& material_of,
                                   const ErrorLocation& where, SceneGeometry& geometry);

}  // namespace prism::model
