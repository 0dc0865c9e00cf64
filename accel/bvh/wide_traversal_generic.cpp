// The wide BVH's portable traversal kernels (baseline x86-64, every width): the fallback on
// CPUs without AVX2 and the only kernels for the binary layout.

#include <cstddef>  // offsetof, for wide_kernel_common.h
#include <utility>  // std::integer_sequence, for wide_kernel_body.h

#include "accel/bvh/build_reference.h"
#include "accel/bvh/wide_node.h"
#include "accel/bvh/wide_traversal.h"
#include "core/primitive_intersection.h"

namespace prism {
namespace wide_generic {

#include "accel/bvh/wide_kernel_common.h"

/// The per-ray constants in plain scalar code (the same for every width W).
template <int W>
PRISM_KERNEL_INLINE void setup_ray(const Ray& ray, RaySetup& s) {
  const float d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const float o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  s.tmin = ray.tmin;
  s.tmax = ray.tmax;
  const float ad[3] = {__builtin_fabsf(d[0]), __builtin_fabsf(d[1]), __builtin_fabsf(d[2])};
  s.kz = (ad[0] >= ad[1] && ad[0] >= ad[2]) ? 0 : (ad[1] >= ad[2] ? 1 : 2);
  s.kx = s.kz == 2 ? 0 : s.kz + 1;
  s.ky = s.kx == 2 ? 0 : s.kx + 1;
  if (d[s.kz] < 0.0f) {
    const int k = s.kx;
    s.kx = s.ky;
    s.ky = k;
  }
  s.shear_z = 1.0f / d[s.kz];
  s.shear_x = -d[s.kx] * s.shear_z;
  s.shear_y = -d[s.ky] * s.shear_z;

  float scale = 0.0f;
  for (int a = 0; a < 3; ++a) {
    s.org[a] = o[a];
    scale = __builtin_fabsf(o[a]) > scale ? __builtin_fabsf(o[a]) : scale;
  }
  const float delta = kOriginPadding * scale;
  s.octant = 0;
  for (int a = 0; a < 3; ++a) {
    const float da = ad[a] < kMinDirection
                         ? (d[a] < 0.0f || __builtin_signbit(d[a]) ? -kMinDirection : kMinDirection)
                         : d[a];
    const float inv = 1.0f / da;
    const float base = -o[a] * inv;
    const float pad = delta * __builtin_fabsf(inv);
    s.inv[a] = inv;
    s.near_offset[a] = base - pad;
    s.far_offset[a] = base + pad;
    if (inv < 0.0f) s.octant |= 1u << a;
  }
}

inline constexpr unsigned kRuntimeOctant = 8;
inline constexpr bool kKernelUsesRuntimeOctant = false;

template <int W, unsigned kOctant>
struct NodeRay {
  explicit NodeRay(const RaySetup& s) : setup(s) {}
  const RaySetup& setup;
};

template <int W, unsigned kOctant>
PRISM_KERNEL_INLINE uint32_t intersect_node(const WideNode<W>& node, const NodeRay<W, kOctant>& ray,
                                            float tmax, float* tnear) {
  const RaySetup& s = ray.setup;
  uint32_t mask = 0;
  for (int i = 0; i < W; ++i) {
    float tn = s.tmin, tf = tmax;
    for (int a = 0; a < 3; ++a) {
      const int near_plane = 2 * a + static_cast<int>((kOctant >> a) & 1);
      const int far_plane = 2 * a + 1 - static_cast<int>((kOctant >> a) & 1);
      const float n = node.bounds[near_plane][i] * s.inv[a] + s.near_offset[a];
      const float f = node.bounds[far_plane][i] * s.inv[a] + s.far_offset[a];
      tn = n > tn ? n : tn;
      tf = f < tf ? f : tf;
    }
    tnear[i] = tn;
    if (tn <= tf) mask |= 1u << i;
  }
  return mask;
}

/// The generic kernels run core's scalar test itself on every lane.
struct TriangleRay {
  TriangleRay(const RaySetup&, const Ray& ray) : watertight(ray) {}
  WatertightRay watertight;
};

PRISM_KERNEL_INLINE bool intersect_blocks(const TriangleBlock* blocks, uint32_t count,
                                          const TriangleRay& ray, float tmax, WideHit& hit,
                                          bool any_hit) {
  WatertightRay w = ray.watertight;
  bool found = false;
  for (uint32_t b = 0; b < count; ++b) {
    const TriangleBlock& block = blocks[b];
    for (int lane = 0; lane < 4; ++lane) {
      // Unused lanes repeat the previous triangle.
      if (lane > 0 && block.prim_id[lane] == block.prim_id[lane - 1] &&
          block.geom_id[lane] == block.geom_id[lane - 1]) {
        continue;
      }
      w.tmax = tmax;
      PrimitiveHit h;
      if (!intersect_block_lane(w, block, lane, h)) continue;
      if (any_hit) return true;
      if (!comes_before_hit(h.t, block.geom_id[lane], block.prim_id[lane], hit)) continue;
      tmax = h.t;
      hit = {h.t, h.u, h.v, block.geom_id[lane], block.prim_id[lane], &block.p[0][0][lane]};
      found = true;
    }
  }
  return found;
}

#include "accel/bvh/wide_kernel_body.h"

}  // namespace wide_generic

const WideKernels& generic_wide_kernels() {
  static constexpr WideKernels kKernels{
      "generic",
      {&wide_generic::intersect_closest<2>, &wide_generic::intersect_closest<4>,
       &wide_generic::intersect_closest<8>},
      {&wide_generic::intersect_any<2>, &wide_generic::intersect_any<4>,
       &wide_generic::intersect_any<8>}};
  return kKernels;
}

}  // namespace prism
