#pragma once

#include <memory>
#include <vector>

#include "core/material.h"
#include "integrators/bsdf/bsdf.h"
#include "integrators/bsdf/microfacet_distribution.h"

namespace prism {

/// Choices the scene format does not carry.
struct BsdfOptions {
  MicrofacetModel microfacet = MicrofacetModel::kBeckmann;  ///< of rough conductors
};

/// An emitter's BSDF: it reflects nothing.
class EmissionBsdf final : public Bsdf {
 public:
  Rgb eval(const Vec3&, const Vec3&) const override { return Rgb(0.0f); }
  std::optional<BsdfSample> sample(const Vec3&, float, Vec2) const override { return std::nullopt; }
  float pdf(const Vec3&, const Vec3&) const override { return 0.0f; }
  uint32_t lobes() const override { return kLobeNone; }
  Rgb albedo() const override { return Rgb(0.0f); }
};

/// The scattering model of `material`. Glass and refraction materials are smooth whatever
/// their `roughness` (every CS184 file has 0).
std::unique_ptr<Bsdf> make_bsdf(const Material& material, const BsdfOptions& options = {});

/// The albedo AOV of `material` (make_bsdf(material)->albedo() without building it).
Rgb material_albedo(const Material& material);

/// make_bsdf() of each material, indexed like `materials`.
std::vector<std::unique_ptr<Bsdf>> make_bsdfs(const std::vector<Material>& materials,
                                              const BsdfOptions& options = {});

}  // namespace prism
