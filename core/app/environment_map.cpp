#include "core/app/environment_map.h"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <cmath>
#include <optional>
#include <string_view>
#include <system_error>

#include "color/image_output.h"
#include "core/error.h"
#include "core/strings.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

constexpr const char* kElement = "environment map (-e)";

Error env_error(const fs::path& path, const std::string& message) {
  return Error(ErrorKind::kInput, message, ErrorLocation{path.string(), 0, kElement});
}

/// Checks the file exists and is not a folder before OpenImageIO, whose messages for these two
/// cases are less plain.
ImageFileContents read_environment_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw env_error(path, "the file does not exist");
  if (fs::is_directory(path, ec)) throw env_error(path, "is a folder, not an image");
  try {
    return read_image_file(path);
  } catch (const Error& e) {
    // read_image_file names the file already; add which option it was read for.
    throw env_error(path, e.message());
  }
}

std::string channel_list(const Image& image) { return join(image.channel_names, ", ", "none"); }

/// The R, G, B channels of the file as a 3-channel image, checked for values that are not
/// radiance. Checked before the colour conversion, so that a message quotes the file's values.
Image rgb_channels(const ImageFileContents& contents, const fs::path& path) {
  const Image& in = contents.image;
  const std::array<int, 3> source = {contents.channel("R"), contents.channel("G"),
                                     contents.channel("B")};
  if (source[0] < 0 || source[1] < 0 || source[2] < 0) {
    throw env_error(path, "has no R, G, B channels (channels: " + channel_list(in) + ")");
  }
  if (in.width <= 0 || in.height <= 0 ||
      in.pixels.size() != size_t(in.width) * size_t(in.height) * size_t(in.channels())) {
    throw env_error(path, fmt::format("has no pixels ({} x {})", in.width, in.height));
  }
  constexpr const char* kNames[3] = {"R", "G", "B"};
  Image rgb;
  rgb.width = in.width;
  rgb.height = in.height;
  rgb.channel_names = {"R", "G", "B"};
  rgb.pixels.resize(size_t(in.width) * in.height * 3);
  for (int y = 0; y < in.height; ++y) {
    for (int x = 0; x < in.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const float v = in.at(x, y, source[size_t(c)]);
        // Radiance is finite and non-negative; anything else is a broken or non-radiance file,
        // and silently zeroing it would hide that.
        if (!std::isfinite(v) || v < 0.0f) {
          throw env_error(path, fmt::format("pixel ({}, {}) has {} = {}; environment radiance "
                                            "must be finite and >= 0",
                                            x, y, kNames[c], v));
        }
        rgb.at(x, y, c) = v;
      }
    }
  }
  return rgb;
}

/// Chooses the colour space of the file's values by the rule documented in the header.
void choose_color_space(const ImageFileContents& contents, const ColorPipeline& pipeline,
                        const fs::path& path, EnvironmentMap& map) {
  std::vector<std::string> unknown;
  const auto warn_unknown = [&] {
    for (const auto& u : unknown) {
      map.warnings.push_back(fmt::format(
          "environment map {}: its {} is not a colour space of the OCIO config; reading it as "
          "{} ('{}')",
          path.string(), u, map.space_rule, map.color_space));
    }
  };
  for (const char* attribute : {"prism:colorSpace", "oiio:ColorSpace"}) {
    const std::string name = contents.attribute(attribute);
    if (name.empty()) continue;
    if (const std::optional<std::string> space = pipeline.find_color_space(name)) {
      map.color_space = *space;
      map.space_rule = attribute;
      warn_unknown();
      return;
    }
    // OpenImageIO labels every EXR "Linear" and every .hdr "linear" without saying which
    // primaries: exactly the case the scene_linear fallback is for, so not worth a warning.
    if (std::string_view(attribute) == "oiio:ColorSpace" && to_lower(name) == "linear") continue;
    unknown.push_back(fmt::format("{} '{}'", attribute, name));
  }
  // A config without scene_linear renders in the --working-space the user chose.
  map.color_space = pipeline.find_color_space("scene_linear").value_or(pipeline.working_space());
  map.space_rule = "scene_linear";
  warn_unknown();
}

}  // namespace

EnvironmentMap load_environment_map(const fs::path& path, const ColorPipeline& pipeline) {
  const ImageFileContents contents = read_environment_file(path);
  EnvironmentMap map;
  map.image = rgb_channels(contents, path);
  choose_color_space(contents, pipeline, path, map);
  try {
    pipeline.convert_image_to_working(map.image, map.color_space);
  } catch (const Error& e) {
    throw env_error(path, fmt::format("converting from '{}': {}", map.color_space, e.message()));
  }
  // A curve (log) space can map a large finite value to infinity; the light would turn it into
  // black, which is not what the file says.
  for (int y = 0; y < map.image.height; ++y) {
    for (int x = 0; x < map.image.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(map.image.at(x, y, c))) {
          throw env_error(path, fmt::format("pixel ({}, {}) is not finite once converted from "
                                            "'{}' to the working space '{}'",
                                            x, y, map.color_space, pipeline.working_space()));
        }
      }
    }
  }
  if (map.image.width != 2 * map.image.height) {
    map.warnings.push_back(fmt::format(
        "environment map {} is {} x {}, not 2:1; using it as a latitude-longitude map anyway "
        "(columns span 360 degrees, rows 180)",
        path.string(), map.image.width, map.image.height));
  }
  return map;
}

}  // namespace prism
