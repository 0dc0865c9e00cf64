#pragma once

#include <memory>
#include <utility>
#include <variant>
#include <vector>

#include "core/material.h"
#include "integrators/bsdf/bsdf.h"
#include "integrators/bsdf/diffuse_bsdf.h"
#include "integrators/bsdf/microfacet_bsdf.h"
#include "integrators/bsdf/microfacet_distribution.h"
#include "integrators/bsdf/mirror_bsdf.h"

namespace prism {

/// Choices the scene format does not carry.
struct BsdfOptions {
  MicrofacetModel microfacet = MicrofacetModel::kBeckmann;  ///< of rough conductors
};

/// An emitter's BSDF: it reflects nothing.
class EmissionBsdf final : public Bsdf {
 public:
  EmissionBsdf() : Bsdf(kLobeNone, false) {}
  Rgb eval(const Vec3&, const Vec3&) const override { return Rgb(0.0f); }
  std::optional<BsdfSample> sample(const Vec3&, float, Vec2) const override { return std::nullopt; }
  float pdf(const Vec3&, const Vec3&) const override { return 0.0f; }
  Rgb albedo() const override { return Rgb(0.0f); }
};

/// The scattering model of `material`. Glass and refraction materials are smooth whatever
/// their `roughness` (every CS184 file has 0).
std::unique_ptr<Bsdf> make_bsdf(const Material& material, const BsdfOptions& options = {});

/// The albedo AOV of `material` (make_bsdf(material)->albedo() without building it); without
/// its texture.
Rgb material_albedo(const Material& material);

/// Room for the BSDF of one hit of a textured material, so that building it per hit allocates
/// nothing. Lives on the stack of the shading code; the BSDF built in it lives as long.
class BsdfStorage {
 public:
  template <typename T, typename... Args>
  const Bsdf& emplace(Args&&... args) {
    return storage_.emplace<T>(std::forward<Args>(args)...);
  }

 private:
  std::variant<std::monostate, DiffuseBsdf, MirrorBsdf, MicrofacetBsdf> storage_;
};

/// The BSDF of a diffuse, mirror or microfacet `material` with `reflectance` in place of its
/// own (its reflectance times its texture at a hit), built in `storage`. A microfacet material
/// takes eta and k from `reflectance` (conductor_from_reflectance()). Throws Error(kInternal)
/// for other types, which take no texture.
const Bsdf& make_bsdf_with_reflectance(const Material& material, const Rgb& reflectance,
                                       const BsdfOptions& options, BsdfStorage& storage);

/// make_bsdf() of each material, indexed like `materials`.
std::vector<std::unique_ptr<Bsdf>> make_bsdfs(const std::vector<Material>& materials,
                                              const BsdfOptions& options = {});

}  // namespace prism
