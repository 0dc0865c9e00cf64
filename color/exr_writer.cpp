// The scene-linear EXR writer. The layout and attributes are described in docs/OUTPUT.md
// ("EXR output").

#include <algorithm>
#include <climits>
#include <cmath>

#include "color/image_writers.h"
#include "core/strings.h"

namespace prism {
namespace fs = std::filesystem;

namespace {

constexpr float kHalfMax = 65504.0f;

std::string layer_of(const std::string& channel) {
  const auto dot = channel.rfind('.');
  return dot == std::string::npos ? channel : channel.substr(0, dot);
}

// Layers whose values half precision would damage (depths, positions, counts and ids above 2048).
bool needs_float(const std::string& channel) {
  constexpr const char* kLayers[] = {"z",           "depth", "p",        "position",
                                     "samplecount", "id",    "objectid", "materialid"};
  const std::string layer = to_lower(layer_of(channel));
  return std::any_of(std::begin(kLayers), std::end(kLayers),
                     [&](const char* l) { return layer == l; });
}

}  // namespace

void write_exr(const fs::path& path, const Image& image, const ImageMetadata& metadata,
               const ColorPipeline& pipeline, const ExrOptions& options) {
  validate_exr_options(options);
  PRISM_CHECK(image.width > 0 && image.height > 0);
  check_output_writable(path);
  color_detail::write_exr_file(path, image, metadata, pipeline, options);
}

namespace color_detail {

ExrImage prepare_exr(const fs::path& path, const Image& image, const ImageMetadata& metadata,
                     const ColorPipeline& pipeline, const ExrOptions& options) {
  PRISM_CHECK(exr_options_are_valid(options));
  PRISM_CHECK(image.width > 0 && image.height > 0);
  PRISM_CHECK(image.pixels.size() == size_t(image.width) * image.height * image.channels());

  // Beauty RGBA first, as compositors expect, then every AOV in the image's order.
  const auto find = [&](const std::string& name) {
    const auto it = std::find(image.channel_names.begin(), image.channel_names.end(), name);
    return it == image.channel_names.end() ? -1 : int(it - image.channel_names.begin());
  };
  std::vector<int> source = {find("R"), find("G"), find("B"), find("A")};
  PRISM_CHECK(source[0] >= 0 && source[1] >= 0 && source[2] >= 0);
  std::vector<std::string> names = {"R", "G", "B", "A"};
  for (int c = 0; c < image.channels(); ++c) {
    const std::string& name = image.channel_names[c];
    if (name == "R" || name == "G" || name == "B" || name == "A") continue;
    PRISM_CHECK(std::find(names.begin(), names.end(), name) == names.end());
    names.push_back(name);
    source.push_back(c);
  }
  const int channels = int(names.size());
  const size_t count = size_t(image.width) * image.height;
  const OIIO::TypeDesc type =
      options.pixel_type == "float" ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF;
  const auto beyond_half = [](float v) { return std::abs(v) > kHalfMax; };
  // The file's pixels are the image's own when they need no change: channels already in the
  // file's order, no colour conversion (the working space is the output space), and in a half
  // file no value to clamp. A new buffer would be one more image's worth of memory touched for
  // the first time, and on the virtual machines prism is measured on that costs about 3 ms per
  // MiB (a 480 x 360 image with its AOVs: 10 MiB).
  bool in_file_order = channels == image.channels();
  for (int c = 0; c < channels && in_file_order; ++c) in_file_order = source[c] == c;
  bool unchanged = in_file_order && !pipeline.converts_to_output();
  if (unchanged && type == OIIO::TypeDesc::HALF) {
    for (int c = 0; c < channels && unchanged; ++c) {
      if (needs_float(names[c])) continue;
      for (size_t i = 0; i < count; ++i) {
        if (beyond_half(image.pixels[i * channels + c])) {
          unchanged = false;
          break;
        }
      }
    }
  }
  ExrImage exr;
  if (unchanged) {
    exr.data = image.pixels.data();
  } else {
    // Reordered into a buffer of the file's layout and converted there, in place.
    Image file_image;
    file_image.width = image.width;
    file_image.height = image.height;
    file_image.channel_names = names;
    file_image.pixels.resize(count * channels);
    for (size_t i = 0; i < count; ++i) {
      for (int c = 0; c < channels; ++c) {
        file_image.pixels[i * channels + c] =
            source[c] < 0 ? 1.0f : image.pixels[i * image.channels() + source[c]];
      }
    }
    pipeline.working_to_output(file_image);
    exr.pixels = std::move(file_image.pixels);
    exr.data = exr.pixels.data();
  }
  check_finite(std::span<const float>(exr.data, count * channels), path);

  OIIO::ImageSpec spec(image.width, image.height, channels, type);
  // A crop keeps its place: its pixels are the data window inside the full display window.
  spec.x = image.x;
  spec.y = image.y;
  spec.full_x = 0;
  spec.full_y = 0;
  spec.full_width = image.full_width > 0 ? image.full_width : image.width;
  spec.full_height = image.full_height > 0 ? image.full_height : image.height;
  spec.channelnames = names;
  spec.alpha_channel = 3;
  if (const auto z = std::find(names.begin(), names.end(), "Z"); z != names.end()) {
    spec.z_channel = int(z - names.begin());
  }
  size_t clamped = 0;
  if (type == OIIO::TypeDesc::HALF) {
    spec.channelformats.assign(channels, OIIO::TypeDesc::HALF);
    for (int c = 0; c < channels; ++c) {
      if (needs_float(names[c])) {
        spec.channelformats[c] = OIIO::TypeDesc::FLOAT;
        continue;
      }
      // Beyond the half range a value would become Inf in the file (only in a buffer of the
      // file's own: the image's pixels are used as they are only when none is).
      if (unchanged) continue;
      for (size_t i = 0; i < count; ++i) {
        float& v = exr.pixels[i * channels + c];
        if (beyond_half(v)) {
          v = std::copysign(kHalfMax, v);
          ++clamped;
        }
      }
    }
  }

  add_header_attributes(spec, metadata, pipeline);
  spec.attribute("prism:colorSpace", pipeline.output_space());
  spec.attribute("oiio:ColorSpace", pipeline.output_space());
  if (const auto chroma = pipeline.output_chromaticities()) {
    spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chroma->data());
  }
  if (clamped > 0) {
    spec.attribute("prism:halfClampedValues", int(std::min<size_t>(clamped, INT_MAX)));
  }
  spec.attribute("compression", options.compression);
  exr.spec = std::move(spec);
  return exr;
}

void write_exr_file(const fs::path& path, const Image& image, const ImageMetadata& metadata,
                    const ColorPipeline& pipeline, const ExrOptions& options) {
  const ExrImage exr = prepare_exr(path, image, metadata, pipeline, options);
  write_atomically(path, "openexr", exr.spec, OIIO::TypeDesc::FLOAT, exr.data);
}

}  // namespace color_detail
}  // namespace prism
