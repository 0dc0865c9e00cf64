// `prism convert`: display-referred images of an existing EXR, so one render can be looked at
// through several OCIO views without rendering it again.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "color/output_plan.h"
#include "core/app/commands.h"
#include "core/error.h"
#include "core/strings.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

Error input_error(const std::string& path, const std::string& message) {
  return Error(ErrorKind::kInput, message, ErrorLocation{path, 0, {}});
}

/// The EXR at `path`, checked to exist and to be an EXR before OpenImageIO's own message (which
/// names neither case plainly) could be the only explanation.
ImageFileContents read_exr(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw input_error(path, "the input file does not exist");
  if (fs::is_directory(path, ec)) throw input_error(path, "the input is a folder, not an EXR");
  ImageFileContents contents = read_image_file(path);
  if (contents.format != "openexr") {
    throw input_error(path, "not an OpenEXR file (OpenImageIO reads it as " + contents.format +
                                "); convert reads scene-linear EXRs");
  }
  return contents;
}

/// The beauty channels R, G, B of `contents`; alpha and AOV layers stay behind because a
/// display-referred file holds only the beauty.
Image beauty_of(const ImageFileContents& contents, const std::string& path) {
  const std::array<int, 3> source = {contents.channel("R"), contents.channel("G"),
                                     contents.channel("B")};
  if (std::any_of(source.begin(), source.end(), [](int c) { return c < 0; })) {
    throw input_error(path, "the EXR has no beauty channels R, G, B (channels: " +
                                join(contents.image.channel_names, ", ", "none") + ")");
  }
  const Image& in = contents.image;
  Image beauty;
  beauty.width = in.width;
  beauty.height = in.height;
  beauty.channel_names = {"R", "G", "B"};
  const size_t count = size_t(in.width) * in.height;
  beauty.pixels.resize(count * 3);
  for (size_t i = 0; i < count; ++i) {
    for (int c = 0; c < 3; ++c) beauty.pixels[i * 3 + c] = in.pixels[i * in.channels() + source[c]];
  }
  // Another tool's EXR may hold Inf or NaN; that is bad input, not the internal error the writer
  // would report for values prism produced itself.
  if (const size_t bad = beauty.count_non_finite(); bad > 0) {
    throw input_error(path, fmt::format("{} NaN or infinite values in R, G, B", bad));
  }
  return beauty;
}

/// The EXR's provenance (prism:version, prism:scene, ...) carried into the converted file, minus
/// the colour attributes the writer records afresh for the new display/view.
ImageMetadata carried_metadata(const ImageFileContents& contents, const std::string& input,
                               const std::string& input_space) {
  constexpr const char* kReplaced[] = {
      "prism:colorSpace",        "prism:workingSpace",  "prism:ocioConfig", "prism:ocioConfigHash",
      "prism:ocioConfigSource",  "prism:display",       "prism:view",       "prism:look",
      "prism:halfClampedValues", "prism:convertedFrom", "prism:inputSpace"};
  ImageMetadata metadata;
  for (const auto& [name, value] : contents.attributes) {
    if (name.rfind("prism:", 0) != 0) continue;
    if (std::find(std::begin(kReplaced), std::end(kReplaced), name) != std::end(kReplaced))
      continue;
    metadata.emplace_back(name, value);
  }
  metadata.emplace_back("prism:convertedFrom", input);
  metadata.emplace_back("prism:inputSpace", input_space);
  return metadata;
}

}  // namespace

int run_convert_command(const ConvertOptions& options) {
  // Checks that need no file first: the output type, then every colour name.
  const OutputPlan outputs{
      .files = {plan_image_file(options.output, "output")}, .color = options.color, .exr = {}};
  if (outputs.files.front().kind != OutputKind::kDisplayImage) {
    throw Error(ErrorKind::kUsage,
                "unsupported output type '" + fs::path(options.output).extension().string() +
                    "' for '" + options.output +
                    "'; convert writes display-referred .png, .jpg, .jpeg, .tif or .tiff");
  }
  const ColorPipeline pipeline(options.color);

  const ImageFileContents contents = read_exr(options.input);
  Image image = beauty_of(contents, options.input);
  // prism writes the EXR's space into prism:colorSpace (OpenImageIO keeps no oiio:ColorSpace in
  // EXR headers); an EXR from elsewhere is assumed to be in the config's scene_linear.
  std::string input_space = options.input_space;
  std::string space_source = "--input-space";
  if (input_space.empty()) {
    input_space = contents.attribute("prism:colorSpace");
    space_source = "prism:colorSpace (override with --input-space)";
  }
  if (input_space.empty()) {
    input_space = "scene_linear";
    space_source = "no prism:colorSpace, so scene_linear (choose with --input-space)";
  }
  try {
    pipeline.convert_image_to_working(image, input_space);
  } catch (const Error& e) {
    // Say where an unknown name came from: a flag, or a file rendered with another config.
    throw Error(e.kind(), e.message(), ErrorLocation{options.input, 0, space_source});
  }

  validate_outputs(outputs);
  write_outputs(outputs, image, carried_metadata(contents, options.input, input_space), pipeline);
  std::printf("%s\n", fmt::format("{} ({}) -> {} through '{}' / '{}'{}", options.input, input_space,
                                  options.output, pipeline.display(), pipeline.view(),
                                  pipeline.look().empty() ? "" : " look '" + pipeline.look() + "'")
                          .c_str());
  return kExitSuccess;
}

}  // namespace prism
