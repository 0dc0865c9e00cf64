// Helpers shared by the wide BVH's kernels. No include guard and no includes on purpose (but
// core/sphere_test_body.h, which is written the same way): each wide_traversal_<isa>.cpp includes
// this file first, inside its own namespace (see wide_kernel_body.h), so nothing here is shared
// with code built for another instruction set.

#define PRISM_KERNEL_INLINE inline __attribute__((always_inline))

/// comes_before() of accel/ray_query.h: smaller t, then lower geom_id, then lower prim_id.
PRISM_KERNEL_INLINE bool comes_before_hit(float t, uint32_t geom_id, uint32_t prim_id,
                                          const WideHit& best) {
  if (t != best.t) return t < best.t;
  if (geom_id != best.geom_id) return geom_id < best.geom_id;
  return prim_id < best.prim_id;
}

PRISM_KERNEL_INLINE int lowest_lane(uint32_t mask) { return __builtin_ctz(mask); }

// sphere_hit_t(): the ray/sphere test of core/primitive_intersection.h, in this namespace.
#include "core/sphere_test_body.h"

// The ray's share of the box padding (core/ray.h), per unit of the origin's largest |coordinate|;
// the boxes' share is in their stored planes.
inline constexpr float kOriginPadding = kBoxOriginPaddingUlps / (1 << 24);
// Direction components below this count as this (with their sign), so that 1 / d is finite
// and plane * (1 / d) has no 0 * inf.
inline constexpr float kMinDirection = 1e-18f;

/// Per-ray constants of one query, filled by each instruction set's setup_ray<W>(ray, setup).
/// The arrays of three have a fourth, unused entry, so that setup_ray<W>() on x86 stores each as
/// one vector of its own.
struct RaySetup {
  float org[3];
  float tmin;  ///< follows org: the x86 set-up stores a Ray's origin and tmin as one vector
  float tmax;
  /// Slab test: plane * inv[a] + near_offset[a] (far_offset[a]) is the padded entry (exit)
  /// distance of the near (far) plane on axis a.
  float inv[4], near_offset[4], far_offset[4];
  /// Bit a is set when the direction is negative on axis a: the near plane is then the upper.
  unsigned octant;
  /// The watertight test's axes and shear, computed exactly as WatertightRay does.
  int kx, ky, kz, unused_k;
  float shear_x, shear_y, shear_z, unused_shear;
  /// The x86 kernels': where the rows of WideNode<W>::bounds holding the near and far planes on
  /// each axis start, in floats from its first.
  uint32_t near_index[4], far_index[4];
};
/// setup_ray<W>() on x86 stores kx to unused_k and shear_x to unused_shear as one vector each.
inline constexpr bool kRaySetupTakesVectorStores =
    offsetof(RaySetup, tmin) == offsetof(RaySetup, org) + 3 * sizeof(float) &&
    offsetof(RaySetup, unused_k) == offsetof(RaySetup, kx) + 3 * sizeof(int) &&
    offsetof(RaySetup, unused_shear) == offsetof(RaySetup, shear_x) + 3 * sizeof(float);
static_assert(kRaySetupTakesVectorStores);

// Each level pushes at most W - 1 siblings and the builders bound the depth.
template <int W>
inline constexpr int kStackSize = kMaxBvhDepth*(W - 1) + 1;
