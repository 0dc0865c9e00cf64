#include "scenes/json/json_document.h"

#include "core/strings.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace prism::json {
namespace {

/// Thrown by the parser callback to stop parsing of over-deep input.
struct TooDeep {};

/// Thrown by the parser callback at the second `key` of one object, its `occurrence`-th in the
/// text.
struct DuplicateKey {
  std::string key;
  int occurrence = 0;
};

/// The line of the `occurrence`-th (1-based) `"key"` followed by a colon in `text`, or 0. Keys
/// with escapes are not found (0): the message still names the key.
int find_key_line(const std::string& text, const std::string& key, int occurrence) {
  const std::string quoted = "\"" + key + "\"";
  size_t at = 0;
  for (int seen = 0;; at += quoted.size()) {
    at = text.find(quoted, at);
    if (at == std::string::npos) return 0;
    size_t after = at + quoted.size();
    while (after < text.size() && std::isspace(static_cast<unsigned char>(text[after]))) ++after;
    if (after < text.size() && text[after] == ':' && ++seen == occurrence) break;
  }
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + long(at), '\n'));
}

/// A forward scanner over valid JSON text that counts lines. Never recursive.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : s_(text) {
    if (s_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 byte order mark
  }

  int line() const { return line_; }
  bool done() const { return pos_ >= s_.size(); }
  char peek() const { return done() ? '\0' : s_[pos_]; }
  void advance() { ++pos_; }

  void skip_whitespace() {
    while (!done()) {
      const char c = s_[pos_];
      if (c == '\n') {
        ++line_;
      } else if (c != ' ' && c != '\t' && c != '\r') {
        return;
      }
      ++pos_;
    }
  }

  /// At a '"': returns the string's content with the simple escapes undone. A \u escape
  /// becomes '?': schema keys are plain ASCII, so such a key never matches one anyway.
  std::string read_string() {
    std::string out;
    ++pos_;
    while (!done() && s_[pos_] != '"') {
      if (s_[pos_] == '\\' && pos_ + 1 < s_.size()) {
        ++pos_;
        const char e = s_[pos_];
        out += e == 'n'   ? '\n'
               : e == 't' ? '\t'
               : e == 'r' ? '\r'
               : e == 'b' ? '\b'
               : e == 'f' ? '\f'
               : e == 'u' ? '?'
                          : e;
        if (e == 'u') pos_ += 4;
      } else {
        out += s_[pos_];
      }
      ++pos_;
    }
    ++pos_;
    return out;
  }

  /// Skips one complete value of any size, counting the lines inside it.
  void skip_value() {
    int depth = 0;
    do {
      skip_whitespace();
      if (done()) return;
      const char c = s_[pos_];
      if (c == '"') {
        read_string();
      } else if (c == '{' || c == '[') {
        ++depth;
        ++pos_;
      } else if (c == '}' || c == ']') {
        --depth;
        ++pos_;
      } else if (c == ',' || c == ':') {
        ++pos_;
      } else {
        while (!done() && std::string_view(",]} \t\r\n").find(s_[pos_]) == std::string_view::npos) {
          ++pos_;
        }
      }
    } while (depth > 0);
  }

 private:
  std::string_view s_;
  size_t pos_ = 0;
  int line_ = 1;
};

/// Line of the first bracket that opens nesting level kMaxDepth + 1.
int find_too_deep_line(std::string_view text) {
  int depth = 0, line = 1;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxDepth) return line;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return 0;
}

/// Levenshtein distance, for "did you mean" on unknown keys.
size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string format_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

std::string to_string(const JsonPath& path) {
  std::string out;
  for (const PathStep& step : path) {
    if (step.is_index) {
      out += "[" + std::to_string(step.index) + "]";
    } else {
      if (!out.empty()) out += '.';
      out += step.key;
    }
  }
  return out;
}

int find_value_line(std::string_view text, const JsonPath& path) {
  Scanner sc(text);
  for (const PathStep& step : path) {
    sc.skip_whitespace();
    if (sc.peek() != (step.is_index ? '[' : '{')) return 0;
    sc.advance();
    for (size_t i = 0;; ++i) {
      sc.skip_whitespace();
      if (sc.peek() == ']' || sc.peek() == '}' || sc.done()) return 0;
      if (step.is_index) {
        if (i == step.index) break;
      } else {
        const std::string key = sc.read_string();
        sc.skip_whitespace();
        sc.advance();  // ':'
        if (key == step.key) break;
      }
      sc.skip_value();
      sc.skip_whitespace();
      if (sc.peek() != ',') return 0;
      sc.advance();
    }
  }
  sc.skip_whitespace();
  return sc.line();
}

JsonDocument::JsonDocument(std::filesystem::path file) : file_(std::move(file)) {
  {
    std::ifstream in(file_, std::ios::binary);
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (!in) {
      throw Error(ErrorKind::kInput, "cannot read scene file", {file_.string(), 0, {}});
    }
    text_ = std::move(buffer).str();
  }
  // The keys of each open object, to refuse a key given twice (nlohmann would keep the last
  // one silently); and how often each key has been seen, to find the line of the repeat.
  std::vector<std::set<std::string>> open_objects;
  std::map<std::string, int> key_seen;
  const auto guard = [&](int depth, Json::parse_event_t event, Json& parsed) {
    if (depth >= kMaxDepth) throw TooDeep{};
    if (event == Json::parse_event_t::object_start) open_objects.emplace_back();
    if (event == Json::parse_event_t::object_end && !open_objects.empty()) open_objects.pop_back();
    if (event == Json::parse_event_t::key && parsed.is_string() && !open_objects.empty()) {
      const std::string& key = parsed.get_ref<const std::string&>();
      const int occurrence = ++key_seen[key];
      if (!open_objects.back().insert(key).second) throw DuplicateKey{key, occurrence};
    }
    return true;
  };
  try {
    root_ = Json::parse(text_, guard);
  } catch (const TooDeep&) {
    throw Error(ErrorKind::kInput,
                "JSON nests deeper than " + std::to_string(kMaxDepth) + " levels",
                {file_.string(), find_too_deep_line(text_), {}});
  } catch (const DuplicateKey& d) {
    throw Error(ErrorKind::kInput, "key '" + d.key + "' is given twice in one object",
                {file_.string(), find_key_line(text_, d.key, d.occurrence), {}});
  } catch (const Json::parse_error& e) {
    // e.byte is the 1-based index of the last character read: the one that broke the parse.
    const size_t end = std::min<size_t>(e.byte == 0 ? 0 : e.byte - 1, text_.size());
    const size_t line = 1 + std::count(text_.begin(), text_.begin() + end, '\n');
    const size_t line_start = text_.rfind('\n', end == 0 ? 0 : end - 1);
    const size_t column = line_start == std::string::npos || end == 0 ? end + 1 : end - line_start;
    std::string reason = e.what();
    // Drop nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: ".
    const size_t colon = reason.find(": ", reason.find("parse error"));
    if (colon != std::string::npos) reason = reason.substr(colon + 2);
    throw Error(ErrorKind::kInput,
                "malformed JSON at line " + std::to_string(line) + ", column " +
                    std::to_string(column) + ": " + reason,
                {file_.string(), static_cast<int>(line), {}});
  } catch (const Json::exception& e) {
    // Numbers beyond double range (1e999) come as out_of_range without a position: find the
    // literal nlohmann quotes in the text instead.
    std::string reason = e.what();
    const size_t bracket = reason.find("] ");
    if (bracket != std::string::npos) reason = reason.substr(bracket + 2);
    int line = 0;
    const size_t open = reason.find('\''), close = reason.rfind('\'');
    if (open != std::string::npos && close > open + 1) {
      const size_t at = text_.find(reason.substr(open + 1, close - open - 1));
      if (at != std::string::npos)
        line = 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + at, '\n'));
    }
    throw Error(ErrorKind::kInput, "malformed JSON: " + reason, {file_.string(), line, {}});
  }
}

ErrorLocation JsonDocument::locate(const JsonPath& path) const {
  return {file_.string(), find_value_line(text_, path), to_string(path)};
}

void JsonDocument::fail(const JsonPath& path, const std::string& message) const {
  throw Error(ErrorKind::kInput, message, locate(path));
}

bool Range::contains(double v) const {
  const bool lo_ok = lo_open ? v > lo : v >= lo;
  const bool hi_ok = hi_open ? v < hi : v <= hi;
  return lo_ok && hi_ok;
}

std::string Range::describe() const {
  if (std::isinf(hi)) return (lo_open ? "> " : ">= ") + format_number(lo);
  return std::string("in ") + (lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
         (hi_open ? ")" : "]");
}

void JsonNode::fail_at(size_t index, const std::string& message) const {
  JsonPath p = path_;
  p.push_back({{}, index, true});
  doc_->fail(p, message);
}

void JsonNode::expect_object() const {
  if (!value_->is_object()) fail(std::string("expected an object, got ") + value_->type_name());
}

void JsonNode::expect_array() const {
  if (!value_->is_array()) fail(std::string("expected an array, got ") + value_->type_name());
}

void JsonNode::check_keys(std::initializer_list<std::string_view> allowed) const {
  expect_object();
  for (const auto& [key, unused] : value_->items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string closest;
    size_t best = std::numeric_limits<size_t>::max();
    for (std::string_view a : allowed) {
      const size_t d = edit_distance(key, a);
      if (d < best) best = d, closest = a;
    }
    std::string message = "unknown key '" + key + "'";
    if (best <= 2) message += " (did you mean '" + closest + "'?)";
    message += "; valid keys: " + join(std::vector<std::string>(allowed.begin(), allowed.end()));
    JsonPath p = path_;
    p.push_back({key});
    doc_->fail(p, message);
  }
}

bool JsonNode::has(std::string_view key) const {
  return value_->is_object() && value_->contains(key);
}

JsonNode JsonNode::child(std::string_view key) const {
  expect_object();
  const auto it = value_->find(key);
  if (it == value_->end()) fail("missing required field '" + std::string(key) + "'");
  JsonPath p = path_;
  p.push_back({std::string(key)});
  return JsonNode(*doc_, *it, std::move(p));
}

std::optional<JsonNode> JsonNode::find(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return child(key);
}

size_t JsonNode::size() const {
  expect_array();
  return value_->size();
}

JsonNode JsonNode::at(size_t index) const {
  expect_array();
  JsonPath p = path_;
  p.push_back({{}, index, true});
  return JsonNode(*doc_, (*value_)[index], std::move(p));
}

std::string JsonNode::string() const {
  if (!value_->is_string()) fail(std::string("expected a string, got ") + value_->type_name());
  return value_->get<std::string>();
}

bool JsonNode::boolean() const {
  if (!value_->is_boolean())
    fail(std::string("expected true or false, got ") + value_->type_name());
  return value_->get<bool>();
}

float JsonNode::number(Range range) const {
  if (!value_->is_number()) fail(std::string("expected a number, got ") + value_->type_name());
  const double v = value_->get<double>();
  if (!std::isfinite(v) || !std::isfinite(static_cast<float>(v))) {
    fail("number is not finite or too large for a float");
  }
  if (!range.contains(v)) fail("must be " + range.describe() + ", got " + format_number(v));
  return static_cast<float>(v);
}

int64_t JsonNode::integer(int64_t lo, int64_t hi) const {
  if (value_->is_number_unsigned()) {
    const uint64_t u = value_->get<uint64_t>();
    if (u > static_cast<uint64_t>(hi) || (lo > 0 && u < static_cast<uint64_t>(lo))) {
      fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
           std::to_string(u));
    }
    return static_cast<int64_t>(u);
  }
  if (!value_->is_number_integer()) {
    fail(std::string("expected an integer, got ") +
         (value_->is_number() ? "a number with a fraction or exponent" : value_->type_name()));
  }
  const int64_t v = value_->get<int64_t>();
  if (v < lo || v > hi) {
    fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
         std::to_string(v));
  }
  return v;
}

uint64_t JsonNode::unsigned_integer() const {
  if (value_->is_number_unsigned()) return value_->get<uint64_t>();
  if (value_->is_number_integer()) fail("must be >= 0");
  fail(std::string("expected an unsigned integer, got ") +
       (value_->is_number() ? "a number with a fraction or exponent" : value_->type_name()));
}

Vec3 JsonNode::vec3() const {
  if (!value_->is_array() || value_->size() != 3) {
    fail("expected an array of 3 numbers [x, y, z]");
  }
  return {at(0).number(), at(1).number(), at(2).number()};
}

Vec3 JsonNode::direction() const {
  const Vec3 v = vec3();
  const float length = glm::length(v);
  if (!(length > 0.0f) || !std::isfinite(length)) fail("direction must have a non-zero length");
  return v / length;
}

Rgb JsonNode::color(Range range) const {
  if (value_->is_number()) {
    const float grey = number(range);
    return Rgb(grey);
  }
  if (!value_->is_array() || value_->size() != 3) {
    fail("expected a colour: [r, g, b] or one number for grey");
  }
  return {at(0).number(range), at(1).number(range), at(2).number(range)};
}

float number_or(const JsonNode& object, std::string_view key, float fallback, Range range) {
  const auto node = object.find(key);
  return node ? node->number(range) : fallback;
}

Rgb color_or(const JsonNode& object, std::string_view key, Rgb fallback, Range range) {
  const auto node = object.find(key);
  return node ? node->color(range) : fallback;
}

Vec3 vec3_or(const JsonNode& object, std::string_view key, Vec3 fallback) {
  const auto node = object.find(key);
  return node ? node->vec3() : fallback;
}

}  // namespace prism::json
