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

/// Reads the image at `path` (an EXR, or any format OpenImageIO reads: .hdr, .tif, .pfm, ...)
/// as a latitude-longitude environment map. Its channels R, G, B are taken to be in:
///   1. the file's `prism:colorSpace` attribute, when it names a colour space (name, alias or
///      role) of the active OCIO config (prism writes it into every EXR);
///   2. else its `oiio:ColorSpace` attribute, when that names a space of the config (OpenImageIO
///      sets it for some formats);
///   3. else the config's scene_linear role (the working space when the config has no
///      scene_linear role). A warning names an attribute that was present but unknown, except
///      OpenImageIO's generic oiio:ColorSpace "Linear" (every EXR, .hdr), which says no more
///      than scene_linear does; "sRGB", "Rec709", "GammaCorrected..." (8-bit formats) do warn,
///      as their values are probably encoded, not linear.
/// and converted from there into the working space. Other channels (A, AOVs) are ignored.
/// Negative values the conversion produces (file colours outside the working gamut) are kept;
/// the light counts them as zero. A map that is not 2:1 is used as it is (columns span 360 degrees,
/// rows 180) with a warning. Throws Error(kInput) naming the file when it is missing, a folder, not
/// a readable image, has no R, G, B channels, has no pixels, or holds a NaN, infinite or negative
/// value in R, G or B (the first such pixel, in row order, is named).
EnvironmentMap load_environment_map(const std::filesystem::path& path,
                                    const ColorPipeline& pipeline);

}  // namespace prism
