#pragma once

#include <map>
#include <string>
#include <vector>

namespace prism {

/// String key/value parameters for backends and integrators (`--set key=value`). Keys are
/// dotted, scoped by component ("bvh.max_leaf_size", "embree.robust"). Typed getters parse and
/// throw Error(kUsage) naming the key on a bad value; every key read is marked used so that the
/// driver can reject typos (unused_with_prefix()). Not thread-safe; read during construction.
class ParamSet {
 public:
  /// Parses "key=value"; throws Error(kUsage) if there is no '=' or the key is empty.
  void add_assignment(const std::string& assignment);
  void set(const std::string& key, const std::string& value);
  bool has(const std::string& key) const;

  std::string get_string(const std::string& key, const std::string& fallback) const;
  /// Integer in [min, max]; throws Error(kUsage) if unparsable or out of range.
  long long get_int(const std::string& key, long long fallback, long long min, long long max) const;
  /// Finite float in [min, max].
  double get_float(const std::string& key, double fallback, double min, double max) const;
  /// true/false/1/0/yes/no/on/off.
  bool get_bool(const std::string& key, bool fallback) const;

  /// Keys starting with `prefix` that no getter has read.
  std::vector<std::string> unused_with_prefix(const std::string& prefix) const;
  /// All keys, in order.
  std::vector<std::string> keys() const;
  /// "key=value key=value" for provenance metadata.
  std::string to_string() const;

 private:
  const std::string* lookup(const std::string& key) const;

  std::map<std::string, std::string> values_;
  mutable std::map<std::string, bool> used_;
};

}  // namespace prism
