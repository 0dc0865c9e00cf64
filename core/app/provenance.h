#pragma once

#include <cstdint>
#include <string>

#include "color/image_output.h"
#include "core/app/render_options.h"
#include "core/param_set.h"

namespace prism {

/// What happened during one render, recorded in the output files.
struct RenderRecord {
  std::string scene;  ///< scene file path
  double build_ms = 0.0;
  double render_ms = 0.0;
  uint64_t non_finite_samples = 0;
  double camera_samples = 0.0;  ///< camera rays traced (adaptive renders stop pixels early)
  std::string command_line;
  std::string environment;        ///< -e file as given; empty: no environment map
  std::string environment_space;  ///< colour space its values were read as
  int passes_complete = 0;        ///< passes of the schedule every pixel has
  int pass_count = 0;             ///< passes of the schedule
  /// Why the render ended before its last pass: "time limit", "SIGINT", "SIGTERM"; empty when
  /// it finished.
  std::string stopped_by;
  int mpi_ranks = 1;       ///< processes that rendered (mpirun -np); 1 without MPI
  uint64_t mpi_bytes = 0;  ///< bytes of messages between them (all pass through rank 0)
};

/// The prism:* header attributes (version, scene, components, settings, timings, --set
/// parameters, command line, non-finite samples, the sample range, passes and what stopped the
/// render, prism:crop for a crop, prism:mpiRanks and prism:mpiBytes for a render on several MPI
/// ranks, and prism:environment / prism:environmentColorSpace when an
/// environment map was used) of an output file. The image
/// writers add the colour attributes (config, its hash, spaces, display, view) themselves.
ImageMetadata make_provenance(const RenderSettings& settings, const ParamSet& params,
                              const RenderRecord& record);

/// argv as one shell-readable line: arguments with spaces or quotes are single-quoted.
/// Camera samples per second of wall-clock render time (record.camera_samples when known, else
/// width * height * spp, over the render time).
double samples_per_second(const RenderSettings& settings, const RenderRecord& record);

std::string quote_command_line(int argc, const char* const* argv);

}  // namespace prism
