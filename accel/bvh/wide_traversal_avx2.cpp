// The wide BVH's traversal kernels compiled for AVX2 + FMA (flags set in accel/CMakeLists.txt).
// Only reached through avx2_wide_kernels() after a CPU check; see wide_kernel_body.h for why
// everything lives in a namespace of its own.

#include <immintrin.h>

#include <cstddef>  // offsetof, for wide_kernel_common.h
#include <utility>  // std::integer_sequence, for wide_kernel_body.h

#include "accel/bvh/build_reference.h"
#include "accel/bvh/wide_node.h"
#include "accel/bvh/wide_traversal.h"
#include "core/primitive_intersection.h"

namespace prism {
namespace wide_avx2 {

// The order matters: each file uses the ones before it.
// clang-format off
#include "accel/bvh/wide_kernel_common.h"
#include "accel/bvh/wide_kernel_x86.h"
#include "accel/bvh/wide_kernel_body.h"
// clang-format on

}  // namespace wide_avx2

const WideKernels& avx2_wide_kernels() {
  static constexpr WideKernels kKernels{
      "avx2",
      {&wide_avx2::intersect_closest<2>, &wide_avx2::intersect_closest<4>,
       &wide_avx2::intersect_closest<8>},
      {&wide_avx2::intersect_any<2>, &wide_avx2::intersect_any<4>, &wide_avx2::intersect_any<8>}};
  return kKernels;
}

}  // namespace prism
