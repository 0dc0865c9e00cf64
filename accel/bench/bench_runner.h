#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "accel/bench/bench_rays.h"
#include "core/param_set.h"
#include "core/scene_geometry.h"

namespace prism {

/// A backend `prism bench` times: a registry name and the parameters it is created with.
struct BenchBackend {
  std::string accel;   ///< registry name: "bvh", "embree", ...
  std::string layout;  ///< bvh: bvh2 | bvh4 | bvh8 (also set in params); empty otherwise
  std::string split;   ///< bvh: median | sah | sbvh (also set in params); empty otherwise
  ParamSet params;
};

/// Every bvh layout and split, then embree first (the reference every row is compared with).
std::vector<BenchBackend> standard_bench_backends();

/// One line of the benchmark: one backend on one scene, ray set and thread count.
struct BenchRow {
  std::string scene;
  size_t triangles = 0;
  std::string accel, layout, split, isa;
  int threads = 1;
  std::string ray_set;
  size_t rays = 0;
  size_t rays_per_pass = 0;  ///< rays a timed pass traces: the set, repeated (BenchSettings)
  double mrays_per_s = 0.0;  ///< median over the timed passes
  double mrays_min = 0.0, mrays_max = 0.0;
  int passes = 0;
  /// Median of rays per second of process CPU time (times threads): less sensitive than
  /// mrays_per_s to other processes on a shared machine, though not to their cache traffic.
  double cpu_mrays_per_s = 0.0;
  double build_ms = 0.0;  ///< median over the builds
  double bytes_per_triangle = 0.0;
  size_t nodes = 0;
  double sah_cost = 0.0;
  size_t hits = 0;               ///< rays with a hit (closest-hit sets) or occluded (shadow set)
  long long hit_difference = 0;  ///< hits minus the reference's hits
  bool valid = true;             ///< hits equal the reference's (embree's)
};

struct BenchSettings {
  std::vector<int> threads{1, 2};
  int passes = 5;         ///< timed passes after one warm-up pass
  int build_repeats = 1;  ///< builds per backend; build_ms is their median
  /// A timed pass traces its set as many whole times as it takes to trace at least this many
  /// rays (at least once). A set of a few thousand bounce rays is otherwise a pass of about a
  /// millisecond, which measures the clock, the workers' wake-up and (at 2 threads) a split into
  /// two or three chunks more than the traversal.
  size_t min_rays_per_pass = 0;
};

/// Builds every backend on `geometry` and times it on every ray set at every thread count.
/// backends[0] is the reference (embree): it stays built, and every other backend is timed in
/// alternation with it pass by pass (which of the two goes first alternates too), so slow
/// drifts of the machine's load hit both alike; the reference's rows gather all of its passes.
/// One backend besides the reference is alive at a time. Rows whose hit count differs from the
/// reference's are marked invalid. `log` receives one line per finished backend.
std::vector<BenchRow> bench_scene(const std::string& scene_name, const SceneGeometry& geometry,
                                  const std::vector<BenchBackend>& backends,
                                  const std::vector<BenchRaySet>& sets,
                                  const BenchSettings& settings,
                                  const std::function<void(const std::string&)>& log);

/// The rows as a JSON array of objects (keys as BenchRow's fields).
nlohmann::json bench_rows_to_json(const std::vector<BenchRow>& rows);

}  // namespace prism
