#pragma once

// The homework's binary BVH as plain data: what build_homework_bvh() produces and the homework
// traversal reads. (The faster BVHs use their own binary tree, BinaryBvh in
// accel/bvh/build_reference.h, collapsed into WideBvh<W>.)

#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/accelerator.h"
#include "accel/primitive_query.h"
#include "core/bounds.h"
#include "core/math.h"

namespace prism {

/// A primitive with what the homework's builder reads: its bounds and their centre.
struct HomeworkBuildPrimitive {
  Bounds3 bounds;
  Vec3 centroid;
  PrimitiveId id;
};

/// One node, 32 bytes. Nodes are stored depth-first: an inner node's left child is the next
/// node in the array, so only the right child's index is stored.
struct HomeworkBvhNode {
  Vec3 lower;
  uint32_t index;  ///< inner: index of the right child; leaf: first entry in HomeworkBvh::prims
  Vec3 upper;
  uint32_t count;  ///< 0 for an inner node, else the number of primitives of the leaf

  bool is_leaf() const { return count != 0; }
};
static_assert(sizeof(HomeworkBvhNode) == 32, "HomeworkBvhNode is meant to fill half a cache line");

/// A flattened binary BVH over the primitives of one SceneGeometry.
/// Invariants (check_homework_bvh()): nodes is empty exactly when prims is; nodes[0] is the root;
/// every primitive appears in exactly one leaf; every node's box contains its subtree.
struct HomeworkBvh {
  std::vector<HomeworkBvhNode> nodes;
  std::vector<PrimitiveId> prims;  ///< reordered so that each leaf's primitives are contiguous
  size_t max_depth = 0;            ///< root has depth 0
};

/// Node and leaf counts, depth, memory and SAH cost (traversal and intersection cost 1, areas
/// relative to the root's) of `bvh`; build_ms is left to Accelerator::stats().
AccelStats homework_bvh_stats(const HomeworkBvh& bvh);

/// Checks the invariants of HomeworkBvh against the primitives it was built from (for tests);
/// throws Error(kInternal) naming the first broken one.
void check_homework_bvh(const HomeworkBvh& bvh, const std::vector<HomeworkBuildPrimitive>& prims);

}  // namespace prism
