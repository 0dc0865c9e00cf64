#pragma once

#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include "core/huge_page_allocator.h"
#include "core/image.h"
#include "core/math.h"

namespace prism {

/// Arbitrary output values of one camera sample, taken at the camera ray's first hit (zero
/// where the ray escapes).
struct AovSample {
  Rgb albedo{0.0f};    ///< surface colour in [0,1]^3
  Vec3 normal{0.0f};   ///< world-space unit shading normal
  float depth = 0.0f;  ///< distance from the ray origin to the hit
};

/// A rectangle of pixels [begin, end) of an image.
struct PixelRect {
  glm::ivec2 begin{0, 0};
  glm::ivec2 end{0, 0};

  /// The sides, for a rectangle whose sides fit an int (any rectangle inside a film).
  int width() const { return end.x - begin.x; }
  int height() const { return end.y - begin.y; }
  /// Exact for any corners (a rectangle read from a file may have any): 0 when empty.
  size_t pixel_count() const {
    return empty() ? 0 : size_t(int64_t(end.x) - begin.x) * size_t(int64_t(end.y) - begin.y);
  }
  bool empty() const { return end.x <= begin.x || end.y <= begin.y; }
  bool contains(glm::ivec2 p) const {
    return p.x >= begin.x && p.y >= begin.y && p.x < end.x && p.y < end.y;
  }
  bool contains(const PixelRect& r) const {
    return r.begin.x >= begin.x && r.begin.y >= begin.y && r.end.x <= end.x && r.end.y <= end.y;
  }
  bool operator==(const PixelRect&) const = default;
};

/// Signed 128-bit integer (GCC/Clang): the film's exact sums.
using Int128 = __int128;

/// Everything the film keeps of one pixel. Sums are fixed-point integers, so that adding the
/// same samples in any order, on any thread or machine, and summing partial films, gives the
/// same bits (floating-point addition is not associative; integer addition is). Plain data
/// with a fixed layout: checkpoints and part files store it as it is (FilmPixel::kWords
/// little-endian 32-bit words).
struct FilmPixel {
  /// Sum of radiance samples x 2^kValueShift, per channel (samples clamped to +-kValueLimit).
  Int128 radiance[3];
  /// Sum of squared radiance samples x 2^kSquareShift (squares clamped to kSquareLimit).
  Int128 radiance_squared[3];
  /// Sum of depths x 2^kValueShift (clamped to kValueLimit).
  Int128 depth;
  /// Sums of albedo and shading-normal components x 2^kUnitShift (components clamped to
  /// [-1, 1]).
  int64_t albedo[3];
  int64_t normal[3];
  /// Adaptive sampling: sums of the samples' luminance and its square, in sample order.
  double illuminance;
  double illuminance_squared;
  uint32_t samples;     ///< samples added
  uint32_t progress;    ///< samples of the schedule processed: the next sample index to take
  uint32_t converged;   ///< 1 once adaptive sampling stopped the pixel
  uint32_t unused = 0;  ///< padding, always 0

  static constexpr int kValueShift = 50;
  static constexpr double kValueLimit = 0x1p50;
  static constexpr int kSquareShift = 40;
  static constexpr double kSquareLimit = 0x1p60;
  static constexpr int kUnitShift = 40;
  static constexpr int kWords = 48;
};
static_assert(sizeof(FilmPixel) == FilmPixel::kWords * 4, "FilmPixel is stored word by word");

/// Largest film prism makes or reads back: large enough for any real render, small enough that
/// counters cannot overflow and a typo or a hostile file cannot ask for a film (about 200 bytes
/// per pixel, plus the images written from it) that exhausts memory.
inline constexpr int kMaxFilmSide = 16384;
inline constexpr long long kMaxFilmPixels = 1LL << 25;  // 8K UHD (7680 x 4320) fits

/// Accumulates the camera samples of the pixels in `window` of a width x height image: exact
/// sums of radiance, its square and the AOVs per pixel, plus the adaptive sampler's state and
/// how far the render schedule got. add_sample() for different pixels may run concurrently;
/// one pixel is written by one thread at a time (the tile loops guarantee it). Non-finite
/// samples count as zero radiance and are counted, so no NaN or Inf reaches an image.
///
/// Precision: each sample is converted to fixed point once (truncating below 2^-50 for
/// radiance and depth, 2^-40 for squares and unit vectors), which is exact for every float
/// above 2^-26 (radiance, depth) and far below what any image format stores; resolve() divides
/// the exact sums once. Radiance and depth above 2^50 (about 1e15) and squares above 2^60 are
/// clamped; no real render reaches them.
class Film {
 public:
  /// A film for the whole width x height image.
  Film(int width, int height);
  /// A film for the pixels `window` (inside the image) of a width x height image.
  Film(int width, int height, const PixelRect& window);
  Film(Film&& other) noexcept;
  Film& operator=(Film&& other) noexcept;

  /// The full image's size: camera rays are generated over it, whatever the window.
  int width() const { return width_; }
  int height() const { return height_; }
  /// The pixels this film holds.
  const PixelRect& window() const { return window_; }

  /// Adds one sample to `pixel` (inside window()).
  void add_sample(glm::ivec2 pixel, const Rgb& radiance, const AovSample& aovs = {});
  /// The state of `pixel` (inside window()), for the tile loops and for storage.
  FilmPixel& pixel(glm::ivec2 p) { return pixels_[index(p)]; }
  const FilmPixel& pixel(glm::ivec2 p) const { return pixels_[index(p)]; }
  /// Starts loading the state of `p` (inside window()) into the cache for a write soon: between
  /// passes a pixel's state leaves the cache.
  void prefetch(glm::ivec2 p) const {
    const char* state = reinterpret_cast<const char*>(&pixels_[index(p)]);
    for (size_t line = 0; line < sizeof(FilmPixel); line += 64) __builtin_prefetch(state + line, 1);
  }
  /// prefetch() of only the cache line holding the state's counts (samples, progress,
  /// converged): all an empty sample touches.
  void prefetch_counts(glm::ivec2 p) const { __builtin_prefetch(&pixels_[index(p)].samples, 1); }
  /// Every pixel of the window, row-major.
  std::span<FilmPixel> pixels() { return pixels_; }
  std::span<const FilmPixel> pixels() const { return pixels_; }

  /// Samples whose radiance was NaN or infinite (counted as zero).
  uint64_t non_finite_samples() const { return non_finite_.load(); }
  void set_non_finite_samples(uint64_t count) { non_finite_.store(count); }
  /// Samples taken in `pixel` so far.
  uint32_t sample_count(glm::ivec2 p) const { return pixel(p).samples; }

  /// Adds the sums and sample counts of `part` (the same image size, its window inside this
  /// one's) to this film, and takes the larger schedule progress. Integer addition: the order
  /// in which parts are added does not change a bit.
  void accumulate(const Film& part);

  /// The per-pixel means over the window as an image (Image::x, y give its place in the full
  /// image) with channels, in this order: R, G, B (radiance); albedo.R/G/B; N.X/Y/Z (mean
  /// shading normal, not renormalised); Z (mean depth, 0 where rays escape); sampleCount.Y
  /// (samples taken); variance.R/G/B (estimated variance of the pixel mean: sample variance /
  /// n, 0 for fewer than two samples). A pure function of the pixel states.
  Image resolve() const { return resolve(ImagePixels()); }
  /// resolve(), into `buffer` when it holds the image's window().pixel_count() * kChannels
  /// values, all zero (a buffer made ahead: ImageBufferAhead); into a new one otherwise.
  Image resolve(ImagePixels buffer) const;
  /// Number of channels resolve() produces, and the index of the first of each group.
  static constexpr int kChannels = 14;
  static constexpr int kAlbedoChannel = 3;
  static constexpr int kNormalChannel = 6;
  static constexpr int kDepthChannel = 9;
  static constexpr int kSampleCountChannel = 10;
  static constexpr int kVarianceChannel = 11;

 private:
  size_t index(glm::ivec2 p) const {
    return size_t(p.y - window_.begin.y) * size_t(window_.width()) + size_t(p.x - window_.begin.x);
  }

  int width_, height_;
  PixelRect window_;
  std::vector<FilmPixel, HugePageAllocator<FilmPixel>> pixels_;  ///< 192 bytes a pixel
  std::atomic<uint64_t> non_finite_{0};
};

}  // namespace prism
