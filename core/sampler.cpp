#include "core/sampler.h"

namespace prism {

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
