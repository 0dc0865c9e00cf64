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
  std::string command_line;
};

/// The prism:* header attributes (version, scene, components, settings, timings, --set
/// parameters, command line, non-finite samples) of an output file. The image writers add the
/// colour attributes (config, its hash, spaces, display, view) themselves.
ImageMetadata make_provenance(const RenderSettings& settings, const ParamSet& params,
                              const RenderRecord& record);

/// argv as one shell-readable line: arguments with spaces or quotes are single-quoted.
/// Camera samples per second of wall-clock render time (width * height * spp / render time).
double samples_per_second(const RenderSettings& settings, const RenderRecord& record);

std::string quote_command_line(int argc, const char* const* argv);

}  // namespace prism
