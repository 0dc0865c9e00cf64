#pragma once

// Model and image files written at test time, byte for byte, without the libraries under test:
// PNG (8-bit RGB, stored deflate blocks), glTF and GLB (a small builder), for the scenes_model,
// color_texture and app_model tests.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace prism::test {

using Bytes = std::vector<unsigned char>;

/// An 8-bit RGB PNG of `width` x `height` pixels, `rgb` holding 3 bytes per pixel, top row
/// first. Uncompressed (stored deflate blocks), so every byte of the image is exact.
Bytes png_rgb8(int width, int height, const std::vector<uint8_t>& rgb);

/// A PNG checkerboard of `cells` x `cells` squares of `cell` pixels: `a` in the top-left
/// square, `b` next to it.
Bytes png_checkerboard(int cells, int cell, const std::vector<uint8_t>& a,
                       const std::vector<uint8_t>& b);

/// Writes `bytes` to `path`.
void write_bytes(const std::filesystem::path& path, const Bytes& bytes);

/// A glTF 2.0 document built in code: meshes of quads, materials, images, nodes, cameras and
/// punctual lights. gltf() writes it with its binary buffer as a data: URI, glb() as a GLB
/// container with the buffer (and images added with embed_image) in its BIN chunk.
class GltfBuilder {
 public:
  GltfBuilder();
  /// A mesh of one quad spanning [-1, 1]^2 in the z = 0 plane facing +z, uvs (0, 0) at the
  /// bottom-left corner and (1, 1) at the top-right (as Assimp reports them; the file stores
  /// glTF's flipped v), with `material` (-1: none). Returns the mesh index.
  int add_quad_mesh(int material, bool with_normals = true);
  /// A material: `pbr` is the pbrMetallicRoughness object; `extra` keys merge into the
  /// material (emissiveFactor, extensions, ...). Returns its index.
  int add_material(const std::string& name, const nlohmann::json& pbr,
                   const nlohmann::json& extra = nlohmann::json::object());
  /// A texture of an image in the binary buffer (embedded). Returns the texture index.
  int embed_image(const Bytes& png);
  /// A texture of an image file `uri` beside the model. Returns the texture index.
  int file_image(const std::string& uri);
  /// A node (translation, rotation, scale, matrix, mesh, camera, extensions, children) in the
  /// scene's root list unless `root` is false. Returns the node index.
  int add_node(const nlohmann::json& node, bool root = true);
  /// A perspective camera. Returns its index.
  int add_camera(double yfov, double aspect, double znear = 0.1, double zfar = 100.0);
  /// A KHR_lights_punctual light ({"type": "point", "color": [...], "intensity": ...}).
  int add_light(const nlohmann::json& light);

  std::string gltf() const;
  Bytes glb() const;

  nlohmann::json doc;

 private:
  int add_view(const Bytes& bytes);
  int add_accessor(int view, int component_type, int count, const std::string& type,
                   const nlohmann::json& extra = nlohmann::json::object());
  Bytes bin_;
};

}  // namespace prism::test
