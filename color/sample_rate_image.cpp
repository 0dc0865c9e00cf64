#include "color/sample_rate_image.h"

#include <algorithm>

#include "core/math.h"

namespace prism {
namespace {

// A jet-like ramp: blue -> cyan -> green -> yellow -> red as rate goes 0 -> 1.
Rgb rate_color(float rate) {
  const float r = glm::clamp(1.5f - std::abs(4.0f * rate - 3.0f), 0.0f, 1.0f);
  const float g = glm::clamp(1.5f - std::abs(4.0f * rate - 2.0f), 0.0f, 1.0f);
  const float b = glm::clamp(1.5f - std::abs(4.0f * rate - 1.0f), 0.0f, 1.0f);
  return {r, g, b};
}

}  // namespace

std::optional<Image> make_sample_rate_image(const Image& image) {
  const auto it =
      std::find(image.channel_names.begin(), image.channel_names.end(), "sampleCount.Y");
  if (it == image.channel_names.end()) return std::nullopt;
  const int channel = static_cast<int>(it - image.channel_names.begin());
  float max_count = 0.0f;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) max_count = std::max(max_count, image.at(x, y, channel));
  }
  Image out;
  out.width = image.width;
  out.height = image.height;
  out.channel_names = {"R", "G", "B"};
  out.pixels.resize(size_t(out.width) * out.height * 3);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float rate = max_count > 0.0f ? image.at(x, y, channel) / max_count : 0.0f;
      const Rgb c = rate_color(rate);
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = c[k];
    }
  }
  return out;
}

}  // namespace prism
