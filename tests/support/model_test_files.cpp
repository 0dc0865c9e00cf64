#include "tests/support/model_test_files.h"

#include <array>
#include <cstring>
#include <fstream>

namespace prism::test {
namespace {

uint32_t crc32(const unsigned char* data, size_t size, uint32_t crc = 0) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xff] ^ (crc >> 8);
  return ~crc;
}

void put_u32_be(Bytes& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back((v >> shift) & 0xff);
}
void put_u32_le(Bytes& out, uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back((v >> shift) & 0xff);
}

void png_chunk(Bytes& out, const char* type, const Bytes& data) {
  put_u32_be(out, uint32_t(data.size()));
  Bytes typed(type, type + 4);
  typed.insert(typed.end(), data.begin(), data.end());
  out.insert(out.end(), typed.begin(), typed.end());
  put_u32_be(out, crc32(typed.data(), typed.size()));
}

/// A zlib stream of stored (uncompressed) deflate blocks.
Bytes zlib_stored(const Bytes& raw) {
  Bytes out = {0x78, 0x01};
  size_t at = 0;
  do {
    const size_t n = std::min<size_t>(65535, raw.size() - at);
    const bool last = at + n == raw.size();
    out.push_back(last ? 1 : 0);
    out.push_back(n & 0xff);
    out.push_back((n >> 8) & 0xff);
    out.push_back(~n & 0xff);
    out.push_back((~n >> 8) & 0xff);
    out.insert(out.end(), raw.begin() + long(at), raw.begin() + long(at + n));
    at += n;
  } while (at < raw.size());
  uint32_t a = 1, b = 0;
  for (const unsigned char c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  put_u32_be(out, (b << 16) | a);
  return out;
}

template <typename T>
void append_values(Bytes& out, const std::vector<T>& values) {
  const auto* p = reinterpret_cast<const unsigned char*>(values.data());
  out.insert(out.end(), p, p + values.size() * sizeof(T));
}

std::string base64(const Bytes& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= bytes[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

}  // namespace

Bytes png_rgb8(int width, int height, const std::vector<uint8_t>& rgb) {
  Bytes out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Bytes header;
  put_u32_be(header, uint32_t(width));
  put_u32_be(header, uint32_t(height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, no interlace
  png_chunk(out, "IHDR", header);
  Bytes raw;
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);  // filter: none
    const auto row = rgb.begin() + long(y) * width * 3;
    raw.insert(raw.end(), row, row + width * 3);
  }
  png_chunk(out, "IDAT", zlib_stored(raw));
  png_chunk(out, "IEND", {});
  return out;
}

Bytes png_checkerboard(int cells, int cell, const std::vector<uint8_t>& a,
                       const std::vector<uint8_t>& b) {
  const int side = cells * cell;
  std::vector<uint8_t> rgb;
  rgb.reserve(size_t(side) * side * 3);
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const auto& c = ((x / cell) + (y / cell)) % 2 == 0 ? a : b;
      rgb.insert(rgb.end(), c.begin(), c.end());
    }
  }
  return png_rgb8(side, side, rgb);
}

void write_bytes(const std::filesystem::path& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

GltfBuilder::GltfBuilder() {
  doc = {{"asset", {{"version", "2.0"}}},
         {"scene", 0},
         {"scenes", {{{"nodes", nlohmann::json::array()}}}},
         {"nodes", nlohmann::json::array()},
         {"meshes", nlohmann::json::array()},
         {"materials", nlohmann::json::array()},
         {"accessors", nlohmann::json::array()},
         {"bufferViews", nlohmann::json::array()}};
}

int GltfBuilder::add_view(const Bytes& bytes) {
  while (bin_.size() % 4 != 0) bin_.push_back(0);
  doc["bufferViews"].push_back(
      {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes.size()}});
  bin_.insert(bin_.end(), bytes.begin(), bytes.end());
  return int(doc["bufferViews"].size()) - 1;
}

int GltfBuilder::add_accessor(int view, int component_type, int count, const std::string& type,
                              const nlohmann::json& extra) {
  nlohmann::json a = {
      {"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
  a.update(extra);
  doc["accessors"].push_back(a);
  return int(doc["accessors"].size()) - 1;
}

int GltfBuilder::add_quad_mesh(int material, bool with_normals) {
  Bytes positions, uvs, normals, indices;
  append_values(positions, std::vector<float>{-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
  // glTF's v runs down the image: the bottom-left corner is (0, 1).
  append_values(uvs, std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0});
  append_values(normals, std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
  append_values(indices, std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
  nlohmann::json attributes = {
      {"POSITION", add_accessor(add_view(positions), 5126, 4, "VEC3",
                                {{"min", {-1, -1, 0}}, {"max", {1, 1, 0}}})},
      {"TEXCOORD_0", add_accessor(add_view(uvs), 5126, 4, "VEC2")}};
  if (with_normals) attributes["NORMAL"] = add_accessor(add_view(normals), 5126, 4, "VEC3");
  nlohmann::json primitive = {{"attributes", attributes},
                              {"indices", add_accessor(add_view(indices), 5123, 6, "SCALAR")}};
  if (material >= 0) primitive["material"] = material;
  doc["meshes"].push_back({{"primitives", {primitive}}});
  return int(doc["meshes"].size()) - 1;
}

int GltfBuilder::add_material(const std::string& name, const nlohmann::json& pbr,
                              const nlohmann::json& extra) {
  nlohmann::json m = {{"name", name}, {"pbrMetallicRoughness", pbr}};
  m.update(extra);
  doc["materials"].push_back(m);
  return int(doc["materials"].size()) - 1;
}

int GltfBuilder::embed_image(const Bytes& png) {
  doc["images"].push_back({{"bufferView", add_view(png)}, {"mimeType", "image/png"}});
  doc["textures"].push_back({{"source", int(doc["images"].size()) - 1}});
  return int(doc["textures"].size()) - 1;
}

int GltfBuilder::file_image(const std::string& uri) {
  doc["images"].push_back({{"uri", uri}});
  doc["textures"].push_back({{"source", int(doc["images"].size()) - 1}});
  return int(doc["textures"].size()) - 1;
}

int GltfBuilder::add_node(const nlohmann::json& node, bool root) {
  doc["nodes"].push_back(node);
  const int index = int(doc["nodes"].size()) - 1;
  if (root) doc["scenes"][0]["nodes"].push_back(index);
  return index;
}

int GltfBuilder::add_camera(double yfov, double aspect, double znear, double zfar) {
  doc["cameras"].push_back(
      {{"type", "perspective"},
       {"perspective",
        {{"yfov", yfov}, {"aspectRatio", aspect}, {"znear", znear}, {"zfar", zfar}}}});
  return int(doc["cameras"].size()) - 1;
}

int GltfBuilder::add_light(const nlohmann::json& light) {
  auto& lights = doc["extensions"]["KHR_lights_punctual"]["lights"];
  lights.push_back(light);
  if (!doc.contains("extensionsUsed")) doc["extensionsUsed"] = {"KHR_lights_punctual"};
  return int(lights.size()) - 1;
}

std::string GltfBuilder::gltf() const {
  nlohmann::json out = doc;
  out["buffers"] = {{{"byteLength", bin_.size()},
                     {"uri", "data:application/octet-stream;base64," + base64(bin_)}}};
  return out.dump(1);
}

Bytes GltfBuilder::glb() const {
  nlohmann::json out = doc;
  Bytes bin = bin_;
  while (bin.size() % 4 != 0) bin.push_back(0);
  out["buffers"] = {{{"byteLength", bin.size()}}};
  std::string json = out.dump();
  while (json.size() % 4 != 0) json += ' ';
  Bytes glb;
  put_u32_le(glb, 0x46546c67);  // "glTF"
  put_u32_le(glb, 2);
  put_u32_le(glb, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  put_u32_le(glb, uint32_t(json.size()));
  put_u32_le(glb, 0x4e4f534a);  // "JSON"
  glb.insert(glb.end(), json.begin(), json.end());
  put_u32_le(glb, uint32_t(bin.size()));
  put_u32_le(glb, 0x004e4942);  // "BIN"
  glb.insert(glb.end(), bin.begin(), bin.end());
  return glb;
}

}  // namespace prism::test
