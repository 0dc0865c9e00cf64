#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "core/param_set.h"
#include "core/registry.h"
#include "core/sampler.h"
#include "core/sobol_dimensions.h"

namespace prism {

/// Stratified samples: every dimension (and every 2D pair) of the samples of one pixel is
/// divided into n x n strata, n = ceil(sqrt(samples per pixel)); each block of n^2 consecutive
/// sample indices visits every stratum once, in a random order per (pixel, dimension), with an
/// independent uniform jitter inside the stratum.
class JitteredSampler final : public Sampler {
 public:
  explicit JitteredSampler(uint64_t seed, int samples_per_pixel = 1);
  std::string_view name() const override { return "jittered"; }
  void start_pixel_sample(glm::ivec2 pixel, uint32_t index) override;
  float get_1d() override;
  Vec2 get_2d() override;
  void skip_dimensions(uint32_t count) override { dimension_ += count; }
  std::unique_ptr<Sampler> clone() const override;
  void set_sample_count(int samples_per_pixel) override;

 private:
  uint64_t seed_;
  uint64_t seed_hash_;  ///< the seed's part of the dimension hashes
  uint32_t strata_per_axis_ = 1;
  uint64_t pixel_hash_ = 0;  ///< the pixel's and seed's part of the dimension hashes
  uint32_t index_ = 0;
  uint32_t dimension_ = 0;
};

/// Owen-scrambled Sobol points, "padded": every 2D pair uses the first two Sobol dimensions (a
/// (0,2)-sequence) and every 1D value the first, each with its own scramble and its own random
/// permutation of the pixel's sample indices per (pixel, dimension), which decorrelates the
/// dimensions. With a power-of-two sample count every pair of a pixel is a (0,m,2)-net.
///
/// get_2d_chained() continues the last get_2d()'s point: the same permuted index in Sobol
/// dimensions 2, 3, then 4, 5, ... (kSobolChainDimensions of them, core/sobol_dimensions.h), each
/// with its own scramble, so that with a power-of-two count the chained pairs and the pair they
/// continue are one scrambled Sobol point set of up to ten dimensions, stratified jointly. The
/// path integrator chains a light sample to the direction sampled at the vertex before it:
/// relMSE 8-14% lower on the diffuse CS184 scenes at 64 spp (docs/PERFORMANCE.md).
///
/// Only the first `sobol_dimensions` dimensions (default kSobolDimensions: the camera's four and
/// the first two bounces of a path) are Sobol points; later ones are independent uniform values
/// from a hash of (pixel, index, dimension, seed). Stratifying deep bounces buys nothing at
/// render sample counts (measured: relMSE no better with every dimension stratified) and the
/// permutation and scrambles cost about ten times the hash (docs/PERFORMANCE.md).
class SobolSampler final : public Sampler {
 public:
  /// Dimensions stratified by default.
  static constexpr uint32_t kSobolDimensions = 16;

  explicit SobolSampler(uint64_t seed, int samples_per_pixel = 1,
                        uint32_t sobol_dimensions = kSobolDimensions);
  std::string_view name() const override { return "sobol"; }
  void start_pixel_sample(glm::ivec2 pixel, uint32_t index) override;
  float get_1d() override;
  Vec2 get_2d() override;
  Vec2 get_2d_chained() override;
  void skip_dimensions(uint32_t count) override { dimension_ += count; }
  std::unique_ptr<Sampler> clone() const override;
  void set_sample_count(int samples_per_pixel) override;

 private:
  /// The permuted Sobol index of the current sample in the dimension keyed by
  /// `dimension_hash`: permutation_element(index % n, n, ...) offset by its block of n.
  uint32_t permuted_index(uint64_t dimension_hash) const;
  /// 64 uniform bits for the current dimension past the Sobol ones.
  uint64_t hashed_bits() const;

  uint64_t seed_;
  uint64_t seed_hash_;  ///< the seed's part of the dimension hashes
  uint32_t sobol_dimensions_;
  uint32_t samples_per_pixel_ = 1;
  uint32_t permutation_bits_ = 0;  ///< bit width of samples_per_pixel_ - 1
  uint64_t pixel_hash_ = 0;        ///< the pixel's and seed's part of the dimension hashes
  uint64_t sample_hash_ = 0;       ///< pixel_hash_ and the index, for the hashed dimensions
  uint32_t index_in_block_ = 0;    ///< index % samples_per_pixel_
  uint32_t block_ = 0;             ///< index / samples_per_pixel_
  uint32_t dimension_ = 0;
  uint32_t chain_index_ = 0;  ///< the permuted Sobol index of the last get_2d()
  int chain_next_ = 0;  ///< the chain goes on in dimension 2 + this; kSobolChainDimensions: ended
};

/// Element `index` (< count) of a pseudo-random permutation of [0, count) chosen by `seed`:
/// a bijection for every seed, computed in O(1) expected time without tables.
uint32_t permutation_element(uint32_t index, uint32_t count, uint64_t seed);

/// A nested uniform (Owen) scramble of the 0.32 fixed-point value `v`: each bit is flipped by
/// a pseudo-random function of the more significant bits and `seed` (hash-based, after Burley,
/// "Practical Hash-based Owen Scrambling", 2020).
uint32_t owen_scramble(uint32_t v, uint32_t seed);

/// The table of samplers: independent, jittered, sobol. Factories read "sampler.seed" (default
/// 0) and "sampler.spp" (default 1; the tile loop also calls set_sample_count()); sobol also
/// "sampler.sobol_dimensions" (default SobolSampler::kSobolDimensions).
const Registry<Sampler>& sampler_registry();

/// sampler_registry().create(name, params) with "sampler.seed" set to `seed` (unless params
/// already hold it).
std::unique_ptr<Sampler> create_sampler(std::string_view name, uint64_t seed,
                                        const ParamSet& params = {});

}  // namespace prism
