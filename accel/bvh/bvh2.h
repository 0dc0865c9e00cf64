#pragma once

// The binary BVH as plain data: what a builder produces and a traversal reads. Other builders
// (SAH, ...) produce the same structure; wider layouts would get their own header next to it.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/accelerator.h"
#include "accel/primitive_ref.h"
#include "core/math.h"

namespace prism {

/// One node, 32 bytes. Nodes are stored depth-first: an inner node's left child is the next
/// node in the array, so only the right child's index is stored.
struct Bvh2Node {
  Vec3 lower;
  uint32_t index;  ///< inner: index of the right child; leaf: first entry in Bvh2::prims
  Vec3 upper;
  uint32_t count;  ///< 0 for an inner node, else the number of primitives of the leaf

  bool is_leaf() const { return count != 0; }
};
static_assert(sizeof(Bvh2Node) == 32, "Bvh2Node is meant to fill half a cache line");

/// A flattened binary BVH over the primitives of one SceneGeometry.
/// Invariants (check_bvh2()): nodes is empty exactly when prims is; nodes[0] is the root; every
/// primitive appears in exactly one leaf; every node's box contains its subtree.
struct Bvh2 {
  std::vector<Bvh2Node> nodes;
  std::vector<PrimitiveRef> prims;  ///< reordered so that each leaf's primitives are contiguous
  size_t max_depth = 0;             ///< root has depth 0
};

/// Node and leaf counts, depth, memory and SAH cost (traversal and intersection cost 1, areas
/// relative to the root's) of `bvh`. build_ms is left 0.
AccelStats bvh2_stats(const Bvh2& bvh);

/// Checks the invariants of Bvh2 against the primitives it was built from (for tests);
/// throws Error(kInternal) naming the first broken one.
void check_bvh2(const Bvh2& bvh, const std::vector<BuildPrimitive>& prims);

}  // namespace prism
