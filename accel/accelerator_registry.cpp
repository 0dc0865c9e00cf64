#include <memory>

#include "accel/accelerator.h"
#include "accel/brute/brute_accelerator.h"
#include "accel/bvh/bvh_accelerator.h"
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
          {"bvh", "handwritten binary BVH, median split (bvh.max_leaf_size, default 4)",
           &make<BvhAccelerator>},
          {"embree",
           "Intel Embree 3 (embree.robust=false, embree.quality=low|medium|high, "
           "embree.refine=true)",
           &make<EmbreeAccelerator>},
      });
  return registry;
}

}  // namespace prism
