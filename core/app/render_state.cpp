#include "core/app/render_state.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "core/error.h"
#include "core/hash.h"
#include "core/scene_hash.h"

namespace prism {
namespace {

using nlohmann::json;

template <typename T>
json optional_json(const std::optional<T>& value) {
  return value ? json(*value) : json(nullptr);
}

template <typename T>
struct is_pair : std::false_type {};
template <typename A, typename B>
struct is_pair<std::pair<A, B>> : std::true_type {};
template <typename T>
struct is_std_array : std::false_type {};
template <typename E, size_t N>
struct is_std_array<std::array<E, N>> : std::true_type {};

/// `j` as a T, or nothing when it is not one: integers must be JSON integers within T's range,
/// floats finite JSON numbers within T's range, pairs and std::arrays arrays of that many such.
/// (nlohmann's own conversion casts a float to an int, or a huge double to a float, unchecked:
/// undefined behaviour on a damaged or hostile state file.)
template <typename T>
std::optional<T> checked_value(const json& j) {
  if constexpr (std::is_same_v<T, bool>) {
    if (!j.is_boolean()) return std::nullopt;
    return j.get<bool>();
  } else if constexpr (std::is_integral_v<T>) {
    if (j.is_number_unsigned()) {
      const auto v = j.get<uint64_t>();
      if (v > uint64_t(std::numeric_limits<T>::max())) return std::nullopt;
      return static_cast<T>(v);
    }
    if (!j.is_number_integer()) return std::nullopt;
    const auto v = j.get<int64_t>();
    if (v < int64_t(std::numeric_limits<T>::lowest()) ||
        v > int64_t(std::numeric_limits<T>::max())) {
      return std::nullopt;
    }
    return static_cast<T>(v);
  } else if constexpr (std::is_floating_point_v<T>) {
    if (!j.is_number()) return std::nullopt;
    const double v = j.get<double>();
    if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<T>::max())) {
      return std::nullopt;
    }
    return static_cast<T>(v);
  } else if constexpr (is_pair<T>::value) {
    if (!j.is_array() || j.size() != 2) return std::nullopt;
    auto first = checked_value<typename T::first_type>(j[0]);
    auto second = checked_value<typename T::second_type>(j[1]);
    if (!first || !second) return std::nullopt;
    return T(*first, *second);
  } else if constexpr (is_std_array<T>::value) {
    T values{};
    if (!j.is_array() || j.size() != values.size()) return std::nullopt;
    for (size_t i = 0; i < values.size(); ++i) {
      auto value = checked_value<typename T::value_type>(j[i]);
      if (!value) return std::nullopt;
      values[i] = *value;
    }
    return values;
  } else {
    try {
      return j.get<T>();
    } catch (const json::exception&) {
      return std::nullopt;
    }
  }
}

/// Reads JSON fields with one-line errors naming the source and the key.
class Fields {
 public:
  Fields(const json& object, std::string source, std::string prefix = "")
      : object_(object), source_(std::move(source)), prefix_(std::move(prefix)) {
    if (!object_.is_object()) fail("", "is not a JSON object");
  }

  template <typename T>
  T get(const std::string& key) const {
    const auto it = object_.find(key);
    if (it == object_.end()) fail(key, "is missing");
    std::optional<T> value = checked_value<T>(*it);
    if (!value) fail(key, "has the wrong type or is out of range");
    return std::move(*value);
  }
  template <typename T>
  T get_or(const std::string& key, T fallback) const {
    return object_.contains(key) ? get<T>(key) : fallback;
  }
  template <typename T>
  std::optional<T> get_optional(const std::string& key) const {
    const auto it = object_.find(key);
    if (it == object_.end()) fail(key, "is missing");
    if (it->is_null()) return std::nullopt;
    return get<T>(key);
  }
  Fields object(const std::string& key) const {
    const auto it = object_.find(key);
    if (it == object_.end()) fail(key, "is missing");
    return Fields(*it, source_, prefix_ + key + ".");
  }

 private:
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw Error(ErrorKind::kInput, "render state field '" + prefix_ + key + "' " + problem,
                ErrorLocation{source_, 0, kRenderStateAttribute});
  }

  const json& object_;
  std::string source_;
  std::string prefix_;
};

}  // namespace

json options_to_json(const RenderOptions& o) {
  return json{
      {"scene", o.scene},
      {"accelerator", o.accelerator},
      {"integrator", optional_json(o.integrator)},
      {"sampler", o.sampler},
      {"spp", optional_json(o.spp)},
      {"light_samples", optional_json(o.light_samples)},
      {"max_depth", optional_json(o.max_depth)},
      {"resolution", optional_json(o.resolution)},
      {"seed", optional_json(o.seed)},
      {"threads", o.threads},
      {"adaptive", optional_json(o.adaptive)},
      {"hemisphere_sampling", o.hemisphere_sampling},
      {"two_sided_emitters", o.two_sided_emitters},
      {"lens_radius", optional_json(o.lens_radius)},
      {"focal_distance", optional_json(o.focal_distance)},
      {"environment_map", o.environment_map},
      {"camera_file", o.camera_file},
      {"output", o.output},
      {"png", o.png},
      {"exr", o.exr},
      {"quiet", o.quiet},
      {"literal_camera", o.literal_camera},
      {"set", o.set},
      {"time_limit", optional_json(o.time_limit)},
      {"checkpoint", o.checkpoint},
      {"checkpoint_interval", o.checkpoint_interval},
      {"crop", optional_json(o.crop)},
      {"sample_range", optional_json(o.sample_range)},
      {"pass_samples", optional_json(o.pass_samples)},
      {"color",
       {{"ocio_config", o.color.ocio_config},
        {"working_space", o.color.working_space},
        {"output_space", o.color.output_space},
        {"display", o.color.display},
        {"view", o.color.view},
        {"look", o.color.look},
        {"exposure", o.color.exposure}}},
      {"exr_options",
       {{"pixel_type", o.exr_options.pixel_type}, {"compression", o.exr_options.compression}}},
      {"command_line", o.command_line},
  };
}

RenderOptions options_from_json(const json& j, const std::string& source) {
  const Fields f(j, source, "options.");
  RenderOptions o;
  o.scene = f.get<std::string>("scene");
  o.accelerator = f.get<std::string>("accelerator");
  o.integrator = f.get_optional<std::string>("integrator");
  o.sampler = f.get<std::string>("sampler");
  o.spp = f.get_optional<int>("spp");
  o.light_samples = f.get_optional<int>("light_samples");
  o.max_depth = f.get_optional<int>("max_depth");
  o.resolution = f.get_optional<std::pair<int, int>>("resolution");
  o.seed = f.get_optional<std::string>("seed");
  o.threads = f.get<int>("threads");
  o.adaptive = f.get_optional<std::pair<int, double>>("adaptive");
  o.hemisphere_sampling = f.get<bool>("hemisphere_sampling");
  // Absent from the state files of prism before the flag existed.
  o.two_sided_emitters = f.get_or<bool>("two_sided_emitters", false);
  o.lens_radius = f.get_optional<float>("lens_radius");
  o.focal_distance = f.get_optional<float>("focal_distance");
  o.environment_map = f.get<std::string>("environment_map");
  o.camera_file = f.get<std::string>("camera_file");
  o.output = f.get<std::string>("output");
  o.png = f.get<bool>("png");
  o.exr = f.get<bool>("exr");
  o.quiet = f.get<bool>("quiet");
  o.literal_camera = f.get<bool>("literal_camera");
  o.set = f.get<std::vector<std::string>>("set");
  o.time_limit = f.get_optional<double>("time_limit");
  o.checkpoint = f.get<std::string>("checkpoint");
  o.checkpoint_interval = f.get<double>("checkpoint_interval");
  o.crop = f.get_optional<std::array<int, 4>>("crop");
  o.sample_range = f.get_optional<std::pair<int, int>>("sample_range");
  o.pass_samples = f.get_optional<int>("pass_samples");
  const Fields color = f.object("color");
  o.color.ocio_config = color.get<std::string>("ocio_config");
  o.color.working_space = color.get<std::string>("working_space");
  o.color.output_space = color.get<std::string>("output_space");
  o.color.display = color.get<std::string>("display");
  o.color.view = color.get<std::string>("view");
  o.color.look = color.get<std::string>("look");
  o.color.exposure = color.get<float>("exposure");
  const Fields exr = f.object("exr_options");
  o.exr_options.pixel_type = exr.get<std::string>("pixel_type");
  o.exr_options.compression = exr.get<std::string>("compression");
  o.command_line = f.get<std::string>("command_line");
  return o;
}

json render_identity(const RenderOptions& o, const Scene& scene, const ColorPipeline& pipeline) {
  return json{
      {"prism", PRISM_VERSION},
      {"scene", hex64(scene_hash(scene))},
      {"ocio_config", pipeline.config_hash()},
      {"working_space", pipeline.working_space()},
      {"output_space", pipeline.output_space()},
      {"display", o.color.display},
      {"view", o.color.view},
      {"look", o.color.look},
      {"exposure", o.color.exposure},
      {"exr_options", {o.exr_options.pixel_type, o.exr_options.compression}},
      {"accelerator", o.accelerator},
      {"integrator", optional_json(o.integrator)},
      {"sampler", o.sampler},
      {"spp", optional_json(o.spp)},
      {"light_samples", optional_json(o.light_samples)},
      {"max_depth", optional_json(o.max_depth)},
      {"resolution", optional_json(o.resolution)},
      {"seed", optional_json(o.seed)},
      {"adaptive", optional_json(o.adaptive)},
      {"hemisphere_sampling", o.hemisphere_sampling},
      {"two_sided_emitters", o.two_sided_emitters},
      {"lens_radius", optional_json(o.lens_radius)},
      {"focal_distance", optional_json(o.focal_distance)},
      {"literal_camera", o.literal_camera},
      {"set", o.set},
  };
}

std::string render_state_to_text(const RenderStateRecord& r) {
  return json{
      {"version", 1},
      {"identity", r.identity},
      {"options", options_to_json(r.options)},
      {"window", {r.window.begin.x, r.window.begin.y, r.window.end.x, r.window.end.y}},
      {"samples", {r.samples.first, r.samples.last}},
      {"pass_samples", r.pass_samples},
      {"resolution", {r.width, r.height}},
      {"spp", r.spp},
      {"render_ms", r.render_ms},
  }
      .dump();
}

RenderStateRecord render_state_from_text(const std::string& text, const std::string& source) {
  if (text.empty()) {
    throw Error(ErrorKind::kInput, "has no render state (not a checkpoint or part of prism's)",
                ErrorLocation{source, 0, kRenderStateAttribute});
  }
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) {
    throw Error(ErrorKind::kInput, "the render state is not valid JSON",
                ErrorLocation{source, 0, kRenderStateAttribute});
  }
  const Fields f(j, source);
  if (f.get<int>("version") != 1) {
    throw Error(ErrorKind::kInput, "render state version is not 1",
                ErrorLocation{source, 0, kRenderStateAttribute});
  }
  RenderStateRecord r;
  f.object("identity");  // present and an object
  r.identity = j.at("identity");
  f.object("options");  // present (options_from_json checks the rest)
  r.options = options_from_json(j.at("options"), source);
  const auto w = f.get<std::array<int, 4>>("window");
  r.window = PixelRect{{w[0], w[1]}, {w[2], w[3]}};
  const auto s = f.get<std::array<uint32_t, 2>>("samples");
  r.samples = SampleRange{s[0], s[1]};
  r.pass_samples = f.get<uint32_t>("pass_samples");
  const auto res = f.get<std::array<int, 2>>("resolution");
  r.width = res[0];
  r.height = res[1];
  r.spp = f.get<int>("spp");
  r.render_ms = f.get<double>("render_ms");
  const auto bad = [&](const std::string& what) {
    throw Error(ErrorKind::kInput, "render state: " + what,
                ErrorLocation{source, 0, kRenderStateAttribute});
  };
  if (r.width < 1 || r.height < 1 || r.width > kMaxFilmSide || r.height > kMaxFilmSide) {
    bad(fmt::format("resolution {} x {} is out of range", r.width, r.height));
  }
  if (r.window.empty() || !PixelRect{{0, 0}, {r.width, r.height}}.contains(r.window)) {
    bad("the window is not inside the image");
  }
  if (r.spp < 1 || r.samples.last <= r.samples.first || r.samples.last > uint32_t(r.spp)) {
    bad("the sample range is not inside [0, spp)");
  }
  if (r.pass_samples < 1) bad("pass_samples must be at least 1");
  if (!(r.render_ms >= 0.0)) bad("render_ms must be >= 0");
  return r;
}

void write_render_state(const std::filesystem::path& path, const Film& film,
                        const RenderStateRecord& record, ImageMetadata metadata,
                        const ColorPipeline& pipeline) {
  metadata.emplace_back(kRenderStateAttribute, render_state_to_text(record));
  write_state_file(path, film.resolve(), film, metadata, pipeline, record.options.exr_options);
}

RenderState read_render_state(const std::filesystem::path& path) {
  StateFileContents contents = read_state_file(path);
  RenderStateRecord record =
      render_state_from_text(contents.attribute(kRenderStateAttribute), path.string());
  const Film& film = contents.film;
  if (film.width() != record.width || film.height() != record.height ||
      film.window() != record.window) {
    throw Error(ErrorKind::kInput, "the film does not match the render state's window",
                ErrorLocation{path.string(), 0, kRenderStateAttribute});
  }
  return RenderState{std::move(contents.film), std::move(record), std::move(contents.attributes)};
}

}  // namespace prism
