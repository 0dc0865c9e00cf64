#pragma once

#include <filesystem>

#include "core/error.h"
#include "core/scene_geometry.h"

namespace prism {

/// Loads every triangle of a Wavefront OBJ or PLY file (ASCII or binary) through Assimp into one
/// mesh: node transforms are applied, polygons are fan-triangulated, points and lines are
/// dropped, identical vertices are shared. Per-corner normals and uvs are kept when every part
/// of the file has them. The mesh's name is the file name; material_id is left 0.
/// Throws Error(kInput) with `path` as the file: when it does not exist, its extension is not
/// .obj/.ply, Assimp cannot read it (Assimp's message is included), it holds no triangle, or a
/// coordinate is not finite. Throws Error(kResource) when memory runs out.
TriangleMesh load_mesh_file(const std::filesystem::path& path);

/// Assimp 5.2's PLY reader loops forever on a header without end_header and quietly accepts
/// truncated bodies (reading garbage vertices), so PLY files are checked before Assimp reads
/// them: the header's syntax, and a body long enough for the elements it declares. Throws
/// Error(kInput) at `where` (with the line when known) otherwise.
void check_ply_structure(const std::filesystem::path& path, const ErrorLocation& where);

}  // namespace prism
