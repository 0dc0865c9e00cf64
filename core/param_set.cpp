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
  Entry& e = entries_[key];
  e.value = value;
  e.used = false;
}

void ParamSet::set_alias(const std::string& key, const std::string& value,
                         const std::string& source) {
  Entry& e = entries_[key];
  e.alias = Alias{value, source};
  e.used = false;
}

bool ParamSet::has(const std::string& key) const { return entries_.count(key) != 0; }

const ParamSet::Entry* ParamSet::lookup(const std::string& key) const {
  const auto it = entries_.find(key);
  if (it == entries_.end()) return nullptr;
  it->second.used = true;
  return &it->second;
}

template <typename T, typename Parse>
T ParamSet::get(const std::string& key, T fallback, const Parse& parse) const {
  const Entry* e = lookup(key);
  if (!e) return fallback;
  if (!e->value) return parse(e->alias->value);
  const T value = parse(*e->value);
  if (e->alias && !(value == parse(e->alias->value))) {
    throw Error(ErrorKind::kUsage, "--set " + key + "=" + *e->value + " conflicts with " +
                                       e->alias->source +
                                       ", which sets the same parameter; give one of them");
  }
  return value;
}

std::string ParamSet::get_string(const std::string& key, const std::string& fallback) const {
  return get(key, fallback, [](const std::string& v) { return v; });
}

long long ParamSet::get_int(const std::string& key, long long fallback, long long min,
                            long long max) const {
  return get(key, fallback, [&](const std::string& v) {
    long long out = 0;
    const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
    if (ec != std::errc() || ptr != v.data() + v.size()) bad_value(key, v, "an integer");
    if (out < min || out > max) {
      bad_value(key, v, "in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    }
    return out;
  });
}

double ParamSet::get_float(const std::string& key, double fallback, double min, double max) const {
  return get(key, fallback, [&](const std::string& v) {
    char* end = nullptr;
    const double out = std::strtod(v.c_str(), &end);
    if (v.empty() || end != v.c_str() + v.size() || !std::isfinite(out)) {
      bad_value(key, v, "a finite number");
    }
    if (out < min || out > max) {
      bad_value(key, v, "in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    }
    return out;
  });
}

bool ParamSet::get_bool(const std::string& key, bool fallback) const {
  return get(key, fallback, [&](const std::string& v) {
    if (v == "true" || v == "1" || v == "yes" || v == "on") return true;
    if (v == "false" || v == "0" || v == "no" || v == "off") return false;
    bad_value(key, v, "a boolean (true/false)");
  });
}

std::vector<std::string> ParamSet::unused_with_prefix(const std::string& prefix) const {
  std::vector<std::string> out;
  for (const auto& [key, e] : entries_) {
    if (e.value && !e.used && key.rfind(prefix, 0) == 0) out.push_back(key);
  }
  return out;
}

std::vector<std::string> ParamSet::keys() const {
  std::vector<std::string> out;
  for (const auto& [key, e] : entries_) {
    if (e.value) out.push_back(key);
  }
  return out;
}

std::string ParamSet::to_string() const {
  std::string out;
  for (const auto& [key, e] : entries_) {
    if (!e.value) continue;
    if (!out.empty()) out += ' ';
    out += key + "=" + *e.value;
  }
  return out;
}

}  // namespace prism
