// The steps of a render shared by `prism render` and prism.render() (render_driver.h).

#include "core/app/render_driver.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "color/texture_set.h"
#include "core/app/component_params.h"
#include "core/app/environment_map.h"
#include "core/app/integrator_aliases.h"
#include "core/app/mpi_world.h"
#include "core/app/progressive_render.h"
#include "core/app/resume.h"
#include "core/atomic_file.h"
#include "core/progress.h"
#include "core/render_schedule.h"
#include "core/samplers.h"
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
  try {
    camera.validate();
  } catch (const Error& e) {
    // The scene's camera passed on load: fitted to this image (or with these lens options) it
    // no longer does, e.g. a field of view of 1e-45 degrees that the fit turns into 0. Name
    // the scene file all the same.
    ErrorLocation where = e.location();
    if (where.file.empty()) where.file = scene.source;
    throw Error(e.kind(),
                e.message() + fmt::format(" (the scene's camera fitted to {} x {})", settings.width,
                                          settings.height),
                where);
  }
  return camera;
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

std::unique_ptr<PreparedRender> prepare_render(const RenderOptions& options,
                                               RenderDestination destination,
                                               const std::optional<RenderState>& resumed,
                                               const std::filesystem::path& resume_file) {
  const bool files = destination == RenderDestination::kFiles;
  const bool writer = mpi::rank() == 0;
  auto r = std::make_unique<PreparedRender>();
  r->options = options;
  // Every check that needs no file comes first, so that a typo costs nothing.
  validate_render_options(options);
  if (mpi::size() > 1 && files && options.time_limit) {
    throw Error(ErrorKind::kUsage,
                "cannot be used under MPI: tiles are rendered with all their samples, so a "
                "distributed render cannot stop at a pass boundary (stop it with SIGTERM and "
                "--checkpoint instead)",
                ErrorLocation{{}, 0, "--time-limit"});
  }
  if (files) {
    // Every file to write, checked (extensions, EXR encoding, writable folders) before the work.
    r->outputs = resolve_output_plan(options);
    if (writer) {
      validate_outputs(r->outputs);
      // An output over an input (the scene, the environment map, the checkpoint resumed from)
      // would destroy it, and so would the checkpoint over the scene or the map; the checkpoint
      // over an image, one of the two. (The checkpoint over the one resumed from is the rule.)
      const std::vector<NamedInput> images = named_outputs(r->outputs);
      const NamedInput scene{"the scene file", render_scene_path(options)};
      const NamedInput environment{"the environment map (-e)", options.environment_map};
      const NamedInput checkpoint{"the --checkpoint file", options.checkpoint};
      refuse_overwriting_inputs(images, {scene,
                                         environment,
                                         {"the checkpoint resumed from (--resume)", resume_file},
                                         checkpoint});
      refuse_overwriting_inputs({{"--checkpoint", options.checkpoint}}, {scene, environment});
      if (!options.checkpoint.empty()) check_output_writable(options.checkpoint);
    }
  }
  r->params = parse_param_assignments(options.set);
  r->thread_limit = std::make_unique<ThreadLimit>(options.threads);
  r->accel = accelerator_registry().create(options.accelerator, r->params);

  r->scene_path = render_scene_path(options);
  r->scene = load_scene(r->scene_path, SceneLoadOptions{.literal_camera = options.literal_camera});
  for (const std::string& warning : r->scene.warnings) {
    if (writer) std::fprintf(stderr, "prism: warning: %s\n", warning.c_str());
  }
  r->settings = resolve_render_settings(options, r->scene);

  r->pipeline = std::make_unique<ColorPipeline>(options.color);
  r->pipeline->convert_scene_to_working(r->scene, r->pipeline->scene_file_space());
  // Textures are scene colours too: read, checked and converted before any long work.
  for (const std::string& warning : load_scene_textures(r->scene, *r->pipeline).warnings) {
    if (writer) std::fprintf(stderr, "prism: warning: %s\n", warning.c_str());
  }
  // The environment map is input like the scene: read and checked before any long work. Its
  // row 0 is the pole along the camera's up.
  if (!options.environment_map.empty()) {
    EnvironmentMap environment = load_environment_map(options.environment_map, *r->pipeline);
    for (const auto& warning : environment.warnings) {
      if (writer) std::fprintf(stderr, "prism: warning: %s\n", warning.c_str());
    }
    r->scene.environment = SceneEnvironment{.image = std::move(environment.image),
                                            .up = r->scene.camera.up,
                                            .file = options.environment_map,
                                            .color_space = environment.color_space};
  }
  if (files) {
    // What decides every pixel: a resumed render must be the one its checkpoint started.
    r->identity = render_identity(options, r->scene, *r->pipeline);
    if (resumed) check_resume_identity(r->identity, resumed->record, resume_file);
  }

  // Every component exists before the (possibly long) build, so mistyped names and --set keys
  // fail fast. -l, -m, -H (and the scene's max_depth) reach the integrator as its parameters.
  add_integrator_aliases(r->options, r->scene, r->settings.integrator, r->params);
  r->integrator = integrator_registry().create(r->settings.integrator, r->params);
  r->sampler = create_sampler(r->settings.sampler, r->settings.seed);
  r->sampler->set_sample_count(r->settings.spp);
  check_component_params(r->params, {{"accelerator", r->settings.accelerator},
                                     {"integrator", r->settings.integrator}});
  record_integrator_aliases(r->params, r->settings);
  r->camera = render_camera(r->scene, r->options, r->settings);
  return r;
}

RenderRecord start_record(const PreparedRender& r) {
  RenderRecord record;
  record.scene = r.scene_path.string();
  record.command_line = r.options.command_line;
  if (r.scene.environment) {
    record.environment = r.scene.environment->file;
    record.environment_space = r.scene.environment->color_space;
  }
  return record;
}

void start_render(PreparedRender& r, RenderRecord& record) {
  r.accel->build(r.scene.geometry);
  record.build_ms = r.accel->stats().build_ms;
  r.context.emplace(RenderContext{
      .scene = r.scene,
      .accel = *r.accel,
      .camera = r.camera,
      .sampler_prototype = *r.sampler,
      .spp = r.settings.spp,
      .image_height = r.settings.height,
      .image_width = r.settings.width,
      .adaptive_batch = r.settings.adaptive_batch,
      .adaptive_tolerance = r.settings.adaptive_tolerance,
      .progress = nullptr,
  });
  r.renderer = r.integrator->start(*r.context);
}

RenderedFrame resolve_frame(const PreparedRender& r, const Film& film, RenderRecord& record,
                            ImagePixels buffer) {
  RenderedFrame frame;
  frame.image = film.resolve(std::move(buffer));
  record.camera_samples = total_camera_samples(frame.image, r.settings);
  frame.metadata = make_provenance(r.settings, r.params, record);
  return frame;
}

RenderedFrame render_in_memory(const RenderOptions& options,
                               const std::function<void()>& between_passes) {
  const std::unique_ptr<PreparedRender> prepared =
      prepare_render(options, RenderDestination::kMemory);
  PreparedRender& r = *prepared;
  const RenderSettings& settings = r.settings;
  RenderRecord record = start_record(r);
  start_render(r, record);

  const RenderSchedule schedule(settings.window, settings.samples, settings.pass_samples);
  Film film(settings.width, settings.height, settings.window);
  ProgressReporter progress("rendering", samples_remaining(schedule, film), options.quiet);
  // The checkpoint hook is the one render_progressively() calls between passes, on this thread.
  std::function<void(const Film&)> hook;
  if (between_passes) hook = [&](const Film&) { between_passes(); };
  const ProgressiveResult result = render_progressively(
      *r.renderer, schedule, film,
      ProgressiveOptions{.time_limit_seconds = options.time_limit.value_or(0.0),
                         .stop_signal = nullptr,
                         .checkpoint = hook,
                         .checkpoint_interval_seconds = 0.0,
                         .progress = &progress});
  progress.done();
  record.render_ms = result.seconds * 1e3;
  record.passes_complete = result.passes_complete;
  record.pass_count = schedule.pass_count();
  record.non_finite_samples = film.non_finite_samples();
  if (result.end == RenderEnd::kTimeLimit) record.stopped_by = "time limit";
  RenderedFrame frame = resolve_frame(r, film, record);
  // The colour attributes an EXR carries, for the image as it is: in the working space.
  const ColorPipeline& pipeline = *r.pipeline;
  frame.metadata.emplace_back("prism:colorSpace", pipeline.working_space());
  frame.metadata.emplace_back("prism:workingSpace", pipeline.working_space());
  frame.metadata.emplace_back("prism:ocioConfig", pipeline.config_name());
  frame.metadata.emplace_back("prism:ocioConfigHash", pipeline.config_hash());
  frame.metadata.emplace_back("prism:ocioConfigSource", pipeline.config_source());
  return frame;
}

}  // namespace prism
