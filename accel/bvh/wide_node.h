#pragma once

// The node and leaf layout of the wide BVH. Plain data and constants only: the traversal
// kernels, compiled with AVX2 or AVX-512, include this and must share no inline functions with
// the baseline x86-64 program (the linker could pick their copy for everyone).

#include <cstdint>

namespace prism {

/// A child reference in a wide node: an interior node index, or a leaf (kLeafFlag) holding
/// `count` consecutive blocks starting at `first` (TriangleBlock, or SphereBlock with
/// kSphereLeafFlag).
inline constexpr uint32_t kLeafFlag = 1u << 31;
inline constexpr uint32_t kSphereLeafFlag = 1u << 30;
inline constexpr int kLeafCountShift = 26;
inline constexpr uint32_t kLeafFirstMask = (1u << kLeafCountShift) - 1;
inline constexpr uint32_t kMaxLeafBlocks = 16;

/// The leaf reference of `blocks` (1..kMaxLeafBlocks) blocks from `first`.
constexpr uint32_t make_leaf_ref(uint32_t first, uint32_t blocks, bool spheres) {
  return kLeafFlag | (spheres ? kSphereLeafFlag : 0u) | ((blocks - 1) << kLeafCountShift) | first;
}

/// A node with W children. bounds[2 * axis] holds the lower and bounds[2 * axis + 1] the upper
/// planes of the children on `axis`, so a ray picks its near and far planes by the sign of its
/// direction (octant) instead of per child. Unused slots have empty (inverted, infinite) bounds
/// that no ray enters.
template <int W>
struct alignas(64) WideNode {
  float bounds[6][W];
  uint32_t child[W];
};
static_assert(sizeof(WideNode<4>) == 128);
static_assert(sizeof(WideNode<8>) == 256);

/// Up to four sphere indices of one leaf; unused lanes repeat the last sphere.
struct SphereBlock {
  uint32_t sphere[4];
};

}  // namespace prism
