#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "core/image.h"

namespace prism {

/// An environment map (-e) read from a file and converted into the working space.
struct EnvironmentMap {
  /// Channels R, G, B in the working space, latitude-longitude layout, row 0 at a pole (what
  /// SceneEnvironment::image holds; the driver puts that pole along the camera's up vector).
  Image image;
  std::string color_space;  ///< the colour space the file's values were read as
  std::string space_rule;   ///< why: "prism:colorSpace", "oiio:ColorSpace" or "scene_linear"
  /// Problems that do not stop the render (a shape other than 2:1, a colour-space name the
  /// config does not know), one line each, for the driver to print.
  std::vector<std::string> warnings;
};

/// Reads the image at `path` (any format OpenImageIO reads) as a latitude-longitude
/// environment map: its R, G, B, in the colour space the file declares (or scene_linear), are
/// converted into the working space of `pipeline`; other channels are ignored. A map that is
/// not 2:1 is used with a warning. Throws Error(kInput) naming the file when it is missing, a
/// folder, unreadable, has no R, G, B channels or no pixels, or holds a value that is not finite
/// and >= 0 (the first such pixel is named). docs/ENVIRONMENT_MAPS.md has the colour-space
/// rule, the layout and the checks in full.
EnvironmentMap load_environment_map(const std::filesystem::path& path,
                                    const ColorPipeline& pipeline);

}  // namespace prism
