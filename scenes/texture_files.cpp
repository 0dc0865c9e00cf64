#include "scenes/texture_files.h"

#include <algorithm>
#include <cctype>
#include <system_error>

namespace prism {
namespace {

namespace fs = std::filesystem;

bool is_file(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  const char lower = char(std::tolower(static_cast<unsigned char>(c)));
  if (lower >= 'a' && lower <= 'f') return lower - 'a' + 10;
  return -1;
}

/// `text` with '\' as '/' and %XX escapes decoded.
std::string normalised(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\') {
      out += '/';
    } else if (text[i] == '%' && i + 2 < text.size() && hex_digit(text[i + 1]) >= 0 &&
               hex_digit(text[i + 2]) >= 0) {
      out += char(hex_digit(text[i + 1]) * 16 + hex_digit(text[i + 2]));
      i += 2;
    } else {
      out += text[i];
    }
  }
  return out;
}

}  // namespace

TextureSource texture_file_source(const std::string& written, const fs::path& base_dir,
                                  const std::string& color_space, const ErrorLocation& origin) {
  if (written.empty()) throw Error(ErrorKind::kInput, "texture file path is empty", origin);
  const fs::path as_written = base_dir / fs::path(written);
  const std::string fixed = normalised(written);
  std::vector<fs::path> candidates = {as_written};
  if (fixed != written) candidates.push_back(base_dir / fs::path(fixed));
  const fs::path file_name = fs::path(fixed).filename();
  if (!file_name.empty() && file_name != fs::path(fixed))
    candidates.push_back(base_dir / file_name);
  for (const fs::path& candidate : candidates) {
    if (!is_file(candidate)) continue;
    TextureSource source;
    source.name = written;
    source.file = candidate;
    source.color_space = color_space;
    source.origin = origin;
    return source;
  }
  throw Error(ErrorKind::kInput,
              "texture file '" + written + "' not found (looked for " + as_written.string() + ")",
              origin);
}

uint32_t add_texture(std::vector<TextureSource>& textures, TextureSource source) {
  for (size_t i = 0; i < textures.size(); ++i) {
    const TextureSource& t = textures[i];
    const bool same_image = source.is_embedded() ? t.is_embedded() && t.bytes == source.bytes &&
                                                       t.raw_width == source.raw_width &&
                                                       t.raw_height == source.raw_height
                                                 : t.file == source.file;
    if (same_image && t.color_space == source.color_space) return uint32_t(i);
  }
  textures.push_back(std::move(source));
  return uint32_t(textures.size() - 1);
}

}  // namespace prism
