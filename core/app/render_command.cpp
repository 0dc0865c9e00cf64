// The render driver: one top-down function from options to files, in the order the work happens.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "accel/accelerator.h"
#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "color/output_plan.h"
#include "core/app/commands.h"
#include "core/app/component_params.h"
#include "core/app/environment_map.h"
#include "core/app/integrator_aliases.h"
#include "core/app/interrupts.h"
#include "core/app/progressive_render.h"
#include "core/app/provenance.h"
#include "core/app/render_state.h"
#include "core/app/resume.h"
#include "core/film.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/samplers.h"
#include "core/strings.h"
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

/// The line printed after the render; it lists the image files, not the sample-rate picture.
std::string summary_line(const std::filesystem::path& scene, const RenderSettings& settings,
                         const OutputPlan& outputs, const RenderRecord& record) {
  const double per_second = samples_per_second(settings, record);
  std::vector<std::string> files;
  for (const auto& file : outputs.files) {
    if (file.kind != OutputKind::kSampleRate) files.push_back(file.path.string());
  }
  const std::string stopped =
      record.stopped_by.empty()
          ? ""
          : fmt::format(" (stopped by {} after {} of {} passes)", record.stopped_by,
                        record.passes_complete, record.pass_count);
  return fmt::format(
      "{}: {} build {:.4g} ms, {} render {}x{} at {} spp {:.4g} ms ({:.3g} Msamples/s){} -> {}",
      scene.filename().string(), settings.accelerator, record.build_ms, settings.integrator,
      settings.width, settings.height, settings.spp, record.render_ms, per_second * 1e-6, stopped,
      join(files));
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

/// Whether the render is a part of a frame: a crop or a sample range.
bool is_part(const RenderSettings& settings) {
  return settings.window != PixelRect{{0, 0}, {settings.width, settings.height}} ||
         settings.samples != SampleRange{0, uint32_t(settings.spp)};
}

/// The options a state file keeps: paths absolute (the render may resume from another folder),
/// the output the plan resolved.
RenderOptions stored_options(const RenderOptions& options, const OutputPlan& outputs) {
  RenderOptions stored = options;
  if (stored.output.empty()) stored.output = outputs.files.front().path.string();
  stored.resume.clear();
  return with_absolute_paths(stored);
}

}  // namespace

int run_render_command(const RenderOptions& given) {
  // --resume: the checkpoint's options, with only run controls from the command line.
  std::optional<RenderState> resumed;
  RenderOptions options = given;
  if (!given.resume.empty()) {
    resumed = read_render_state(given.resume);
    options = resumed_options(given, resumed->record, given.resume);
  }
  // Every check that needs no file comes first, so that a typo costs nothing.
  validate_render_options(options);
  // Every file to write, checked (extensions, EXR encoding, writable folders) before the work.
  const OutputPlan outputs = resolve_output_plan(options);
  validate_outputs(outputs);
  if (!options.checkpoint.empty()) check_output_writable(options.checkpoint);
  ParamSet params = parse_param_assignments(options.set);
  ThreadLimit thread_limit(options.threads);
  const std::unique_ptr<Accelerator> accel =
      accelerator_registry().create(options.accelerator, params);

  const std::filesystem::path scene_path = render_scene_path(options);
  Scene scene = load_scene(scene_path, SceneLoadOptions{.literal_camera = options.literal_camera});
  for (const std::string& warning : scene.warnings) {
    std::fprintf(stderr, "prism: warning: %s\n", warning.c_str());
  }
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
  // What decides every pixel: a resumed render must be the one its checkpoint started.
  const nlohmann::json identity = render_identity(options, scene, pipeline);
  if (resumed) check_resume_identity(identity, resumed->record, given.resume);

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
  accel->build(scene.geometry);
  record.build_ms = accel->stats().build_ms;

  const RenderSchedule schedule(settings.window, settings.samples, settings.pass_samples);
  Film film =
      resumed ? std::move(resumed->film) : Film(settings.width, settings.height, settings.window);
  if (film.width() != settings.width || film.height() != settings.height ||
      film.window() != settings.window) {
    throw Error(ErrorKind::kInput, "the checkpoint's film does not fit its options",
                ErrorLocation{given.resume, 0, "--resume"});
  }
  const double earlier_ms = resumed ? resumed->record.render_ms : 0.0;
  RenderStateRecord state{.identity = identity,
                          .options = stored_options(options, outputs),
                          .window = settings.window,
                          .samples = settings.samples,
                          .pass_samples = settings.pass_samples,
                          .width = settings.width,
                          .height = settings.height,
                          .spp = settings.spp,
                          .render_ms = earlier_ms};
  const auto finish_record = [&](const ProgressiveResult& result, const Film& f) {
    record.render_ms = earlier_ms + result.seconds * 1e3;
    record.passes_complete = result.passes_complete;
    record.pass_count = schedule.pass_count();
    record.non_finite_samples = f.non_finite_samples();
  };
  const auto save_checkpoint = [&](const Film& f, double run_seconds) {
    state.render_ms = earlier_ms + run_seconds * 1e3;
    RenderRecord snapshot = record;
    snapshot.render_ms = state.render_ms;
    snapshot.passes_complete = passes_complete(schedule, f);
    snapshot.pass_count = schedule.pass_count();
    snapshot.non_finite_samples = f.non_finite_samples();
    write_render_state(options.checkpoint, f, state, make_provenance(settings, params, snapshot),
                       pipeline);
  };

  ProgressReporter progress("rendering", samples_remaining(schedule, film), options.quiet);
  const RenderContext context{
      .scene = scene,
      .accel = *accel,
      .camera = camera,
      .sampler_prototype = *sampler,
      .spp = settings.spp,
      .adaptive_batch = settings.adaptive_batch,
      .adaptive_tolerance = settings.adaptive_tolerance,
      .progress = nullptr,
  };
  const std::unique_ptr<const TileRenderer> renderer = integrator->start(context);
  // From here a first SIGINT/SIGTERM stops the render and writes what it has.
  const InterruptHandlers interrupts;
  const auto run_start = std::chrono::steady_clock::now();
  ProgressiveOptions run{.time_limit_seconds = options.time_limit.value_or(0.0),
                         .stop_signal = &interrupts.stop_signal(),
                         .checkpoint_interval_seconds = options.checkpoint_interval,
                         .progress = &progress};
  if (!options.checkpoint.empty()) {
    run.checkpoint = [&](const Film& f) {
      save_checkpoint(
          f, std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count());
    };
  }
  const ProgressiveResult result = render_progressively(*renderer, schedule, film, run);
  progress.done();
  finish_record(result, film);
  if (result.end == RenderEnd::kTimeLimit) record.stopped_by = "time limit";
  if (result.end == RenderEnd::kSignal) record.stopped_by = signal_name(interrupts.stop_signal());
  // A stopped render can be continued: its checkpoint holds every sample taken.
  if (result.end != RenderEnd::kComplete && !options.checkpoint.empty()) {
    save_checkpoint(film, result.seconds);
  }
  if (record.non_finite_samples > 0) {
    std::fprintf(stderr, "prism: warning: %llu NaN or infinite samples counted as zero\n",
                 static_cast<unsigned long long>(record.non_finite_samples));
  }

  const Image image = film.resolve();
  record.camera_samples = total_camera_samples(image, settings);
  const ImageMetadata metadata = make_provenance(settings, params, record);
  if (is_part(settings) && outputs.files.front().kind == OutputKind::kSceneLinearExr) {
    // A part of a frame keeps its exact sums, for `prism merge`.
    state.render_ms = record.render_ms;
    write_render_state(outputs.files.front().path, film, state, metadata, pipeline);
    OutputPlan rest = outputs;
    rest.files.erase(rest.files.begin());
    write_outputs(rest, image, metadata, pipeline);
  } else {
    write_outputs(outputs, image, metadata, pipeline);
  }
  std::printf("%s\n", summary_line(scene_path, settings, outputs, record).c_str());
  if (const int signal = interrupts.stop_signal(); signal != 0) {
    return interrupted_exit_code(signal);
  }
  return kExitSuccess;
}

}  // namespace prism
