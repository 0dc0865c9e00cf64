#include "scenes/json/json_textures.h"

#include "scenes/texture_files.h"

namespace prism::json {

Rgb read_textured_color(const JsonNode& value, Range range, TextureContext& context,
                        uint32_t& texture) {
  texture = kNoTexture;
  if (!value.raw().is_object()) return value.color(range);
  value.check_keys({"texture", "color_space", "scale"});
  const JsonNode file = value.child("texture");
  std::string color_space;
  if (const auto space = value.find("color_space")) {
    color_space = space->string();
    if (color_space.empty()) space->fail("color_space is empty");
  }
  const Rgb scale = color_or(value, "scale", Rgb(1.0f), range);
  const ErrorLocation origin = file.document().locate(file.path());
  texture = add_texture(*context.textures,
                        texture_file_source(file.string(), context.base_dir, color_space, origin));
  return scale;
}

}  // namespace prism::json
