#include "integrators/bsdf/bsdf_factory.h"

#include <cmath>

#include "core/error.h"

#include "integrators/bsdf/fresnel.h"
#include "integrators/bsdf/glass_bsdf.h"

namespace prism {

std::unique_ptr<Bsdf> make_bsdf(const Material& material, const BsdfOptions& options) {
  const bool dielectric =
      material.type == MaterialType::kGlass || material.type == MaterialType::kRefraction;
  if (dielectric && !(std::isfinite(material.ior) && material.ior > 0.0f)) {
    throw Error(ErrorKind::kInput, "index of refraction must be a positive number",
                {{}, 0, "material '" + material.name + "'"});
  }
  switch (material.type) {
    case MaterialType::kDiffuse:
      return std::make_unique<DiffuseBsdf>(material.reflectance);
    case MaterialType::kMirror:
      return std::make_unique<MirrorBsdf>(material.reflectance);
    case MaterialType::kGlass:
      return std::make_unique<GlassBsdf>(material.reflectance, material.transmittance,
                                         material.ior);
    case MaterialType::kRefraction:
      return std::make_unique<RefractionBsdf>(material.transmittance, material.ior);
    case MaterialType::kMicrofacet:
      return std::make_unique<MicrofacetBsdf>(material.eta, material.k, material.alpha,
                                              options.microfacet);
    case MaterialType::kEmission:
      return std::make_unique<EmissionBsdf>();
  }
  return std::make_unique<EmissionBsdf>();
}

const Bsdf& make_bsdf_with_reflectance(const Material& material, const Rgb& reflectance,
                                       const BsdfOptions& options, BsdfStorage& storage) {
  switch (material.type) {
    case MaterialType::kDiffuse:
      return storage.emplace<DiffuseBsdf>(reflectance);
    case MaterialType::kMirror:
      return storage.emplace<MirrorBsdf>(reflectance);
    case MaterialType::kMicrofacet: {
      Rgb eta, k;
      conductor_from_reflectance(reflectance, eta, k);
      return storage.emplace<MicrofacetBsdf>(eta, k, material.alpha, options.microfacet);
    }
    default:
      throw Error(
          ErrorKind::kInternal,
          "a " + std::string(to_string(material.type)) + " material takes no reflectance texture",
          {{}, 0, "material '" + material.name + "'"});
  }
}

Rgb material_albedo(const Material& material) {
  switch (material.type) {
    case MaterialType::kDiffuse:
    case MaterialType::kMirror:
      return glm::clamp(material.reflectance, Rgb(0.0f), Rgb(1.0f));
    case MaterialType::kGlass:
    case MaterialType::kRefraction:
      return glm::clamp(material.transmittance, Rgb(0.0f), Rgb(1.0f));
    case MaterialType::kMicrofacet:
      return glm::clamp(fresnel_conductor(1.0f, material.eta, material.k), Rgb(0.0f), Rgb(1.0f));
    case MaterialType::kEmission:
      return Rgb(0.0f);
  }
  return Rgb(0.0f);
}

std::vector<std::unique_ptr<Bsdf>> make_bsdfs(const std::vector<Material>& materials,
                                              const BsdfOptions& options) {
  std::vector<std::unique_ptr<Bsdf>> out;
  out.reserve(materials.size());
  for (const Material& m : materials) out.push_back(make_bsdf(m, options));
  return out;
}

}  // namespace prism
