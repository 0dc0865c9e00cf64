#pragma once

#include <string>
#include <vector>

namespace prism {

/// What `prism bench` measures.
struct BenchOptions {
  /// Scene files (.dae, .json) or generated meshes "gen:KIND:COUNT" (COUNT may end in k or M,
  /// e.g. gen:soup:100k). Empty: the standard suite (standard_bench_scenes()).
  std::vector<std::string> scenes;
  std::string json;    ///< output file (required): a JSON array of rows
  bool quick = false;  ///< reduced suite (10k and 100k meshes) and 256 x 256 primary rays
  std::vector<int> threads{1, 2};
  int passes = 5;      ///< timed passes after one warm-up
  int resolution = 0;  ///< primary rays per image side; 0: 512 (quick: 256)
  /// Which backends: "embree" (always the reference), "bvh" (every split and layout) or
  /// "bvh:SPLIT:LAYOUT". Empty: embree and every bvh split and layout.
  std::vector<std::string> backends;
  std::vector<std::string> set;  ///< --set key=value for every backend
  /// A scene whose sets would take Embree longer than this per pass (one thread) is benched on
  /// every k-th ray instead, the same rays for every backend.
  double max_pass_seconds = 1.0;
  /// A timed pass traces a smaller ray set several whole times, up to at least this many rays,
  /// the same for every backend; 0: as many as the scene's largest set (its primary rays).
  long long min_pass_rays = 0;
};

/// `prism bench`: builds every backend on every scene and times them on the same stored rays;
/// writes options.json after each scene and prints a summary (bvh / embree per scene and ray
/// set) on stdout, progress on stderr. Throws prism::Error on bad options or input.
int run_bench_command(const BenchOptions& options);

/// The scenes `prism bench` runs without SCENE: generated sphere, noisy sphere, soup and
/// slivers at 10k, 100k, 1M and 10M triangles (quick: 10k and 100k), then the bundled scenes.
std::vector<std::string> standard_bench_scenes(bool quick);

}  // namespace prism
