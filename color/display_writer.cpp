// The display-referred 8-bit writer (PNG, JPEG, TIFF): the beauty through the pipeline's
// display, view, look and exposure.

#include <cmath>

#include "color/image_writers.h"
#include "color/output_plan.h"
#include "core/strings.h"

namespace prism {
namespace fs = std::filesystem;

void write_display_image(const fs::path& path, const Image& image, const ImageMetadata& metadata,
                         const ColorPipeline& pipeline) {
  const PlannedOutput file = plan_image_file(path, {});
  if (file.kind != OutputKind::kDisplayImage) {
    throw Error(ErrorKind::kUsage, "unsupported image type '" + path.extension().string() +
                                       "' for '" + path.string() +
                                       "'; available: " + join(image_output_extensions()));
  }
  PRISM_CHECK(image.width > 0 && image.height > 0);
  check_output_writable(path);
  color_detail::write_display_file(path, file.format, image, metadata, pipeline);
}

namespace color_detail {

void write_display_file(const fs::path& path, const std::string& format, const Image& image,
                        const ImageMetadata& metadata, const ColorPipeline& pipeline) {
  PRISM_CHECK(format == "png" || format == "jpeg" || format == "tiff");
  PRISM_CHECK(image.width > 0 && image.height > 0);
  // Checked before the view, whose clipping would hide an Inf.
  const auto triples = color_channel_triples(image);
  PRISM_CHECK(!triples.empty());
  std::vector<float> beauty;
  beauty.reserve(size_t(image.width) * image.height * 3);
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
    for (int c : triples[0]) beauty.push_back(image.pixels[i * image.channels() + c]);
  }
  check_finite(beauty, path);
  const Image display = pipeline.working_to_display(image);
  check_finite(display.pixels, path);

  std::vector<unsigned char> bytes(display.pixels.size());
  for (size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = static_cast<unsigned char>(std::lround(display.pixels[i] * 255.0f));
  }
  OIIO::ImageSpec spec(display.width, display.height, 3, OIIO::TypeDesc::UINT8);
  add_header_attributes(spec, metadata, pipeline);
  spec.attribute("prism:colorSpace", pipeline.display_color_space());
  // Tags the file as sRGB (PNG sRGB chunk) only when the display really is sRGB.
  if (to_lower(pipeline.display_color_space()).find("srgb") != std::string::npos) {
    spec.attribute("oiio:ColorSpace", "sRGB");
  }
  if (format == "jpeg") spec.attribute("Compression", "jpeg:95");
  write_atomically(path, format, spec, OIIO::TypeDesc::UINT8, bytes.data());
}

}  // namespace color_detail
}  // namespace prism
