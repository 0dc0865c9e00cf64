#pragma once

#include <string>
#include <string_view>

#include "core/math.h"

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
/// its type are meaningful.
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

  bool is_emissive() const { return type == MaterialType::kEmission; }
};

/// Lower-case name of a material type ("diffuse", "mirror", ...).
std::string_view to_string(MaterialType type);

}  // namespace prism
