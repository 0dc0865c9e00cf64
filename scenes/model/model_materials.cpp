#include "scenes/model/model_materials.h"

#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "core/strings.h"
#include "scenes/texture_files.h"

namespace prism::model {
namespace {

std::optional<Rgb> get_color(const aiMaterial& m, const char* key, unsigned type, unsigned index) {
  aiColor4D c;
  if (m.Get(key, type, index, c) != AI_SUCCESS) return std::nullopt;
  const Rgb rgb(c.r, c.g, c.b);
  if (!is_finite(rgb)) return std::nullopt;
  return rgb;
}

std::optional<float> get_float(const aiMaterial& m, const char* key, unsigned type,
                               unsigned index) {
  ai_real value = 0;
  if (m.Get(key, type, index, value) != AI_SUCCESS || !std::isfinite(float(value))) {
    return std::nullopt;
  }
  return float(value);
}

std::string get_string(const aiMaterial& m, const char* key, unsigned type, unsigned index) {
  aiString value;
  if (m.Get(key, type, index, value) != AI_SUCCESS) return {};
  return value.C_Str();
}

/// The first texture of `type`, or "".
std::string texture_path(const aiMaterial& m, aiTextureType type, unsigned& uv_set,
                         aiTextureMapping& mapping) {
  aiString path;
  uv_set = 0;
  mapping = aiTextureMapping_UV;
  if (m.GetTextureCount(type) == 0 ||
      m.GetTexture(type, 0, &path, &mapping, &uv_set) != AI_SUCCESS) {
    return {};
  }
  return path.C_Str();
}

}  // namespace

ModelMaterials::ModelMaterials(const aiScene& scene, const std::filesystem::path& file, Scene& out)
    : scene_(scene), file_(file), out_(out) {
  const std::string ext = lower_case_extension(file);
  gltf_ = ext == ".gltf" || ext == ".glb";
  has_materials_ = ext != ".stl" && ext != ".ply";
}

uint32_t ModelMaterials::index_of(unsigned index) {
  const auto it = converted_.find(index);
  if (it != converted_.end()) return it->second;
  out_.materials.push_back(convert(index));
  const uint32_t id = uint32_t(out_.materials.size() - 1);
  converted_.emplace(index, id);
  return id;
}

uint32_t ModelMaterials::texture(const std::string& path, const std::string& material) {
  const ErrorLocation origin{file_.string(), 0, "material '" + material + "'"};
  if (const aiTexture* embedded = scene_.GetEmbeddedTexture(path.c_str())) {
    TextureSource source;
    source.name = file_.filename().string() + ": embedded texture " + path;
    source.origin = origin;
    if (embedded->mHeight == 0) {
      // Compressed: mWidth bytes of a PNG, JPEG, ... file.
      const auto* bytes = reinterpret_cast<const unsigned char*>(embedded->pcData);
      source.bytes.assign(bytes, bytes + embedded->mWidth);
      source.format_hint = embedded->achFormatHint;
    } else {
      // Raw texels: B, G, R, A bytes each.
      const size_t count = size_t(embedded->mWidth) * embedded->mHeight;
      source.raw_width = int(std::min<unsigned>(embedded->mWidth, 1u << 30));
      source.raw_height = int(std::min<unsigned>(embedded->mHeight, 1u << 30));
      source.bytes.reserve(4 * count);
      for (size_t i = 0; i < count; ++i) {
        const aiTexel& t = embedded->pcData[i];
        source.bytes.insert(source.bytes.end(), {t.r, t.g, t.b, t.a});
      }
    }
    return add_texture(out_.textures, std::move(source));
  }
  if (!path.empty() && path[0] == '*') {
    throw Error(ErrorKind::kInput,
                "names embedded texture " + path + ", which the file does not have", origin);
  }
  return add_texture(out_.textures, texture_file_source(path, file_.parent_path(), "", origin));
}

Material ModelMaterials::convert(unsigned index) {
  Material m;
  m.type = MaterialType::kDiffuse;
  m.reflectance = Rgb(kDefaultGrey);
  m.name = "material " + std::to_string(index);
  if (index >= scene_.mNumMaterials || scene_.mMaterials[index] == nullptr) return m;
  const aiMaterial& a = *scene_.mMaterials[index];
  const std::string name = get_string(a, AI_MATKEY_NAME);
  if (!name.empty()) m.name = name;
  // Assimp's stand-ins for files without materials (STL and PLY carry none; OBJ without a
  // material library gets "DefaultMaterial"): prism's grey.
  if (name == AI_DEFAULT_MATERIAL_NAME || !has_materials_) return m;
  const auto warn = [&](const std::string& what) {
    out_.warnings.push_back(file_.string() + ": material '" + m.name + "': " + what);
  };

  const Rgb base =
      glm::clamp(get_color(a, AI_MATKEY_BASE_COLOR)
                     .value_or(get_color(a, AI_MATKEY_COLOR_DIFFUSE).value_or(Rgb(kDefaultGrey))),
                 Rgb(0.0f), Rgb(1.0f));
  const float metallic =
      std::clamp(get_float(a, AI_MATKEY_METALLIC_FACTOR).value_or(0.0f), 0.0f, 1.0f);
  const float roughness =
      std::clamp(get_float(a, AI_MATKEY_ROUGHNESS_FACTOR).value_or(1.0f), 0.0f, 1.0f);
  const float transmission =
      std::clamp(get_float(a, AI_MATKEY_TRANSMISSION_FACTOR).value_or(0.0f), 0.0f, 1.0f);
  float opacity = std::clamp(get_float(a, AI_MATKEY_OPACITY).value_or(1.0f), 0.0f, 1.0f);
  // glTF: the base colour's alpha is opacity only in BLEND mode (MASK cut-outs are not
  // supported; OPAQUE ignores alpha).
  if (gltf_ && get_string(a, "$mat.gltf.alphaMode", 0, 0) != "BLEND") opacity = 1.0f;
  const float file_ior = get_float(a, AI_MATKEY_REFRACTI).value_or(0.0f);
  const Rgb emissive =
      glm::max(get_color(a, AI_MATKEY_COLOR_EMISSIVE).value_or(Rgb(0.0f)), Rgb(0.0f)) *
      std::max(0.0f, get_float(a, AI_MATKEY_EMISSIVE_INTENSITY).value_or(1.0f));

  unsigned uv_set = 0;
  aiTextureMapping mapping = aiTextureMapping_UV;
  std::string base_texture = texture_path(a, aiTextureType_BASE_COLOR, uv_set, mapping);
  if (base_texture.empty()) base_texture = texture_path(a, aiTextureType_DIFFUSE, uv_set, mapping);
  const auto check_mapping = [&](const std::string& texture) {
    if (texture.empty()) return;
    if (uv_set != 0) {
      warn("texture '" + texture + "' uses texture coordinate set " + std::to_string(uv_set) +
           "; prism reads set 0");
    }
    if (mapping != aiTextureMapping_UV) {
      warn("texture '" + texture + "' has a projected mapping; prism uses the uv coordinates");
    }
  };
  check_mapping(base_texture);

  if (transmission > 0.0f || opacity < 1.0f) {
    m.type = MaterialType::kGlass;
    m.reflectance = Rgb(1.0f);
    m.transmittance = base;
    m.ior = file_ior > 1.0f ? file_ior : 1.5f;
    if (!base_texture.empty()) {
      warn("the base colour texture of a transparent material is not used");
    }
  } else if (metallic >= kMetallicThreshold) {
    m.type = MaterialType::kMicrofacet;
    m.reflectance = base;
    m.alpha = std::max(roughness * roughness, kMinMetalAlpha);
    conductor_from_reflectance(base, m.eta, m.k);
    if (!base_texture.empty()) m.reflectance_texture = texture(base_texture, m.name);
  } else {
    m.type = MaterialType::kDiffuse;
    m.reflectance = base;
    if (!base_texture.empty()) m.reflectance_texture = texture(base_texture, m.name);
  }

  if (max_component(emissive) > 0.0f) {
    m.radiance = emissive;
    const std::string emissive_texture = texture_path(a, aiTextureType_EMISSIVE, uv_set, mapping);
    check_mapping(emissive_texture);
    if (!emissive_texture.empty()) m.radiance_texture = texture(emissive_texture, m.name);
  }
  return m;
}

}  // namespace prism::model
