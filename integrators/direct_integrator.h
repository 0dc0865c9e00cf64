#pragma once

#include "integrators/light_transport.h"

namespace prism {

/// Direct illumination, zero bounce plus one bounce: emission seen directly,
/// plus light reflected once, estimated by light importance sampling (default; every light,
/// direct.light_samples samples per non-delta light) or by uniform hemisphere sampling
/// (direct.hemisphere). At a purely specular surface the one bounce follows the specular
/// direction instead, so mirrors show the lights they reflect. Parameters: those of
/// LightTransportSettings, prefix "direct.".
class DirectIntegrator final : public PixelIntegrator {
 public:
  explicit DirectIntegrator(const ParamSet& params);
  std::string_view name() const override { return "direct"; }

 protected:
  std::unique_ptr<PixelEstimator> prepare(const RenderContext& context) const override;

 private:
  LightTransportSettings settings_;
};

}  // namespace prism
