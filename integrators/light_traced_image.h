#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "core/math.h"
#include "core/scene.h"

namespace prism {

/// What one light path deposits on the image: radiance (already divided by the number of
/// paths of its sample index) on one pixel of the full image.
struct Splat {
  uint32_t pixel = 0;  ///< y * width + x
  uint32_t path = 0;   ///< the path's index among its sample index's paths
  Rgb radiance{0.0f};
};

/// Where a light path's caustic lands: the first surface after its specular bounces whose BSDF
/// is not purely specular, and the light arriving there.
struct CausticVertex {
  SurfaceInteraction si;
  Vec3 to_light{0.0f};       ///< unit, toward the path's previous vertex
  Rgb beta{0.0f};            ///< the path's throughput arriving at si (one path's, not divided)
  int specular_bounces = 0;  ///< purely specular surfaces between the light and si
};

/// What the light paths of one sample index left: the radiance they deposited per pixel (a
/// sparse image: most pixels receive nothing) and the caustic vertices camera paths connect
/// to. Immutable.
class LightTracedSample {
 public:
  /// Sums `splats` (in any order) per pixel, in the order of their paths, in double: the same
  /// bits whatever order the splats arrive in. Pixels must lie inside the width x height image.
  /// `vertices` must be in path order (as the paths were traced); `paths` is how many paths
  /// were traced.
  LightTracedSample(std::vector<Splat> splats, std::vector<CausticVertex> vertices, int width,
                    int height, uint32_t paths);
  /// The radiance deposited on `pixel` (inside the image): 0 for most pixels.
  Rgb at(glm::ivec2 pixel) const;
  /// Where at_in_row() is in the entries of one row.
  struct RowPosition {
    int y = -1;                  ///< the row; another row starts over
    uint32_t next = 0, end = 0;  ///< the first entry not yet passed, the row's end
  };
  /// at(), for pixels taken along a row left to right: the entries of `position`'s row are
  /// searched once, at its first pixel, then walked forward. Any order of pixels gives at()'s
  /// value; a pixel left of the previous one in the same row is searched for again.
  Rgb at_in_row(glm::ivec2 pixel, RowPosition& position) const;

  /// Whether no pixel x0 <= x < x1 of row y (inside the image) received anything.
  bool row_is_empty(int y, int x0, int x1) const;
  /// The caustic vertices, in path order, and the number of paths they came from.
  const std::vector<CausticVertex>& vertices() const { return vertices_; }
  uint32_t paths() const { return paths_; }
  /// One caustic vertex chosen uniformly with u in [0, 1) (null when there are none), its
  /// memory starting to load; what it brings, times vertices().size() / paths(), estimates
  /// what all the paths bring.
  const CausticVertex* choose_vertex(float u) const {
    if (vertices_.empty()) return nullptr;
    const CausticVertex* v =
        &vertices_[std::min(vertices_.size() - 1, size_t(u * float(vertices_.size())))];
    __builtin_prefetch(v);
    __builtin_prefetch(reinterpret_cast<const char*>(v) + 64);
    return v;
  }

 private:
  int width_;
  uint32_t paths_;
  std::vector<CausticVertex> vertices_;
  std::vector<uint32_t> row_begin_;  ///< per row y, the first entry of rows >= y; height + 1
  std::vector<uint32_t> pixels_;     ///< ascending
  std::vector<Rgb> radiance_;
};

/// What a light tracer leaves per sample index (LightTracedSample), traced on demand: the threads
/// that ask for a sample index not traced yet share its paths in chunks, then all receive the same
/// image. Each image is a pure function of its sample index (the tracer must be), so an image
/// dropped from the cache and traced again has the same bits. The cache keeps as many of the
/// most recent indices as a caller has needed at once (see sample()): all of a render's spp when
/// tiles come with every sample, as MPI's schedule hands them out, so that each index is traced
/// once (kMemoryBudget bounds what that holds, see max_paths()); a pass's samples when a render
/// goes in passes (4 at the default of 64 spp), so that a pass's images are freed after it and
/// the next pass reuses their memory instead of faulting in fresh pages. Thread-safe.
class LightTracedImage {
 public:
  /// Traces the paths [first, last) of sample index `sample` and appends their splats and
  /// caustic vertices.
  using TraceFunction = std::function<void(uint32_t sample, uint32_t first, uint32_t last,
                                           std::vector<Splat>&, std::vector<CausticVertex>&)>;

  /// Sample indices traced with `paths` paths each, over a width x height image.
  LightTracedImage(TraceFunction trace, uint32_t paths, int width, int height);
  ~LightTracedImage();

  /// The image of sample index `sample`, for a caller that uses the images of `in_use` sample
  /// indices at once (a tile's range of samples): from now on the cache keeps at least that
  /// many. Traces the index (with whichever other threads ask for it meanwhile) if it is not
  /// cached. Rethrows what the tracing threw.
  std::shared_ptr<const LightTracedSample> sample(uint32_t sample, uint32_t in_use) const;

  static constexpr uint32_t kChunkPaths = 256;
  /// The most paths per sample index whose samples, `samples` of them, fit kMemoryBudget however
  /// many of the paths leave a splat and a caustic vertex (at least 1).
  static uint32_t max_paths(uint32_t samples);

  static constexpr size_t kMemoryBudget = size_t(1) << 30;

 private:
  struct Tracing;
  std::shared_ptr<Tracing> tracing_of(uint32_t sample, uint32_t in_use) const;

  TraceFunction trace_;
  uint32_t paths_;
  int width_, height_;
  mutable std::mutex mutex_;
  mutable size_t cached_ = 1;  ///< the most indices kept: the largest in_use asked with
  mutable std::map<uint32_t, std::shared_ptr<Tracing>> cache_;
  mutable std::deque<uint32_t> order_;  ///< cached sample indices, oldest first
};

}  // namespace prism
