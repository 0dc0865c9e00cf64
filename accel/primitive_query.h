#pragma once

// The primitive test that brute force and the homework's BVH share, so that they return the same
// hits bit for bit.

#include <cstdint>
#include <optional>

#include "core/hit.h"
#include "core/primitive_intersection.h"
#include "core/ray.h"
#include "core/scene_geometry.h"

namespace prism {

/// Names one primitive of a SceneGeometry: a triangle (geom_id = mesh index, prim_id = triangle
/// index) or a sphere (geom_id = SceneGeometry::sphere_geom_id(), prim_id = sphere index).
struct PrimitiveId {
  uint32_t geom_id = 0;
  uint32_t prim_id = 0;
};

/// A ray prepared once for many primitive tests (see prepare_query()). `ray.tmax` and
/// `watertight.tmax` must be narrowed together (narrow()).
struct PrimitiveQuery {
  explicit PrimitiveQuery(const Ray& prepared) : ray(prepared), watertight(prepared) {}
  void narrow(float tmax) {
    ray.tmax = tmax;
    watertight.tmax = tmax;
  }

  Ray ray;
  WatertightRay watertight;
};

/// Core's watertight triangle test or sphere test on primitive `id`, with t in
/// [query.ray.tmin, query.ray.tmax].
inline std::optional<PrimitiveHit> intersect_primitive(const SceneGeometry& geometry,
                                                       const PrimitiveQuery& query,
                                                       PrimitiveId id) {
  if (id.geom_id == geometry.sphere_geom_id()) {
    const Sphere& s = geometry.spheres[id.prim_id];
    return intersect_sphere(query.ray, s.center, s.radius);
  }
  const TriangleMesh& mesh = geometry.meshes[id.geom_id];
  const glm::uvec3& tri = mesh.triangles[id.prim_id];
  return intersect_triangle(query.watertight, mesh.positions[tri.x], mesh.positions[tri.y],
                            mesh.positions[tri.z]);
}

/// Tests `id` and, if it comes before `best` (comes_before()), replaces `best` and narrows
/// the query to the new t (closed, so an exact tie is still tested). Returns whether `best`
/// changed.
bool update_closest(const SceneGeometry& geometry, PrimitiveQuery& query, PrimitiveId id,
                    std::optional<Hit>& best);

}  // namespace prism
