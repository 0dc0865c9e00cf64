#pragma once

#include <string>
#include <vector>

#include "core/huge_page_allocator.h"

namespace prism {

/// The storage of Image::pixels.
using ImagePixels = std::vector<float, HugePageAllocator<float>>;

/// A float image with named, interleaved channels ("R", "G", "B", "albedo.R", "Z", ...).
/// Row 0 is the top row. Plain data handed from the film to the writers. An image may be a
/// window of a larger one (a crop): (x, y) is the place of its top-left pixel in the full
/// full_width x full_height image (EXR's data window inside its display window).
struct Image {
  int width = 0;
  int height = 0;
  int x = 0;
  int y = 0;
  int full_width = 0;   ///< 0: the same as width
  int full_height = 0;  ///< 0: the same as height
  std::vector<std::string> channel_names;
  /// width * height * channels, row-major, interleaved; in huge pages when large (a film
  /// resolves to 15 channels: 10 MB at 480 x 360, copied again on the way to the file).
  ImagePixels pixels;

  int channels() const { return static_cast<int>(channel_names.size()); }
  float& at(int x, int y, int c) { return pixels[(size_t(y) * width + x) * channels() + c]; }
  float at(int x, int y, int c) const { return pixels[(size_t(y) * width + x) * channels() + c]; }
  /// Whether the image covers less than its full image.
  bool is_window() const {
    return x != 0 || y != 0 || (full_width != 0 && full_width != width) ||
           (full_height != 0 && full_height != height);
  }
  /// Number of values that are NaN or infinite.
  size_t count_non_finite() const;
};

}  // namespace prism
