#pragma once

#include <cstdint>

namespace prism {

/// Sobol dimensions past the first two that SobolSampler::get_2d_chained() continues a pair
/// with: dimensions 2 to 2 + kSobolChainDimensions - 1 of the Sobol sequence.
inline constexpr int kSobolChainDimensions = 8;

/// Sample `index` of Sobol dimension 2 + `k` (k in [0, kSobolChainDimensions)) as 0.32 fixed
/// point, from the direction numbers of Joe and Kuo (file new-joe-kuo-6.21201, its dimensions 3
/// to 10; its dimensions 1 and 2 are sobol_dimension0() and sobol_dimension1()).
uint32_t sobol_chain_dimension(int k, uint32_t index);

/// reverse_bits(sobol_chain_dimension(k, index)): the form the Owen scramble of SobolSampler
/// works on, computed without the reversal.
uint32_t sobol_chain_dimension_reversed(int k, uint32_t index);

}  // namespace prism
