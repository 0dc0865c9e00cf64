#pragma once

#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "core/image.h"
#include "core/texture.h"

namespace prism {

/// Largest texture side read, in pixels (a 32768 x 32768 RGB float image is 12 GB already).
inline constexpr int kMaxTextureSide = 32768;

/// A texture's pixels, read and converted into the working space.
struct TextureImage {
  Image image;              ///< channels R, G, B in the working space; row 0 is the top row
  std::string color_space;  ///< the colour space the file's values were read as
  /// Why: "scene file" (TextureSource::color_space), "prism:colorSpace" or "oiio:ColorSpace"
  /// (the image's declaration), "8-bit/16-bit integer image" (sRGB by convention) or
  /// "float image" (scene_linear).
  std::string space_rule;
};

/// Reads `source` (a file, or embedded bytes through an in-memory reader, or raw RGBA8
/// texels) and converts its R, G, B into the working space of `pipeline`. Grey images give R =
/// G = B; alpha and other channels are ignored. The colour space is, in this order: the
/// scene's declaration (TextureSource::color_space), the image's own (prism:colorSpace, else
/// oiio:ColorSpace, where OpenImageIO's generic "sRGB" means the config's sRGB texture space
/// and "Linear" scene_linear), else by pixel type: integer images are sRGB-encoded (the glTF
/// and common convention for colour textures), float and half images scene_linear.
/// Throws Error(kInput) at source.origin naming the texture when it cannot be read, has no
/// pixels, is larger than kMaxTextureSide, declares a colour space the config does not know (a
/// scene file's declaration; an image's unknown one falls back with a warning, appended to
/// `warnings`), or holds values that are not finite once converted.
TextureImage read_texture_image(const TextureSource& source, const ColorPipeline& pipeline,
                                std::vector<std::string>& warnings);

}  // namespace prism
