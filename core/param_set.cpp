#include "core/param_set.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace prism {
namespace {

[[noreturn]] void bad_value(const std::string& key, const std::string& value,
                            const std::string& expected) {
  throw Error(ErrorKind::kUsage, "parameter '" + key + "': '" + value + "' is not " + expected);
}

}  // namespace

void ParamSet::add_assignment(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw Error(ErrorKind::kUsage, "--set expects key=value, got '" + assignment + "'");
  }
  set(assignment.substr(0, eq), assignment.substr(eq + 1));
}

void ParamSet::set(const std::string& key, const std::string& value) {
  values_[key] = value;
  used_[key] = false;
}

bool ParamSet::has(const std::string& key) const { return values_.count(key) != 0; }

const std::string* ParamSet::lookup(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end()) return nullptr;
  used_[key] = true;
  return &it->second;
}

std::string ParamSet::get_string(const std::string& key, const std::string& fallback) const {
  const std::string* v = lookup(key);
  return v ? *v : fallback;
}

long long ParamSet::get_int(const std::string& key, long long fallback, long long min,
                            long long max) const {
  const std::string* v = lookup(key);
  if (!v) return fallback;
  long long out = 0;
  const auto [ptr, ec] = std::from_chars(v->data(), v->data() + v->size(), out);
  if (ec != std::errc() || ptr != v->data() + v->size()) bad_value(key, *v, "an integer");
  if (out < min || out > max) {
    bad_value(key, *v, "in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  return out;
}

double ParamSet::get_float(const std::string& key, double fallback, double min, double max) const {
  const std::string* v = lookup(key);
  if (!v) return fallback;
  char* end = nullptr;
  const double out = std::strtod(v->c_str(), &end);
  if (v->empty() || end != v->c_str() + v->size() || !std::isfinite(out)) {
    bad_value(key, *v, "a finite number");
  }
  if (out < min || out > max) {
    bad_value(key, *v, "in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  return out;
}

bool ParamSet::get_bool(const std::string& key, bool fallback) const {
  const std::string* v = lookup(key);
  if (!v) return fallback;
  if (*v == "true" || *v == "1" || *v == "yes" || *v == "on") return true;
  if (*v == "false" || *v == "0" || *v == "no" || *v == "off") return false;
  bad_value(key, *v, "a boolean (true/false)");
}

std::vector<std::string> ParamSet::unused_with_prefix(const std::string& prefix) const {
  std::vector<std::string> out;
  for (const auto& [key, used] : used_) {
    if (!used && key.rfind(prefix, 0) == 0) out.push_back(key);
  }
  return out;
}

std::vector<std::string> ParamSet::keys() const {
  std::vector<std::string> out;
  for (const auto& [key, value] : values_) out.push_back(key);
  return out;
}

std::string ParamSet::to_string() const {
  std::string out;
  for (const auto& [key, value] : values_) {
    if (!out.empty()) out += ' ';
    out += key + "=" + value;
  }
  return out;
}

}  // namespace prism
