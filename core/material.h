#pragma once

#include <string>
#include <string_view>

#include "core/math.h"
#include "core/texture.h"

namespace prism {

/// The scattering models a scene can name (the CGL profile's set plus plain Lambertian).
enum class MaterialType {
  kDiffuse,     ///< Lambertian, `reflectance`
  kMirror,      ///< perfect specular reflection, `reflectance`
  kGlass,       ///< smooth dielectric: `reflectance`, `transmittance`, `roughness`, `ior`
  kRefraction,  ///< refraction only: `transmittance`, `roughness`, `ior`
  kMicrofacet,  ///< rough conductor: Beckmann `alpha`, complex IOR `eta` + i `k`
  kEmission,    ///< diffuse emitter of `radiance`; reflects nothing
};

/// Plain material description; scattering code lives with the integrators. Only the fields of
/// its type are meaningful, except `radiance`: any material may emit (model files give
/// emission to surfaces that also reflect); an `emission` material emits and reflects nothing.
struct Material {
  std::string name;
  MaterialType type = MaterialType::kDiffuse;
  Rgb reflectance{0.5f};
  Rgb transmittance{1.0f};
  float roughness = 0.0f;
  float ior = 1.5f;
  float alpha = 0.5f;
  Rgb eta{1.0f};
  Rgb k{0.0f};
  Rgb radiance{0.0f};
  /// Index into Scene::textures of an image that multiplies `reflectance` at each point
  /// (diffuse, mirror and microfacet materials), or kNoTexture. A microfacet material with one
  /// takes its eta and k at each point from that colour (conductor_from_reflectance()).
  uint32_t reflectance_texture = kNoTexture;
  /// Index into Scene::textures of an image that multiplies `radiance`, or kNoTexture.
  uint32_t radiance_texture = kNoTexture;

  /// Whether surfaces of this material emit light: an emission material, or any material with
  /// a radiance other than black.
  bool is_emissive() const {
    return type == MaterialType::kEmission || max_component(radiance) > 0.0f;
  }
  bool is_textured() const {
    return reflectance_texture != kNoTexture || radiance_texture != kNoTexture;
  }
};

/// The complex index of refraction eta + i k of a conductor whose reflectance at normal
/// incidence is `reflectance` (per channel, clamped to [0, 0.999]), by Gulbrandsen's
/// "artist friendly metallic Fresnel" (JCGT 2014) with a white edge tint (g = 1): the conductor
/// Fresnel term then equals `reflectance` at normal incidence and rises to white at grazing
/// angles, as the Schlick term of glTF's metals does.
void conductor_from_reflectance(const Rgb& reflectance, Rgb& eta, Rgb& k);

/// Lower-case name of a material type ("diffuse", "mirror", ...).
std::string_view to_string(MaterialType type);

}  // namespace prism
