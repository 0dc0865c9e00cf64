#include "accel/bench/bench_runner.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <map>
#include <memory>

#include "accel/accelerator.h"
#include "accel/bvh/cpu_features.h"
#include "core/parallel.h"
#include "core/parallel_reduce.h"

namespace prism {
namespace {

struct Timing {
  std::vector<double> mrays;
  std::vector<double> cpu_mrays;
  size_t hits = 0;
  size_t rays_per_pass = 0;
};

struct PassResult {
  double mrays;      ///< per wall-clock second
  double cpu_mrays;  ///< per second of process CPU time, times the thread count
  size_t hits;
};

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

using TimingKey = std::pair<int, size_t>;  // (threads, ray set index)

size_t trace(const Accelerator& accel, const BenchRaySet& set, size_t begin, size_t end) {
  size_t hits = 0;
  if (set.occlusion) {
    for (size_t i = begin; i < end; ++i) hits += accel.occluded(set.rays[i]) ? 1 : 0;
  } else {
    for (size_t i = begin; i < end; ++i) hits += accel.intersect(set.rays[i]).has_value() ? 1 : 0;
  }
  return hits;
}

/// Traces rays [begin, end) of the set repeated end-to-end (index i is ray i mod the set's size).
size_t trace_repeated(const Accelerator& accel, const BenchRaySet& set, size_t begin, size_t end) {
  const size_t n = set.rays.size();
  size_t hits = 0;
  while (begin < end) {
    const size_t offset = begin % n;
    const size_t count = std::min(end - begin, n - offset);
    hits += trace(accel, set, offset, offset + count);
    begin += count;
  }
  return hits;
}

/// How many times a pass traces the set: enough for min_rays rays, at least once.
size_t repeats_for(const BenchRaySet& set, size_t min_rays) {
  const size_t n = set.rays.size();
  return std::max<size_t>(1, (min_rays + n - 1) / n);
}

// One pass: the set, `repeats` times; hits are those of one time through it.
PassResult time_pass(const Accelerator& accel, const BenchRaySet& set, ThreadArena& arena,
                     size_t repeats) {
  const int threads = arena.threads();
  const size_t total = repeats * set.rays.size();
  const double cpu_start = process_cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  size_t hits = 0;
  if (threads == 1) {
    hits = trace_repeated(accel, set, 0, total);
  } else {
    arena.execute([&] {
      hits = parallel_reduce(
          0, total, 2048, size_t{0},
          [&](size_t begin, size_t end, size_t n) {
            return n + trace_repeated(accel, set, begin, end);
          },
          [](size_t a, size_t b) { return a + b; });
    });
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu_seconds = (process_cpu_seconds() - cpu_start) / threads;
  const auto rays = static_cast<double>(total);
  return {rays / std::max(seconds, 1e-9) / 1e6, rays / std::max(cpu_seconds, 1e-9) / 1e6,
          hits / repeats};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Built {
  std::unique_ptr<Accelerator> accel;
  double build_ms = 0.0;
};

Built build_backend(const BenchBackend& backend, const SceneGeometry& geometry, int repeats) {
  std::vector<double> times;
  Built built;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    built.accel.reset();  // free the previous build before the next
    built.accel = accelerator_registry().create(backend.accel, backend.params);
    built.accel->build(geometry);
    times.push_back(built.accel->stats().build_ms);
  }
  built.build_ms = median(times);
  return built;
}

BenchRow make_row(const std::string& scene, const SceneGeometry& geometry,
                  const BenchBackend& backend, const Built& built, int threads,
                  const BenchRaySet& set, const Timing& timing) {
  const AccelStats stats = built.accel->stats();
  BenchRow row;
  row.scene = scene;
  row.triangles = geometry.triangle_count();
  row.accel = backend.accel;
  row.layout = backend.layout;
  row.split = backend.split;
  if (backend.accel == "bvh") {
    const std::string isa = backend.params.get_string("bvh.isa", "auto");
    row.isa = isa != "auto"      ? isa
              : cpu_has_avx512() ? "avx512"
              : cpu_has_avx2()   ? "avx2"
                                 : "generic";
  }
  row.threads = threads;
  row.ray_set = set.name;
  row.rays = set.rays.size();
  row.rays_per_pass = timing.rays_per_pass;
  row.mrays_per_s = median(timing.mrays);
  row.mrays_min =
      timing.mrays.empty() ? 0.0 : *std::min_element(timing.mrays.begin(), timing.mrays.end());
  row.mrays_max =
      timing.mrays.empty() ? 0.0 : *std::max_element(timing.mrays.begin(), timing.mrays.end());
  row.passes = static_cast<int>(timing.mrays.size());
  row.cpu_mrays_per_s = median(timing.cpu_mrays);
  row.build_ms = built.build_ms;
  const size_t prims = std::max<size_t>(
      1, geometry.triangle_count() > 0 ? geometry.triangle_count() : geometry.primitive_count());
  row.bytes_per_triangle = static_cast<double>(stats.bytes) / static_cast<double>(prims);
  row.nodes = stats.nodes;
  row.sah_cost = stats.sah_cost;
  row.hits = timing.hits;
  return row;
}

}  // namespace

std::vector<BenchBackend> standard_bench_backends() {
  std::vector<BenchBackend> out;
  out.push_back({"embree", "", "", ParamSet()});
  for (const char* split : {"sah", "sbvh", "median"}) {
    for (const char* layout : {"bvh8", "bvh4", "bvh2"}) {
      BenchBackend b{"bvh", layout, split, ParamSet()};
      b.params.set("bvh.split", split);
      b.params.set("bvh.layout", layout);
      out.push_back(std::move(b));
    }
  }
  return out;
}

std::vector<BenchRow> bench_scene(const std::string& scene_name, const SceneGeometry& geometry,
                                  const std::vector<BenchBackend>& backends,
                                  const std::vector<BenchRaySet>& sets,
                                  const BenchSettings& settings,
                                  const std::function<void(const std::string&)>& log) {
  std::vector<BenchRow> rows;
  if (backends.empty()) return rows;
  std::map<int, std::unique_ptr<ThreadArena>> arenas;
  for (int t : settings.threads) arenas[t] = std::make_unique<ThreadArena>(t);

  const Built reference = build_backend(backends[0], geometry, settings.build_repeats);
  std::map<TimingKey, Timing> reference_timing;

  auto run_pair = [&](const Accelerator* other, std::map<TimingKey, Timing>& other_timing) {
    for (int threads : settings.threads) {
      ThreadArena& arena = *arenas[threads];
      for (size_t s = 0; s < sets.size(); ++s) {
        const BenchRaySet& set = sets[s];
        if (set.rays.empty()) continue;
        Timing& ref = reference_timing[{threads, s}];
        Timing* oth = other ? &other_timing[{threads, s}] : nullptr;
        const size_t repeats = repeats_for(set, settings.min_rays_per_pass);
        ref.rays_per_pass = repeats * set.rays.size();
        if (other) oth->rays_per_pass = ref.rays_per_pass;
        // Warm-up: caches, page faults, the arena's workers.
        ref.hits = time_pass(*reference.accel, set, arena, repeats).hits;
        if (other) oth->hits = time_pass(*other, set, arena, repeats).hits;
        auto timed = [&](const Accelerator& accel, Timing& timing) {
          const PassResult r = time_pass(accel, set, arena, repeats);
          timing.mrays.push_back(r.mrays);
          timing.cpu_mrays.push_back(r.cpu_mrays);
        };
        for (int p = 0; p < settings.passes; ++p) {
          const bool reference_first = p % 2 == 0 || other == nullptr;
          if (reference_first) timed(*reference.accel, ref);
          if (other) timed(*other, *oth);
          if (!reference_first) timed(*reference.accel, ref);
        }
      }
    }
  };

  for (size_t b = 1; b < backends.size(); ++b) {
    const Built built = build_backend(backends[b], geometry, settings.build_repeats);
    std::map<TimingKey, Timing> timing;
    run_pair(built.accel.get(), timing);
    for (const auto& [key, t] : timing) {
      rows.push_back(
          make_row(scene_name, geometry, backends[b], built, key.first, sets[key.second], t));
    }
    if (log) {
      log(scene_name + ": " + backends[b].accel + " " + backends[b].split + " " +
          backends[b].layout + " done (build " + std::to_string(built.build_ms) + " ms)");
    }
  }
  if (backends.size() == 1) run_pair(nullptr, reference_timing);

  std::vector<BenchRow> reference_rows;
  for (const auto& [key, t] : reference_timing) {
    reference_rows.push_back(
        make_row(scene_name, geometry, backends[0], reference, key.first, sets[key.second], t));
  }
  for (BenchRow& row : rows) {
    for (const BenchRow& ref : reference_rows) {
      if (ref.threads == row.threads && ref.ray_set == row.ray_set) {
        row.hit_difference = static_cast<long long>(row.hits) - static_cast<long long>(ref.hits);
        row.valid = row.hit_difference == 0;
      }
    }
  }
  rows.insert(rows.begin(), reference_rows.begin(), reference_rows.end());
  return rows;
}

nlohmann::json bench_rows_to_json(const std::vector<BenchRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const BenchRow& r : rows) {
    out.push_back({{"scene", r.scene},
                   {"triangles", r.triangles},
                   {"accel", r.accel},
                   {"layout", r.layout},
                   {"split", r.split},
                   {"isa", r.isa},
                   {"threads", r.threads},
                   {"ray_set", r.ray_set},
                   {"rays", r.rays},
                   {"rays_per_pass", r.rays_per_pass},
                   {"mrays_per_s", r.mrays_per_s},
                   {"mrays_min", r.mrays_min},
                   {"mrays_max", r.mrays_max},
                   {"passes", r.passes},
                   {"cpu_mrays_per_s", r.cpu_mrays_per_s},
                   {"build_ms", r.build_ms},
                   {"bytes_per_triangle", r.bytes_per_triangle},
                   {"nodes", r.nodes},
                   {"sah_cost", r.sah_cost},
                   {"hits", r.hits},
                   {"hit_difference", r.hit_difference},
                   {"valid", r.valid}});
  }
  return out;
}

}  // namespace prism
