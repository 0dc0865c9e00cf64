// Sobol dimensions 2 to 9 (core/sobol_dimensions) and the Sobol sampler's chained pairs
// (SobolSampler::get_2d_chained()): the sequence itself, and the joint stratification that the
// path integrator's light samples get from it.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "core/samplers.h"
#include "core/sobol_dimensions.h"

namespace prism {
namespace {

/// Whether every way of splitting `bits` index bits over the coordinates in `dims` (2^bits[k]
/// equal parts on axis k, bits in total) puts exactly `per_cell` of the points in each cell.
bool every_split_holds(const std::vector<const std::vector<double>*>& dims, std::vector<int>& bits,
                       size_t axis, int left, int per_cell) {
  if (axis + 1 < dims.size()) {
    for (int b = 0; b <= left; ++b) {
      bits[axis] = b;
      if (!every_split_holds(dims, bits, axis + 1, left - b, per_cell)) return false;
    }
    return true;
  }
  bits[axis] = left;
  int total = 0;
  for (int b : bits) total += b;
  std::vector<int> cells(size_t(1) << total, 0);
  for (size_t i = 0; i < dims[0]->size(); ++i) {
    size_t cell = 0;
    for (size_t k = 0; k < dims.size(); ++k) {
      cell = (cell << bits[k]) | size_t((*dims[k])[i] * (1 << bits[k]));
    }
    ++cells[cell];
  }
  for (int n : cells) {
    if (n != per_cell) return false;
  }
  return true;
}

/// The smallest t for which the 2^m points whose coordinates are `dims` are a (t, m, s)-net,
/// s = dims.size(): every elementary interval of volume 2^(t - m) holds exactly 2^t of them.
int net_quality(const std::vector<const std::vector<double>*>& dims, int m) {
  for (int t = 0; t <= m; ++t) {
    std::vector<int> bits(dims.size(), 0);
    if (every_split_holds(dims, bits, 0, m - t, 1 << t)) return t;
  }
  return m + 1;
}

TEST(CoreSobolDimensions, DimensionsAreTheSobolSequence) {
  // Indices in binary order (not Gray code). Dimension 2: v1 = 1/2, v2 = 3/4, v3 = 3/8 (from
  // the recurrence of x^2 + x + 1); dimension 3: v1 = 1/2, v2 = 3/4, v3 = 1/8 (m = 1, 3, 1).
  const double dimension2[] = {0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125};
  const double dimension3[] = {0, 0.5, 0.75, 0.25, 0.125, 0.625, 0.875, 0.375};
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(sobol_dimension(2, i) / 4294967296.0, dimension2[i]) << i;
    EXPECT_EQ(sobol_dimension(3, i) / 4294967296.0, dimension3[i]) << i;
  }
  // The byte tables against the definition, a bit at a time (Bratley and Fox's recurrence on
  // the same direction numbers), for every index below 2^16 and random ones up to 2^32.
  struct Numbers {
    int s;
    uint32_t a;
    std::vector<uint32_t> m;
  };
  const Numbers numbers[kSobolChainDimensions] = {
      {2, 1, {1, 3}},          {3, 1, {1, 3, 1}},        {3, 2, {1, 1, 1}},
      {4, 1, {1, 1, 3, 3}},    {4, 4, {1, 3, 5, 13}},    {5, 2, {1, 1, 5, 5, 17}},
      {5, 4, {1, 1, 5, 5, 5}}, {5, 7, {1, 1, 7, 11, 19}}};
  std::mt19937 rng(11);
  for (int k = 0; k < kSobolChainDimensions; ++k) {
    const Numbers& n = numbers[k];
    std::array<uint32_t, 32> v{};
    for (int j = 0; j < 32; ++j) {
      if (j < n.s) {
        v[j] = n.m[j] << (31 - j);
        continue;
      }
      v[j] = v[j - n.s] ^ (v[j - n.s] >> n.s);
      for (int i = 1; i < n.s; ++i) v[j] ^= ((n.a >> (n.s - 1 - i)) & 1u) ? v[j - i] : 0u;
    }
    const auto by_definition = [&](uint32_t index) {
      uint32_t result = 0;
      for (int j = 0; index != 0; ++j, index >>= 1) result ^= (index & 1u) ? v[j] : 0u;
      return result;
    };
    for (uint32_t i = 0; i < (1u << 16); ++i) {
      ASSERT_EQ(sobol_dimension(2 + k, i), by_definition(i)) << "dimension " << 2 + k << " " << i;
    }
    for (int r = 0; r < 10000; ++r) {
      const uint32_t i = uint32_t(rng());
      ASSERT_EQ(sobol_dimension(2 + k, i), by_definition(i)) << "dimension " << 2 + k << " " << i;
    }
    // Every dimension is a (0, 1)-sequence: 2^m consecutive points fill the 2^m intervals.
    std::vector<int> cells(256, 0);
    for (uint32_t i = 0; i < 256; ++i) ++cells[sobol_dimension(2 + k, i) >> 24];
    for (int c : cells) ASSERT_EQ(c, 1) << "dimension " << 2 + k;
  }
}

/// The values of one pixel's 2^m samples: a pair drawn with get_2d() after `pairs_before`
/// others, then `chained` pairs drawn with get_2d_chained(); coordinate lists x0, y0, x1, y1, ...
std::vector<std::vector<double>> chained_values(Sampler& s, int m, glm::ivec2 pixel,
                                                int pairs_before, int chained) {
  std::vector<std::vector<double>> dims(size_t(2 + 2 * chained));
  for (uint32_t i = 0; i < (1u << m); ++i) {
    s.start_pixel_sample(pixel, i);
    for (int p = 0; p < pairs_before; ++p) s.get_2d();
    for (int p = 0; p <= chained; ++p) {
      const Vec2 u = p == 0 ? s.get_2d() : s.get_2d_chained();
      dims[size_t(2 * p)].push_back(u.x);
      dims[size_t(2 * p + 1)].push_back(u.y);
    }
  }
  return dims;
}

TEST(CoreSobolDimensions, ChainedPairsAreStratifiedWithThePairTheyContinue) {
  // Owen scrambles and the permutation of the pixel's indices keep the Sobol points' nets, so
  // every projection of a pixel's chained values is as good a net as the unscrambled Sobol
  // dimensions 0-9 it comes from: dimensions 0-3 are a (2, m, 4)-net, the pairs (t, m, 2)-nets
  // with t at most 2 (mostly 0 or 1). Pairs drawn each on its own (padded) are only nets one
  // pair at a time: over 64 samples their joint t is 4 to 6.
  constexpr int kChained = kSobolChainDimensions / 2;
  constexpr int kDimensions = 2 + 2 * kChained;
  for (int m : {4, 6}) {
    std::vector<std::vector<double>> sobol(kDimensions);
    for (uint32_t i = 0; i < (1u << m); ++i) {
      sobol[0].push_back(sobol_dimension(0, i) / 4294967296.0);
      sobol[1].push_back(sobol_dimension(1, i) / 4294967296.0);
      for (int k = 0; k < kSobolChainDimensions; ++k) {
        sobol[size_t(2 + k)].push_back(sobol_dimension(2 + k, i) / 4294967296.0);
      }
    }
    EXPECT_EQ(net_quality({&sobol[0], &sobol[1], &sobol[2], &sobol[3]}, m), 2) << "m=" << m;
    SobolSampler s(5, 1 << m);
    for (int pixel = 0; pixel < 3; ++pixel) {
      const auto dims = chained_values(s, m, {pixel, 3 * pixel}, pixel, kChained);
      EXPECT_EQ(net_quality({&dims[0], &dims[1], &dims[2], &dims[3]}, m), 2)
          << "m=" << m << " pixel " << pixel;
      for (int a = 0; a < kDimensions; ++a) {
        for (int b = a + 1; b < kDimensions; ++b) {
          const int t = net_quality({&sobol[size_t(a)], &sobol[size_t(b)]}, m);
          if (b == a + 1 && a % 2 == 0) EXPECT_LE(t, 2) << "m=" << m << " pair " << a / 2;
          EXPECT_EQ(net_quality({&dims[size_t(a)], &dims[size_t(b)]}, m), t)
              << "m=" << m << " pixel " << pixel << " dimensions " << a << ", " << b;
        }
      }
    }
  }
}

/// Whether two samplers give the same next pair, `a` by get_2d_chained() and `b` by get_2d().
bool chained_is_fresh_pair(Sampler& a, Sampler& b) {
  const Vec2 u = a.get_2d_chained();
  return u == b.get_2d();
}

TEST(CoreSobolDimensions, ChainsEndAndRestartAsDocumented) {
  for (uint32_t i = 0; i < 16; ++i) {
    SobolSampler a(7, 16), b(7, 16);
    a.start_pixel_sample({2, 5}, i);
    b.start_pixel_sample({2, 5}, i);
    // Before any get_2d() there is no chain: a fresh pair, in the same dimensions.
    EXPECT_TRUE(chained_is_fresh_pair(a, b)) << i;
    // A chain of kSobolChainDimensions / 2 pairs, then the next is a fresh pair that begins
    // the next chain, as get_2d() would.
    for (int p = 0; p < kSobolChainDimensions / 2; ++p) {
      const Vec2 u = a.get_2d_chained();
      EXPECT_EQ(u, b.get_2d_chained()) << i;
    }
    EXPECT_TRUE(chained_is_fresh_pair(a, b)) << i;
    EXPECT_EQ(a.get_2d_chained(), b.get_2d_chained()) << i;
    // 1D values do not break a chain: the chained pair is the same with a get_1d() between.
    SobolSampler c(7, 16), d(7, 16);
    c.start_pixel_sample({2, 5}, i);
    d.start_pixel_sample({2, 5}, i);
    c.get_2d();
    d.get_2d();
    c.get_1d();
    d.skip_dimensions(1);
    EXPECT_EQ(c.get_2d_chained(), d.get_2d_chained()) << i;
  }
  // Past the Sobol dimensions a chained pair is a hashed one, as get_2d() gives it.
  SobolSampler two(5, 64, 2), twin(5, 64, 2);
  for (uint32_t i = 0; i < 8; ++i) {
    two.start_pixel_sample({7, 9}, i);
    twin.start_pixel_sample({7, 9}, i);
    two.get_2d();
    twin.get_2d();
    EXPECT_TRUE(chained_is_fresh_pair(two, twin)) << i;
  }
  // Samplers without chains give get_2d().
  for (const char* name : {"independent", "jittered"}) {
    const auto a = create_sampler(name, 3);
    const auto b = create_sampler(name, 3);
    a->set_sample_count(16);
    b->set_sample_count(16);
    for (uint32_t i = 0; i < 16; ++i) {
      a->start_pixel_sample({1, 2}, i);
      b->start_pixel_sample({1, 2}, i);
      EXPECT_EQ(a->get_2d(), b->get_2d()) << name;
      EXPECT_TRUE(chained_is_fresh_pair(*a, *b)) << name;
    }
  }
}

}  // namespace
}  // namespace prism
