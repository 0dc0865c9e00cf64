#pragma once

#include <cstdint>

namespace prism {

/// v with its bits in reverse order (bit 0 becomes bit 31): the byte order reversed, then the
/// bits within each byte.
constexpr uint32_t reverse_bits(uint32_t v) {
  v = __builtin_bswap32(v);
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  return ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
}

/// Sobol dimensions past the first two that SobolSampler::get_2d_chained() continues a pair
/// with: dimensions 2 to 2 + kSobolChainDimensions - 1.
inline constexpr int kSobolChainDimensions = 8;
/// Dimensions 1 to kSobolTableDimensions have generator tables (dimension 0 is reverse_bits()).
inline constexpr int kSobolTableDimensions = 1 + kSobolChainDimensions;

/// Each tabled dimension's generator matrix, columns bit-reversed, folded eight index bits at a
/// time: byte[d - 1][b][x] is the XOR of the columns 8 b + i for the set bits i of x.
struct SobolTables {
  uint32_t byte[kSobolTableDimensions][4][256];
};
extern const SobolTables kSobolTables;

/// reverse_bits(sobol_dimension(dimension, index)) for dimension in [1, kSobolTableDimensions]:
/// the form the Owen scramble of SobolSampler works on. The generator is linear over GF(2), so
/// this is the XOR of the columns of index's set bits, one lookup per eight bits (sample indices
/// are mostly below 256: one lookup).
inline uint32_t sobol_dimension_reversed(int dimension, uint32_t index) {
  const auto& table = kSobolTables.byte[dimension - 1];
  uint32_t result = table[0][index & 0xffu];
  for (int byte = 1; (index >>= 8) != 0; ++byte) result ^= table[byte][index & 0xffu];
  return result;
}

/// Sample `index` of Sobol dimension `dimension` in [0, kSobolTableDimensions] as 0.32 fixed
/// point: dimension 0 is the van der Corput sequence, the others come from the direction
/// numbers of Joe and Kuo (file new-joe-kuo-6.21201, its dimensions 2 to 10; dimension 1 is the
/// Pascal matrix mod 2).
inline uint32_t sobol_dimension(int dimension, uint32_t index) {
  return reverse_bits(dimension == 0 ? index : sobol_dimension_reversed(dimension, index));
}

}  // namespace prism
