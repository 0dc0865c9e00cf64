#include <memory>

#include "accel/accelerator.h"
#include "accel/brute/brute_accelerator.h"
#include "accel/bvh/wide_bvh_accelerator.h"
#include "accel/embree/embree_accelerator.h"

namespace prism {
namespace {

template <typename T>
std::unique_ptr<Accelerator> make(const ParamSet& params) {
  return std::make_unique<T>(params);
}

}  // namespace

const Registry<Accelerator>& accelerator_registry() {
  static const Registry<Accelerator> registry(
      "accelerator",
      {
          {"brute", "tests every primitive for every ray; the exact reference for validation",
           &make<BruteAccelerator>},
          {"bvh",
           "handwritten BVH: bvh.split=median|sah|sbvh (default sah), "
           "bvh.layout=bvh2|bvh4|bvh8 (default bvh8), bvh.bins, bvh.leaf_cost, "
           "bvh.traversal_cost, bvh.max_leaf_size, bvh.sbvh_alpha, bvh.sbvh_budget, "
           "bvh.reinsertion_passes (0-16, default 2; 0 for median), "
           "bvh.isa=auto|avx512|avx2|generic; "
           "median + bvh2 is the homework's binary BVH",
           &make_bvh_accelerator},
          {"embree",
           "Intel Embree 3 (embree.robust=false, embree.quality=low|medium|high, "
           "embree.refine=true)",
           &make<EmbreeAccelerator>},
      });
  return registry;
}

}  // namespace prism
