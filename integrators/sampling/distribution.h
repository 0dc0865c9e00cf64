#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace prism {

/// A discrete distribution proportional to non-negative weights (light selection by power,
/// triangle selection by area). Zero total weight makes every entry equally likely.
class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  explicit DiscreteDistribution(std::span<const float> weights);

  size_t size() const { return pmf_.size(); }
  bool empty() const { return pmf_.empty(); }
  /// Index drawn with probability pmf(index) from u in [0, 1); `u_remapped`, if given, receives
  /// u rescaled to [0, 1) within the chosen entry (a fresh uniform value). Requires !empty().
  size_t sample(float u, float* pmf = nullptr, float* u_remapped = nullptr) const;
  float pmf(size_t index) const { return pmf_[index]; }
  /// Sum of the weights given to the constructor.
  double total() const { return total_; }

 private:
  std::vector<float> pmf_;
  std::vector<double> cdf_;  ///< cdf_[i] = P(index < i); size() + 1 entries, last is 1
  double total_ = 0.0;
};

}  // namespace prism
