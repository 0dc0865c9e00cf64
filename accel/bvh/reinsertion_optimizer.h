#pragma once

// Improves a built binary tree by moving subtrees to where they cost less (reinsertion, after
// Bittner et al. 2013 and Meister and Bittner 2018), before the collapse into wide nodes.

#include "accel/bvh/build_reference.h"

namespace prism {

/// Runs `passes` rounds of reinsertion over `bvh`: each round takes the 1024 largest interior
/// nodes and leaves in order of decreasing area, removes each from the tree and puts it back as the
/// sibling of the node where the surface area of the interior nodes grows least, when that is
/// less than the removal saved. Leaves keep their references, so `bvh.refs` is untouched; the
/// nodes are renumbered (node 0 the root, children adjacent). A tree that would grow deeper
/// than kMaxBvhDepth is left as it was. Returns the number of moves made.
size_t optimize_by_reinsertion(BinaryBvh& bvh, int passes);

}  // namespace prism
