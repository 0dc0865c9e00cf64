#pragma once

#include <string>
#include <vector>

namespace prism {

/// A float image with named, interleaved channels ("R", "G", "B", "albedo.R", "Z", ...).
/// Row 0 is the top row. Plain data handed from the film to the writers.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::string> channel_names;
  std::vector<float> pixels;  ///< width * height * channels, row-major, interleaved

  int channels() const { return static_cast<int>(channel_names.size()); }
  float& at(int x, int y, int c) { return pixels[(size_t(y) * width + x) * channels() + c]; }
  float at(int x, int y, int c) const { return pixels[(size_t(y) * width + x) * channels() + c]; }
  /// Number of values that are NaN or infinite.
  size_t count_non_finite() const;
};

}  // namespace prism
