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
    // t first: a shadow ray needs nothing else, and u, v (two inverse trigonometric
    // functions) are computed only for a hit that becomes the closest so far.
    const std::optional<float> t = intersect_sphere_t(ray, s.center, s.radius);
    if (!t) continue;
    if (any_hit) return true;
    if (!comes_before(*t, bvh.sphere_geom_id, ids[i], {hit.t, 0, 0, hit.geom_id, hit.prim_id})) {
      continue;
    }
    found = true;
    ray.tmax = *t;
    const Vec2 uv = sphere_hit_uv(ray, *t, s.center);
    hit = {*t, uv.x, uv.y, bvh.sphere_geom_id, ids[i], nullptr};
  }
  return found;
}

}  // namespace prism
