#pragma once

#include <cstdint>

#include "accel/bvh/build_reference.h"
#include "core/primitive_intersection.h"
#include "core/scene_geometry.h"

namespace prism {

/// Four triangles of one leaf with their vertices gathered in structure-of-arrays form:
/// p[vertex][axis][lane]. The SIMD test subtracts the ray origin from these very vertices in
/// the order intersect_triangle() does, so its t, u, v are bit-identical to the scalar test
/// (edge vectors are deliberately not precomputed: p1 - p0 - o rounds differently from p1 - o).
/// Unused lanes repeat the block's last triangle, which can only report the same hit again.
struct alignas(16) TriangleBlock {
  float p[3][3][4];
  uint32_t geom_id[4];
  uint32_t prim_id[4];
};
static_assert(sizeof(TriangleBlock) == 176);

/// Fills `block` from up to four triangle references (count in 1..4).
void fill_triangle_block(const SceneGeometry& geometry, const PrimRef* refs, int count,
                         TriangleBlock& block);

/// The scalar watertight test on one lane of a block: intersect_triangle() itself, used by the
/// SIMD kernels when an edge function is exactly zero and the test needs its double-precision
/// path. `ray` carries the current tmax.
bool intersect_block_lane(const WatertightRay& ray, const TriangleBlock& block, int lane,
                          PrimitiveHit& hit);

}  // namespace prism
