#include "core/app/resume.h"

#include <filesystem>

#include "core/error.h"

namespace prism {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// Fields of RenderOptions a resume may change: they do not change a pixel.
bool is_run_control(const std::string& key) {
  return key == "threads" || key == "quiet" || key == "time_limit" ||
         key == "checkpoint_interval" || key == "checkpoint" || key == "command_line";
}

std::string absolute(const std::string& path) {
  if (path.empty()) return path;
  std::error_code ec;
  const fs::path full = fs::absolute(path, ec);
  return ec ? path : full.lexically_normal().string();
}

}  // namespace

RenderOptions resumed_options(const RenderOptions& given, const RenderStateRecord& state,
                              const fs::path& resumed_file) {
  const json given_json = options_to_json(given);
  const json default_json = options_to_json(RenderOptions{});
  const json stored_json = options_to_json(state.options);
  for (const auto& [key, value] : given_json.items()) {
    if (is_run_control(key) || value == default_json[key] || value == stored_json[key]) continue;
    throw Error(ErrorKind::kUsage,
                "'" + key + "' is " + value.dump() + " on the command line but " +
                    stored_json[key].dump() + " in the checkpoint; --resume continues with the " +
                    "checkpoint's options (only -t, -q, --time-limit, --checkpoint and " +
                    "--checkpoint-interval may change)",
                ErrorLocation{resumed_file.string(), 0, "--resume"});
  }
  RenderOptions options = state.options;
  options.threads = given.threads;
  options.quiet = given.quiet;
  options.time_limit = given.time_limit;
  // The interval and path are kept unless given again; threads and quiet are this run's.
  if (given.checkpoint_interval != RenderOptions{}.checkpoint_interval) {
    options.checkpoint_interval = given.checkpoint_interval;
  }
  if (!given.checkpoint.empty()) {
    options.checkpoint = given.checkpoint;
  } else if (options.checkpoint.empty()) {
    options.checkpoint = resumed_file.string();
  }
  options.command_line = given.command_line;
  options.resume = resumed_file.string();
  return options;
}

RenderOptions with_absolute_paths(const RenderOptions& options) {
  RenderOptions out = options;
  out.scene = absolute(options.scene);
  out.output = absolute(options.output);
  out.environment_map = absolute(options.environment_map);
  out.color.ocio_config = absolute(options.color.ocio_config);
  out.checkpoint = absolute(options.checkpoint);
  return out;
}

void check_resume_identity(const json& identity, const RenderStateRecord& state,
                           const fs::path& resumed_file) {
  if (identity == state.identity) return;
  std::string field = "?";
  for (const auto& [key, value] : state.identity.items()) {
    if (!identity.contains(key) || identity[key] != value) {
      field = key;
      break;
    }
  }
  // A checkpoint of an older prism may lack a field this one records.
  for (const auto& [key, value] : identity.items()) {
    if (field == "?" && !state.identity.contains(key)) field = key;
  }
  const std::string why = field == "scene"
                              ? "the scene (its file, a file it names, or its colours) "
                                "changed since the checkpoint"
                              : "'" + field + "' differs from the checkpoint's";
  throw Error(ErrorKind::kUsage, "cannot resume: " + why,
              ErrorLocation{resumed_file.string(), 0, "--resume"});
}

}  // namespace prism
