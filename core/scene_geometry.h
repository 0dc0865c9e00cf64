#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/bounds.h"
#include "core/lanes3.h"
#include "core/math.h"

namespace prism {

/// A triangle mesh in world space with one material.
/// Invariants (checked by validate()): every index < positions.size(); normals and uvs are
/// either empty or hold exactly three entries per triangle (per corner, in triangle order).
/// positions has capacity for one extra vertex so Embree may read 16 bytes past the last
/// vertex (see finalize()).
struct TriangleMesh {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<glm::uvec3> triangles;
  std::vector<Vec3> normals;  ///< per-corner shading normals, or empty
  std::vector<Vec2> uvs;      ///< per-corner texture coordinates, or empty
  uint32_t material_id = 0;

  size_t triangle_count() const { return triangles.size(); }
  Bounds3 bounds() const;
  /// Reserves the padding Embree needs. Call after the last change to positions.
  void finalize();
};

/// An analytic sphere in world space.
struct Sphere {
  Vec3 center{0.0f};
  float radius = 1.0f;
  uint32_t material_id = 0;

  Bounds3 bounds() const { return {center - Vec3(radius), center + Vec3(radius)}; }
};

/// All the geometry an accelerator sees. Geometry ids: mesh i has id i; all spheres share the id
/// sphere_geom_id() == meshes.size(), with the sphere index as primitive id.
struct SceneGeometry {
  std::vector<TriangleMesh> meshes;
  std::vector<Sphere> spheres;

  uint32_t sphere_geom_id() const { return static_cast<uint32_t>(meshes.size()); }
  bool is_sphere(uint32_t geom_id) const { return geom_id == sphere_geom_id(); }
  size_t triangle_count() const;
  size_t primitive_count() const { return triangle_count() + spheres.size(); }
  Bounds3 bounds() const;
  /// Throws Error(kInput) naming the mesh if an invariant above is broken or a coordinate is
  /// not finite.
  void validate() const;
  /// finalize() on every mesh.
  void finalize();
};

/// The sides of the triangle's bounding box, corners and result in vector lanes (core/lanes3.h).
inline Lanes3 triangle_extent(Lanes3 p0, Lanes3 p1, Lanes3 p2) {
  return component_max(p0, component_max(p1, p2)) - component_min(p0, component_min(p1, p2));
}
/// The sides of the triangle's bounding box.
inline Vec3 triangle_extent(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  return vec3_of(triangle_extent(lanes_of(p0), lanes_of(p1), lanes_of(p2)));
}

/// The size the wide BVH pads a triangle's boxes by (kBoxSizePaddingUlps, core/ray.h): the
/// largest side of the triangle's bounding box.
inline float triangle_size(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  return max_component(triangle_extent(p0, p1, p2));
}

}  // namespace prism
