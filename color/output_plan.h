#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "core/image.h"

namespace prism {

/// What a planned file holds, which decides how it is written.
enum class OutputKind {
  kUnsupported,     ///< an extension prism cannot write; validate_outputs rejects it
  kSceneLinearExr,  ///< every channel of the image in the output space (see write_exr)
  kDisplayImage,    ///< the beauty through display, view, look and exposure, 8-bit
  kSampleRate,      ///< the adaptive sampler's sample-rate picture, 8-bit through the Raw view
};

/// One file of an output plan.
struct PlannedOutput {
  std::filesystem::path path;
  OutputKind kind = OutputKind::kUnsupported;
  std::string format;  ///< OpenImageIO's name: "openexr", "png", "jpeg", "tiff"; "" if unsupported
  std::string option;  ///< what asked for the file ("--output (-f)", "--png"), named in errors
};

/// The file `path` names, with its kind and format from its extension in any case: .exr is a
/// scene-linear EXR; .png, .jpg, .jpeg, .tif and .tiff are display images; anything else is
/// kUnsupported. The one place prism maps extensions to kinds and formats.
PlannedOutput plan_image_file(const std::filesystem::path& path, std::string option);

/// The adaptive sampler's sample-rate picture at `path`, whose extension must be a display
/// image's (the render plans "<output stem>_rate.png").
PlannedOutput plan_sample_rate_file(const std::filesystem::path& path, std::string option);

/// Every extension plan_image_file accepts, in the order messages list them.
const std::vector<std::string>& image_output_extensions();

/// Every file one run writes and how: resolved once from the options, validated once before the
/// work (validate_outputs), written once at the end (write_outputs).
struct OutputPlan {
  std::vector<PlannedOutput> files;  ///< in writing order, the main output first
  ColorOptions color;                ///< the sample-rate picture uses them with the Raw view
  ExrOptions exr;                    ///< encoding of every EXR of the plan
};

/// Throws unless every file of `plan` can be written, checking in this order: the EXR encoding
/// (Error(kUsage) as validate_exr_options, even when no EXR is planned), every file's extension
/// (Error(kUsage) naming the file's option), then every path as check_output_writable
/// (Error(kOutput) naming the path). Leaves nothing behind.
void validate_outputs(const OutputPlan& plan);

/// An input file of a run and what it is ("the scene file", "the environment map (-e)", ...).
struct NamedInput {
  std::string what;
  std::filesystem::path path;
};

/// Whether `a` and `b` are one file: the same file when both exist (through links, `..`, a
/// relative path), else the same absolute path.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// The files of `plan`, each with the option that asked for it.
std::vector<NamedInput> named_outputs(const OutputPlan& plan);

/// Throws Error(kUsage) naming the output (path and option) when one of `outputs` is one of
/// `inputs` (same_file): writing it would destroy a file the run reads. Empty paths are skipped.
void refuse_overwriting_inputs(const std::vector<NamedInput>& outputs,
                               const std::vector<NamedInput>& inputs);

/// Writes every file of a validated `plan` from `image` (working-space beauty and AOVs, as the
/// film resolves it), in order, each atomically (see write_exr): EXRs as write_exr with
/// plan.exr, display images as write_display_image, the sample-rate picture (which needs the
/// image's "sampleCount.Y" channel) through a pipeline of plan.color with the Raw view and no
/// look or exposure. `pipeline` is the render's, made from plan.color. Throws as those writers;
/// files written before a failure stay.
void write_outputs(const OutputPlan& plan, const Image& image, const ImageMetadata& metadata,
                   const ColorPipeline& pipeline);

}  // namespace prism
