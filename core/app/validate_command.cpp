// `prism validate`: two backends and the double-precision oracle on the same rays.

#include "core/app/validate_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "accel/accelerator.h"
#include "accel/bench/bench_rays.h"
#include "accel/validation/double_oracle.h"
#include "accel/validation/hit_comparison.h"
#include "accel/validation/ray_sets.h"
#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "core/app/component_params.h"
#include "core/app/render_options.h"
#include "core/error.h"
#include "core/parallel.h"
#include "scenes/generated_scene.h"

namespace prism {
namespace {

constexpr uint64_t kSeed = 7;
constexpr size_t kMaxFailuresWritten = 1000000;
constexpr const char* kReplayHeader = "# prism validate replay file";

/// The two backends under comparison and how to judge them.
struct Judge {
  const Accelerator& a;
  const Accelerator& b;
  const DoubleOracle& oracle;
  bool exact;  ///< both share core's primitive tests and the tie rule: bits must match

  HitComparison operator()(const Ray& ray) const {
    const std::optional<Hit> ha = a.intersect(ray);
    const std::optional<Hit> hb = b.intersect(ray);
    HitComparison c = exact ? compare_exact(ha, hb) : compare_tolerant(ray, ha, hb, oracle);
    for (const auto& [accel, hit] : {std::pair{&a, ha}, std::pair{&b, hb}}) {
      if (accel->occluded(ray) != hit.has_value()) {
        c = {HitAgreement::kHard, std::string(accel->name()) +
                                      ": occluded() disagrees with intersect() " + format_hit(hit)};
      }
    }
    if (c.agreement == HitAgreement::kHard) {
      const std::optional<OracleHit> o = oracle.closest(ray);
      c.reason +=
          o ? fmt::format("; oracle: t={:.9g} geom={} prim={}", o->t, o->geom_id, o->prim_id)
            : std::string("; oracle: miss");
    }
    return c;
  }

  /// For a hard mismatch: which backend's answer is not the oracle's (bit 0: a, bit 1: b), by
  /// primitive (or miss), so a report can tell which side is wrong.
  int off_oracle(const Ray& ray) const {
    const std::optional<OracleHit> o = oracle.closest(ray);
    const auto off = [&](const std::optional<Hit>& h) {
      if (!o || !h) return o.has_value() != h.has_value();
      return h->geom_id != o->geom_id || h->prim_id != o->prim_id;
    };
    return (off(a.intersect(ray)) ? 1 : 0) | (off(b.intersect(ray)) ? 2 : 0);
  }
};

/// The pixel of a width x height image through `camera` (as generate_ray() maps film
/// positions) that sees point p, or -1 when p is behind the camera or outside the image.
int64_t project_to_pixel(const Camera& camera, const Vec3& p, int width, int height) {
  const Vec3 forward = glm::normalize(camera.target - camera.position);
  const Vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const Vec3 true_up = glm::cross(right, forward);
  const Vec3 d = p - camera.position;
  const float z = glm::dot(d, forward);
  if (!(z > 0.0f)) return -1;
  const float fx =
      0.5f * (glm::dot(d, right) / z / std::tan(radians(camera.hfov_deg) * 0.5f) + 1.0f);
  const float fy =
      0.5f * (1.0f - glm::dot(d, true_up) / z / std::tan(radians(camera.vfov_deg) * 0.5f));
  if (!(fx >= 0.0f && fx < 1.0f && fy >= 0.0f && fy < 1.0f)) return -1;
  const int x = std::min(width - 1, static_cast<int>(fx * float(width)));
  const int y = std::min(height - 1, static_cast<int>(fy * float(height)));
  return int64_t(y) * width + x;
}

bool shares_primitive_tests(const std::string& name) { return name == "bvh" || name == "brute"; }

/// One ray to judge, with where it came from.
struct Probe {
  std::string set;
  Ray ray;
  int64_t pixel = -1;  ///< of the camera ray it descends from, -1 when none
};

struct ReplayFile {
  std::string scene, accel, against;
  std::vector<std::string> set;
  std::vector<Probe> probes;
};

ReplayFile read_replay(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(ErrorKind::kInput, "cannot open replay file", {path.string(), 0, {}});
  ReplayFile file;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const ErrorLocation where{path.string(), number, {}};
    if (number == 1 && line != kReplayHeader) {
      throw Error(ErrorKind::kInput, "not a prism validate replay file", where);
    }
    if (line.empty() || number == 1) continue;
    auto value = [&](const std::string& key) -> std::optional<std::string> {
      const std::string prefix = "# " + key + ": ";
      if (line.rfind(prefix, 0) != 0) return std::nullopt;
      return line.substr(prefix.size());
    };
    if (auto v = value("scene")) {
      file.scene = *v;
    } else if (auto v2 = value("accel")) {
      file.accel = *v2;
    } else if (auto v3 = value("against")) {
      file.against = *v3;
    } else if (auto v4 = value("set")) {
      file.set.push_back(*v4);
    } else if (line[0] != '#') {
      const size_t bar = line.find(" | ");
      const std::optional<Ray> ray =
          bar == std::string::npos ? std::nullopt : parse_ray(line.substr(bar + 3));
      if (!ray) throw Error(ErrorKind::kInput, "expected 'SET VERDICT | <ray>'", where);
      file.probes.push_back({line.substr(0, line.find(' ')), *ray, -1});
    }
  }
  return file;
}

void write_failures(const std::filesystem::path& path, const ValidateOptions& options,
                    const std::string& scene, const std::vector<Probe>& probes,
                    const std::vector<HitComparison>& verdicts) {
  std::ofstream out(path);
  out << kReplayHeader << "\n# scene: " << scene << "\n# accel: " << options.accel
      << "\n# against: " << options.against << "\n";
  for (const std::string& s : options.set) out << "# set: " << s << "\n";
  out << "# SET VERDICT | ray (hex floats); re-run with: prism validate --replay " << path.string()
      << "\n";
  size_t written = 0;
  for (size_t i = 0; i < probes.size() && written < kMaxFailuresWritten; ++i) {
    if (verdicts[i].agreement == HitAgreement::kSame) continue;
    out << probes[i].set << " " << to_string(verdicts[i].agreement) << " | "
        << format_ray(probes[i].ray) << "\n";
    ++written;
  }
  if (!out) throw Error(ErrorKind::kOutput, "cannot write", {path.string(), 0, {}});
}

/// Red: hard mismatches, yellow: ambiguous, blue: ties, brighter with more rays; dim grey
/// where the camera ray hit something, for orientation.
void write_heatmap(const std::filesystem::path& path, int width, int height,
                   const std::vector<Probe>& probes, const std::vector<HitComparison>& verdicts,
                   const std::vector<char>& camera_hit) {
  std::vector<int> hard(size_t(width) * height), ambiguous(hard.size()), tie(hard.size());
  for (size_t i = 0; i < probes.size(); ++i) {
    const int64_t p = probes[i].pixel;
    if (p < 0 || size_t(p) >= hard.size()) continue;
    switch (verdicts[i].agreement) {
      case HitAgreement::kHard:
        ++hard[size_t(p)];
        break;
      case HitAgreement::kAmbiguous:
        ++ambiguous[size_t(p)];
        break;
      case HitAgreement::kTie:
        ++tie[size_t(p)];
        break;
      case HitAgreement::kSame:
        break;
    }
  }
  Image image;
  image.width = width;
  image.height = height;
  image.channel_names = {"R", "G", "B"};
  image.pixels.assign(size_t(width) * height * 3, 0.0f);
  auto level = [](int n) { return n == 0 ? 0.0f : std::min(1.0f, 0.4f + 0.2f * float(n)); };
  for (size_t p = 0; p < hard.size(); ++p) {
    float* rgb = &image.pixels[3 * p];
    const float base = camera_hit[p] ? 0.12f : 0.0f;
    rgb[0] = rgb[1] = rgb[2] = base;
    if (hard[p]) {
      rgb[0] = level(hard[p]);
      rgb[1] = rgb[2] = 0.0f;
    } else if (ambiguous[p]) {
      rgb[0] = rgb[1] = level(ambiguous[p]);
      rgb[2] = 0.0f;
    } else if (tie[p]) {
      rgb[2] = level(tie[p]);
    }
  }
  ColorOptions raw;
  raw.view = "Raw";  // the colours are display values already
  write_display_image(path, image, {{"prism:command", "validate"}}, ColorPipeline(raw));
}

}  // namespace

int run_validate_command(const ValidateOptions& given) {
  ValidateOptions options = given;
  std::optional<ReplayFile> replay;
  if (!options.replay.empty()) {
    replay = read_replay(options.replay);
    if (options.scene.empty()) options.scene = replay->scene;
    // The file's backends unless the command line names others.
    if (!replay->accel.empty() && !options.accel_given) options.accel = replay->accel;
    if (!replay->against.empty() && !options.against_given) options.against = replay->against;
    if (options.set.empty()) options.set = replay->set;
  }
  if (options.scene.empty()) throw Error(ErrorKind::kUsage, "SCENE is required");
  if (options.rays == 0) throw Error(ErrorKind::kUsage, "--rays must be positive");
  ParamSet params = parse_param_assignments(options.set);
  ThreadLimit thread_limit(options.threads);
  const auto a = accelerator_registry().create(options.accel, params);
  const auto b = accelerator_registry().create(options.against, params);
  check_component_params(params,
                         {{"accelerator", options.accel}, {"accelerator", options.against}});

  std::string name;
  const Scene scene = load_scene_or_generated(options.scene, name);
  a->build(scene.geometry);
  b->build(scene.geometry);
  const DoubleOracle oracle(scene.geometry);
  const Judge judge{
      *a, *b, oracle,
      shares_primitive_tests(options.accel) && shares_primitive_tests(options.against)};

  std::vector<Probe> probes;
  BenchRayOptions ray_options;
  ray_options.width = ray_options.height =
      std::max(1, static_cast<int>(std::lround(std::sqrt(double(options.rays)))));
  if (replay) {
    probes = replay->probes;
  } else {
    const std::vector<BenchRaySet> sets = make_bench_ray_sets(scene, *b, ray_options);
    for (const BenchRaySet& s : sets) {
      for (size_t i = 0; i < s.rays.size() && i < options.rays; ++i) {
        probes.push_back({s.name, s.rays[i], s.pixels.empty() ? -1 : int64_t(s.pixels[i])});
      }
    }
    // Feature rays are aimed at a vertex, edge or silhouette point at t = 1: the heatmap shows
    // them where the camera sees that point.
    for (const Ray& r : feature_rays(scene.geometry, options.rays, kSeed)) {
      probes.push_back({"F", r,
                        project_to_pixel(scene.camera, r.origin + r.direction, ray_options.width,
                                         ray_options.height)});
    }
  }

  std::vector<HitComparison> verdicts(probes.size());
  parallel_for_range(
      probes.size(),
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) verdicts[i] = judge(probes[i].ray);
      },
      256);

  fmt::print("{} ({} triangles, {} spheres): {} vs {}, {} rule\n", name,
             scene.geometry.triangle_count(), scene.geometry.spheres.size(), options.accel,
             options.against, judge.exact ? "exact (same bits)" : "tolerance (DESIGN)");
  std::vector<std::string> set_names;
  for (const Probe& p : probes) {
    if (std::find(set_names.begin(), set_names.end(), p.set) == set_names.end()) {
      set_names.push_back(p.set);
    }
  }
  AgreementTally total;
  for (const std::string& set : set_names) {
    AgreementTally tally;
    for (size_t i = 0; i < probes.size(); ++i) {
      if (probes[i].set != set) continue;
      const std::string context =
          verdicts[i].agreement == HitAgreement::kSame ? "" : format_ray(probes[i].ray);
      tally.add(verdicts[i], context);
      total.add(verdicts[i], context);
    }
    std::string blame;
    if (tally.hard > 0) {
      size_t a_off = 0, b_off = 0;
      for (size_t i = 0; i < probes.size(); ++i) {
        if (probes[i].set != set || verdicts[i].agreement != HitAgreement::kHard) continue;
        const int off = judge.off_oracle(probes[i].ray);
        a_off += (off & 1) != 0;
        b_off += (off & 2) != 0;
      }
      blame = fmt::format(" ({} off the oracle's primitive: {}, {}: {})", options.accel, a_off,
                          options.against, b_off);
    }
    fmt::print("  {:<3} {:>8} rays: {}{}\n", set, tally.total(), tally.summary(), blame);
  }
  if (!total.first_hard.empty()) fmt::print("first hard mismatch: {}\n", total.first_hard);

  if (!replay) {
    write_failures(options.failures, options, options.scene, probes, verdicts);
    std::vector<char> camera_hit(size_t(ray_options.width) * ray_options.height, 0);
    for (size_t i = 0; i < probes.size(); ++i) {
      if (probes[i].set == "S" && probes[i].pixel >= 0) camera_hit[size_t(probes[i].pixel)] = 1;
    }
    write_heatmap(options.heatmap, ray_options.width, ray_options.height, probes, verdicts,
                  camera_hit);
    fmt::print("wrote {} ({} rays) and {}\n", options.failures, total.total() - total.same,
               options.heatmap);
  }
  return total.hard == 0 ? kExitSuccess : kExitInternal;
}

}  // namespace prism
