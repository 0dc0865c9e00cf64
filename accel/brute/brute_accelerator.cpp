#include "accel/brute/brute_accelerator.h"

#include "accel/primitive_query.h"

namespace prism {

BruteAccelerator::BruteAccelerator(const ParamSet& /*params*/) {}

void BruteAccelerator::build_structure(const SceneGeometry& geometry) {
  stats_ = {};
  const size_t count = geometry.primitive_count();
  if (count > 0) {
    stats_.nodes = 1;
    stats_.leaves = 1;
    stats_.sah_cost = double(count);  // one leaf: every primitive is tested
  }
}

std::optional<Hit> BruteAccelerator::intersect_prepared(const Ray& ray) const {
  PrimitiveQuery query(ray);
  std::optional<Hit> best;
  const SceneGeometry& g = geometry();
  for (uint32_t m = 0; m < g.meshes.size(); ++m) {
    // The hot loop of the reference: plain arrays, core's triangle test, the shared order.
    const Vec3* positions = g.meshes[m].positions.data();
    const glm::uvec3* triangles = g.meshes[m].triangles.data();
    const uint32_t n = static_cast<uint32_t>(g.meshes[m].triangles.size());
    for (uint32_t i = 0; i < n; ++i) {
      const glm::uvec3& tri = triangles[i];
      const std::optional<PrimitiveHit> h = intersect_triangle(query.watertight, positions[tri.x],
                                                               positions[tri.y], positions[tri.z]);
      if (!h || (best && !comes_before(h->t, m, i, *best))) continue;
      best = Hit{h->t, h->u, h->v, m, i};
      query.narrow(h->t);
    }
  }
  const uint32_t sphere_geom = g.sphere_geom_id();
  for (uint32_t i = 0; i < g.spheres.size(); ++i) update_closest(g, query, {sphere_geom, i}, best);
  return best;
}

bool BruteAccelerator::occluded_prepared(const Ray& ray) const {
  const PrimitiveQuery query(ray);
  const SceneGeometry& g = geometry();
  for (uint32_t m = 0; m < g.meshes.size(); ++m) {
    const uint32_t n = static_cast<uint32_t>(g.meshes[m].triangles.size());
    for (uint32_t i = 0; i < n; ++i) {
      if (intersect_primitive(g, query, {m, i})) return true;
    }
  }
  const uint32_t sphere_geom = g.sphere_geom_id();
  for (uint32_t i = 0; i < g.spheres.size(); ++i) {
    if (intersect_primitive(g, query, {sphere_geom, i})) return true;
  }
  return false;
}

}  // namespace prism
