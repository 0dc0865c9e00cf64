#pragma once

// Bit-exact comparison of rendered images, for the tests that check that a render split into
// passes, threads, runs, crops or sample ranges gives the same bits as one uninterrupted render.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "color/image_output.h"
#include "core/image.h"

namespace prism::test {

namespace detail {
inline uint32_t float_bits(float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}
}  // namespace detail

/// The image of an EXR file (the first image of a checkpoint or part file).
inline Image read_exr_image(const std::filesystem::path& path) {
  return read_image_file(path).image;
}

/// The values of channel `name` ("sampleCount.Y") of every pixel, row by row; empty when the
/// image has no such channel.
inline std::vector<float> channel_values(const Image& image, const std::string& name) {
  const auto it = std::find(image.channel_names.begin(), image.channel_names.end(), name);
  std::vector<float> values;
  if (it == image.channel_names.end()) return values;
  const int c = int(it - image.channel_names.begin());
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) values.push_back(image.at(x, y, c));
  }
  return values;
}

/// Whether `part` (an image or a window of one) equals the same pixels of `full` in every
/// channel, bit for bit: the same channels in the same order, every value's bits. `part`'s
/// place (x, y) in the full image says which pixels of `full` it is compared with; `full`
/// covers its whole image. The message names the first difference and how many values differ.
inline ::testing::AssertionResult same_bits_in(const Image& part, const Image& full) {
  if (part.channel_names != full.channel_names) {
    return ::testing::AssertionFailure() << "the channels differ";
  }
  if (full.x != 0 || full.y != 0 || part.x < 0 || part.y < 0 || part.x + part.width > full.width ||
      part.y + part.height > full.height) {
    return ::testing::AssertionFailure()
           << part.width << "x" << part.height << " at (" << part.x << ", " << part.y
           << ") is not inside the full image " << full.width << "x" << full.height;
  }
  const int channels = part.channels();
  size_t differing = 0;
  std::ostringstream first;
  for (int y = 0; y < part.height; ++y) {
    for (int x = 0; x < part.width; ++x) {
      for (int c = 0; c < channels; ++c) {
        const float a = part.at(x, y, c);
        const float b = full.at(part.x + x, part.y + y, c);
        if (detail::float_bits(a) == detail::float_bits(b)) continue;
        if (differing++ == 0) {
          first << "pixel (" << part.x + x << ", " << part.y + y << ") "
                << part.channel_names[size_t(c)] << ": " << a << " vs " << b;
        }
      }
    }
  }
  if (differing == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << differing << " of " << part.pixels.size() << " values differ, first at " << first.str();
}

/// Whether two images have the same size, place and channels, and the same bits everywhere.
inline ::testing::AssertionResult same_bits(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.x != b.x || a.y != b.y) {
    return ::testing::AssertionFailure()
           << a.width << "x" << a.height << " at (" << a.x << ", " << a.y << ") vs " << b.width
           << "x" << b.height << " at (" << b.x << ", " << b.y << ")";
  }
  Image a_full = a, b_full = b;  // compare as whole images: the places are equal
  a_full.x = a_full.y = b_full.x = b_full.y = 0;
  return same_bits_in(a_full, b_full);
}

}  // namespace prism::test
