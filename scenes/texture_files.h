#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/texture.h"

namespace prism {

/// The texture file a scene or model file names as `written`, relative to `base_dir` (the
/// folder of the file that names it) unless absolute. Tries, in order: the path as written;
/// with '\' read as '/' and %XX escapes decoded (files written on Windows, URIs in glTF); its
/// file name alone in `base_dir` (models whose textures were moved next to them). Returns a
/// source with `color_space` and `origin` set and `name` the path as written. Throws
/// Error(kInput) at `origin`, naming the texture and the path looked for, when none of them
/// is a regular file.
TextureSource texture_file_source(const std::string& written, const std::filesystem::path& base_dir,
                                  const std::string& color_space, const ErrorLocation& origin);

/// Index of `source` in `textures`: the one already there for the same file (or the same
/// embedded bytes) and the same declared colour space, else `source` appended.
uint32_t add_texture(std::vector<TextureSource>& textures, TextureSource source);

}  // namespace prism
