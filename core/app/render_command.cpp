// The render driver: one top-down function from options to files, in the order the work happens.

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <optional>

#include "accel/accelerator.h"
#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "core/app/commands.h"
#include "core/app/component_params.h"
#include "core/app/environment_map.h"
#include "core/app/integrator_aliases.h"
#include "core/app/provenance.h"
#include "core/app/sample_rate_image.h"
#include "core/film.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/samplers.h"
#include "core/strings.h"
#include "core/timing.h"
#include "integrators/integrator.h"
#include "scenes/scene_loader.h"

namespace prism {
namespace {

/// The scene's camera with the lens flags applied, fitted to the image's aspect ratio.
Camera render_camera(const Scene& scene, const RenderOptions& options,
                     const RenderSettings& settings) {
  Camera camera = scene.camera;
  if (options.lens_radius) camera.lens_radius = *options.lens_radius;
  if (options.focal_distance) camera.focal_distance = *options.focal_distance;
  camera.fit_to_aspect(float(settings.width) / float(settings.height));
  camera.validate();
  return camera;
}

void write_outputs(const std::vector<OutputFile>& outputs, const Image& image,
                   const ImageMetadata& metadata, const ColorPipeline& pipeline,
                   const ExrOptions& exr_options) {
  for (const auto& output : outputs) {
    if (output.exr) {
      write_exr(output.path, image, metadata, pipeline, exr_options);
    } else {
      write_display_image(output.path, image, metadata, pipeline);
    }
  }
}

std::string summary_line(const std::filesystem::path& scene, const RenderSettings& settings,
                         const RenderRecord& record) {
  const double per_second = samples_per_second(settings, record);
  std::vector<std::string> files;
  for (const auto& o : settings.outputs) files.push_back(o.path.string());
  return fmt::format(
      "{}: {} build {:.4g} ms, {} render {}x{} at {} spp {:.4g} ms ({:.3g} Msamples/s) -> {}",
      scene.filename().string(), settings.accelerator, record.build_ms, settings.integrator,
      settings.width, settings.height, settings.spp, record.render_ms, per_second * 1e-6,
      join(files));
}

/// Where the adaptive sampler's "sample rate" picture goes: <first output>_rate.png.
std::filesystem::path sample_rate_path(const RenderSettings& settings) {
  std::filesystem::path path = settings.outputs.front().path;
  return path.replace_filename(path.stem().string() + "_rate.png");
}

/// Writes the homework's colour-mapped sample-rate PNG of an adaptive render. Its colours are
/// already display values, so they go through the display's Raw view.
void write_sample_rate_image(const std::filesystem::path& path, const Image& image,
                             const ImageMetadata& metadata, const ColorOptions& color) {
  const std::optional<Image> rate = make_sample_rate_image(image);
  if (!rate) return;
  ColorOptions raw = color;
  raw.view = "Raw";
  raw.look.clear();
  raw.exposure = 0.0f;
  write_display_image(path, *rate, metadata, ColorPipeline(raw));
}

/// Camera samples the film received (the adaptive sampler stops pixels early).
double total_camera_samples(const Image& image, const RenderSettings& settings) {
  const auto it =
      std::find(image.channel_names.begin(), image.channel_names.end(), "sampleCount.Y");
  if (it == image.channel_names.end()) {
    return double(settings.width) * settings.height * settings.spp;
  }
  const int channel = static_cast<int>(it - image.channel_names.begin());
  double total = 0.0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) total += image.at(x, y, channel);
  }
  return total;
}

}  // namespace

int run_render_command(const RenderOptions& options) {
  // Every check that needs no file comes first, so that a typo costs nothing.
  validate_render_options(options);
  ParamSet params = parse_param_assignments(options.set);
  ThreadLimit thread_limit(options.threads);
  const std::unique_ptr<Accelerator> accel =
      accelerator_registry().create(options.accelerator, params);

  const std::filesystem::path scene_path = render_scene_path(options);
  Scene scene = load_scene(scene_path, SceneLoadOptions{.literal_camera = options.literal_camera});
  RenderSettings settings = resolve_render_settings(options, scene);

  const ColorPipeline pipeline(options.color);
  pipeline.convert_scene_to_working(scene, pipeline.scene_file_space());
  // The environment map is input like the scene: read and checked before any long work. Its
  // row 0 is the pole along the camera's up.
  if (!options.environment_map.empty()) {
    EnvironmentMap environment = load_environment_map(options.environment_map, pipeline);
    for (const auto& warning : environment.warnings) {
      std::fprintf(stderr, "prism: warning: %s\n", warning.c_str());
    }
    scene.environment = SceneEnvironment{.image = std::move(environment.image),
                                         .up = scene.camera.up,
                                         .file = options.environment_map,
                                         .color_space = environment.color_space};
  }

  // Fail on an unwritable output now rather than after a long render.
  for (const auto& output : settings.outputs) check_output_writable(output.path);
  const bool adaptive = settings.adaptive_batch > 0;
  if (adaptive) check_output_writable(sample_rate_path(settings));

  // Every component exists before the (possibly long) build, so mistyped names and --set keys
  // fail fast. -l, -m, -H (and the scene's max_depth) reach the integrator as its parameters.
  add_integrator_aliases(options, scene, settings.integrator, params);
  const std::unique_ptr<Integrator> integrator =
      integrator_registry().create(settings.integrator, params);
  const std::unique_ptr<Sampler> sampler = create_sampler(settings.sampler, settings.seed);
  sampler->set_sample_count(settings.spp);
  check_component_params(
      params, {{"accelerator", settings.accelerator}, {"integrator", settings.integrator}});
  record_integrator_aliases(params, settings);
  const Camera camera = render_camera(scene, options, settings);

  RenderRecord record;
  record.scene = scene_path.string();
  record.command_line = options.command_line;
  if (scene.environment) {
    record.environment = scene.environment->file;
    record.environment_space = scene.environment->color_space;
  }
  record.build_ms = time_ms([&] { accel->build(scene.geometry); });

  Film film(settings.width, settings.height);
  ProgressReporter progress(
      "rendering", integrator->progress_total(settings.width, settings.height, settings.spp),
      options.quiet);
  const RenderContext context{
      .scene = scene,
      .accel = *accel,
      .camera = camera,
      .sampler_prototype = *sampler,
      .spp = settings.spp,
      .adaptive_batch = settings.adaptive_batch,
      .adaptive_tolerance = settings.adaptive_tolerance,
      .progress = &progress,
  };
  record.render_ms = time_ms([&] { integrator->render(context, film); });
  progress.done();
  record.non_finite_samples = film.non_finite_samples();
  if (record.non_finite_samples > 0) {
    std::fprintf(stderr, "prism: warning: %llu NaN or infinite samples counted as zero\n",
                 static_cast<unsigned long long>(record.non_finite_samples));
  }

  const Image image = film.resolve();
  record.camera_samples = total_camera_samples(image, settings);
  const ImageMetadata metadata = make_provenance(settings, params, record);
  write_outputs(settings.outputs, image, metadata, pipeline, options.exr_options);
  if (adaptive) write_sample_rate_image(sample_rate_path(settings), image, metadata, options.color);
  std::printf("%s\n", summary_line(scene_path, settings, record).c_str());
  return kExitSuccess;
}

}  // namespace prism
