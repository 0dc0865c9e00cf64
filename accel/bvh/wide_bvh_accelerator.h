#pragma once

#include <memory>
#include <string>
#include <variant>

#include "accel/accelerator.h"
#include "accel/bvh/build_reference.h"
#include "accel/bvh/wide_bvh.h"
#include "accel/bvh/wide_traversal.h"

namespace prism {

/// Options of the custom BVH (`--set bvh.*`).
struct WideBvhOptions {
  BvhBuildSettings build;
  int width = 8;             ///< bvh.layout: bvh2 | bvh4 | bvh8
  std::string isa = "auto";  ///< bvh.isa: auto | avx512 | avx2 | generic
};

/// Reads bvh.split (median|sah|sbvh), bvh.layout (bvh2|bvh4|bvh8), bvh.bins, bvh.leaf_cost,
/// bvh.traversal_cost, bvh.max_leaf_size, bvh.isa from `params`; throws Error(kUsage) naming
/// the key on a bad value, and when bvh.isa names an instruction set this CPU lacks.
WideBvhOptions parse_wide_bvh_options(const ParamSet& params);

/// The registry's `bvh`: the homework's BVH (HomeworkBvhAccelerator) for bvh.split=median with
/// bvh.layout=bvh2, a WideBvhAccelerator for every other combination (default: sah, bvh8).
/// Throws Error(kUsage) on a bad parameter value.
std::unique_ptr<Accelerator> make_bvh_accelerator(const ParamSet& params);

/// "bvh2", "bvh4", "bvh8" for a width; "median", "sah", "sbvh" for a split.
std::string layout_name(int width);
std::string split_name(SplitMethod split);

/// The fast handwritten BVH: a binary tree from the chosen builder (binned SAH, median or
/// SBVH) collapsed into 2-, 4- or 8-wide SoA nodes, traversed by the best kernels this CPU runs
/// (AVX-512, AVX2 or portable). Hits are bit-identical to the brute-force backend's: the same
/// primitive tests, and exact ties go to the lowest (geom_id, prim_id) (comes_before()).
class WideBvhAccelerator final : public Accelerator {
 public:
  explicit WideBvhAccelerator(WideBvhOptions options);

  std::string_view name() const override { return "bvh"; }

  /// The instruction set of the kernels in use ("avx512", "avx2", "generic").
  std::string_view isa() const { return kernels_->isa; }
  const WideBvhOptions& options() const { return options_; }

 protected:
  void build_structure(const SceneGeometry& geometry) override;
  std::optional<Hit> intersect_prepared(const Ray& ray) const override;
  bool occluded_prepared(const Ray& ray) const override;
  AccelStats structure_stats() const override;

 private:
  /// The tree of the last build, of the width options_.width names; monostate before a build.
  using Tree = std::variant<std::monostate, WideBvh<2>, WideBvh<4>, WideBvh<8>>;

  WideBvhOptions options_;
  const WideKernels* kernels_ = nullptr;
  WideIntersectFn intersect_fn_ = nullptr;
  WideOccludedFn occluded_fn_ = nullptr;
  Tree tree_;
  /// What the kernels read: pointers into tree_ and the geometry; valid when !empty_.
  WideBvhView view_{};
  bool empty_ = true;  ///< no tree, or a tree without primitives: every query misses
};

}  // namespace prism
