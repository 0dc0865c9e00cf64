// `prism merge`: parts of a frame (render --crop, --samples) added up into the image, or into a
// larger part. The film holds exact integer sums, so the parts add up to the single render's
// film bit for bit, whatever the split and the order of the parts.

#include "core/app/merge_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "color/color_pipeline.h"
#include "color/output_plan.h"
#include "color/state_file.h"
#include "core/app/render_options.h"
#include "core/app/render_state.h"
#include "core/app/resume.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/strings.h"

namespace prism {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Error part_error(const std::string& file, const std::string& message) {
  return Error(ErrorKind::kInput, message, ErrorLocation{file, 0, {}});
}

std::string attribute(const ImageMetadata& attributes, const std::string& name) {
  for (const auto& [key, value] : attributes) {
    if (key == name) return value;
  }
  return {};
}

bool same_file_name(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::absolute(a, ec).lexically_normal() == fs::absolute(b, ec).lexically_normal();
}

/// A box of (pixel, sample) space in none of `parts` (disjoint, leaving a gap in `box`): the
/// first cell, in sample, row, column order, of the grid the parts' edges make that no part
/// holds, grown along x, then y, then samples while every cell it takes in is in no part. On
/// that grid a cell is either wholly in a part or wholly outside every part.
PartsCoverage find_gap(const std::vector<PartExtent>& parts) {
  std::vector<int> xs, ys;
  std::vector<uint32_t> ss;
  for (const auto& p : parts) {
    xs.insert(xs.end(), {p.window.begin.x, p.window.end.x});
    ys.insert(ys.end(), {p.window.begin.y, p.window.end.y});
    ss.insert(ss.end(), {p.samples.first, p.samples.last});
  }
  for (auto* edges : {&xs, &ys}) {
    std::sort(edges->begin(), edges->end());
    edges->erase(std::unique(edges->begin(), edges->end()), edges->end());
  }
  std::sort(ss.begin(), ss.end());
  ss.erase(std::unique(ss.begin(), ss.end()), ss.end());
  const size_t nx = xs.size() - 1, ny = ys.size() - 1, ns = ss.size() - 1;
  const auto free = [&](size_t i, size_t j, size_t k) {
    const glm::ivec2 corner{xs[i], ys[j]};
    return std::none_of(parts.begin(), parts.end(), [&](const PartExtent& p) {
      return p.window.contains(corner) && p.samples.first <= ss[k] && ss[k] < p.samples.last;
    });
  };
  for (size_t k = 0; k < ns; ++k) {
    for (size_t j = 0; j < ny; ++j) {
      for (size_t i = 0; i < nx; ++i) {
        if (!free(i, j, k)) continue;
        size_t i1 = i + 1, j1 = j + 1, k1 = k + 1;
        while (i1 < nx && free(i1, j, k)) ++i1;
        const auto row_free = [&](size_t jj, size_t kk) {
          for (size_t ii = i; ii < i1; ++ii) {
            if (!free(ii, jj, kk)) return false;
          }
          return true;
        };
        while (j1 < ny && row_free(j1, k)) ++j1;
        const auto layer_free = [&](size_t kk) {
          for (size_t jj = j; jj < j1; ++jj) {
            if (!row_free(jj, kk)) return false;
          }
          return true;
        };
        while (k1 < ns && layer_free(k1)) ++k1;
        return PartsCoverage{PixelRect{{xs[i], ys[j]}, {xs[i1], ys[j1]}},
                             SampleRange{ss[k], ss[k1]}};
      }
    }
  }
  fail_check("find_gap() found no gap", __FILE__, __LINE__);
}

/// One part as the first look finds it: its header, before its pixels.
struct PartHeader {
  std::string file;
  ImageMetadata attributes;
  std::string state_text;  ///< prism:renderState as found; the second look must find the same
  RenderStateRecord record;
};

PartHeader read_part_header(const std::string& file) {
  PartHeader part;
  part.file = file;
  part.attributes = read_state_file_attributes(file);
  part.state_text = attribute(part.attributes, kRenderStateAttribute);
  part.record = render_state_from_text(part.state_text, file);
  return part;
}

/// Throws Error(kInput) naming `part` and the first field (in the identity's order) that differs
/// unless it is a part of the render `first` is a part of.
void check_same_render(const PartHeader& part, const PartHeader& first) {
  const json& mine = part.record.identity;
  const json& theirs = first.record.identity;
  const std::string prefix = "part of a different render: ";
  if (mine != theirs) {
    std::set<std::string> keys;
    for (const auto& [key, value] : mine.items()) keys.insert(key);
    for (const auto& [key, value] : theirs.items()) keys.insert(key);
    for (const std::string& key : keys) {
      const json a = mine.contains(key) ? mine[key] : json();
      const json b = theirs.contains(key) ? theirs[key] : json();
      if (a == b) continue;
      const std::string what =
          key == "scene" ? "'scene' (the hash of the scene as rendered)" : "'" + key + "'";
      const auto text = [](const json& v) { return v.is_null() ? "(unset)" : v.dump(); };
      throw part_error(part.file, fmt::format("{}{} is {}, {} has {}", prefix, what, text(a),
                                              first.file, text(b)));
    }
  }
  const RenderStateRecord& r = part.record;
  const RenderStateRecord& f = first.record;
  if (r.width != f.width || r.height != f.height) {
    throw part_error(part.file, fmt::format("{}its resolution is {} x {}, {} has {} x {}", prefix,
                                            r.width, r.height, first.file, f.width, f.height));
  }
  if (r.spp != f.spp) {
    throw part_error(part.file,
                     fmt::format("{}its spp is {}, {} has {}", prefix, r.spp, first.file, f.spp));
  }
}

/// Adaptive sampling decides where a pixel stops from every sample before: only crops of an
/// adaptive render add up (render refuses -a with --samples; this catches a file that says
/// otherwise).
void check_adaptive_split(const PartHeader& part) {
  const RenderStateRecord& r = part.record;
  const bool adaptive = r.identity.contains("adaptive") && !r.identity["adaptive"].is_null();
  if (adaptive && r.samples != SampleRange{0, uint32_t(r.spp)}) {
    throw part_error(part.file,
                     fmt::format("an adaptive render cannot be split into sample ranges (this "
                                 "part has samples [{}, {}) of {}); split it by --crop",
                                 r.samples.first, r.samples.last, r.spp));
  }
}

/// The colour pipeline merge builds from the parts' options must be the one they were rendered
/// with: the same OCIO config (the default one comes from $OCIO, which may differ here) and
/// spaces, or the EXR's values would differ.
void check_pipeline(const ColorPipeline& pipeline, const PartHeader& first) {
  const json here{{"ocio_config", pipeline.config_hash()},
                  {"working_space", pipeline.working_space()},
                  {"output_space", pipeline.output_space()}};
  const json& identity = first.record.identity;
  for (const auto& [key, value] : here.items()) {
    const json stored = identity.contains(key) ? identity[key] : json();
    if (stored == value) continue;
    throw part_error(first.file,
                     fmt::format("the parts were rendered with another OCIO config or colour "
                                 "spaces than merge finds here ('{}' is {} here, {} in the "
                                 "parts); merge with the config they were rendered with ($OCIO "
                                 "or the path of their --ocio-config)",
                                 key, value.dump(), stored.dump()));
  }
}

/// Throws Error(kInput) naming the file unless every pixel of the part went through its whole
/// sample range (a render stopped by a signal or a time limit still writes its part).
void check_complete(const RenderState& part, const std::string& file) {
  const SampleRange samples = part.record.samples;
  const PixelRect& w = part.film.window();
  for (int y = w.begin.y; y < w.end.y; ++y) {
    for (int x = w.begin.x; x < w.end.x; ++x) {
      const uint32_t progress = part.film.pixel({x, y}).progress;
      if (progress >= samples.last) continue;
      const std::string stopped = attribute(part.attributes, "prism:stoppedBy");
      const std::string by = stopped.empty() || stopped == "-" ? "" : " by " + stopped;
      throw part_error(
          file,
          fmt::format("the part is incomplete: its render was stopped{} before the end of "
                      "its samples [{}, {}) (pixel ({}, {}) reached sample {}); resume it "
                      "from its checkpoint (render --resume) or render it again",
                      by, samples.first, samples.last, x, y, std::max(progress, samples.first)));
    }
  }
}

/// Carries the adaptive sampler's per-pixel state of a part holding every sample of its pixels
/// (Film::accumulate adds only the exact sums), so that a merged part keeps every FilmPixel.
void copy_adaptive_state(const Film& part, Film& merged) {
  const PixelRect& w = part.window();
  for (int y = w.begin.y; y < w.end.y; ++y) {
    for (int x = w.begin.x; x < w.end.x; ++x) {
      const FilmPixel& from = part.pixel({x, y});
      FilmPixel& to = merged.pixel({x, y});
      to.illuminance = from.illuminance;
      to.illuminance_squared = from.illuminance_squared;
      to.converged = from.converged;
    }
  }
}

double number_attribute(const ImageMetadata& attributes, const std::string& name) {
  const std::string text = attribute(attributes, name);
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  return end != text.c_str() && value >= 0.0 ? value : 0.0;
}

/// prism:mergedFrom: each part's file as given, window, samples and rendering time, with the
/// parts a merged part was merged from.
json merged_from(const std::vector<PartHeader>& parts) {
  json list = json::array();
  for (const auto& part : parts) {
    const RenderStateRecord& r = part.record;
    json entry{{"file", part.file},
               {"window", {r.window.begin.x, r.window.begin.y, r.window.end.x, r.window.end.y}},
               {"samples", {r.samples.first, r.samples.last}},
               {"render_ms", r.render_ms}};
    const json nested = json::parse(attribute(part.attributes, "prism:mergedFrom"), nullptr,
                                    /*allow_exceptions=*/false);
    if (nested.is_array()) entry["mergedFrom"] = nested;
    list.push_back(std::move(entry));
  }
  return list;
}

/// The prism:* attributes of the merged file, in make_provenance()'s order: the render's
/// settings as the first part records them (every part has the same), times added over the
/// parts, counts from the merged film, this command line, and prism:mergedFrom.
ImageMetadata merged_provenance(const std::vector<PartHeader>& parts,
                                const RenderStateRecord& merged, const Film& film, double build_ms,
                                const std::string& command_line) {
  const ImageMetadata& first = parts.front().attributes;
  ImageMetadata metadata;
  const auto copy = [&](const char* key) { metadata.emplace_back(key, attribute(first, key)); };
  for (const char* key :
       {"prism:version", "prism:scene", "prism:accelerator", "prism:integrator", "prism:sampler",
        "prism:spp", "prism:light_samples", "prism:max_depth", "prism:seed", "prism:resolution"}) {
    copy(key);
  }
  uint64_t camera_samples = 0;
  for (const FilmPixel& p : film.pixels()) camera_samples += p.samples;
  const double per_second =
      merged.render_ms > 0.0 ? double(camera_samples) / (merged.render_ms * 1e-3) : 0.0;
  metadata.emplace_back("prism:build_ms", fmt::format("{:.3f}", build_ms));
  metadata.emplace_back("prism:render_ms", fmt::format("{:.3f}", merged.render_ms));
  metadata.emplace_back("prism:samples_per_second", fmt::format("{:.0f}", per_second));
  metadata.emplace_back("prism:command_line", command_line);
  copy("prism:params");
  metadata.emplace_back("prism:camera_samples", std::to_string(camera_samples));
  metadata.emplace_back("prism:non_finite_samples", std::to_string(film.non_finite_samples()));
  metadata.emplace_back("prism:samples",
                        fmt::format("{} {}", merged.samples.first, merged.samples.last));
  const int passes =
      RenderSchedule(merged.window, merged.samples, merged.pass_samples).pass_count();
  metadata.emplace_back("prism:passes", fmt::format("{} of {}", passes, passes));
  metadata.emplace_back("prism:stoppedBy", "-");
  if (merged.window != PixelRect{{0, 0}, {merged.width, merged.height}}) {
    const PixelRect& w = merged.window;
    metadata.emplace_back("prism:crop",
                          fmt::format("{} {} {} {}", w.begin.x, w.begin.y, w.end.x, w.end.y));
  }
  if (!attribute(first, "prism:environment").empty()) {
    copy("prism:environment");
    copy("prism:environmentColorSpace");
  }
  metadata.emplace_back("prism:mergedFrom", merged_from(parts).dump());
  return metadata;
}

}  // namespace

std::string describe_extent(const PixelRect& w, SampleRange s) {
  return fmt::format("x in [{}, {}), y in [{}, {}), samples [{}, {})", w.begin.x, w.end.x,
                     w.begin.y, w.end.y, s.first, s.last);
}

PartsCoverage check_part_coverage(const std::vector<PartExtent>& parts) {
  PRISM_CHECK(!parts.empty());
  PartsCoverage box{parts.front().window, parts.front().samples};
  for (const auto& p : parts) {
    PRISM_CHECK(!p.window.empty() && p.samples.count() > 0 && p.window.begin.x >= 0 &&
                p.window.begin.y >= 0 && p.window.end.x <= kMaxFilmSide &&
                p.window.end.y <= kMaxFilmSide);
    box.window.begin = glm::min(box.window.begin, p.window.begin);
    box.window.end = glm::max(box.window.end, p.window.end);
    box.samples.first = std::min(box.samples.first, p.samples.first);
    box.samples.last = std::max(box.samples.last, p.samples.last);
  }
  for (size_t j = 1; j < parts.size(); ++j) {
    for (size_t i = 0; i < j; ++i) {
      const PartExtent& a = parts[i];
      const PartExtent& b = parts[j];
      const PixelRect both{glm::max(a.window.begin, b.window.begin),
                           glm::min(a.window.end, b.window.end)};
      const SampleRange samples{std::max(a.samples.first, b.samples.first),
                                std::min(a.samples.last, b.samples.last)};
      if (both.empty() || samples.count() == 0) continue;
      if (same_file_name(a.file, b.file)) throw part_error(b.file, "is given twice");
      throw part_error(b.file, fmt::format("overlaps {}: {} are in both (every sample of a pixel "
                                           "must come from one part)",
                                           a.file, describe_extent(both, samples)));
    }
  }
  // Disjoint parts inside the box fill it exactly when their volumes add up to its volume, which
  // is below 2^28 pixels x 2^32 samples: no overflow.
  uint64_t volume = 0;
  for (const auto& p : parts) volume += uint64_t(p.window.pixel_count()) * p.samples.count();
  if (volume == uint64_t(box.window.pixel_count()) * box.samples.count()) return box;
  const PartsCoverage gap = find_gap(parts);
  throw Error(ErrorKind::kInput,
              fmt::format("the parts leave a gap: {} are in no part (the parts span {})",
                          describe_extent(gap.window, gap.samples),
                          describe_extent(box.window, box.samples)));
}

int run_merge_command(const MergeOptions& options) {
  if (options.parts.empty()) {
    throw Error(ErrorKind::kUsage, "give at least one part file", ErrorLocation{{}, 0, "merge"});
  }
  if (options.output.empty()) {
    throw Error(ErrorKind::kUsage, "give the output file", ErrorLocation{{}, 0, "--output (-f)"});
  }
  // The output first: a bad extension or folder costs no reading.
  RenderOptions probe;
  probe.output = options.output;
  probe.png = options.png;
  const OutputPlan probe_plan = resolve_output_plan(probe);
  validate_outputs(probe_plan);
  std::vector<NamedInput> inputs;
  for (const std::string& part : options.parts) inputs.push_back({"a part to merge", part});
  refuse_overwriting_inputs(named_outputs(probe_plan), inputs);

  // First look, at the headers only: do the parts belong together and fill a box?
  std::vector<PartHeader> parts;
  parts.reserve(options.parts.size());
  for (const std::string& file : options.parts) parts.push_back(read_part_header(file));
  const PartHeader& first = parts.front();
  std::vector<PartExtent> extents;
  for (const PartHeader& part : parts) {
    check_same_render(part, first);
    check_adaptive_split(part);
    extents.push_back(PartExtent{part.file, part.record.window, part.record.samples});
  }
  const PartsCoverage coverage = check_part_coverage(extents);
  const RenderStateRecord& reference = first.record;
  const PixelRect image{{0, 0}, {reference.width, reference.height}};
  const SampleRange all_samples{0, uint32_t(reference.spp)};
  const bool complete = coverage.window == image && coverage.samples == all_samples;

  // The result's options: the parts' (colour settings, EXR encoding, adaptive sampling for the
  // sample-rate picture), with this command's output and the merged extent.
  RenderOptions merged = reference.options;
  merged.output = options.output;
  merged.png = options.png;
  merged.exr = false;
  merged.quiet = options.quiet;
  merged.command_line = options.command_line;
  merged.time_limit.reset();
  merged.checkpoint.clear();
  merged.resume.clear();
  merged.crop.reset();
  if (coverage.window != image) {
    const PixelRect& w = coverage.window;
    merged.crop = std::array<int, 4>{w.begin.x, w.begin.y, w.end.x, w.end.y};
  }
  merged.sample_range.reset();
  if (coverage.samples != all_samples) {
    merged.sample_range = std::pair<int, int>(coverage.samples.first, coverage.samples.last);
  }
  const OutputPlan plan = resolve_output_plan(merged);
  validate_outputs(plan);
  if (!complete && plan.files.front().kind != OutputKind::kSceneLinearExr) {
    throw Error(ErrorKind::kUsage,
                fmt::format("the parts make up {} of the {} x {} frame at {} spp, a part again, "
                            "which only an EXR holds (for merging with the rest): give -f "
                            "FILE.exr",
                            describe_extent(coverage.window, coverage.samples), reference.width,
                            reference.height, reference.spp),
                ErrorLocation{{}, 0, "--output (-f)"});
  }
  const ColorPipeline pipeline(merged.color);
  check_pipeline(pipeline, first);

  // Second look, at the pixels, one part at a time: only the merged film and one part in memory.
  Film film(reference.width, reference.height, coverage.window);
  uint64_t pixels_to_read = 0;
  for (const auto& e : extents) pixels_to_read += e.window.pixel_count();
  ProgressReporter progress("merging", pixels_to_read, options.quiet);
  double build_ms = 0.0;
  double render_ms = 0.0;
  for (const PartHeader& header : parts) {
    RenderState part = read_render_state(header.file);
    if (attribute(part.attributes, kRenderStateAttribute) != header.state_text) {
      throw part_error(header.file, "the file changed while merging");
    }
    check_complete(part, header.file);
    film.accumulate(part.film);
    if (part.record.samples == all_samples) copy_adaptive_state(part.film, film);
    build_ms += number_attribute(part.attributes, "prism:build_ms");
    render_ms += part.record.render_ms;
    progress.update(part.film.window().pixel_count());
  }
  progress.done();

  RenderStateRecord record = reference;
  record.options = with_absolute_paths(merged);
  record.window = coverage.window;
  record.samples = coverage.samples;
  record.render_ms = render_ms;
  const ImageMetadata metadata =
      merged_provenance(parts, record, film, build_ms, options.command_line);
  std::vector<std::string> files;
  for (const auto& file : plan.files) files.push_back(file.path.string());
  const char* noun = parts.size() == 1 ? "part" : "parts";
  if (complete) {
    write_outputs(plan, film.resolve(), metadata, pipeline);
    std::printf("merged %zu %s: %dx%d at %d spp, %.4g ms of rendering in all -> %s\n", parts.size(),
                noun, reference.width, reference.height, reference.spp, render_ms,
                join(files).c_str());
  } else {
    // A part again, with its exact sums, for a further merge.
    write_render_state(plan.files.front().path, film, record, metadata, pipeline);
    OutputPlan rest = plan;
    rest.files.erase(rest.files.begin());
    write_outputs(rest, film.resolve(), metadata, pipeline);
    std::printf(
        "merged %zu %s into a part (%s of the %dx%d frame at %d spp): merge it with the rest "
        "of the frame -> %s\n",
        parts.size(), noun, describe_extent(coverage.window, coverage.samples).c_str(),
        reference.width, reference.height, reference.spp, join(files).c_str());
  }
  return kExitSuccess;
}

}  // namespace prism
