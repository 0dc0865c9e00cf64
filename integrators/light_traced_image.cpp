#include "integrators/light_traced_image.h"

#include <algorithm>
#include <atomic>
#include <exception>

namespace prism {

LightTracedSample::LightTracedSample(std::vector<Splat> splats, std::vector<CausticVertex> vertices,
                                     int width, int height, uint32_t paths)
    : width_(width),
      paths_(paths),
      vertices_(std::move(vertices)),
      row_begin_(size_t(height) + 1, 0) {
  std::sort(splats.begin(), splats.end(), [](const Splat& a, const Splat& b) {
    return a.pixel != b.pixel ? a.pixel < b.pixel : a.path < b.path;
  });
  for (size_t i = 0; i < splats.size();) {
    const uint32_t pixel = splats[i].pixel;
    DVec3 sum(0.0);
    for (; i < splats.size() && splats[i].pixel == pixel; ++i) sum += DVec3(splats[i].radiance);
    pixels_.push_back(pixel);
    radiance_.push_back(Rgb(sum));
  }
  // row_begin_[y]: the first entry in row y or later.
  size_t entry = 0;
  for (int y = 0; y <= height; ++y) {
    while (entry < pixels_.size() && pixels_[entry] < uint64_t(y) * uint64_t(width)) ++entry;
    row_begin_[size_t(y)] = uint32_t(entry);
  }
}

Rgb LightTracedSample::at(glm::ivec2 pixel) const {
  RowPosition position;
  return at_in_row(pixel, position);
}

Rgb LightTracedSample::at_in_row(glm::ivec2 pixel, RowPosition& position) const {
  const uint32_t index = uint32_t(pixel.y) * uint32_t(width_) + uint32_t(pixel.x);
  // Entries before the row's are of earlier rows, all below index: one at or above it means
  // the pixel is left of the previous one.
  if (position.y != pixel.y || (position.next > 0 && pixels_[position.next - 1] >= index)) {
    const auto first = pixels_.begin() + row_begin_[size_t(pixel.y)];
    const auto last = pixels_.begin() + row_begin_[size_t(pixel.y) + 1];
    position = {pixel.y, uint32_t(std::lower_bound(first, last, index) - pixels_.begin()),
                uint32_t(last - pixels_.begin())};
  } else {
    while (position.next < position.end && pixels_[position.next] < index) ++position.next;
  }
  return position.next < position.end && pixels_[position.next] == index ? radiance_[position.next]
                                                                         : Rgb(0.0f);
}

bool LightTracedSample::row_is_empty(int y, int x0, int x1) const {
  const uint32_t row = uint32_t(y) * uint32_t(width_);
  const auto last = pixels_.begin() + row_begin_[size_t(y) + 1];
  const auto next = std::lower_bound(pixels_.begin() + row_begin_[size_t(y)], last, row + x0);
  return next == last || *next >= row + uint32_t(x1);
}

/// One sample index being traced (or traced): its chunks, handed out to the threads that ask.
struct LightTracedImage::Tracing {
  explicit Tracing(uint32_t chunk_count)
      : chunks(chunk_count), parts(chunk_count), vertex_parts(chunk_count) {}
  const uint32_t chunks;
  std::atomic<uint32_t> next_chunk{0};
  std::atomic<uint32_t> finished_chunks{0};
  std::vector<std::vector<Splat>> parts;  ///< per chunk, written by the thread that traced it
  std::vector<std::vector<CausticVertex>> vertex_parts;  ///< likewise
  std::mutex mutex;
  std::condition_variable done;
  bool ready = false;                              ///< under mutex
  std::exception_ptr error;                        ///< under mutex
  std::shared_ptr<const LightTracedSample> image;  ///< set before ready
};

LightTracedImage::LightTracedImage(TraceFunction trace, uint32_t paths, int width, int height)
    : trace_(std::move(trace)), paths_(paths), width_(width), height_(height) {}

uint32_t LightTracedImage::max_paths(uint32_t samples) {
  const size_t per_path = sizeof(Splat) + sizeof(CausticVertex);
  const size_t paths = kMemoryBudget / (per_path * std::max<size_t>(1, samples));
  return uint32_t(std::clamp<size_t>(paths, 1, uint32_t(1) << 31));
}

LightTracedImage::~LightTracedImage() = default;

std::shared_ptr<LightTracedImage::Tracing> LightTracedImage::tracing_of(uint32_t sample,
                                                                        uint32_t in_use) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  cached_ = std::max<size_t>(cached_, in_use);
  if (const auto it = cache_.find(sample); it != cache_.end()) return it->second;
  auto tracing = std::make_shared<Tracing>(std::max(1u, (paths_ + kChunkPaths - 1) / kChunkPaths));
  cache_.emplace(sample, tracing);
  order_.push_back(sample);
  // A dropped entry stays alive while threads use it; asked for again, it is traced again.
  while (order_.size() > cached_) {
    cache_.erase(order_.front());
    order_.pop_front();
  }
  return tracing;
}

std::shared_ptr<const LightTracedSample> LightTracedImage::sample(uint32_t sample,
                                                                  uint32_t in_use) const {
  const std::shared_ptr<Tracing> tracing = tracing_of(sample, in_use);
  Tracing& t = *tracing;
  for (uint32_t chunk; (chunk = t.next_chunk.fetch_add(1)) < t.chunks;) {
    try {
      const uint32_t first = chunk * kChunkPaths;
      trace_(sample, first, std::min(paths_, first + kChunkPaths), t.parts[chunk],
             t.vertex_parts[chunk]);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(t.mutex);
      if (!t.error) t.error = std::current_exception();
    }
    if (t.finished_chunks.fetch_add(1) + 1 != t.chunks) continue;
    // The last chunk: gather every chunk's splats and vertices, in chunk order (path order).
    std::shared_ptr<const LightTracedSample> image;
    try {
      size_t count = 0;
      for (const std::vector<Splat>& part : t.parts) count += part.size();
      std::vector<Splat> splats;
      splats.reserve(count);
      for (std::vector<Splat>& part : t.parts) {
        splats.insert(splats.end(), part.begin(), part.end());
        std::vector<Splat>().swap(part);
      }
      std::vector<CausticVertex> vertices;
      for (std::vector<CausticVertex>& part : t.vertex_parts) {
        vertices.insert(vertices.end(), part.begin(), part.end());
        std::vector<CausticVertex>().swap(part);
      }
      image = std::make_shared<const LightTracedSample>(std::move(splats), std::move(vertices),
                                                        width_, height_, paths_);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(t.mutex);
      if (!t.error) t.error = std::current_exception();
    }
    {
      const std::lock_guard<std::mutex> lock(t.mutex);
      t.image = std::move(image);
      t.ready = true;
    }
    t.done.notify_all();
  }
  std::unique_lock<std::mutex> lock(t.mutex);
  t.done.wait(lock, [&] { return t.ready; });
  if (t.error) std::rethrow_exception(t.error);
  return t.image;
}

}  // namespace prism
