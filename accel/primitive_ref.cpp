#include "accel/primitive_ref.h"

#include "accel/ray_query.h"

namespace prism {

std::vector<BuildPrimitive> gather_build_primitives(const SceneGeometry& geometry) {
  std::vector<BuildPrimitive> prims;
  prims.reserve(geometry.primitive_count());
  for (uint32_t g = 0; g < geometry.meshes.size(); ++g) {
    const TriangleMesh& mesh = geometry.meshes[g];
    for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
      const glm::uvec3& tri = mesh.triangles[i];
      BuildPrimitive p;
      p.bounds.extend(mesh.positions[tri.x]);
      p.bounds.extend(mesh.positions[tri.y]);
      p.bounds.extend(mesh.positions[tri.z]);
      p.centroid = p.bounds.center();
      p.ref = {g, i};
      prims.push_back(p);
    }
  }
  const uint32_t sphere_geom = geometry.sphere_geom_id();
  for (uint32_t i = 0; i < geometry.spheres.size(); ++i) {
    const Sphere& s = geometry.spheres[i];
    prims.push_back({s.bounds(), s.center, {sphere_geom, i}});
  }
  return prims;
}

bool update_closest(const SceneGeometry& geometry, PrimitiveQuery& query, PrimitiveRef ref,
                    std::optional<Hit>& best) {
  const std::optional<PrimitiveHit> h = intersect_primitive(geometry, query, ref);
  if (!h) return false;
  if (best && !comes_before(h->t, ref.geom_id, ref.prim_id, *best)) return false;
  best = Hit{h->t, h->u, h->v, ref.geom_id, ref.prim_id};
  query.narrow(h->t);
  return true;
}

}  // namespace prism
