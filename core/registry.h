#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/param_set.h"
#include "core/strings.h"

namespace prism {

/// An explicit table of named implementations of one interface (no self-registering statics).
/// `kind` names the table in messages ("accelerator", "integrator").
template <typename Interface>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Interface>(const ParamSet&)>;
  struct Entry {
    std::string name;
    std::string description;
    Factory factory;
  };

  Registry(std::string kind, std::vector<Entry> entries)
      : kind_(std::move(kind)), entries_(std::move(entries)) {}

  /// Builds the implementation called `name`. Throws Error(kUsage) listing the valid names
  /// when there is none.
  std::unique_ptr<Interface> create(std::string_view name, const ParamSet& params) const {
    for (const auto& e : entries_) {
      if (e.name == name) return e.factory(params);
    }
    throw Error(ErrorKind::kUsage,
                "unknown " + kind_ + " '" + std::string(name) + "'; available: " + names_joined());
  }
  bool contains(std::string_view name) const {
    for (const auto& e : entries_) {
      if (e.name == name) return true;
    }
    return false;
  }
  const std::vector<Entry>& entries() const { return entries_; }
  const std::string& kind() const { return kind_; }
  /// The names in table order.
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.name);
    return out;
  }
  /// The names as "a, b, c", for messages and help text.
  std::string names_joined() const { return join(names()); }

 private:
  std::string kind_;
  std::vector<Entry> entries_;
};

}  // namespace prism
