#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace prism::test {

/// Whether this build is instrumented by AddressSanitizer or ThreadSanitizer (scripts/test
/// --sanitize), and so is the prism it runs: several times slower, with a slower start-up.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif

/// `count` in the normal build, a quarter of it (at least 1) in a sanitizer build: for the
/// tests whose own work (samples, rays, repeated runs) would take a minute or more instrumented,
/// where prism renders 7 to 15 times slower (docs/RELIABILITY.md, "Sanitizers"). The same code
/// runs, with the same checks, a quarter as often; the normal build keeps the full count.
template <typename Count>
constexpr Count sanitizer_share(Count count) {
  if (!kSanitizedBuild) return count;
  const Count quarter = count / 4;
  return quarter > Count(0) ? quarter : Count(1);
}

/// ../shared/scenes/cs184 beside the repository, if present.
std::optional<std::filesystem::path> cs184_scene_dir();

/// Path of one CS184 scene ("CBbunny.dae"), or nothing when ../shared is absent.
std::optional<std::filesystem::path> cs184_scene(const std::string& file_name);

/// File names of every *.dae in the shared CS184 folder (empty when absent), sorted.
std::vector<std::string> cs184_scene_names();

/// A fresh empty temporary directory, removed by the caller (or left in /tmp).
std::filesystem::path make_temp_dir(const std::string& tag);

/// Result of running the prism program.
struct ProgramResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs the built prism program with `args` (no shell; arguments passed as they are), with a
/// time limit in seconds after which it is killed (exit_code is then -9). A sanitizer report
/// in its stderr (sanitizer builds instrument the program too) fails the calling test.
ProgramResult run_prism(const std::vector<std::string>& args, int timeout_seconds = 120);

/// Writes `text` to `path`.
void write_text(const std::filesystem::path& path, const std::string& text);

/// The whole content of `path`, byte for byte (empty when it cannot be read).
std::string read_bytes(const std::filesystem::path& path);

}  // namespace prism::test

/// Skips the current test with a message when the shared CS184 scenes are absent.
#define PRISM_REQUIRE_CS184(var, file_name)                                                \
  const auto var##_opt = ::prism::test::cs184_scene(file_name);                            \
  if (!var##_opt) GTEST_SKIP() << "../shared/scenes/cs184 absent: skipping " << file_name; \
  const std::filesystem::path var = *var##_opt
