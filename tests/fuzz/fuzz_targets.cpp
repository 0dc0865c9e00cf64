// The fuzz targets: each feeds its bytes to one parser prism owns (tests/fuzz/README.md). Shared
// by the libFuzzer program (fuzz_main.cpp, build-fuzz/) and the corpus replay test
// (tests/app_fuzz_corpus_test.cpp, the normal build).

#include "tests/fuzz/fuzz_targets.h"

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "color/color_pipeline.h"
#include "core/app/cli.h"
#include "core/app/environment_map.h"
#include "core/app/merge_command.h"
#include "core/app/render_options.h"
#include "core/app/render_state.h"
#include "core/app/resume.h"
#include "core/error.h"
#include "core/param_set.h"
#include "scenes/scene_loader.h"

namespace prism::fuzz {
namespace {

namespace fs = std::filesystem;

/// A folder of this process's own in the temporary folder, removed at exit.
class ScratchFolder {
 public:
  ScratchFolder()
      : root_(fs::temp_directory_path() / ("prism-fuzz-" + std::to_string(::getpid()))) {
    fs::create_directories(root_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  const fs::path& root() const { return root_; }

 private:
  fs::path root_;
};

/// `<scratch>/<target>/`, made on first use.
fs::path target_folder(const char* target) {
  static ScratchFolder scratch;
  const fs::path folder = scratch.root() / target;
  fs::create_directories(folder);
  return folder;
}

/// `<scratch>/<target>/<file>`, holding `bytes`.
fs::path write_input(const char* target, const std::string& file, std::string_view bytes) {
  const fs::path path = target_folder(target) / file;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out) throw std::runtime_error("fuzz: cannot write " + path.string());
  return path;
}

std::string_view as_text(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

bool starts_with(std::string_view text, std::string_view prefix) {
  return text.substr(0, prefix.size()) == prefix;
}

/// The input cut at newlines (a trailing '\r' kept: the parsers must cope).
std::vector<std::string> lines(std::string_view text) {
  std::vector<std::string> out;
  size_t begin = 0;
  while (begin <= text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    out.emplace_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  if (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

/// Runs `body`; prism::Error is the expected answer to bad input, anything else escapes.
template <class Body>
void expect_only_prism_errors(Body&& body) {
  try {
    body();
  } catch (const Error&) {
  }
}

void run_collada(const uint8_t* data, size_t size) {
  const fs::path path = write_input("collada", "scene.dae", as_text(data, size));
  expect_only_prism_errors([&] { load_scene(path); });
  expect_only_prism_errors([&] { load_scene(path, SceneLoadOptions{.literal_camera = true}); });
}

void run_json_scene(const uint8_t* data, size_t size) {
  const fs::path path = write_input("json_scene", "scene.json", as_text(data, size));
  expect_only_prism_errors([&] { load_scene(path); });
}

/// The model file's extension from its first bytes, as a user's file would have it.
std::string model_file_name(std::string_view text) {
  if (starts_with(text, "ply")) return "model.ply";
  if (starts_with(text, "glTF")) return "model.glb";
  if (starts_with(text, "Kaydara FBX") || starts_with(text, "; FBX")) return "model.fbx";
  if (starts_with(text, "solid") || (text.size() >= 84 && text.find('\0') < 84)) {
    return "model.stl";
  }
  if (starts_with(text, "{")) return "model.gltf";
  return "model.obj";
}

void run_model(const uint8_t* data, size_t size) {
  const std::string_view text = as_text(data, size);
  const fs::path path = write_input("model", model_file_name(text), text);
  expect_only_prism_errors([&] { load_scene(path); });
}

/// Each line one --set assignment; every key read back as every type.
void run_set_params(const uint8_t* data, size_t size) {
  expect_only_prism_errors([&] {
    const ParamSet params = parse_param_assignments(lines(as_text(data, size)));
    for (const std::string& key : params.keys()) {
      expect_only_prism_errors([&] { params.get_int(key, 0, -1000, 1000); });
      expect_only_prism_errors([&] { params.get_float(key, 0.0, -1e30, 1e30); });
      expect_only_prism_errors([&] { params.get_bool(key, false); });
      params.get_string(key, "");
    }
    params.unused_with_prefix("bvh.");
    params.to_string();
  });
}

/// Each line one argument of `prism render`: parsed, checked, and the options a checkpoint would
/// record read back. A checked set of options that does not survive the trip through JSON is a
/// bug (a checkpoint that cannot be resumed), so that step is outside the catch.
void run_render_options(const uint8_t* data, size_t size) {
  RenderOptions options;
  try {
    options = parse_render_arguments(lines(as_text(data, size)));
    validate_render_options(options);
    parse_param_assignments(options.set);
    resolve_output_plan(options);
  } catch (const Error&) {
    return;
  }
  const nlohmann::json json = options_to_json(options);
  const RenderOptions back = options_from_json(json, "fuzz");
  if (options_to_json(back) != json) {
    throw std::logic_error("render options changed through JSON: " + json.dump());
  }
}

/// The environment-map file's extension from its magic number.
std::string environment_file_name(std::string_view text) {
  if (starts_with(text, "#?")) return "map.hdr";
  if (starts_with(text, "PF") || starts_with(text, "Pf")) return "map.pfm";
  if (starts_with(text, "\x89PNG")) return "map.png";
  return "map.exr";
}

void run_environment_map(const uint8_t* data, size_t size) {
  static const ColorPipeline pipeline{ColorOptions{}};
  const std::string_view text = as_text(data, size);
  const fs::path path = write_input("environment_map", environment_file_name(text), text);
  expect_only_prism_errors([&] { load_environment_map(path, pipeline); });
}

/// The bytes as a checkpoint or part file (an EXR state file).
void run_state_file(const uint8_t* data, size_t size) {
  const fs::path path = write_input("state_file", "state.exr", as_text(data, size));
  expect_only_prism_errors([&] { read_render_state(path); });
}

/// The bytes as the prism:renderState attribute of a checkpoint, then resumed as `--resume`
/// would.
void run_render_state(const uint8_t* data, size_t size) {
  expect_only_prism_errors([&] {
    const RenderStateRecord record =
        render_state_from_text(std::string(as_text(data, size)), "state.exr");
    RenderOptions given;
    given.resume = "state.exr";
    const RenderOptions resumed = resumed_options(given, record, "state.exr");
    with_absolute_paths(resumed);
    render_state_to_text(record);
  });
}

/// Parts of a frame for `prism merge`: the input cut at kPartSeparator into at most 4 part
/// files, merged into an EXR.
constexpr std::string_view kPartSeparator = "\n--prism-part--\n";

void run_merge(const uint8_t* data, size_t size) {
  std::string_view text = as_text(data, size);
  MergeOptions options;
  options.quiet = true;
  for (int i = 0; i < 4 && !text.empty(); ++i) {
    size_t end = text.find(kPartSeparator);
    if (i == 3 || end == std::string_view::npos) end = text.size();
    options.parts.push_back(
        write_input("merge", "part" + std::to_string(i) + ".exr", text.substr(0, end)).string());
    text.remove_prefix(std::min(text.size(), end + kPartSeparator.size()));
  }
  options.output = (target_folder("merge") / "merged.exr").string();
  expect_only_prism_errors([&] { run_merge_command(options); });
}

/// Little-endian integers from the input, 0 when it runs out.
class Reader {
 public:
  Reader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool empty() const { return offset_ >= size_; }
  uint32_t u32() {
    uint32_t value = 0;
    for (int i = 0; i < 4; ++i)
      value |= uint32_t(offset_ < size_ ? data_[offset_++] : 0) << (8 * i);
    return value;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
};

/// Up to 64 parts, each 6 integers (x0 y0 x1 y1 first last, small or extreme), checked for
/// covering a box exactly; the answer is compared with a count of (pixel, sample) cells when the
/// box is small.
void run_merge_coverage(const uint8_t* data, size_t size) {
  Reader in(data, size);
  std::vector<PartExtent> parts;
  while (!in.empty() && parts.size() < 64) {
    int v[4];
    for (int& x : v) {
      const uint32_t raw = in.u32();
      // Mostly small coordinates (to make real tilings), sometimes any 32-bit value.
      x = (raw & 0x80000000u) ? int32_t(raw << 1) : int(raw % 17);
    }
    const uint32_t first = in.u32() % 9, last = in.u32() % 9;
    parts.push_back(PartExtent{"part" + std::to_string(parts.size()) + ".exr",
                               PixelRect{{v[0], v[1]}, {v[2], v[3]}}, SampleRange{first, last}});
  }
  PartsCoverage box;
  try {
    box = check_part_coverage(parts);
  } catch (const Error&) {
    return;
  }
  // Accepted: every cell of the box is in exactly one part.
  if (box.window.pixel_count() * box.samples.count() > 100000) return;
  for (int y = box.window.begin.y; y < box.window.end.y; ++y) {
    for (int x = box.window.begin.x; x < box.window.end.x; ++x) {
      for (uint32_t s = box.samples.first; s < box.samples.last; ++s) {
        int owners = 0;
        for (const PartExtent& p : parts) {
          owners +=
              p.window.contains(glm::ivec2(x, y)) && s >= p.samples.first && s < p.samples.last;
        }
        if (owners != 1) throw std::logic_error("check_part_coverage accepted a bad tiling");
      }
    }
  }
}

}  // namespace

const std::vector<Target>& targets() {
  static const std::vector<Target> all = {
      {"collada", "a .dae scene (CS184 COLLADA), homework and literal camera", run_collada},
      {"json_scene", "a .json scene (docs/SCENE_FORMAT.md)", run_json_scene},
      {"model", "a model file through Assimp; .ply/.glb/.fbx/.stl/.gltf by magic, else .obj",
       run_model},
      {"set_params", "--set assignments, one a line, each key read as every type", run_set_params},
      {"render_options", "`prism render` arguments, one a line: parsed, checked, through JSON",
       run_render_options},
      {"environment_map", "an -e image: .hdr/.pfm/.png by magic, else .exr", run_environment_map},
      {"state_file", "a checkpoint or part file (EXR state file)", run_state_file},
      {"render_state", "the prism:renderState JSON of a checkpoint, resumed", run_render_state},
      {"merge", "up to 4 part files cut at \"\\n--prism-part--\\n\", merged", run_merge},
      {"merge_coverage", "part extents (6 x u32 each) checked for tiling a box",
       run_merge_coverage},
  };
  return all;
}

const Target* find_target(const std::string& name) {
  for (const Target& target : targets()) {
    if (name == target.name) return &target;
  }
  return nullptr;
}

}  // namespace prism::fuzz
