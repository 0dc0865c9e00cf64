#pragma once

// The traversal kernels of the wide BVH, one set per instruction set, chosen at run time.
// The types crossing this interface are plain data so that kernels compiled with AVX2 or
// AVX-512 share no inline code with the baseline x86-64 program.

#include <cstdint>

#include "accel/bvh/triangle_block.h"
#include "core/ray.h"
#include "core/scene_geometry.h"

namespace prism {

/// The closest hit found by a kernel. Kernels start from kNoWideHit and replace the hit only
/// by one that comes before it (smaller t; at equal t lower geom_id, then prim_id), the order
/// of comes_before() in accel/ray_query.h.
struct WideHit {
  float t, u, v;
  uint32_t geom_id, prim_id;
  const float* vertex_lanes;  ///< Hit::vertex_lanes: &block.p[0][0][lane] of a triangle
};
inline constexpr WideHit kNoWideHit{kInfinity, 0.0f, 0.0f, ~0u, ~0u, nullptr};

/// What a kernel reads: one W-wide tree (nodes points at WideNode<W>) and the scene's spheres.
struct WideBvhView {
  const void* nodes;
  const TriangleBlock* triangle_blocks;
  const uint32_t* sphere_blocks;  ///< SphereBlock::sphere, 4 per block
  const Sphere* spheres;
  uint32_t sphere_geom_id;
  uint32_t root;
};

/// A kernel: the closest hit (replacing `hit`, which starts as kNoWideHit) or any hit of a ray
/// already through prepare_query() (accel/ray_query.h) on a non-empty tree.
using WideIntersectFn = bool (*)(const WideBvhView&, const Ray&, WideHit&);
using WideOccludedFn = bool (*)(const WideBvhView&, const Ray&);

/// The kernels of one instruction set, indexed by log2(width) - 1 (bvh2, bvh4, bvh8).
/// A null entry means the set does not implement that width.
struct WideKernels {
  const char* isa;
  WideIntersectFn intersect[3];
  WideOccludedFn occluded[3];
};

/// Portable kernels (any x86-64; every width): core's scalar triangle test on every lane.
const WideKernels& generic_wide_kernels();
/// AVX2 + FMA kernels (every width). Call only when cpu_has_avx2() is true.
const WideKernels& avx2_wide_kernels();
/// AVX-512 (F, VL, BW, DQ) kernels (every width). Call only when cpu_has_avx512() is true.
const WideKernels& avx512_wide_kernels();

}  // namespace prism
