#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "core/scene.h"

namespace prism {

/// One of the ray sets `prism bench` times every backend on.
struct BenchRaySet {
  std::string name;        ///< "P", "S", "D1", "D2" or "R"
  bool occlusion = false;  ///< traced with occluded() (shadow rays) instead of intersect()
  std::vector<Ray> rays;
  /// For each ray, the pixel (y * width + x) of the camera ray it descends from; empty for
  /// sets not tied to the image (R). Lets `prism validate` map disagreements onto the image.
  std::vector<uint32_t> pixels;
};

struct BenchRayOptions {
  int width = 512;  ///< primary rays: one per pixel of width x height
  int height = 512;
  uint64_t seed = 1;
};

/// The five standard sets for `scene`, generated once and then given to every backend:
/// - P: one camera ray through each pixel centre (jittered by the seed);
/// - S: from each P hit towards one light (lights taken in turn; a point on area lights; no
///   lights: a point above the scene), ending just short of it;
/// - D1: a cosine-distributed bounce off each P hit, on the side the ray came from;
/// - D2: the same off each D1 hit;
/// - R: width x height rays with origins uniform in the scene's bounds and uniform directions.
/// `tracer` (any built backend over scene.geometry) only decides where secondary rays start.
/// Deterministic in options.seed.
std::vector<BenchRaySet> make_bench_ray_sets(const Scene& scene, const Accelerator& tracer,
                                             const BenchRayOptions& options);

/// Keeps every `stride`-th ray (and its pixel) of each set: a smaller sample for slow scenes.
void thin_ray_sets(std::vector<BenchRaySet>& sets, size_t stride);

/// Stores ray sets in a small binary file (host byte order); throws Error(kOutput).
void save_ray_sets(const std::filesystem::path& path, const std::vector<BenchRaySet>& sets);
/// Reads save_ray_sets() output; throws Error(kInput) on a missing or malformed file.
std::vector<BenchRaySet> load_ray_sets(const std::filesystem::path& path);

}  // namespace prism
