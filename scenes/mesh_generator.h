#pragma once

#include <cstdint>
#include <string>

#include "core/scene_geometry.h"

namespace prism {

/// Procedural test meshes. All are deterministic functions of their parameters and seed, fit in
/// the unit-ish box around the origin unless stated, and scale to 10M triangles (memory is
/// reserved up front; generation is linear time).
enum class GeneratedMeshKind {
  kSphere,         ///< tessellated UV sphere of radius 1, shared vertices
  kNoisySphere,    ///< the sphere with each vertex moved radially by deterministic noise
  kSoup,           ///< independent random triangles in [-1,1]^3 (no shared vertices)
  kSlivers,        ///< long thin triangles (aspect ~1000:1) crossing the box
  kGrid,           ///< a flat n x n grid in the z=0 plane over [-1,1]^2, two triangles per cell
                   ///< sharing edges and vertices
  kFoldedSlivers,  ///< pairs of thin triangles (1.4 x 0.0003..0.003) folded along a shared long
                   ///< edge by 0.05..30 degrees, as thin panels of architectural meshes
  kInterior,       ///< a cutaway floor plan: rooms with large floor triangles and thin walls,
                   ///< the rest furniture-sized boxes and spheres (large and small triangles
                   ///< mixed), inside [-1,1]^2 x [0, 0.2]
};

/// Parses "sphere", "noisy_sphere", "soup", "slivers", "grid", "folded_slivers", "interior"; throws
/// Error(kUsage) listing them.
GeneratedMeshKind parse_generated_mesh_kind(const std::string& name);
std::string to_string(GeneratedMeshKind kind);

/// A mesh of `kind` with approximately `triangle_count` triangles (exact for soup and slivers;
/// the nearest tessellation for sphere and grid; for interior at least its rooms' walls and
/// floors). material_id is set to `material_id`.
TriangleMesh generate_mesh(GeneratedMeshKind kind, size_t triangle_count, uint64_t seed = 1,
                           uint32_t material_id = 0);

}  // namespace prism
