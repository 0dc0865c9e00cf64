#include "accel/bvh/wide_bvh_accelerator.h"

#include <type_traits>

#include "accel/bvh/binned_sah_builder.h"
#include "accel/bvh/cpu_features.h"
#include "accel/bvh/homework/homework_bvh_accelerator.h"
#include "accel/bvh/reinsertion_optimizer.h"
#include "accel/bvh/spatial_split_builder.h"
#include "core/error.h"

namespace prism {
namespace {

const WideKernels& select_kernels(const std::string& isa) {
  if (isa == "auto") {
    if (cpu_has_avx512()) return avx512_wide_kernels();
    if (cpu_has_avx2()) return avx2_wide_kernels();
    return generic_wide_kernels();
  }
  if (isa == "generic") return generic_wide_kernels();
  const bool supported = isa == "avx2" ? cpu_has_avx2() : cpu_has_avx512();
  if (!supported) {
    throw Error(ErrorKind::kUsage, "bvh.isa=" + isa + ": this CPU does not support it");
  }
  return isa == "avx2" ? avx2_wide_kernels() : avx512_wide_kernels();
}

}  // namespace

std::string layout_name(int width) { return "bvh" + std::to_string(width); }

std::string split_name(SplitMethod split) {
  switch (split) {
    case SplitMethod::kMedian:
      return "median";
    case SplitMethod::kSah:
      return "sah";
    case SplitMethod::kSpatial:
      return "sbvh";
  }
  return "?";
}

WideBvhOptions parse_wide_bvh_options(const ParamSet& params) {
  WideBvhOptions o;
  const std::string split = params.get_string("bvh.split", "sah");
  if (split == "median") {
    o.build.split = SplitMethod::kMedian;
    o.build.max_leaf_size = 4;
    o.build.reinsertion_passes = 0;  // the textbook tree, as the homework builds it
  } else if (split == "sah") {
    o.build.split = SplitMethod::kSah;
  } else if (split == "sbvh") {
    o.build.split = SplitMethod::kSpatial;
  } else {
    throw Error(ErrorKind::kUsage, "bvh.split='" + split + "' is not one of: median, sah, sbvh");
  }
  const std::string layout = params.get_string("bvh.layout", "bvh8");
  if (layout == "bvh2" || layout == "bvh4" || layout == "bvh8") {
    o.width = layout[3] - '0';
  } else {
    throw Error(ErrorKind::kUsage, "bvh.layout='" + layout + "' is not one of: bvh2, bvh4, bvh8");
  }
  o.build.bins = static_cast<int>(params.get_int("bvh.bins", o.build.bins, 2, 64));
  o.build.leaf_cost =
      static_cast<float>(params.get_float("bvh.leaf_cost", o.build.leaf_cost, 1e-3, 1e3));
  o.build.traversal_cost =
      static_cast<float>(params.get_float("bvh.traversal_cost", o.build.traversal_cost, 1e-3, 1e3));
  o.build.max_leaf_size = static_cast<int>(
      params.get_int("bvh.max_leaf_size", o.build.max_leaf_size, 1, kMaxLeafPrimitives));
  o.build.spatial_alpha =
      static_cast<float>(params.get_float("bvh.sbvh_alpha", o.build.spatial_alpha, 0.0, 1.0));
  o.build.spatial_budget =
      static_cast<float>(params.get_float("bvh.sbvh_budget", o.build.spatial_budget, 0.0, 4.0));
  o.build.reinsertion_passes =
      static_cast<int>(params.get_int("bvh.reinsertion_passes", o.build.reinsertion_passes, 0, 16));
  o.isa = params.get_string("bvh.isa", "auto");
  if (o.isa != "auto" && o.isa != "avx512" && o.isa != "avx2" && o.isa != "generic") {
    throw Error(ErrorKind::kUsage,
                "bvh.isa='" + o.isa + "' is not one of: auto, avx512, avx2, generic");
  }
  select_kernels(o.isa);  // reject an unsupported instruction set now, not at build()
  return o;
}

std::unique_ptr<Accelerator> make_bvh_accelerator(const ParamSet& params) {
  // Peek at split and layout without marking them used: the chosen class reads them again.
  const bool homework = params.has("bvh.split") && params.has("bvh.layout") &&
                        ParamSet(params).get_string("bvh.split", "") == "median" &&
                        ParamSet(params).get_string("bvh.layout", "") == "bvh2";
  if (homework) {
    params.get_string("bvh.split", "");
    params.get_string("bvh.layout", "");
    params.get_string("bvh.isa", "");  // the homework traversal is scalar
    return std::make_unique<HomeworkBvhAccelerator>(params);
  }
  return std::make_unique<WideBvhAccelerator>(parse_wide_bvh_options(params));
}

WideBvhAccelerator::WideBvhAccelerator(WideBvhOptions options) : options_(std::move(options)) {
  PRISM_CHECK(options_.width == 2 || options_.width == 4 || options_.width == 8);
  kernels_ = &select_kernels(options_.isa);
  // Widths an instruction set lacks (the binary layout) use the portable kernels.
  const int slot = options_.width == 2 ? 0 : options_.width == 4 ? 1 : 2;
  if (kernels_->intersect[slot] == nullptr) kernels_ = &generic_wide_kernels();
  intersect_fn_ = kernels_->intersect[slot];
  occluded_fn_ = kernels_->occluded[slot];
}

void WideBvhAccelerator::build_structure(const SceneGeometry& geometry) {
  tree_ = std::monostate{};
  empty_ = true;
  std::vector<PrimRef> refs = make_prim_refs(geometry);
  BinaryBvh binary =
      options_.build.split == SplitMethod::kSpatial
          ? build_spatial_split_bvh(geometry, std::move(refs), options_.build)
          : build_object_split_bvh(std::move(refs), geometry.sphere_geom_id(), options_.build);
  optimize_by_reinsertion(binary, options_.build.reinsertion_passes);
  switch (options_.width) {
    case 2:
      tree_ = collapse_to_wide<2>(binary, geometry);
      break;
    case 4:
      tree_ = collapse_to_wide<4>(binary, geometry);
      break;
    default:
      tree_ = collapse_to_wide<8>(binary, geometry);
      break;
  }
  std::visit(
      [&](const auto& bvh) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(bvh)>, std::monostate>) {
          view_.nodes = bvh.nodes.data();
          view_.triangle_blocks = bvh.triangle_blocks.data();
          view_.sphere_blocks = bvh.sphere_blocks.empty() ? nullptr : bvh.sphere_blocks[0].sphere;
          view_.spheres = geometry.spheres.data();
          view_.sphere_geom_id = geometry.sphere_geom_id();
          view_.root = bvh.root;
          empty_ = bvh.empty;
        }
      },
      tree_);
}

AccelStats WideBvhAccelerator::structure_stats() const {
  return std::visit(
      [](const auto& bvh) {
        if constexpr (std::is_same_v<std::decay_t<decltype(bvh)>, std::monostate>) {
          return AccelStats{};
        } else {
          return bvh.stats;
        }
      },
      tree_);
}

std::optional<Hit> WideBvhAccelerator::intersect_prepared(const Ray& ray) const {
  if (empty_) return std::nullopt;
  WideHit hit = kNoWideHit;
  if (!intersect_fn_(view_, ray, hit)) return std::nullopt;
  return Hit{hit.t, hit.u, hit.v, hit.geom_id, hit.prim_id, hit.vertex_lanes};
}

bool WideBvhAccelerator::occluded_prepared(const Ray& ray) const {
  if (empty_) return false;
  return occluded_fn_(view_, ray);
}

}  // namespace prism
