#include "color/output_plan.h"

#include <optional>
#include <system_error>

#include "color/image_file_writers.h"
#include "color/sample_rate_image.h"
#include "core/error.h"
#include "core/strings.h"

namespace prism {
namespace fs = std::filesystem;

namespace {

struct ImageFormat {
  const char* extension;
  OutputKind kind;
  const char* format;  // OpenImageIO's writer
};

// Every image file prism writes, in the order messages list them.
constexpr ImageFormat kImageFormats[] = {
    {".exr", OutputKind::kSceneLinearExr, "openexr"}, {".png", OutputKind::kDisplayImage, "png"},
    {".jpg", OutputKind::kDisplayImage, "jpeg"},      {".jpeg", OutputKind::kDisplayImage, "jpeg"},
    {".tif", OutputKind::kDisplayImage, "tiff"},      {".tiff", OutputKind::kDisplayImage, "tiff"},
};

// ".exr, .png, ... or .tiff"
std::string extension_choices() {
  std::vector<std::string> all = image_output_extensions();
  const std::string last = all.back();
  all.pop_back();
  return join(all) + " or " + last;
}

void write_sample_rate_file(const PlannedOutput& file, const Image& image,
                            const ImageMetadata& metadata, const ColorOptions& color) {
  const std::optional<Image> rate = make_sample_rate_image(image);
  PRISM_CHECK(rate.has_value());
  // The picture's colours are display values already.
  ColorOptions raw = color;
  raw.view = "Raw";
  raw.look.clear();
  raw.exposure = 0.0f;
  color_detail::write_display_file(file.path, file.format, *rate, metadata, ColorPipeline(raw));
}

}  // namespace

PlannedOutput plan_image_file(const fs::path& path, std::string option) {
  PlannedOutput file;
  file.path = path;
  file.option = std::move(option);
  const std::string extension = lower_case_extension(path);
  for (const ImageFormat& f : kImageFormats) {
    if (extension == f.extension) {
      file.kind = f.kind;
      file.format = f.format;
    }
  }
  return file;
}

PlannedOutput plan_sample_rate_file(const fs::path& path, std::string option) {
  PlannedOutput file = plan_image_file(path, std::move(option));
  PRISM_CHECK(file.kind == OutputKind::kDisplayImage);
  file.kind = OutputKind::kSampleRate;
  return file;
}

const std::vector<std::string>& image_output_extensions() {
  static const std::vector<std::string> extensions = [] {
    std::vector<std::string> list;
    for (const ImageFormat& f : kImageFormats) list.push_back(f.extension);
    return list;
  }();
  return extensions;
}

bool is_display_image_path(const fs::path& path) {
  return plan_image_file(path, {}).kind == OutputKind::kDisplayImage;
}

void validate_outputs(const OutputPlan& plan) {
  validate_exr_options(plan.exr);
  for (const PlannedOutput& file : plan.files) {
    if (file.kind != OutputKind::kUnsupported) continue;
    throw Error(ErrorKind::kUsage,
                "unsupported extension '" + file.path.extension().string() + "' in '" +
                    file.path.string() + "'; use " + extension_choices(),
                ErrorLocation{{}, 0, file.option});
  }
  for (const PlannedOutput& file : plan.files) check_output_writable(file.path);
}

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  if (std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec)) {
    const bool same = std::filesystem::equivalent(a, b, ec);
    if (!ec) return same;
  }
  const auto absolute_a = std::filesystem::absolute(a, ec).lexically_normal();
  const auto absolute_b = std::filesystem::absolute(b, ec).lexically_normal();
  return absolute_a == absolute_b;
}

std::vector<NamedInput> named_outputs(const OutputPlan& plan) {
  std::vector<NamedInput> named;
  for (const PlannedOutput& file : plan.files) named.push_back({file.option, file.path});
  return named;
}

void refuse_overwriting_inputs(const std::vector<NamedInput>& outputs,
                               const std::vector<NamedInput>& inputs) {
  for (const NamedInput& output : outputs) {
    for (const NamedInput& input : inputs) {
      if (output.path.empty() || input.path.empty() || !same_file(output.path, input.path)) {
        continue;
      }
      throw Error(ErrorKind::kUsage,
                  "is also " + input.what + ": writing it would destroy what the run reads",
                  ErrorLocation{output.path.string(), 0, output.what});
    }
  }
}

void write_outputs(const OutputPlan& plan, const Image& image, const ImageMetadata& metadata,
                   const ColorPipeline& pipeline) {
  for (const PlannedOutput& file : plan.files) {
    switch (file.kind) {
      case OutputKind::kSceneLinearExr:
        color_detail::write_exr_file(file.path, image, metadata, pipeline, plan.exr);
        break;
      case OutputKind::kDisplayImage:
        color_detail::write_display_file(file.path, file.format, image, metadata, pipeline);
        break;
      case OutputKind::kSampleRate:
        write_sample_rate_file(file, image, metadata, plan.color);
        break;
      case OutputKind::kUnsupported:
        PRISM_CHECK(file.kind != OutputKind::kUnsupported);  // validate_outputs rejects it
    }
  }
}

}  // namespace prism
