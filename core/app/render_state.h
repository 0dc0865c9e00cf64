#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "color/color_pipeline.h"
#include "color/state_file.h"
#include "core/app/provenance.h"
#include "core/app/render_options.h"
#include "core/film.h"
#include "core/scene.h"

namespace prism {

/// Every RenderOptions field as JSON (the command line a checkpoint resumes with), and back.
/// options_from_json() throws Error(kInput) naming `source` when a field is missing or of the
/// wrong type.
nlohmann::json options_to_json(const RenderOptions& options);
RenderOptions options_from_json(const nlohmann::json& json, const std::string& source);

/// What decides every pixel value of a render, as JSON: the options that change pixels (not the
/// output files, crop, sample range, passes, threads, time limit or checkpointing), the hash of
/// the scene as rendered (scene_hash(), after colour conversion, with its environment map), the
/// OCIO config's hash and prism's version. Two renders with equal identities give the same bits
/// for the same pixel and sample; parts of a frame must have equal identities to be merged.
nlohmann::json render_identity(const RenderOptions& options, const Scene& scene,
                               const ColorPipeline& pipeline);

/// What a state file (checkpoint or part) records beside the film, in its attribute
/// prism:renderState.
struct RenderStateRecord {
  nlohmann::json identity;
  RenderOptions options;  ///< as given (a resumed render continues with them)
  PixelRect window;
  SampleRange samples;
  uint32_t pass_samples = 1;
  int width = 0, height = 0, spp = 0;
  double render_ms = 0.0;  ///< rendering time spent so far, over every run
};

/// The attribute's name and its JSON text.
inline constexpr const char* kRenderStateAttribute = "prism:renderState";
std::string render_state_to_text(const RenderStateRecord& record);
/// Parses the attribute; throws Error(kInput) naming `source` when it is missing or malformed.
RenderStateRecord render_state_from_text(const std::string& text, const std::string& source);

/// Writes `film` with `record` and the provenance `metadata` as a state file (checkpoint or
/// part) at `path` (write_state_file()), converting with `pipeline` and the options' EXR
/// encoding.
void write_render_state(const std::filesystem::path& path, const Film& film,
                        const RenderStateRecord& record, ImageMetadata metadata,
                        const ColorPipeline& pipeline);

/// A state file read back: the film and its record, checked against each other (the film's
/// size and window are the record's). Throws Error(kInput) naming the file.
struct RenderState {
  Film film;
  RenderStateRecord record;
  ImageMetadata attributes;
};
RenderState read_render_state(const std::filesystem::path& path);

}  // namespace prism
