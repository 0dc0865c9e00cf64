#pragma once

// Typed, located access to a parsed JSON scene file: every value knows its JSON path
// ("materials[2].reflectance"), and an error on it reports the file, the line where the value
// starts and that path. Lines are found only when an error is raised, by rescanning the text, so
// loading large inline meshes pays nothing for them.

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/math.h"

namespace prism::json {

using Json = nlohmann::json;

/// Deepest nesting of arrays and objects a scene file may have. The scene schema needs 6; the
/// limit keeps hostile input (a million '[') away from anything that might recurse.
inline constexpr int kMaxDepth = 64;

/// One step of a JSON path: an object key or an array index.
struct PathStep {
  std::string key;
  size_t index = 0;
  bool is_index = false;
};
using JsonPath = std::vector<PathStep>;

/// "materials[2].reflectance"; empty for the root.
std::string to_string(const JsonPath& path);

/// Line (1-based) where the value at `path` starts in the JSON `text`, or 0 if there is none.
/// `text` must be valid JSON (it is scanned without a full parser, iteratively).
int find_value_line(std::string_view text, const JsonPath& path);

/// A scene file's text and parsed tree.
class JsonDocument {
 public:
  /// Reads and parses `file`. Throws Error(kInput) if it cannot be read, is not valid JSON
  /// (with line and column), or nests deeper than kMaxDepth.
  explicit JsonDocument(std::filesystem::path file);

  const std::filesystem::path& file() const { return file_; }
  const Json& root() const { return root_; }
  /// File, line of the value at `path` (0 if unknown) and the path as element.
  ErrorLocation locate(const JsonPath& path) const;
  [[noreturn]] void fail(const JsonPath& path, const std::string& message) const;

 private:
  std::filesystem::path file_;
  std::string text_;
  Json root_;
};

/// Inclusive or exclusive bounds for a number, with the wording of its error message.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range any() { return {}; }
  static Range at_least(double v) { return {v, std::numeric_limits<double>::infinity()}; }
  static Range above(double v) { return {v, std::numeric_limits<double>::infinity(), true}; }
  static Range closed(double lo, double hi) { return {lo, hi}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  bool contains(double v) const;
  std::string describe() const;  ///< "> 0", "in [0, 1]", ...
};

/// A value inside a JsonDocument together with its path. Cheap to copy for schema-sized data;
/// bulk arrays (vertex data) are read through raw() and fail_at() instead of one node per entry.
class JsonNode {
 public:
  JsonNode(const JsonDocument& doc, const Json& value, JsonPath path)
      : doc_(&doc), value_(&value), path_(std::move(path)) {}

  const Json& raw() const { return *value_; }
  const JsonPath& path() const { return path_; }
  const JsonDocument& document() const { return *doc_; }
  std::string path_string() const { return to_string(path_); }
  [[noreturn]] void fail(const std::string& message) const { doc_->fail(path_, message); }
  /// Fails at entry `index` of this array.
  [[noreturn]] void fail_at(size_t index, const std::string& message) const;

  void expect_object() const;
  void expect_array() const;
  /// Fails on the first key not in `allowed`, listing the valid keys (and the closest one).
  void check_keys(std::initializer_list<std::string_view> allowed) const;
  bool has(std::string_view key) const;
  /// The value of a required key: fails "missing required field" if absent.
  JsonNode child(std::string_view key) const;
  std::optional<JsonNode> find(std::string_view key) const;
  size_t size() const;  ///< entries of an array
  JsonNode at(size_t index) const;

  std::string string() const;
  bool boolean() const;
  /// A finite number in `range` that also fits a float.
  float number(Range range = Range::any()) const;
  /// An integer (no fraction, no exponent form) in [lo, hi].
  int64_t integer(int64_t lo, int64_t hi) const;
  /// An unsigned 64-bit integer.
  uint64_t unsigned_integer() const;
  /// [x, y, z] of finite numbers.
  Vec3 vec3() const;
  /// [x, y, z] with a non-zero length, normalized.
  Vec3 direction() const;
  /// [r, g, b] or one number for grey; every component in `range`.
  Rgb color(Range range) const;

 private:
  const JsonDocument* doc_;
  const Json* value_;
  JsonPath path_;
};

/// Optional-field helpers: the field's value, or `fallback` when the key is absent.
float number_or(const JsonNode& object, std::string_view key, float fallback, Range range);
Rgb color_or(const JsonNode& object, std::string_view key, Rgb fallback, Range range);
Vec3 vec3_or(const JsonNode& object, std::string_view key, Vec3 fallback);

}  // namespace prism::json
