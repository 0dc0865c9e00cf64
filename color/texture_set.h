#pragma once

#include <memory>
#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "core/image.h"
#include "core/scene.h"
#include "core/texture.h"

namespace prism {

/// Makes the lookups of `images` (channels R, G, B in the working space, row 0 at the top),
/// one texture each, in order, through one OpenImageIO TextureSystem of its own: each image is
/// MIP-mapped (each level half the previous one's size, box-filtered, down to 1 x 1) and held
/// as a tiled half-float OpenEXR (float when a value exceeds half's range) in memory, which the
/// TextureSystem reads through an in-memory reader. Lookups filter anisotropically over the
/// footprint given with bilinear interpolation inside levels, and repeat the image outside
/// [0, 1)^2. `names` (one per image) name textures in messages. Throws Error(kInput) naming
/// the texture if the TextureSystem cannot open one, Error(kResource) when memory runs out.
std::shared_ptr<const TextureLookup> make_texture_lookup(const std::vector<Image>& images,
                                                         const std::vector<std::string>& names);

/// What load_scene_textures() read.
struct SceneTexturesReport {
  /// Problems that do not stop the render (a colour-space label the config does not know),
  /// one line each, for the driver to print.
  std::vector<std::string> warnings;
  /// Per texture: "name: colour space (why)", for provenance and `prism info`.
  std::vector<std::string> descriptions;
};

/// Reads every texture of `scene` (read_texture_image() in texture_image.h: the colour space
/// rule, the checks) into the working space of `pipeline` and sets scene.texture_lookup
/// (make_texture_lookup()). Does nothing for a scene without textures. Throws as those two do.
SceneTexturesReport load_scene_textures(Scene& scene, const ColorPipeline& pipeline);

}  // namespace prism
