#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "core/math.h"

namespace prism {

/// Source of sample values in [0, 1). Every value is a pure function of (pixel, sample index,
/// dimension, seed), so images do not depend on thread count, tile order or scheduling.
/// A Sampler instance is used by one thread at a time; clone() one per thread.
class Sampler {
 public:
  virtual ~Sampler() = default;
  virtual std::string_view name() const = 0;
  /// Positions the sampler at sample `index` of `pixel`; the dimension counter restarts at 0.
  virtual void start_pixel_sample(glm::ivec2 pixel, uint32_t index) = 0;
  /// The next dimension's value in [0, 1).
  virtual float get_1d() = 0;
  /// The next two dimensions' values in [0, 1)^2.
  virtual Vec2 get_2d() = 0;
  /// The next two dimensions' values in [0, 1)^2, drawn as further dimensions of the point the
  /// last get_2d() began, so that the pairs of a chain are stratified jointly, not each on its
  /// own: for values whose integrand is smooth across them (a path's direction at one vertex and
  /// its light sample and direction at the next). Samplers without such points, and a chain that
  /// has run out, return get_2d() (which begins a new chain). 1D values between do not break it.
  virtual Vec2 get_2d_chained() { return get_2d(); }
  /// Passes over the next `count` dimensions without computing their values: the dimensions
  /// after them get the values they would have had (a pinhole camera's lens pair).
  virtual void skip_dimensions(uint32_t count) = 0;
  virtual std::unique_ptr<Sampler> clone() const = 0;
  /// Tells the sampler how many samples per pixel the render takes (stratified samplers size
  /// their strata from it; sample indices beyond it stay valid). Call before the first
  /// start_pixel_sample(); clone() keeps the setting. The default ignores it.
  virtual void set_sample_count(int samples_per_pixel) {}
};

/// Uniform independent samples from a counter-based hash of (pixel, index, dimension, seed).
class IndependentSampler final : public Sampler {
 public:
  explicit IndependentSampler(uint64_t seed) : seed_(seed) {}
  std::string_view name() const override { return "independent"; }
  void start_pixel_sample(glm::ivec2 pixel, uint32_t index) override;
  float get_1d() override;
  Vec2 get_2d() override;
  void skip_dimensions(uint32_t count) override { dimension_ += count; }
  std::unique_ptr<Sampler> clone() const override;

 private:
  uint64_t seed_;
  uint64_t stream_ = 0;
  uint32_t dimension_ = 0;
};

/// 64-bit finalizer (SplitMix64): a bijective avalanche hash. Inline: samplers call it for
/// every dimension of every sample.
inline uint64_t mix_bits(uint64_t v) {
  v ^= v >> 30;
  v *= 0xbf58476d1ce4e5b9ULL;
  v ^= v >> 27;
  v *= 0x94d049bb133111ebULL;
  v ^= v >> 31;
  return v;
}
/// Maps 32 random bits to a float in [0, 1).
inline float bits_to_unit_float(uint32_t bits) {
  // 24 significant bits: exactly representable, strictly below 1.
  return static_cast<float>(bits >> 8) * 0x1p-24f;
}

}  // namespace prism
