#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/math.h"

namespace prism {

/// The texture index of a material field that has no texture.
inline constexpr uint32_t kNoTexture = std::numeric_limits<uint32_t>::max();

/// An image a scene uses as a texture, as the scene loader found it: plain data. Its pixels
/// are read, checked and converted when a render loads the scene's textures
/// (color/texture_set.h); the loader only checks that a file exists.
struct TextureSource {
  /// What messages call it: the file's path, or "<model file>: embedded texture N".
  std::string name;
  /// The image file; empty for an image embedded in the scene file.
  std::filesystem::path file;
  /// An embedded image: the encoded file's bytes (PNG, JPEG, ...), or, when raw_width > 0,
  /// raw_width x raw_height texels of 4 bytes (R, G, B, A), the top row first.
  std::vector<unsigned char> bytes;
  std::string format_hint;  ///< embedded: the format's usual extension ("png", "jpg"), or ""
  int raw_width = 0;
  int raw_height = 0;
  /// The colour space the scene file declares for the image (a name of the OCIO config);
  /// empty: the image's own declaration, else its format decides (docs/SCENE_FORMAT.md,
  /// "Textures").
  std::string color_space;
  /// Where the scene file names the texture, for error messages.
  ErrorLocation origin;

  bool is_embedded() const { return file.empty(); }
};

/// Filtered lookups in a scene's textures, whose values are already in the working space.
/// Texture coordinates (u, v) have v up: (0, 0) is the bottom-left corner of the image, (1, 1)
/// the top-right one, and the image repeats outside [0, 1)^2. Implemented in color/ with
/// OpenImageIO's TextureSystem. Immutable after construction; thread-safe.
class TextureLookup {
 public:
  virtual ~TextureLookup() = default;
  /// Number of textures (Scene::textures, in the same order).
  virtual size_t size() const = 0;
  /// R, G, B of `texture` at `uv`, filtered over the parallelogram spanned by the uv offsets
  /// `duv_dx` and `duv_dy` around it (both zero: the finest MIP level, interpolated).
  virtual Rgb lookup(uint32_t texture, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy) const = 0;
  /// The mean R, G, B of `texture` (the power of textured emitters is based on it).
  virtual Rgb average(uint32_t texture) const = 0;
  /// A hash of every texture's converted pixels (part of scene_hash()).
  virtual uint64_t content_hash() const = 0;
};

}  // namespace prism
