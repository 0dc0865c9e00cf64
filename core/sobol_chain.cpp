#include "core/sobol_chain.h"

namespace prism {
namespace {

/// One dimension's primitive polynomial x^s + a_1 x^(s-1) + ... + a_(s-1) x + 1 (a holds the
/// bits a_1 ... a_(s-1), a_1 highest) and its initial direction numbers m_1 ... m_s.
struct DirectionNumbers {
  int s;
  uint32_t a;
  uint32_t m[6];
};

// new-joe-kuo-6.21201, dimensions 3 to 10.
constexpr DirectionNumbers kDirectionNumbers[kSobolChainDimensions] = {
    {2, 1, {1, 3}},          {3, 1, {1, 3, 1}},         {3, 2, {1, 1, 1}},
    {4, 1, {1, 1, 3, 3}},    {4, 4, {1, 3, 5, 13}},     {5, 2, {1, 1, 5, 5, 17}},
    {5, 4, {1, 1, 5, 5, 5}}, {5, 7, {1, 1, 7, 11, 19}},
};

constexpr uint32_t reverse_bits_constexpr(uint32_t v) {
  uint32_t r = 0;
  for (int i = 0; i < 32; ++i) r |= ((v >> i) & 1u) << (31 - i);
  return r;
}

/// Column j of each dimension's generator matrix, bit-reversed, folded eight index bits at a
/// time into tables as sobol_dimension1_reversed() does: sample indices are mostly below 256,
/// one lookup each.
struct SobolChainTables {
  uint32_t byte[kSobolChainDimensions][4][256];
};

constexpr SobolChainTables make_sobol_chain_tables() {
  SobolChainTables tables{};
  for (int k = 0; k < kSobolChainDimensions; ++k) {
    const DirectionNumbers& d = kDirectionNumbers[k];
    uint32_t v[32] = {};  // direction numbers v_j = m_j / 2^j as 0.32 fixed point
    for (int j = 0; j < d.s; ++j) v[j] = d.m[j] << (31 - j);
    for (int j = d.s; j < 32; ++j) {
      uint32_t x = v[j - d.s] ^ (v[j - d.s] >> d.s);
      for (int i = 1; i < d.s; ++i) {
        if ((d.a >> (d.s - 1 - i)) & 1u) x ^= v[j - i];
      }
      v[j] = x;
    }
    for (uint32_t& column : v) column = reverse_bits_constexpr(column);
    for (int byte = 0; byte < 4; ++byte) {
      for (uint32_t bits = 0; bits < 256; ++bits) {
        uint32_t result = 0;
        for (int bit = 0; bit < 8; ++bit) {
          if ((bits >> bit) & 1u) result ^= v[8 * byte + bit];
        }
        tables.byte[k][byte][bits] = result;
      }
    }
  }
  return tables;
}

constexpr SobolChainTables kSobolChainTables = make_sobol_chain_tables();

}  // namespace

uint32_t sobol_chain_dimension_reversed(int k, uint32_t index) {
  const auto& table = kSobolChainTables.byte[k];
  uint32_t result = table[0][index & 0xffu];
  for (int byte = 1; (index >>= 8) != 0; ++byte) result ^= table[byte][index & 0xffu];
  return result;
}

uint32_t sobol_chain_dimension(int k, uint32_t index) {
  return reverse_bits_constexpr(sobol_chain_dimension_reversed(k, index));
}

}  // namespace prism
