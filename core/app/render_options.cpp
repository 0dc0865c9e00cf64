#include "core/app/render_options.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "core/error.h"
#include "scenes/scene_loader.h"

namespace prism {
namespace {

[[noreturn]] void bad_option(const std::string& option, const std::string& message) {
  throw Error(ErrorKind::kUsage, message, ErrorLocation{{}, 0, option});
}

void check_int(const std::optional<int>& value, const std::string& option, long long min,
               long long max) {
  if (!value) return;
  if (*value < min || *value > max) {
    bad_option(option, "must be in [" + std::to_string(min) + ", " + std::to_string(max) +
                           "], got " + std::to_string(*value));
  }
}

void check_resolution(long long width, long long height, const std::string& option,
                      const ErrorLocation& scene_location) {
  std::string problem;
  if (width < 1 || height < 1) {
    problem = "must be positive, got " + std::to_string(width) + " x " + std::to_string(height);
  } else if (width > kMaxResolution || height > kMaxResolution) {
    problem = "at most " + std::to_string(kMaxResolution) + " pixels per side, got " +
              std::to_string(width) + " x " + std::to_string(height);
  } else if (width * height > kMaxPixels) {
    problem = std::to_string(width) + " x " + std::to_string(height) + " exceeds the limit of " +
              std::to_string(kMaxPixels) + " pixels";
  }
  if (problem.empty()) return;
  if (!scene_location.file.empty()) throw Error(ErrorKind::kInput, problem, scene_location);
  bad_option(option, problem);
}

uint64_t parse_seed(const std::string& text) {
  uint64_t seed = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seed);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
    bad_option("--seed", "'" + text + "' is not an integer in [0, 2^64)");
  }
  return seed;
}

/// A scene setting checked against [min, max]: out of range is the scene file's fault.
int scene_setting(const std::optional<int>& value, int fallback, long long min, long long max,
                  const Scene& scene, const std::string& name) {
  if (!value) return fallback;
  if (*value < min || *value > max) {
    throw Error(ErrorKind::kInput,
                "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
                    std::to_string(*value),
                ErrorLocation{scene.source, 0, "settings." + name});
  }
  return *value;
}

}  // namespace

void validate_render_options(const RenderOptions& options) {
  check_int(options.spp, "--spp (-s)", 1, kMaxSpp);
  check_int(options.light_samples, "--light-samples (-l)", 1, kMaxLightSamples);
  check_int(options.max_depth, "--max-depth (-m)", 0, kMaxDepth);
  validate_thread_count(options.threads);
  if (options.resolution) {
    check_resolution(options.resolution->first, options.resolution->second, "--resolution (-r)",
                     {});
  }
  if (options.seed) parse_seed(*options.seed);
  if (options.adaptive) {
    const auto [batch, tolerance] = *options.adaptive;
    if (batch < 1 || batch > kMaxSpp) {
      bad_option("--adaptive (-a)", "batch size must be in [1, " + std::to_string(kMaxSpp) +
                                        "], got " + std::to_string(batch));
    }
    // A relative tolerance: above 1 every pixel would stop after its first batch.
    if (!(tolerance > 0.0 && tolerance <= 1.0)) {
      bad_option("--adaptive (-a)",
                 "tolerance must be in (0, 1], got " + std::to_string(tolerance));
    }
  }
  if (options.lens_radius && !(std::isfinite(*options.lens_radius) && *options.lens_radius >= 0)) {
    bad_option("--lens-radius (-b)",
               "must be a finite number >= 0, got " + std::to_string(*options.lens_radius));
  }
  if (options.focal_distance &&
      !(std::isfinite(*options.focal_distance) && *options.focal_distance > 0)) {
    bad_option("--focal-distance (-d)",
               "must be a finite number > 0, got " + std::to_string(*options.focal_distance));
  }
  if (!std::isfinite(options.color.exposure)) {
    bad_option("--exposure", "must be a finite number of stops");
  }
  if (!options.camera_file.empty()) {
    bad_option("--camera-file (-c)", "camera settings files are not supported yet");
  }
  if (options.time_limit && !(std::isfinite(*options.time_limit) && *options.time_limit > 0)) {
    bad_option("--time-limit", "must be a finite number of seconds > 0");
  }
  if (!(std::isfinite(options.checkpoint_interval) && options.checkpoint_interval > 0)) {
    bad_option("--checkpoint-interval", "must be a finite number of seconds > 0");
  }
  check_int(options.pass_samples, "--pass-samples", 1, kMaxSpp);
  if (options.crop) {
    const auto [x0, y0, x1, y1] = *options.crop;
    if (x0 < 0 || y0 < 0 || x1 <= x0 || y1 <= y0) {
      bad_option("--crop", "X0 Y0 X1 Y1 must satisfy 0 <= X0 < X1 and 0 <= Y0 < Y1, got " +
                               std::to_string(x0) + " " + std::to_string(y0) + " " +
                               std::to_string(x1) + " " + std::to_string(y1));
    }
  }
  if (options.sample_range) {
    const auto [first, last] = *options.sample_range;
    if (first < 0 || last <= first || last > kMaxSpp) {
      bad_option("--samples",
                 "FIRST LAST must satisfy 0 <= FIRST < LAST <= " + std::to_string(kMaxSpp) +
                     ", got " + std::to_string(first) + " " + std::to_string(last));
    }
    // Where adaptive sampling stops a pixel depends on every sample before: a range cannot
    // know them, and parts could not be summed.
    if (options.adaptive) {
      bad_option("--samples", "cannot be combined with adaptive sampling (-a)");
    }
  }
}

void validate_thread_count(int threads) { check_int(threads, "--threads (-t)", 0, kMaxThreads); }

std::filesystem::path render_scene_path(const RenderOptions& options) {
  return options.scene.empty() ? default_scene_path() : std::filesystem::path(options.scene);
}

RenderSettings resolve_render_settings(const RenderOptions& options, const Scene& scene) {
  const SceneRenderSettings& file = scene.settings;
  RenderSettings s;
  s.accelerator = options.accelerator;
  s.sampler = options.sampler;
  s.integrator = options.integrator.value_or(file.integrator.value_or(kDefaultIntegrator));
  if (options.resolution) {
    s.width = options.resolution->first;
    s.height = options.resolution->second;
  } else {
    s.width = file.width.value_or(kDefaultWidth);
    s.height = file.height.value_or(kDefaultHeight);
    check_resolution(s.width, s.height, {}, ErrorLocation{scene.source, 0, "settings.resolution"});
  }
  s.spp =
      options.spp ? *options.spp : scene_setting(file.spp, kDefaultSpp, 1, kMaxSpp, scene, "spp");
  s.max_depth = options.max_depth ? *options.max_depth
                                  : scene_setting(file.max_depth, kDefaultMaxDepth, 0, kMaxDepth,
                                                  scene, "max_depth");
  s.light_samples = options.light_samples.value_or(kDefaultLightSamples);
  s.seed = options.seed ? parse_seed(*options.seed) : file.seed.value_or(kDefaultSeed);
  if (options.adaptive) {
    s.adaptive_batch = options.adaptive->first;
    s.adaptive_tolerance = static_cast<float>(options.adaptive->second);
  }
  s.window = PixelRect{{0, 0}, {s.width, s.height}};
  if (options.crop) {
    const auto [x0, y0, x1, y1] = *options.crop;
    if (x1 > s.width || y1 > s.height) {
      bad_option("--crop", "X1 Y1 (" + std::to_string(x1) + " " + std::to_string(y1) +
                               ") must be inside the image (" + std::to_string(s.width) + " x " +
                               std::to_string(s.height) + ")");
    }
    s.window = PixelRect{{x0, y0}, {x1, y1}};
  }
  s.samples = SampleRange{0, uint32_t(s.spp)};
  if (options.sample_range) {
    const auto [first, last] = *options.sample_range;
    if (last > s.spp) {
      bad_option("--samples", "LAST (" + std::to_string(last) + ") must be at most the samples " +
                                  "per pixel (" + std::to_string(s.spp) + ")");
    }
    s.samples = SampleRange{uint32_t(first), uint32_t(last)};
  }
  s.pass_samples = uint32_t(options.pass_samples.value_or(default_pass_samples(s.spp)));
  return s;
}

OutputPlan resolve_output_plan(const RenderOptions& options) {
  namespace fs = std::filesystem;
  const fs::path primary = options.output.empty()
                               ? fs::path(render_scene_path(options).stem().string() + ".exr")
                               : fs::path(options.output);
  OutputPlan plan{.files = {}, .color = options.color, .exr = options.exr_options};
  plan.files.push_back(plan_image_file(primary, "--output (-f)"));
  const PlannedOutput output = plan.files.front();
  if (options.exr && output.kind != OutputKind::kSceneLinearExr) {
    plan.files.push_back(plan_image_file(fs::path(primary).replace_extension(".exr"), "--exr"));
  }
  if (options.png && output.format != "png") {
    plan.files.push_back(plan_image_file(fs::path(primary).replace_extension(".png"), "--png"));
  }
  if (options.adaptive) {
    plan.files.push_back(plan_sample_rate_file(
        fs::path(primary).replace_filename(primary.stem().string() + "_rate.png"),
        "--adaptive (-a)"));
  }
  return plan;
}

ParamSet parse_param_assignments(const std::vector<std::string>& assignments) {
  ParamSet params;
  for (const auto& a : assignments) params.add_assignment(a);
  return params;
}

}  // namespace prism
