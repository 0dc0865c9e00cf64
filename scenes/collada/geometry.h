#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <pugixml.hpp>

#include "core/math.h"
#include "core/scene_geometry.h"
#include "scenes/collada/document.h"

namespace prism::collada {

/// One <polylist> or <triangles> element of a mesh, already triangulated (polygons as fans
/// around their first corner), as indices into its Geometry's arrays.
struct PrimitiveGroup {
  pugi::xml_node element;
  std::string material_symbol;      ///< its material="..." symbol; empty when it names none
  std::vector<uint32_t> positions;  ///< 3 per triangle, into Geometry::positions
  int normal_source = -1;           ///< index into Geometry::normal_sources, or -1 for none
  std::vector<uint32_t> normals;    ///< 3 per triangle when normal_source >= 0
  int uv_source = -1;               ///< index into Geometry::uv_sources, or -1 for none
  std::vector<uint32_t> uvs;        ///< 3 per triangle when uv_source >= 0

  size_t triangle_count() const { return positions.size() / 3; }
};

/// A parsed <geometry> in its own (object) frame: a triangle mesh, or a CGL analytic sphere.
struct Geometry {
  pugi::xml_node element;
  std::string id;
  bool is_sphere = false;
  float radius = 0.0f;  ///< sphere only
  std::vector<Vec3> positions;
  std::vector<std::vector<Vec3>> normal_sources;
  std::vector<std::vector<Vec2>> uv_sources;
  std::vector<PrimitiveGroup> groups;

  size_t triangle_count() const;
};

/// Parses a <geometry> element: its <mesh> (sources through their accessors, <vertices>, every
/// <polylist> and <triangles>) or, without a mesh, the CGL <sphere><radius>. Validates every
/// count against the content actually present (float_array count, accessor range, vcount vs
/// <p> length, each index against its source) and throws Error(kInput) naming the element, the
/// id or index, and the line.
Geometry parse_geometry(const Document& doc, pugi::xml_node geometry);

/// Appends one instance of mesh `geometry` placed by `world` to `out`: one TriangleMesh per
/// primitive group, named "<name_prefix>/<material symbol or group index>", with material
/// `material_ids[group]`. Only the vertices a group uses are copied. Positions go through
/// `world`, normals through its normal matrix (normalized; a normal that degenerates falls back
/// to the triangle's geometric one); a mirroring transform swaps two corners of every triangle
/// so the winding keeps agreeing with the transformed normals.
void append_mesh_instance(const Geometry& geometry, const DMat4& world,
                          std::span<const uint32_t> material_ids, const std::string& name_prefix,
                          SceneGeometry& out);

}  // namespace prism::collada
