// The render driver: one top-down function from options to files, in the order the work happens;
// the steps it shares with the Python module are in render_driver.cpp.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <new>
#include <optional>

#include "color/color_pipeline.h"
#include "color/image_io.h"
#include "color/image_output.h"
#include "color/output_plan.h"
#include "core/app/commands.h"
#include "core/app/interrupts.h"
#include "core/app/mpi_render.h"
#include "core/app/mpi_world.h"
#include "core/app/progressive_render.h"
#include "core/app/provenance.h"
#include "core/app/rank_agreement.h"
#include "core/app/render_driver.h"
#include "core/app/render_state.h"
#include "core/app/resume.h"
#include "core/film.h"
#include "core/image_buffer_ahead.h"
#include "core/progress.h"
#include "core/strings.h"

namespace prism {
namespace {

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
  const std::string ranks = record.mpi_ranks > 1
                                ? fmt::format(" on {} MPI ranks ({:.3g} MB exchanged)",
                                              record.mpi_ranks, double(record.mpi_bytes) * 1e-6)
                                : "";
  return fmt::format(
      "{}: {} build {:.4g} ms, {} render {}x{} at {} spp {:.4g} ms ({:.3g} Msamples/s){}{} -> {}",
      scene.filename().string(), settings.accelerator, record.build_ms, settings.integrator,
      settings.width, settings.height, settings.spp, record.render_ms, per_second * 1e-6, ranks,
      stopped, join(files));
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

/// The options of the render: `given`, or with --resume the checkpoint's (read into `resumed`).
/// Under MPI rank 0 reads the checkpoint and the other ranks take its options (they may not
/// see the file), keeping their own --threads. Collective under MPI.
RenderOptions options_to_render(const RenderOptions& given, std::optional<RenderState>& resumed) {
  RenderOptions options = given;
  RankStatus mine;
  if (mpi::rank() == 0 && !given.resume.empty()) {
    try {
      resumed = read_render_state(given.resume);
      options = resumed_options(given, resumed->record, given.resume);
      mine.data = options_to_json(options);
    } catch (...) {
      if (mpi::size() <= 1) throw;
      const ErrorReport report = current_error_report();
      mine = RankStatus{report.exit_code, report.message, nullptr};
    }
  }
  const RankStatus rank0 = take_rank0_status(mine);
  if (mpi::rank() != 0 && !rank0.data.is_null()) {
    options = options_from_json(rank0.data, given.resume);
    options.threads = given.threads;
  }
  return options;
}

/// What every rank of a distributed render must share: the identity, and the pixels and samples
/// rendered (which the identity leaves out).
nlohmann::json frame_of(const PreparedRender& r) {
  nlohmann::json frame = r.identity;
  const PixelRect& w = r.settings.window;
  frame["window"] = {w.begin.x, w.begin.y, w.end.x, w.end.y};
  frame["samples"] = {r.settings.samples.first, r.settings.samples.last};
  frame["image"] = {r.settings.width, r.settings.height};
  return frame;
}

/// run_render_command without its out-of-memory message.
int render_command(const RenderOptions& given) {
  // Under mpirun (mpi::size() > 1) every rank runs this; rank 0 coordinates and writes.
  const bool distributed = mpi::size() > 1;
  const bool writer = mpi::rank() == 0;
  // --resume: the checkpoint's options, with only run controls from the command line.
  std::optional<RenderState> resumed;
  const RenderOptions options = options_to_render(given, resumed);
  // Under MPI the ranks agree before the build that each of them read everything and would
  // render the same frame; otherwise they all exit with the first failing rank's error.
  std::unique_ptr<PreparedRender> prepared;
  RankStatus status;
  try {
    prepared = prepare_render(options, RenderDestination::kFiles, resumed, given.resume);
    if (distributed) status.data = frame_of(*prepared);
  } catch (...) {
    if (!distributed) throw;
    const ErrorReport report = current_error_report();
    status = RankStatus{report.exit_code, report.message, nullptr};
  }
  agree_across_ranks(status, "the frame to render (scene file, options or prism version)");
  PreparedRender& r = *prepared;
  const OutputPlan& outputs = r.outputs;
  const RenderSettings& settings = r.settings;
  const ColorPipeline& pipeline = *r.pipeline;
  // From here the ranks depend on each other: a rank failing alone ends them all.
  MpiJob job;

  RenderRecord record = start_record(r);
  start_render(r, record);
  const TileRenderer& renderer = *r.renderer;

  const RenderSchedule schedule(settings.window, settings.samples, settings.pass_samples);
  if (!writer) {
    // A worker: renders what rank 0 hands out, and exits as rank 0 says.
    const InterruptHandlers interrupts;
    MpiChannel channel;
    const int code = serve_render(renderer, schedule, settings.width, settings.height, channel,
                                  r.thread_limit->threads(), &interrupts.stop_signal());
    channel.flush();
    job.close();
    return code;
  }

  Film film =
      resumed ? std::move(resumed->film) : Film(settings.width, settings.height, settings.window);
  if (film.width() != settings.width || film.height() != settings.height ||
      film.window() != settings.window) {
    throw Error(ErrorKind::kInput, "the checkpoint's film does not fit its options",
                ErrorLocation{given.resume, 0, "--resume"});
  }
  const double earlier_ms = resumed ? resumed->record.render_ms : 0.0;
  RenderStateRecord state{.identity = r.identity,
                          .options = stored_options(options, outputs),
                          .window = settings.window,
                          .samples = settings.samples,
                          .pass_samples = settings.pass_samples,
                          .width = settings.width,
                          .height = settings.height,
                          .spp = settings.spp,
                          .render_ms = earlier_ms};
  record.mpi_ranks = mpi::size();
  std::optional<MpiChannel> channel;  // under MPI: the messages to and from the workers
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
    if (channel) snapshot.mpi_bytes = channel->bytes_sent() + channel->bytes_received();
    write_render_state(options.checkpoint, f, state, make_provenance(settings, r.params, snapshot),
                       pipeline);
  };

  ProgressReporter progress("rendering", samples_remaining(schedule, film), options.quiet);
  // From here a first SIGINT/SIGTERM stops the render and writes what it has.
  const InterruptHandlers interrupts;
  // The image module loads on one of the render's threads while the others render
  // (color/image_io.h). Only now: a thread started while it loads (the interrupt handlers' one)
  // would wait for the load to end. Not under MPI, whose lanes are threads of their own.
  const int threads_beside = distributed ? 1 : r.thread_limit->threads();
  const ImageIoPreload image_io_preload(threads_beside);
  // The image's buffer is made beside the render too (core/image_buffer_ahead.h).
  ImageBufferAhead image_buffer(film.window().pixel_count() * Film::kChannels, threads_beside);
  const auto run_start = std::chrono::steady_clock::now();
  std::function<void(const Film&)> checkpoint;
  if (!options.checkpoint.empty()) {
    checkpoint = [&](const Film& f) {
      save_checkpoint(
          f, std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count());
    };
  }
  ProgressiveResult result;
  int stop_signal = 0;
  if (distributed) {
    channel.emplace();
    const DistributedResult distributed_result = coordinate_render(
        renderer, schedule, film, *channel,
        DistributedOptions{.lanes = r.thread_limit->threads(),
                           .stop_signal = &interrupts.stop_signal(),
                           .checkpoint = checkpoint,
                           .checkpoint_interval_seconds = options.checkpoint_interval,
                           .progress = &progress});
    result = distributed_result.run;
    stop_signal = distributed_result.signal;
    record.mpi_bytes = distributed_result.bytes_exchanged;
  } else {
    result = render_progressively(
        renderer, schedule, film,
        ProgressiveOptions{.time_limit_seconds = options.time_limit.value_or(0.0),
                           .stop_signal = &interrupts.stop_signal(),
                           .checkpoint = checkpoint,
                           .checkpoint_interval_seconds = options.checkpoint_interval,
                           .progress = &progress});
  }
  progress.done();
  if (stop_signal == 0) stop_signal = interrupts.stop_signal();
  finish_record(result, film);
  if (result.end == RenderEnd::kTimeLimit) record.stopped_by = "time limit";
  if (result.end == RenderEnd::kSignal) record.stopped_by = signal_name(stop_signal);
  // A stopped render can be continued: its checkpoint holds every sample taken.
  if (result.end != RenderEnd::kComplete && !options.checkpoint.empty()) {
    save_checkpoint(film, result.seconds);
  }
  if (record.non_finite_samples > 0) {
    std::fprintf(stderr, "prism: warning: %llu NaN or infinite samples counted as zero\n",
                 static_cast<unsigned long long>(record.non_finite_samples));
  }

  const RenderedFrame frame = resolve_frame(r, film, record, image_buffer.take());
  const Image& image = frame.image;
  const ImageMetadata& metadata = frame.metadata;
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
  std::printf("%s\n", summary_line(r.scene_path, settings, outputs, record).c_str());
  // A signal during the writing still says the run was interrupted.
  if (stop_signal == 0) stop_signal = interrupts.stop_signal();
  const int code = stop_signal != 0 ? interrupted_exit_code(stop_signal) : kExitSuccess;
  if (channel) finish_workers(*channel, code);
  job.close();
  return code;
}

}  // namespace

int run_render_command(const RenderOptions& given) {
  try {
    return render_command(given);
  } catch (const std::bad_alloc&) {
    // Under `ulimit -v` (or on a small machine) the scene, the accelerator or the film may not
    // fit: say which scene, and what to change. Nothing has been written (the writers are
    // atomic).
    const std::string scene = given.resume.empty() || !given.scene.empty()
                                  ? render_scene_path(given).string()
                                  : given.resume;
    throw Error(ErrorKind::kResource,
                "out of memory rendering the scene (raise the memory limit, e.g. ulimit -v, or "
                "lower --resolution, the scene's size or --threads)",
                ErrorLocation{scene, 0, {}});
  }
}

}  // namespace prism
