#include "accel/bvh/homework/homework_bvh_traversal.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "accel/primitive_query.h"

namespace prism {
namespace {

// Box intervals are widened by this fraction of the distance to the box along the ray's
// dominant axis. A triangle's computed t is a convex combination of its vertices' distances
// plus rounding, so it can fall a little outside the box's computed interval (by ulps, more for
// grazing rays); culling such a box against the current closest t or tmin would make the BVH
// disagree with brute force. 2^-12 costs almost nothing in visited nodes.
constexpr float kBoxSlack = 1.0f / 4096.0f;

/// Per-ray constants of the slab test.
struct BoxRay {
  explicit BoxRay(const Ray& ray) : origin(ray.origin), inv_dir(1.0f / ray.direction) {
    for (int a = 0; a < 3; ++a) negative[a] = std::signbit(inv_dir[a]);
    dominant = max_dimension(glm::abs(ray.direction));
  }
  Vec3 origin;
  Vec3 inv_dir;
  bool negative[3];  // by sign bit, so a direction of -0 orders its +-inf slab ends correctly
  int dominant;
};

/// Whether the widened box interval of `node` overlaps [tmin, tmax]; `entry` is where.
inline bool enter_box(const BoxRay& r, const HomeworkBvhNode& node, float tmin, float tmax,
                      float& entry) {
  float t_lo[3], t_hi[3];
  for (int a = 0; a < 3; ++a) {
    const float lo = r.negative[a] ? node.upper[a] : node.lower[a];
    const float hi = r.negative[a] ? node.lower[a] : node.upper[a];
    t_lo[a] = (lo - r.origin[a]) * r.inv_dir[a];
    t_hi[a] = (hi - r.origin[a]) * r.inv_dir[a];
  }
  // 0 * inf = NaN on an axis the ray runs parallel to, inside the slab's plane: such an axis
  // must not constrain the interval, and these comparisons skip NaN.
  float near = -kInfinity, far = kInfinity;
  for (int a = 0; a < 3; ++a) {
    near = t_lo[a] > near ? t_lo[a] : near;
    far = t_hi[a] < far ? t_hi[a] : far;
  }
  // The dominant axis has a finite, non-zero direction component, so its slab is finite.
  const int d = r.dominant;
  const float slack = kBoxSlack * std::max(std::abs(t_lo[d]), std::abs(t_hi[d]));
  near -= slack;
  far += slack;
  if (!(near <= far && near <= tmax && far >= tmin)) return false;
  entry = std::max(near, tmin);
  return true;
}

struct StackEntry {
  uint32_t node;
  float entry;
};

/// One traversal for both queries: kAnyHit returns at the first primitive hit, otherwise the
/// closest hit is kept in `best` and the query narrowed to it.
template <bool kAnyHit>
bool traverse(const HomeworkBvh& bvh, const SceneGeometry& geometry, PrimitiveQuery& query,
              std::optional<Hit>& best) {
  if (bvh.nodes.empty()) return false;
  const BoxRay box_ray(query.ray);
  const HomeworkBvhNode* nodes = bvh.nodes.data();
  float root_entry;
  if (!enter_box(box_ray, nodes[0], query.ray.tmin, query.ray.tmax, root_entry)) return false;

  StackEntry stack[kHomeworkBvhMaxDepth + 1];
  int size = 0;
  uint32_t current = 0;
  while (true) {
    const HomeworkBvhNode& node = nodes[current];
    if (node.is_leaf()) {
      for (uint32_t k = node.index; k < node.index + node.count; ++k) {
        if constexpr (kAnyHit) {
          if (intersect_primitive(geometry, query, bvh.prims[k])) return true;
        } else {
          update_closest(geometry, query, bvh.prims[k], best);
        }
      }
    } else {
      const uint32_t left = current + 1, right = node.index;
      float t_left, t_right;
      const bool hit_left = enter_box(box_ray, nodes[left], query.ray.tmin, query.ray.tmax, t_left);
      const bool hit_right =
          enter_box(box_ray, nodes[right], query.ray.tmin, query.ray.tmax, t_right);
      if (hit_left && hit_right) {
        const bool right_first = t_right < t_left;
        stack[size++] = right_first ? StackEntry{left, t_left} : StackEntry{right, t_right};
        current = right_first ? right : left;
        continue;
      }
      if (hit_left || hit_right) {
        current = hit_left ? left : right;
        continue;
      }
    }
    // Pop the next subtree that can still hold a hit at or before the current closest t.
    bool found = false;
    while (size > 0) {
      const StackEntry e = stack[--size];
      if (e.entry <= query.ray.tmax) {
        current = e.node;
        found = true;
        break;
      }
    }
    if (!found) return best.has_value();
  }
}

}  // namespace

std::optional<Hit> homework_bvh_intersect(const HomeworkBvh& bvh, const SceneGeometry& geometry,
                                          const Ray& ray) {
  PrimitiveQuery query(ray);
  std::optional<Hit> best;
  traverse<false>(bvh, geometry, query, best);
  return best;
}

bool homework_bvh_occluded(const HomeworkBvh& bvh, const SceneGeometry& geometry, const Ray& ray) {
  PrimitiveQuery query(ray);
  std::optional<Hit> unused;
  return traverse<true>(bvh, geometry, query, unused);
}

}  // namespace prism
