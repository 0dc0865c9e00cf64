#pragma once

// The steps of a render that every caller shares: `prism render` (render_command.cpp, which adds
// the output files, checkpoints, --resume and MPI around them) and the Python module's
// prism.render(), which keeps the image in memory (render_in_memory()).

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "accel/accelerator.h"
#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "color/output_plan.h"
#include "core/app/provenance.h"
#include "core/app/render_options.h"
#include "core/app/render_state.h"
#include "core/film.h"
#include "core/image.h"
#include "core/parallel.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "integrators/integrator.h"

namespace prism {

/// Where a render's image goes, which decides what prepare_render() checks.
enum class RenderDestination {
  kFiles,   ///< `prism render`: the output plan is resolved and its files checked writable
  kMemory,  ///< render_in_memory(): no output plan, nothing checked or written on disk
};

/// Everything a render needs from its options up to the (possibly long) build, every input
/// read and checked; start_render() adds the built accelerator and the started integrator.
struct PreparedRender {
  RenderOptions options;
  OutputPlan outputs;  ///< empty for RenderDestination::kMemory
  ParamSet params;
  std::unique_ptr<ThreadLimit> thread_limit;
  std::unique_ptr<Accelerator> accel;
  std::filesystem::path scene_path;
  Scene scene;
  RenderSettings settings;
  std::unique_ptr<ColorPipeline> pipeline;
  nlohmann::json identity;  ///< render_identity(); null for RenderDestination::kMemory
  std::unique_ptr<Integrator> integrator;
  std::unique_ptr<Sampler> sampler;
  Camera camera;
  /// Set by start_render(): what renders tiles, and the context it reads (which refers to the
  /// members above, so a PreparedRender never moves: it lives behind a unique_ptr).
  std::optional<RenderContext> context;
  std::unique_ptr<const TileRenderer> renderer;
};

/// Reads and checks everything before the build, in the order that makes mistakes cheap: the
/// options, (for kFiles) the output files and the checkpoint, --set, the accelerator, the scene,
/// the colour pipeline and environment map, the integrator and sampler, the --set keys nobody
/// read. With `resumed` (kFiles only), the render identity must be the checkpoint's. Only the
/// rank that writes (rank 0) checks the output files and prints warnings. Throws Error naming
/// what is wrong.
std::unique_ptr<PreparedRender> prepare_render(const RenderOptions& options,
                                               RenderDestination destination,
                                               const std::optional<RenderState>& resumed = {},
                                               const std::filesystem::path& resume_file = {});

/// What the render records from the start: its scene file, command line and environment map.
RenderRecord start_record(const PreparedRender& r);

/// Builds the accelerator over the scene (its time into record.build_ms) and starts the
/// integrator: r.context and r.renderer are set.
void start_render(PreparedRender& r, RenderRecord& record);

/// A render's result in memory: the resolved film (beauty and AOVs, working space; only the
/// rendered window for a crop) and its provenance (the prism:* attributes of make_provenance()).
struct RenderedFrame {
  Image image;
  ImageMetadata metadata;
};

/// film.resolve() and its provenance, with record.camera_samples counted from the image: what
/// every output of the render is made from. The image goes into `buffer` when it fits
/// (Film::resolve()).
RenderedFrame resolve_frame(const PreparedRender& r, const Film& film, RenderRecord& record,
                            ImagePixels buffer = {});

/// A whole render in this process, in memory: prepare_render(kMemory), start_render(), every
/// pass of the schedule (render_progressively(), stopping at options.time_limit), then
/// resolve_frame(). The pixels are those `prism render` writes for the same options (in the
/// working space: an EXR holds them converted to its output space, by default the same). The
/// metadata adds to the provenance the colour attributes an EXR carries for them:
/// prism:colorSpace (the working space), prism:workingSpace, prism:ocioConfig,
/// prism:ocioConfigHash and prism:ocioConfigSource.
/// `between_passes`, when set, is called on the calling thread after each pass but the last; it
/// may throw to stop the render (the exception then leaves this function). --checkpoint,
/// --resume and the output options are not read; under mpirun this process renders alone.
RenderedFrame render_in_memory(const RenderOptions& options,
                               const std::function<void()>& between_passes = {});

}  // namespace prism
