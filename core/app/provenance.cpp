#include "core/app/provenance.h"

#include <fmt/format.h>

namespace prism {

ImageMetadata make_provenance(const RenderSettings& settings, const ParamSet& params,
                              const RenderRecord& record) {
  ImageMetadata metadata{
      {"prism:version", PRISM_VERSION},
      {"prism:scene", record.scene},
      {"prism:accelerator", settings.accelerator},
      {"prism:integrator", settings.integrator},
      {"prism:sampler", settings.sampler},
      {"prism:spp", std::to_string(settings.spp)},
      {"prism:light_samples", std::to_string(settings.light_samples)},
      {"prism:max_depth", std::to_string(settings.max_depth)},
      {"prism:seed", std::to_string(settings.seed)},
      {"prism:resolution", fmt::format("{}x{}", settings.width, settings.height)},
      {"prism:build_ms", fmt::format("{:.3f}", record.build_ms)},
      {"prism:render_ms", fmt::format("{:.3f}", record.render_ms)},
      {"prism:samples_per_second", fmt::format("{:.0f}", samples_per_second(settings, record))},
      {"prism:command_line", record.command_line},
      {"prism:params", params.to_string()},
      {"prism:camera_samples", fmt::format("{:.0f}", record.camera_samples)},
      {"prism:non_finite_samples", std::to_string(record.non_finite_samples)},
  };
  metadata.emplace_back("prism:samples",
                        fmt::format("{} {}", settings.samples.first, settings.samples.last));
  metadata.emplace_back("prism:passes",
                        fmt::format("{} of {}", record.passes_complete, record.pass_count));
  metadata.emplace_back("prism:stoppedBy", record.stopped_by.empty() ? "-" : record.stopped_by);
  if (settings.window != PixelRect{{0, 0}, {settings.width, settings.height}}) {
    const PixelRect& w = settings.window;
    metadata.emplace_back("prism:crop",
                          fmt::format("{} {} {} {}", w.begin.x, w.begin.y, w.end.x, w.end.y));
  }
  if (record.mpi_ranks > 1) {
    metadata.emplace_back("prism:mpiRanks", std::to_string(record.mpi_ranks));
    metadata.emplace_back("prism:mpiBytes", std::to_string(record.mpi_bytes));
  }
  if (!record.environment.empty()) {
    metadata.emplace_back("prism:environment", record.environment);
    metadata.emplace_back("prism:environmentColorSpace", record.environment_space);
  }
  return metadata;
}

double samples_per_second(const RenderSettings& settings, const RenderRecord& record) {
  const double samples = record.camera_samples > 0.0
                             ? record.camera_samples
                             : double(settings.width) * settings.height * settings.spp;
  return record.render_ms > 0.0 ? samples / (record.render_ms * 1e-3) : 0.0;
}

std::string quote_command_line(int argc, const char* const* argv) {
  std::string out;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (!out.empty()) out += ' ';
    const bool plain =
        !arg.empty() && arg.find_first_of(" \t\n'\"\\$`*?;&|<>()") == std::string::npos;
    if (plain) {
      out += arg;
      continue;
    }
    // Single quotes protect everything except a single quote, which is closed, escaped, reopened.
    out += '\'';
    for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += '\'';
  }
  return out;
}

}  // namespace prism
