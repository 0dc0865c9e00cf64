#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace prism {

/// String key/value parameters for backends and integrators (`--set key=value`). Keys are
/// dotted, scoped by component ("bvh.max_leaf_size", "embree.robust"). Typed getters parse and
/// throw Error(kUsage) naming the key on a bad value; every key read is marked used so that the
/// driver can reject typos (unused_with_prefix()). Not thread-safe; read during construction.
///
/// A key may also get a value through an alias: a command-line flag that stands for it
/// (`-m 3` for path.max_depth). Such a value applies only if a component reads the key: an
/// alias never makes a key unknown or unused, and keys(), unused_with_prefix() and to_string()
/// list explicit values only. A key with both an explicit and an alias value reads as the
/// explicit one; the getters throw Error(kUsage) naming both when they parse to different
/// values.
class ParamSet {
 public:
  /// Parses "key=value"; throws Error(kUsage) if there is no '=' or the key is empty.
  void add_assignment(const std::string& assignment);
  /// An explicit value; replaces the earlier explicit value of `key`.
  void set(const std::string& key, const std::string& value);
  /// An alias value of `key`, given on the command line as `source` (what the user typed, for
  /// messages: "-m 3"); replaces the earlier alias value of `key`.
  void set_alias(const std::string& key, const std::string& value, const std::string& source);
  /// Whether `key` has a value, explicit or alias.
  bool has(const std::string& key) const;

  std::string get_string(const std::string& key, const std::string& fallback) const;
  /// Integer in [min, max]; throws Error(kUsage) if unparsable or out of range.
  long long get_int(const std::string& key, long long fallback, long long min, long long max) const;
  /// Finite float in [min, max].
  double get_float(const std::string& key, double fallback, double min, double max) const;
  /// true/false/1/0/yes/no/on/off.
  bool get_bool(const std::string& key, bool fallback) const;

  /// Keys with an explicit value starting with `prefix` that no getter has read.
  std::vector<std::string> unused_with_prefix(const std::string& prefix) const;
  /// All keys with an explicit value, in order.
  std::vector<std::string> keys() const;
  /// "key=value key=value" of the explicit values, for provenance metadata.
  std::string to_string() const;

 private:
  struct Alias {
    std::string value;
    std::string source;
  };
  struct Entry {
    std::optional<std::string> value;  ///< explicit
    std::optional<Alias> alias;
    mutable bool used = false;  ///< read by a getter
  };
  /// Marks `key` used; null when it has no value.
  const Entry* lookup(const std::string& key) const;
  /// The value of `key` parsed by `parse` (which throws naming the key on a bad value), checked
  /// for a conflict between its explicit and alias values; `fallback` when there is none.
  template <typename T, typename Parse>
  T get(const std::string& key, T fallback, const Parse& parse) const;

  std::map<std::string, Entry> entries_;
};

}  // namespace prism
