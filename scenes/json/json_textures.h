#pragma once

// Material colours of a JSON scene that may name a texture.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/texture.h"
#include "scenes/json/json_document.h"

namespace prism::json {

/// Where the textures of a scene file go while its materials are read.
struct TextureContext {
  std::filesystem::path base_dir;  ///< the scene file's folder: texture paths are relative to it
  std::vector<TextureSource>* textures;  ///< Scene::textures
};

/// A material colour that may be textured: a colour (JsonNode::color(range)), or an object
/// {"texture": path, "color_space": name (optional), "scale": colour in `range` (1)} meaning the
/// image times `scale`. Returns the colour (the scale for a texture) and sets `texture` to the
/// image's index in context.textures (kNoTexture for a plain colour). The file must exist
/// (texture_file_source()); the colour-space name is checked when the render loads the
/// textures.
Rgb read_textured_color(const JsonNode& value, Range range, TextureContext& context,
                        uint32_t& texture);

}  // namespace prism::json
