// Reading image files back through OpenImageIO (tests, comparisons, `prism convert`, environment
// maps).

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <new>
#include <string>

#include "color/image_output.h"
#include "core/error.h"

namespace prism {

std::string ImageFileContents::attribute(const std::string& name) const {
  for (const auto& [key, value] : attributes) {
    if (key == name) return value;
  }
  return {};
}

int ImageFileContents::channel(const std::string& name) const {
  const auto& names = image.channel_names;
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : int(it - names.begin());
}

ImageFileContents read_image_file(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    throw Error(ErrorKind::kInput, "cannot read the image: " + OIIO::geterror(),
                ErrorLocation{path.string(), 0, {}});
  }
  const OIIO::ImageSpec& spec = in->spec();
  const ErrorLocation where{path.string(), 0, {}};
  // The header's sizes are checked before anything is allocated: a file may declare any size
  // (a negative one, or 100000 x 100000 in a few bytes).
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw Error(ErrorKind::kInput,
                "the header declares " + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " pixels of " + std::to_string(spec.nchannels) +
                    " channels: not an image",
                where);
  }
  const uint64_t values = uint64_t(spec.width) * uint64_t(spec.height) * uint64_t(spec.nchannels);
  if (values > kMaxImageFileValues) {
    throw Error(ErrorKind::kInput,
                "the header declares " + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " pixels of " + std::to_string(spec.nchannels) +
                    " channels, more than the " + std::to_string(kMaxImageFileValues) +
                    " values prism reads from one image",
                where);
  }
  ImageFileContents contents;
  contents.format = in->format_name();
  contents.image.width = spec.width;
  contents.image.height = spec.height;
  contents.image.x = spec.x;
  contents.image.y = spec.y;
  contents.image.full_width = spec.full_width;
  contents.image.full_height = spec.full_height;
  contents.image.channel_names = spec.channelnames;
  try {
    contents.image.pixels.resize(size_t(values));
  } catch (const std::bad_alloc&) {
    throw Error(ErrorKind::kResource,
                "out of memory for the " + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " pixels of the image",
                where);
  }
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                      contents.image.pixels.data())) {
    throw Error(ErrorKind::kInput, "cannot read the pixels: " + in->geterror(),
                ErrorLocation{path.string(), 0, {}});
  }
  for (int c = 0; c < spec.nchannels; ++c) {
    contents.channel_formats.push_back(spec.channelformat(c).c_str());
  }
  contents.compression = spec.get_string_attribute("compression");
  if (const auto* chroma =
          spec.find_attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8))) {
    std::array<float, 8> values{};
    std::memcpy(values.data(), chroma->data(), sizeof(values));
    contents.chromaticities = values;
  }
  for (const auto& p : spec.extra_attribs) {
    contents.attributes.emplace_back(p.name().string(), p.get_string());
  }
  return contents;
}

}  // namespace prism
