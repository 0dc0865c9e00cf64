#include "accel/bvh/wide_traversal.h"

#include "accel/ray_query.h"

namespace prism {
bool intersect_sphere_leaf(const WideBvhView& bvh, const Ray& query_ray, uint32_t first,
                           uint32_t count, float tmax, WideHit& hit, bool any_hit) {
  Ray ray = query_ray;
  ray.tmax = tmax;
  bool found = false;
  const uint32_t* ids = bvh.sphere_blocks + 4 * first;
  for (uint32_t i = 0; i < 4 * count; ++i) {
    // Unused lanes repeat the previous sphere.
    if ((i & 3) != 0 && ids[i] == ids[i - 1]) continue;
    const Sphere& s = bvh.spheres[ids[i]];
    const std::optional<PrimitiveHit> h = intersect_sphere(ray, s.center, s.radius);
    if (!h) continue;
    if (any_hit) return true;
    if (!comes_before(h->t, bvh.sphere_geom_id, ids[i], {hit.t, 0, 0, hit.geom_id, hit.prim_id})) {
      continue;
    }
    found = true;
    ray.tmax = h->t;
    hit = {h->t, h->u, h->v, bvh.sphere_geom_id, ids[i]};
  }
  return found;
}

}  // namespace prism
