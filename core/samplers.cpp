#include "core/samplers.h"

#include <bit>
#include <cmath>
#include <string>

namespace prism {
namespace {

uint64_t key_of(glm::ivec2 pixel) {
  return (uint64_t(uint32_t(pixel.x)) << 32) | uint32_t(pixel.y);
}

/// The hash of (pixel, dimension, seed) that keys one dimension's permutation and scramble is
/// dimension_hash(pixel_hash(key_of(pixel), seed_hash(seed)), dimension): the parts that do
/// not change from one dimension to the next are computed once per seed and per pixel sample.
uint64_t seed_hash(uint64_t seed) { return mix_bits(seed + 0x9e3779b97f4a7c15ULL); }
uint64_t pixel_hash(uint64_t pixel_key, uint64_t seed_hash) {
  return mix_bits(pixel_key ^ seed_hash);
}
uint64_t dimension_hash(uint64_t pixel_hash, uint32_t dimension) {
  return mix_bits(pixel_hash + uint64_t(dimension) * 0xd1b54a32d192ed03ULL);
}

/// The body of owen_scramble() on an already bit-reversed value: owen_scramble(v, seed) ==
/// reverse_bits(owen_scramble_reversed(reverse_bits(v), seed)).
uint32_t owen_scramble_reversed(uint32_t x, uint32_t seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

/// permutation_element() with its count's bit width precomputed (`bits` = bit_width(count -
/// 1), count > 1): the same bijection step for step.
uint32_t permutation_element_of_width(uint32_t index, uint32_t count, int bits, uint64_t seed) {
  const uint32_t mask = bits >= 32 ? 0xffffffffu : (1u << bits) - 1u;
  const int shift = std::max(1, bits / 2);
  const uint32_t a = uint32_t(seed) & mask;
  const uint32_t m = (uint32_t(seed >> 32) | 1u) & mask;  // odd: invertible modulo 2^bits
  const uint32_t c = uint32_t(mix_bits(seed) >> 32) & mask;
  uint32_t v = index;
  do {
    // Every step is invertible modulo 2^bits.
    v ^= a;
    v = (v * m) & mask;
    v ^= v >> shift;
    v = (v + c) & mask;
    v = (v * 0x9e3779b1u) & mask;
    v ^= v >> shift;
  } while (v >= count);
  return v;
}

uint32_t positive_count(int n) { return n > 0 ? uint32_t(n) : 1u; }

}  // namespace

uint32_t permutation_element(uint32_t index, uint32_t count, uint64_t seed) {
  if (count <= 1) return 0;
  // A bijection on k-bit integers (k = bit width of count - 1), iterated until the value is in
  // [0, count) again ("cycle walking"): the cycle through `index` returns into the range, so
  // the restriction is a permutation of [0, count).
  return permutation_element_of_width(index, count, std::bit_width(count - 1), seed);
}

uint32_t owen_scramble(uint32_t v, uint32_t seed) {
  // After reversal, the most significant bit of the value is the least significant bit of x.
  // Adding, multiplying and xoring with x * even only carry information from low to high bits,
  // so each output bit depends on itself (flipped or not) and on less significant bits of x:
  // a nested scramble of the original value.
  return reverse_bits(owen_scramble_reversed(reverse_bits(v), seed));
}

// ---- JitteredSampler -------------------------------------------------------------------

JitteredSampler::JitteredSampler(uint64_t seed, int samples_per_pixel)
    : seed_(seed), seed_hash_(seed_hash(seed)) {
  set_sample_count(samples_per_pixel);
}

void JitteredSampler::set_sample_count(int samples_per_pixel) {
  strata_per_axis_ = uint32_t(std::ceil(std::sqrt(double(positive_count(samples_per_pixel)))));
}

void JitteredSampler::start_pixel_sample(glm::ivec2 pixel, uint32_t index) {
  pixel_hash_ = pixel_hash(key_of(pixel), seed_hash_);
  index_ = index;
  dimension_ = 0;
}

float JitteredSampler::get_1d() {
  const uint64_t h = dimension_hash(pixel_hash_, dimension_++);
  const uint32_t strata = strata_per_axis_ * strata_per_axis_;
  const uint32_t round = index_ / strata;
  const uint32_t stratum = permutation_element(index_ % strata, strata, mix_bits(h + round));
  const float jitter = bits_to_unit_float(uint32_t(mix_bits(h ^ (uint64_t(index_) << 1)) >> 32));
  return std::min((float(stratum) + jitter) / float(strata), 0x1.fffffep-1f);
}

Vec2 JitteredSampler::get_2d() {
  const uint64_t h = dimension_hash(pixel_hash_, dimension_);
  dimension_ += 2;
  const uint32_t n = strata_per_axis_;
  const uint32_t strata = n * n;
  const uint32_t round = index_ / strata;
  const uint32_t stratum = permutation_element(index_ % strata, strata, mix_bits(h + round));
  const uint64_t j = mix_bits(h ^ (uint64_t(index_) << 1));
  const float jx = bits_to_unit_float(uint32_t(j >> 32));
  const float jy = bits_to_unit_float(uint32_t(j));
  return {std::min((float(stratum % n) + jx) / float(n), 0x1.fffffep-1f),
          std::min((float(stratum / n) + jy) / float(n), 0x1.fffffep-1f)};
}

std::unique_ptr<Sampler> JitteredSampler::clone() const {
  auto copy = std::make_unique<JitteredSampler>(seed_);
  copy->strata_per_axis_ = strata_per_axis_;
  return copy;
}

// ---- SobolSampler ----------------------------------------------------------------------

SobolSampler::SobolSampler(uint64_t seed, int samples_per_pixel, uint32_t sobol_dimensions)
    : seed_(seed), seed_hash_(seed_hash(seed)), sobol_dimensions_(sobol_dimensions) {
  set_sample_count(samples_per_pixel);
}

void SobolSampler::set_sample_count(int samples_per_pixel) {
  samples_per_pixel_ = positive_count(samples_per_pixel);
  permutation_bits_ = uint32_t(std::bit_width(samples_per_pixel_ - 1));
}

void SobolSampler::start_pixel_sample(glm::ivec2 pixel, uint32_t index) {
  pixel_hash_ = pixel_hash(key_of(pixel), seed_hash_);
  // Indices past the sample count form further blocks, each permuted on its own, so that any
  // index stays valid. The split does not depend on the dimension: done once here.
  block_ = index / samples_per_pixel_;
  index_in_block_ = index % samples_per_pixel_;
  sample_hash_ = mix_bits(pixel_hash_ ^ (uint64_t(index) * 0x9e3779b97f4a7c15ULL));
  dimension_ = 0;
  chain_next_ = kSobolChainDimensions;  // no chain yet
}

uint64_t SobolSampler::hashed_bits() const {
  return mix_bits(sample_hash_ + uint64_t(dimension_) * 0xd1b54a32d192ed03ULL);
}

uint32_t SobolSampler::permuted_index(uint64_t h) const {
  const uint32_t n = samples_per_pixel_;
  if (n <= 1) return block_;
  // The permutation's key: the dimension hash turned, so that the permutation's constants (the
  // low bits of each half of the key) come from other bits than the scrambles' additive low
  // bits, and varied per block. No mix_bits() of its own: the dimension hash is already well
  // mixed (permutation_element_of_width() derives one more constant from it with mix_bits()).
  const uint64_t key = std::rotl(h, 23) ^ (uint64_t(block_) * 0x9e3779b97f4a7c15ULL);
  return block_ * n + permutation_element_of_width(index_in_block_, n, int(permutation_bits_), key);
}

// The scrambles below work on bit-reversed values: sobol_dimension(0, i) is reverse_bits(i), so
// owen_scramble(sobol_dimension(0, i), s) is reverse_bits(owen_scramble_reversed(i, s)), and the
// other dimensions are tabled reversed; the values are those of owen_scramble() bit for bit.

float SobolSampler::get_1d() {
  if (dimension_ >= sobol_dimensions_) {
    const uint64_t bits = hashed_bits();
    ++dimension_;
    return bits_to_unit_float(uint32_t(bits >> 32));
  }
  const uint64_t h = dimension_hash(pixel_hash_, dimension_++);
  const uint32_t i = permuted_index(h);
  return bits_to_unit_float(reverse_bits(owen_scramble_reversed(i, uint32_t(h >> 32))));
}

Vec2 SobolSampler::get_2d() {
  if (dimension_ >= sobol_dimensions_) {
    const uint64_t bits = hashed_bits();
    dimension_ += 2;
    chain_next_ = kSobolChainDimensions;  // hashed values begin no chain
    return {bits_to_unit_float(uint32_t(bits >> 32)), bits_to_unit_float(uint32_t(bits))};
  }
  const uint64_t h = dimension_hash(pixel_hash_, dimension_);
  dimension_ += 2;
  const uint32_t i = permuted_index(h);
  chain_index_ = i;
  chain_next_ = 0;
  return {bits_to_unit_float(reverse_bits(owen_scramble_reversed(i, uint32_t(h >> 32)))),
          bits_to_unit_float(
              reverse_bits(owen_scramble_reversed(sobol_dimension_reversed(1, i), uint32_t(h))))};
}

Vec2 SobolSampler::get_2d_chained() {
  if (dimension_ >= sobol_dimensions_ || chain_next_ + 2 > kSobolChainDimensions) return get_2d();
  // The dimension's own hash gives the two scrambles, as in get_2d(); the index is the chain's.
  const uint64_t h = dimension_hash(pixel_hash_, dimension_);
  dimension_ += 2;
  const int k = chain_next_;
  chain_next_ += 2;
  return {bits_to_unit_float(reverse_bits(owen_scramble_reversed(
              sobol_dimension_reversed(2 + k, chain_index_), uint32_t(h >> 32)))),
          bits_to_unit_float(reverse_bits(
              owen_scramble_reversed(sobol_dimension_reversed(3 + k, chain_index_), uint32_t(h))))};
}

std::unique_ptr<Sampler> SobolSampler::clone() const {
  auto copy = std::make_unique<SobolSampler>(seed_, int(samples_per_pixel_), sobol_dimensions_);
  return copy;
}

// ---- registry --------------------------------------------------------------------------

namespace {

uint64_t seed_param(const ParamSet& params) {
  return uint64_t(params.get_int("sampler.seed", 0, 0, std::numeric_limits<long long>::max()));
}
int spp_param(const ParamSet& params) {
  return int(params.get_int("sampler.spp", 1, 1, std::numeric_limits<int>::max()));
}

}  // namespace

const Registry<Sampler>& sampler_registry() {
  using Entry = Registry<Sampler>::Entry;
  static const Registry<Sampler> registry(
      "sampler",
      {
          Entry{"independent",
                "uniform random values from a hash of (pixel, index, dimension, seed)",
                [](const ParamSet& p) -> std::unique_ptr<Sampler> {
                  return std::make_unique<IndependentSampler>(seed_param(p));
                }},
          Entry{"jittered", "n x n strata per dimension pair, n = ceil(sqrt(spp)), jittered",
                [](const ParamSet& p) -> std::unique_ptr<Sampler> {
                  return std::make_unique<JitteredSampler>(seed_param(p), spp_param(p));
                }},
          Entry{"sobol",
                "Owen-scrambled Sobol (0,2)-sequence per dimension pair, padded by per-pixel "
                "index permutations, for the first sampler.sobol_dimensions (" +
                    std::to_string(SobolSampler::kSobolDimensions) +
                    ") dimensions; chained pairs continue a pair's point in Sobol dimensions "
                    "2-9",
                [](const ParamSet& p) -> std::unique_ptr<Sampler> {
                  return std::make_unique<SobolSampler>(
                      seed_param(p), spp_param(p),
                      uint32_t(p.get_int("sampler.sobol_dimensions", SobolSampler::kSobolDimensions,
                                         0, 1 << 30)));
                }},
      });
  return registry;
}

std::unique_ptr<Sampler> create_sampler(std::string_view name, uint64_t seed,
                                        const ParamSet& params) {
  ParamSet copy = params;
  if (!copy.has("sampler.seed")) copy.set("sampler.seed", std::to_string(seed));
  return sampler_registry().create(name, copy);
}

}  // namespace prism
