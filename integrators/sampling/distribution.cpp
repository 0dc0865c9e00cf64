#include "integrators/sampling/distribution.h"

#include <algorithm>
#include <cmath>

namespace prism {

DiscreteDistribution::DiscreteDistribution(std::span<const float> weights)
    : pmf_(weights.size()), cdf_(weights.size() + 1, 0.0) {
  for (float w : weights) total_ += (std::isfinite(w) && w > 0.0f) ? double(w) : 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    const float w = weights[i];
    const double p = total_ > 0.0 ? ((std::isfinite(w) && w > 0.0f) ? double(w) / total_ : 0.0)
                                  : 1.0 / double(weights.size());
    pmf_[i] = float(p);
    cdf_[i + 1] = cdf_[i] + p;
  }
  if (!weights.empty()) cdf_.back() = 1.0;
}

size_t DiscreteDistribution::sample(float u, float* pmf, float* u_remapped) const {
  // One entry (a scene's only light): what the search below would give, without it.
  if (pmf_.size() == 1) {
    if (pmf) *pmf = pmf_[0];
    if (u_remapped) *u_remapped = float(std::clamp(double(u), 0.0, double(0x1.fffffep-1f)));
    return 0;
  }
  // The last entry whose cdf is <= u, skipping zero-probability entries.
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), double(u));
  size_t i = size_t(std::max<std::ptrdiff_t>(0, (it - cdf_.begin()) - 1));
  i = std::min(i, pmf_.size() - 1);
  while (pmf_[i] == 0.0f && i > 0) --i;
  if (pmf) *pmf = pmf_[i];
  if (u_remapped) {
    const double width = cdf_[i + 1] - cdf_[i];
    const double r = width > 0.0 ? (double(u) - cdf_[i]) / width : 0.0;
    *u_remapped = float(std::clamp(r, 0.0, double(0x1.fffffep-1f)));
  }
  return i;
}

}  // namespace prism
