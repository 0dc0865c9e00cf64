#pragma once

namespace prism {

/// Defaults and bounds of the integrator parameters that render flags stand for:
/// `<integrator>.light_samples` (-l) and `<integrator>.max_depth` (-m). The driver checks the
/// flags against the same bounds.
inline constexpr int kDefaultLightSamples = 1;
inline constexpr int kMaxLightSamples = 1 << 16;
inline constexpr int kDefaultMaxDepth = 5;
inline constexpr int kMaxDepth = 1024;

}  // namespace prism
