#pragma once

// The wide BVH (2, 4 or 8 children per node) that the traversal kernels walk, and the collapse
// of a binary tree into it.

#include <cstdint>
#include <vector>

#include "accel/accelerator.h"
#include "accel/bvh/build_reference.h"
#include "accel/bvh/triangle_block.h"
#include "accel/bvh/wide_node.h"
#include "core/huge_page_allocator.h"

namespace prism {

/// A binary tree collapsed into W-wide nodes, with the leaf primitives copied into blocks. Each
/// child box is stored widened by the box's share of the traversal's padding (core/ray.h):
/// kBoxCoordinatePaddingUlps ulps of its largest |coordinate| and kBoxSizePaddingUlps ulps of the
/// largest primitive under it. The nodes and triangle blocks of a big
/// tree lie in transparent huge pages: incoherent rays through a tree larger than the caches miss
/// the TLB at almost every node with 4 KiB pages.
template <int W>
struct WideBvh {
  std::vector<WideNode<W>, HugePageAllocator<WideNode<W>>> nodes;
  std::vector<TriangleBlock, HugePageAllocator<TriangleBlock>> triangle_blocks;
  std::vector<SphereBlock> sphere_blocks;
  uint32_t root = 0;  ///< a node index or a leaf reference
  bool empty = true;  ///< no primitives: every query misses
  AccelStats stats;   ///< nodes, leaves, depth, bytes, SAH cost (build_ms: Accelerator::stats())
};

/// Collapses `binary` (built over `geometry`) into a W-wide tree: each wide node adopts the
/// children of its binary descendants with the largest area until it has W children. Leaves
/// are copied into triangle or sphere blocks (mixed leaves are not allowed). In parallel
/// (core/parallel.h).
template <int W>
WideBvh<W> collapse_to_wide(const BinaryBvh& binary, const SceneGeometry& geometry);

extern template WideBvh<2> collapse_to_wide<2>(const BinaryBvh&, const SceneGeometry&);
extern template WideBvh<4> collapse_to_wide<4>(const BinaryBvh&, const SceneGeometry&);
extern template WideBvh<8> collapse_to_wide<8>(const BinaryBvh&, const SceneGeometry&);

}  // namespace prism
