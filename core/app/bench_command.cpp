// `prism bench`: every backend on the same stored rays, scene by scene.

#include "core/app/bench_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

#include "accel/bench/bench_runner.h"
#include "core/app/host_check.h"
#include "core/app/render_options.h"
#include "core/error.h"
#include "scenes/generated_scene.h"
#include "scenes/scene_loader.h"

namespace prism {
namespace {

std::vector<BenchBackend> selected_backends(const BenchOptions& options, const ParamSet& extra) {
  std::vector<BenchBackend> all = standard_bench_backends();
  std::vector<BenchBackend> out;
  for (BenchBackend& b : all) {
    bool wanted = b.accel == "embree" || options.backends.empty();
    for (const std::string& want : options.backends) {
      if (want == b.accel || want == b.accel + ":" + b.split + ":" + b.layout) wanted = true;
    }
    if (!wanted) continue;
    // Embree races as Embree: its own t, u, v (no refinement by prism's triangle test).
    if (b.accel == "embree") b.params.set("embree.refine", "false");
    for (const std::string& key : extra.keys()) {
      if (key.rfind(b.accel + ".", 0) == 0) b.params.set(key, extra.get_string(key, ""));
    }
    out.push_back(std::move(b));
  }
  for (const std::string& want : options.backends) {
    const bool known = std::any_of(out.begin(), out.end(), [&](const BenchBackend& b) {
      return want == b.accel || want == b.accel + ":" + b.split + ":" + b.layout;
    });
    if (!known) {
      throw Error(ErrorKind::kUsage, "--backend '" + want +
                                         "' is not one of: embree, bvh, bvh:SPLIT:LAYOUT "
                                         "(SPLIT median|sah|sbvh, LAYOUT bvh2|bvh4|bvh8)");
    }
  }
  return out;
}

/// One in every returned stride rays keeps a pass of Embree under max_seconds (one thread).
size_t choose_stride(const Accelerator& tracer, const std::vector<BenchRaySet>& sets,
                     double max_seconds) {
  double worst = 0.0;
  for (const BenchRaySet& s : sets) {
    const size_t n = std::min<size_t>(s.rays.size(), 2048);
    if (n == 0) continue;
    // Rays spread over the whole set: the first rows of an image may all miss the scene.
    const size_t step = s.rays.size() / n;
    const auto start = std::chrono::steady_clock::now();
    size_t hits = 0;
    for (size_t k = 0; k < n; ++k) {
      const Ray& ray = s.rays[k * step];
      hits += s.occlusion ? tracer.occluded(ray) : tracer.intersect(ray).has_value();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    worst = std::max(worst, seconds * static_cast<double>(s.rays.size()) / static_cast<double>(n));
    (void)hits;
  }
  return std::max<size_t>(1, static_cast<size_t>(std::ceil(worst / max_seconds)));
}

void write_json(const std::filesystem::path& path, const std::vector<BenchRow>& rows) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp);
    out << bench_rows_to_json(rows).dump(1) << "\n";
    if (!out) throw Error(ErrorKind::kOutput, "cannot write", {path.string(), 0, {}});
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw Error(ErrorKind::kOutput, "cannot write: " + ec.message(), {path.string(), 0, {}});
}

bool is_default_bvh(const BenchRow& r) {
  return r.accel == "bvh" && r.split == "sah" && r.layout == "bvh8";
}

/// bvh (default split and layout) / embree per scene, ray set and thread count, and the
/// geometric mean over scenes of at least 10k triangles.
void print_summary(const std::vector<BenchRow>& rows, const std::vector<int>& threads) {
  std::map<std::tuple<std::string, int, std::string>, double> embree;
  for (const BenchRow& r : rows) {
    if (r.accel == "embree") embree[{r.scene, r.threads, r.ray_set}] = r.mrays_per_s;
  }
  std::map<int, std::pair<double, int>> log_sum;  // threads -> (sum of log ratios, count)
  fmt::print("{:<22} {:>3} {:>9} {:>9} {:>9} {:>9} {:>9}   (bvh sah/bvh8 / embree, Mrays/s)\n",
             "scene", "thr", "P", "S", "D1", "D2", "R");
  std::string last;
  for (const BenchRow& r : rows) {
    if (!is_default_bvh(r) || r.ray_set != "P") continue;
    for (int t : threads) {
      if (t != r.threads) continue;
      std::string line = fmt::format("{:<22} {:>3}", r.scene, t);
      for (const char* set : {"P", "S", "D1", "D2", "R"}) {
        const auto bvh = std::find_if(rows.begin(), rows.end(), [&](const BenchRow& x) {
          return is_default_bvh(x) && x.scene == r.scene && x.threads == t && x.ray_set == set;
        });
        const auto e = embree.find({r.scene, t, set});
        if (bvh == rows.end() || e == embree.end() || e->second <= 0.0) {
          line += fmt::format(" {:>9}", "-");
          continue;
        }
        const double ratio = bvh->mrays_per_s / e->second;
        line += fmt::format(" {:>8.2f}{}", ratio, bvh->valid ? " " : "!");
        if (r.triangles >= 10000) {
          log_sum[t].first += std::log(ratio);
          ++log_sum[t].second;
        }
      }
      fmt::print("{}\n", line);
    }
  }
  for (const auto& [t, sum] : log_sum) {
    fmt::print("geometric mean bvh/embree, scenes >= 10k triangles, {} thread{}: {:.3f}\n", t,
               t == 1 ? "" : "s", std::exp(sum.first / sum.second));
  }
}

/// Times every CPU's add chain (host_check.h) and logs it; returns whether some CPU was slow.
bool check_host(const char* when) {
  const std::vector<CpuSpeed> speeds = measure_cpu_speeds();
  if (speeds.empty()) return false;
  std::fprintf(stderr, "bench: host check %s: %s G adds/s\n", when,
               format_cpu_speeds(speeds).c_str());
  const std::string slow = describe_slow_cpus(speeds);
  if (slow.empty()) return false;
  std::fprintf(stderr, "bench: warning: %s\n", slow.c_str());
  return true;
}

}  // namespace

std::vector<std::string> standard_bench_scenes(bool quick) {
  std::vector<std::string> out;
  const std::vector<std::string> sizes = quick
                                             ? std::vector<std::string>{"10k", "100k"}
                                             : std::vector<std::string>{"10k", "100k", "1M", "10M"};
  for (const std::string& size : sizes) {
    for (const char* kind : {"sphere", "noisy_sphere", "soup", "slivers", "interior"}) {
      out.push_back(std::string("gen:") + kind + ":" + size);
    }
  }
  std::vector<std::string> bundled;
  for (const auto& entry : std::filesystem::directory_iterator(bundled_scene_dir())) {
    if (entry.path().extension() == ".json") bundled.push_back(entry.path().string());
  }
  std::sort(bundled.begin(), bundled.end());
  out.insert(out.end(), bundled.begin(), bundled.end());
  return out;
}

int run_bench_command(const BenchOptions& options) {
  if (options.json.empty()) throw Error(ErrorKind::kUsage, "--json FILE is required");
  if (options.passes < 5) throw Error(ErrorKind::kUsage, "--passes must be at least 5");
  if (options.min_pass_rays < 0 || options.min_pass_rays > (1LL << 32)) {
    throw Error(ErrorKind::kUsage, "--min-pass-rays must be between 0 and 2^32");
  }
  for (int t : options.threads) {
    if (t < 1 || t > 256) throw Error(ErrorKind::kUsage, "--threads values must be in 1..256");
  }
  const ParamSet extra = parse_param_assignments(options.set);
  const std::vector<BenchBackend> backends = selected_backends(options, extra);
  const std::vector<std::string> specs =
      options.scenes.empty() ? standard_bench_scenes(options.quick) : options.scenes;
  const std::filesystem::path json_path(options.json);
  write_json(json_path, {});  // fail now, not after an hour, if the file cannot be written

  BenchRayOptions ray_options;
  ray_options.width = ray_options.height =
      options.resolution > 0 ? options.resolution : (options.quick ? 256 : 512);
  BenchSettings settings;
  settings.threads = options.threads;
  settings.passes = options.passes;

  std::vector<BenchRow> rows;
  int checks = 0, slow_checks = 0;
  for (const std::string& spec : specs) {
    std::string name;
    const Scene scene = load_scene_or_generated(spec, name);
    std::vector<BenchRaySet> sets;
    size_t stride = 1;
    {
      ParamSet tracer_params;
      tracer_params.set("embree.refine", "false");
      const auto tracer = accelerator_registry().create("embree", tracer_params);
      tracer->build(scene.geometry);
      sets = make_bench_ray_sets(scene, *tracer, ray_options);
      stride = choose_stride(*tracer, sets, options.max_pass_seconds);
    }
    thin_ray_sets(sets, stride);
    size_t largest_set = 0;
    for (const BenchRaySet& set : sets) largest_set = std::max(largest_set, set.rays.size());
    settings.min_rays_per_pass =
        options.min_pass_rays > 0 ? size_t(options.min_pass_rays) : largest_set;
    std::fprintf(stderr, "bench: %s: %zu triangles%s\n", name.c_str(),
                 scene.geometry.triangle_count(),
                 stride > 1 ? fmt::format(", one ray in {} (slow scene)", stride).c_str() : "");
    settings.build_repeats = scene.geometry.triangle_count() < 1000000 ? 3 : 1;
    ++checks;
    if (check_host(("before " + name).c_str())) ++slow_checks;
    const std::vector<BenchRow> scene_rows = bench_scene(
        name, scene.geometry, backends, sets, settings,
        [](const std::string& line) { std::fprintf(stderr, "bench: %s\n", line.c_str()); });
    rows.insert(rows.end(), scene_rows.begin(), scene_rows.end());
    write_json(json_path, rows);
  }
  ++checks;
  if (check_host("at the end")) ++slow_checks;
  print_summary(rows, options.threads);
  if (slow_checks > 0) {
    fmt::print(
        "host check: some CPU ran at under 0.8 of the fastest in {} of {} checks (bench's "
        "stderr): another workload shared its core, and the ratios above may be off\n",
        slow_checks, checks);
  }
  fmt::print("wrote {} rows to {}\n", rows.size(), json_path.string());
  return kExitSuccess;
}

}  // namespace prism
