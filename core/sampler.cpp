#include "core/sampler.h"

namespace prism {

uint64_t mix_bits(uint64_t v) {
  v ^= v >> 30;
  v *= 0xbf58476d1ce4e5b9ULL;
  v ^= v >> 27;
  v *= 0x94d049bb133111ebULL;
  v ^= v >> 31;
  return v;
}

float bits_to_unit_float(uint32_t bits) {
  // 24 significant bits: exactly representable, strictly below 1.
  return static_cast<float>(bits >> 8) * 0x1p-24f;
}

void IndependentSampler::start_pixel_sample(glm::ivec2 pixel, uint32_t index) {
  const uint64_t pixel_key = (uint64_t(uint32_t(pixel.x)) << 32) | uint32_t(pixel.y);
  stream_ = mix_bits(mix_bits(pixel_key ^ mix_bits(seed_)) + index);
  dimension_ = 0;
}

float IndependentSampler::get_1d() {
  return bits_to_unit_float(static_cast<uint32_t>(mix_bits(stream_ + dimension_++) >> 32));
}

Vec2 IndependentSampler::get_2d() {
  const float a = get_1d();
  const float b = get_1d();
  return {a, b};
}

std::unique_ptr<Sampler> IndependentSampler::clone() const {
  return std::make_unique<IndependentSampler>(seed_);
}

}  // namespace prism
