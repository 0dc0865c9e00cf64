#pragma once

#include <cstdint>
#include <vector>

#include "accel/bvh/bvh2.h"
#include "accel/primitive_ref.h"

namespace prism {

/// Options of the median-split builder.
struct MedianSplitOptions {
  uint32_t max_leaf_size = 4;  ///< a node with at most this many primitives becomes a leaf
};

/// The CS184 homework BVH: split each node on the largest axis of its centroid bounds, at the
/// median primitive (so both halves hold n/2 primitives), until a node holds at most
/// max_leaf_size primitives. Iterative and depth-bounded: depth <= ceil(log2(n)) for any input,
/// including n identical primitives. Deterministic: equal centroids are ordered by
/// (geom_id, prim_id). Takes `prims` by value because it reorders them.
Bvh2 build_median_split(std::vector<BuildPrimitive> prims, const MedianSplitOptions& options);

}  // namespace prism
