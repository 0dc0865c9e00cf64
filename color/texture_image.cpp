// Reading a texture's pixels (file, embedded bytes or raw texels) into the working space.

#include "color/texture_image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <memory>
#include <new>
#include <optional>

#include "core/error.h"
#include "core/strings.h"

namespace prism {
namespace {

Error texture_error(const TextureSource& source, const std::string& message) {
  return Error(ErrorKind::kInput, "texture '" + source.name + "': " + message, source.origin);
}

/// The pixels as the file holds them, every channel as float.
struct DecodedImage {
  Image image;
  bool integer = true;  ///< integer pixels (uint8, uint16, ...), not half or float
  std::vector<std::pair<std::string, std::string>> attributes;

  std::string attribute(const std::string& name) const {
    for (const auto& [key, value] : attributes) {
      if (key == name) return value;
    }
    return {};
  }
};

void check_size(const TextureSource& source, int width, int height) {
  if (width <= 0 || height <= 0) {
    throw texture_error(source, fmt::format("the image has no pixels ({} x {})", width, height));
  }
  if (width > kMaxTextureSide || height > kMaxTextureSide) {
    throw texture_error(source, fmt::format("the image is {} x {}; textures may be at most {} "
                                            "pixels on a side",
                                            width, height, kMaxTextureSide));
  }
}

DecodedImage decode_raw(const TextureSource& source) {
  check_size(source, source.raw_width, source.raw_height);
  const size_t count = size_t(source.raw_width) * size_t(source.raw_height);
  if (source.bytes.size() != 4 * count) {
    throw texture_error(source, "the embedded texels do not fill the image");
  }
  DecodedImage out;
  out.image.width = source.raw_width;
  out.image.height = source.raw_height;
  out.image.channel_names = {"R", "G", "B", "A"};
  out.image.pixels.resize(4 * count);
  for (size_t i = 0; i < 4 * count; ++i) out.image.pixels[i] = float(source.bytes[i]) / 255.0f;
  return out;
}

DecodedImage decode(const TextureSource& source) {
  if (source.raw_width > 0) return decode_raw(source);
  // The reader of embedded bytes must outlive the ImageInput that reads through it.
  std::optional<OIIO::Filesystem::IOMemReader> memory;
  std::unique_ptr<OIIO::ImageInput> in;
  if (source.is_embedded()) {
    if (source.bytes.empty()) throw texture_error(source, "the embedded image is empty");
    memory.emplace(source.bytes.data(), source.bytes.size());
    // The name only suggests a format; OpenImageIO tries the others when it is wrong.
    const std::string hint = source.format_hint.empty() ? "png" : source.format_hint;
    in = OIIO::ImageInput::open("embedded." + hint, nullptr, &*memory);
  } else {
    in = OIIO::ImageInput::open(source.file.string());
  }
  if (!in) {
    std::string message = OIIO::geterror();
    if (message.empty()) message = "unknown format";
    throw texture_error(source, "cannot read the image: " + message);
  }
  const OIIO::ImageSpec& spec = in->spec();
  check_size(source, spec.width, spec.height);
  if (spec.depth > 1) throw texture_error(source, "volume images are not textures");
  if (spec.nchannels < 1) throw texture_error(source, "the image has no channels");
  DecodedImage out;
  out.integer = !spec.format.is_floating_point();
  out.image.width = spec.width;
  out.image.height = spec.height;
  out.image.channel_names = spec.channelnames;
  out.image.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.image.pixels.data())) {
    throw texture_error(source, "cannot read the pixels: " + in->geterror());
  }
  for (const auto& p : spec.extra_attribs) {
    out.attributes.emplace_back(p.name().string(), p.get_string());
  }
  return out;
}

/// R, G, B of the decoded image: channels named R, G, B, else the first three, else grey
/// from the first channel (grey and grey + alpha images).
Image rgb_of(const Image& in) {
  const auto find = [&](const char* name) {
    for (int c = 0; c < in.channels(); ++c) {
      if (in.channel_names[size_t(c)] == name) return c;
    }
    return -1;
  };
  std::array<int, 3> source = {find("R"), find("G"), find("B")};
  if (source[0] < 0 || source[1] < 0 || source[2] < 0) {
    source = in.channels() >= 3 ? std::array<int, 3>{0, 1, 2} : std::array<int, 3>{0, 0, 0};
  }
  Image rgb;
  rgb.width = in.width;
  rgb.height = in.height;
  rgb.channel_names = {"R", "G", "B"};
  rgb.pixels.resize(size_t(in.width) * in.height * 3);
  for (int y = 0; y < in.height; ++y) {
    for (int x = 0; x < in.width; ++x) {
      for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = in.at(x, y, source[size_t(c)]);
    }
  }
  return rgb;
}

/// The config's sRGB-encoded texture space, by the names configs commonly give it.
std::optional<std::string> srgb_texture_space(const ColorPipeline& pipeline) {
  for (const char* name :
       {"sRGB - Texture", "srgb_texture", "Utility - sRGB - Texture", "sRGB", "texture_paint"}) {
    if (auto space = pipeline.find_color_space(name)) return space;
  }
  return std::nullopt;
}

std::string scene_linear_space(const ColorPipeline& pipeline) {
  return pipeline.find_color_space("scene_linear").value_or(pipeline.working_space());
}

/// The colour space an image's own label means, if the config has it: the name itself, or
/// OpenImageIO's generic labels "sRGB" and "Linear".
std::optional<std::string> labelled_space(const std::string& label, const ColorPipeline& pipeline) {
  if (auto space = pipeline.find_color_space(label)) return space;
  if (to_lower(label) == "srgb") return srgb_texture_space(pipeline);
  if (to_lower(label) == "linear") return scene_linear_space(pipeline);
  return std::nullopt;
}

/// Chooses the colour space by the rule in the header.
void choose_color_space(const TextureSource& source, const DecodedImage& decoded,
                        const ColorPipeline& pipeline, TextureImage& out,
                        std::vector<std::string>& warnings) {
  if (!source.color_space.empty()) {
    const std::optional<std::string> space = pipeline.find_color_space(source.color_space);
    if (!space) {
      throw texture_error(source, "color_space '" + source.color_space +
                                      "' is not a colour space of the OCIO config (prism "
                                      "colorspaces lists them)");
    }
    out.color_space = *space;
    out.space_rule = "scene file";
    return;
  }
  for (const char* attribute : {"prism:colorSpace", "oiio:ColorSpace"}) {
    const std::string label = decoded.attribute(attribute);
    if (label.empty()) continue;
    if (const std::optional<std::string> space = labelled_space(label, pipeline)) {
      out.color_space = *space;
      out.space_rule = attribute;
      return;
    }
    warnings.push_back(fmt::format(
        "texture {}: its {} '{}' is not a colour space of the OCIO config; reading it by its "
        "pixel type instead",
        source.name, attribute, label));
  }
  if (decoded.integer) {
    const std::optional<std::string> srgb = srgb_texture_space(pipeline);
    if (!srgb) {
      throw texture_error(source,
                          "an integer image is read as sRGB-encoded, but the OCIO config has no "
                          "sRGB texture colour space ('sRGB - Texture', 'srgb_texture', ...); name "
                          "its colour space in the scene file");
    }
    out.color_space = *srgb;
    out.space_rule = "integer image";
  } else {
    out.color_space = scene_linear_space(pipeline);
    out.space_rule = "float image";
  }
}

}  // namespace

TextureImage read_texture_image(const TextureSource& source, const ColorPipeline& pipeline,
                                std::vector<std::string>& warnings) {
  try {
    const DecodedImage decoded = decode(source);
    TextureImage out;
    choose_color_space(source, decoded, pipeline, out, warnings);
    out.image = rgb_of(decoded.image);
    for (const float v : out.image.pixels) {
      if (!std::isfinite(v))
        throw texture_error(source, "the image holds values that are not finite");
    }
    try {
      pipeline.convert_image_to_working(out.image, out.color_space);
    } catch (const Error& e) {
      throw texture_error(source, "converting from '" + out.color_space + "': " + e.message());
    }
    if (out.image.count_non_finite() != 0) {
      throw texture_error(source, "values are not finite once converted from '" + out.color_space +
                                      "' to the working space");
    }
    return out;
  } catch (const std::bad_alloc&) {
    throw Error(ErrorKind::kResource, "texture '" + source.name + "': out of memory",
                source.origin);
  }
}

}  // namespace prism
