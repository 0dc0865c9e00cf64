#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "color/output_plan.h"
#include "core/param_set.h"
#include "core/render_schedule.h"
#include "core/scene.h"
#include "integrators/integrator_defaults.h"

namespace prism {

inline constexpr const char* kDefaultAccelerator = "bvh";
/// Stratified low-discrepancy points converge faster than independent ones at the same spp.
inline constexpr const char* kDefaultSampler = "sobol";
/// Used when neither --integrator nor the scene file names one.
inline constexpr const char* kDefaultIntegrator = "path";
/// 480 x 360 (the size CS184 scenes are made for), used when neither -r nor the scene file
/// gives one.
inline constexpr int kDefaultWidth = 480;
inline constexpr int kDefaultHeight = 360;
inline constexpr int kDefaultSpp = 16;
inline constexpr uint64_t kDefaultSeed = 0;

/// Bounds on option values: the film's limits (core/film.h), and counts large enough for any
/// real render, small enough that counters cannot overflow.
inline constexpr int kMaxResolution = kMaxFilmSide;
inline constexpr long long kMaxPixels = kMaxFilmPixels;
inline constexpr int kMaxSpp = 1 << 20;
inline constexpr int kMaxThreads = 4096;

/// What the user typed for `prism render`. Unset optionals fall back to the scene file's
/// settings, then to the defaults above. Plain data filled by the command-line parser.
struct RenderOptions {
  std::string scene;  ///< empty: default_scene_path()
  std::string accelerator = kDefaultAccelerator;
  std::optional<std::string> integrator;
  std::string sampler = kDefaultSampler;
  std::optional<int> spp;
  std::optional<int> light_samples;
  std::optional<int> max_depth;
  std::optional<std::pair<int, int>> resolution;  ///< width, height
  /// Kept as text: CLI11 would read "-1" as 2^64 - 1 for an unsigned type.
  std::optional<std::string> seed;
  int threads = 0;                                 ///< 0: all hardware threads
  std::optional<std::pair<int, double>> adaptive;  ///< batch size, tolerance (-a)
  bool hemisphere_sampling = false;                ///< -H
  bool two_sided_emitters = false;                 ///< --two-sided-emitters
  std::optional<float> lens_radius;                ///< -b
  std::optional<float> focal_distance;             ///< -d
  std::string environment_map;                     ///< -e: lat-long image file; empty: none
  std::string camera_file;                         ///< -c (not supported yet)
  std::string output;                              ///< empty: <scene stem>.exr here
  bool png = false;                                ///< also write <output stem>.png
  bool exr = false;  ///< also write <output stem>.exr when the output is a display image
  bool quiet = false;
  bool literal_camera = false;
  std::vector<std::string> set;  ///< --set key=value, in order
  /// Production runs (docs/PRODUCTION.md).
  std::optional<double> time_limit;                 ///< --time-limit SECONDS
  std::string checkpoint;                           ///< --checkpoint FILE; empty: none
  std::string resume;                               ///< --resume FILE; empty: a new render
  double checkpoint_interval = 60.0;                ///< --checkpoint-interval SECONDS
  std::optional<std::array<int, 4>> crop;           ///< --crop X0 Y0 X1 Y1
  std::optional<std::pair<int, int>> sample_range;  ///< --samples FIRST LAST
  std::optional<int> pass_samples;                  ///< --pass-samples N
  ColorOptions color;
  ExrOptions exr_options;
  std::string command_line;  ///< for provenance metadata
};

/// Every setting of one render after flags, scene settings and defaults have been merged and
/// checked.
struct RenderSettings {
  std::string accelerator;
  std::string integrator;
  std::string sampler;
  int width = kDefaultWidth;
  int height = kDefaultHeight;
  int spp = kDefaultSpp;
  /// -l and -m as recorded in the output files: resolve_render_settings() gives the flags (for
  /// max_depth, else the scene file) or the defaults; record_integrator_aliases() then the
  /// values of the integrator's parameters where it has them.
  int light_samples = kDefaultLightSamples;
  int max_depth = kDefaultMaxDepth;
  uint64_t seed = kDefaultSeed;
  int adaptive_batch = 0;  ///< 0: adaptive sampling off
  float adaptive_tolerance = 0.05f;
  PixelRect window;           ///< the pixels rendered (--crop; else the whole image)
  SampleRange samples;        ///< the samples rendered of every pixel (--samples; else all)
  uint32_t pass_samples = 1;  ///< samples per pixel and pass
};

/// Samples per pass when --pass-samples is not given: spp / kDefaultPasses, so that a long
/// render has about that many passes to stop, checkpoint or report after, but at least
/// kMinDefaultPassSamples (all of them below that): every pass reads and writes every pixel's
/// film state again, which at one sample per pass cost 2.5-4% of a 64-spp render
/// (docs/PERFORMANCE.md, 2026-12-07, twelfth session). Renders of 256 spp and more keep 64
/// passes.
inline constexpr int kDefaultPasses = 64;
inline constexpr int kMinDefaultPassSamples = 4;

/// The samples per pass of a render of `spp` samples without --pass-samples.
inline int default_pass_samples(int spp) {
  return std::max(std::min(kMinDefaultPassSamples, spp), spp / kDefaultPasses);
}

/// Checks every option value that does not depend on the scene: ranges, finite numbers, features
/// not supported yet (--set is checked by parse_param_assignments(), the output files by
/// validate_outputs() on resolve_output_plan()). Throws Error(kUsage) naming the option. Call
/// before any work.
void validate_render_options(const RenderOptions& options);

/// Throws Error(kUsage) naming --threads unless 0 <= threads <= kMaxThreads.
void validate_thread_count(int threads);

/// The scene file the render loads: --scene, else default_scene_path().
std::filesystem::path render_scene_path(const RenderOptions& options);

/// Merges `options` (already validated) over the scene's settings over the defaults. Throws
/// Error(kInput) naming the scene file when one of its settings is out of range.
RenderSettings resolve_render_settings(const RenderOptions& options, const Scene& scene);

/// The files the render writes, in this order: the output path (default "<scene stem>.exr" in the
/// current folder; kind by extension), with --exr the same path as .exr unless it is an EXR,
/// with --png as .png unless it is a PNG, and with --adaptive "<output stem>_rate.png" beside it;
/// plus the colour options and EXR encoding. Judges nothing: validate_outputs() does.
OutputPlan resolve_output_plan(const RenderOptions& options);

/// The --set assignments as a ParamSet; throws Error(kUsage) on a malformed one.
ParamSet parse_param_assignments(const std::vector<std::string>& assignments);

}  // namespace prism
