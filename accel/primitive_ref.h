#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/bounds.h"
#include "core/hit.h"
#include "core/primitive_intersection.h"
#include "core/ray.h"
#include "core/scene_geometry.h"

namespace prism {

/// One primitive of a SceneGeometry: a triangle (geom_id = mesh index) or a sphere
/// (geom_id = SceneGeometry::sphere_geom_id(), prim_id = sphere index).
struct PrimitiveRef {
  uint32_t geom_id = 0;
  uint32_t prim_id = 0;
};

/// A primitive with the data a BVH builder needs.
struct BuildPrimitive {
  Bounds3 bounds;
  Vec3 centroid;
  PrimitiveRef ref;
};

/// Every primitive of `geometry` (triangles of mesh 0, 1, ..., then spheres), with bounds.
std::vector<BuildPrimitive> gather_build_primitives(const SceneGeometry& geometry);

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

/// The shared primitive test of brute and bvh: core's watertight triangle test or sphere test
/// on primitive `ref`, with t in [query.ray.tmin, query.ray.tmax].
inline std::optional<PrimitiveHit> intersect_primitive(const SceneGeometry& geometry,
                                                       const PrimitiveQuery& query,
                                                       PrimitiveRef ref) {
  if (ref.geom_id == geometry.sphere_geom_id()) {
    const Sphere& s = geometry.spheres[ref.prim_id];
    return intersect_sphere(query.ray, s.center, s.radius);
  }
  const TriangleMesh& mesh = geometry.meshes[ref.geom_id];
  const glm::uvec3& tri = mesh.triangles[ref.prim_id];
  return intersect_triangle(query.watertight, mesh.positions[tri.x], mesh.positions[tri.y],
                            mesh.positions[tri.z]);
}

/// Tests `ref` and, if it comes before `best` (comes_before()), replaces `best` and narrows
/// the query to the new t (closed, so an exact tie is still tested). Returns whether `best`
/// changed.
bool update_closest(const SceneGeometry& geometry, PrimitiveQuery& query, PrimitiveRef ref,
                    std::optional<Hit>& best);

}  // namespace prism
