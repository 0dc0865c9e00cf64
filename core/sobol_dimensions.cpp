#include "core/sobol_dimensions.h"

namespace prism {
namespace {

/// One dimension's primitive polynomial x^s + a_1 x^(s-1) + ... + a_(s-1) x + 1 (a holds the
/// bits a_1 ... a_(s-1), a_1 highest) and its initial direction numbers m_1 ... m_s.
struct DirectionNumbers {
  int s;
  uint32_t a;
  uint32_t m[6];
};

// new-joe-kuo-6.21201, dimensions 2 to 10 (Sobol dimensions 1 to 9 here, counted from 0).
constexpr DirectionNumbers kDirectionNumbers[kSobolTableDimensions] = {
    {1, 0, {1}},
    {2, 1, {1, 3}},
    {3, 1, {1, 3, 1}},
    {3, 2, {1, 1, 1}},
    {4, 1, {1, 1, 3, 3}},
    {4, 4, {1, 3, 5, 13}},
    {5, 2, {1, 1, 5, 5, 17}},
    {5, 4, {1, 1, 5, 5, 5}},
    {5, 7, {1, 1, 7, 11, 19}},
};

constexpr SobolTables make_sobol_tables() {
  SobolTables tables{};
  for (int d = 0; d < kSobolTableDimensions; ++d) {
    const DirectionNumbers& n = kDirectionNumbers[d];
    uint32_t v[32] = {};  // direction numbers v_j = m_j / 2^j as 0.32 fixed point
    for (int j = 0; j < n.s; ++j) v[j] = n.m[j] << (31 - j);
    for (int j = n.s; j < 32; ++j) {
      uint32_t x = v[j - n.s] ^ (v[j - n.s] >> n.s);
      for (int i = 1; i < n.s; ++i) {
        if ((n.a >> (n.s - 1 - i)) & 1u) x ^= v[j - i];
      }
      v[j] = x;
    }
    for (uint32_t& column : v) column = reverse_bits(column);
    for (int byte = 0; byte < 4; ++byte) {
      for (uint32_t bits = 0; bits < 256; ++bits) {
        uint32_t result = 0;
        for (int bit = 0; bit < 8; ++bit) {
          if ((bits >> bit) & 1u) result ^= v[8 * byte + bit];
        }
        tables.byte[d][byte][bits] = result;
      }
    }
  }
  return tables;
}

}  // namespace

constexpr SobolTables kSobolTables = make_sobol_tables();

}  // namespace prism
