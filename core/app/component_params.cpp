#include "core/app/component_params.h"

#include <algorithm>
#include <cstdio>

#include "accel/accelerator.h"
#include "core/error.h"
#include "core/strings.h"
#include "integrators/integrator.h"

namespace prism {
namespace {}  // namespace

void check_component_params(const ParamSet& params, const std::vector<ComponentInUse>& in_use) {
  const auto& accels = accelerator_registry();
  const auto& integrators = integrator_registry();
  // Every error is found before any warning is printed, so a failure stays one line on stderr.
  std::vector<std::string> ignored;
  for (const auto& key : params.keys()) {
    const auto dot = key.find('.');
    const std::string prefix = dot == std::string::npos ? std::string() : key.substr(0, dot);
    const bool used = std::any_of(in_use.begin(), in_use.end(),
                                  [&](const ComponentInUse& c) { return c.name == prefix; });
    if (used) continue;
    if (accels.contains(prefix) || integrators.contains(prefix)) {
      ignored.push_back(key);
      continue;
    }
    throw Error(ErrorKind::kUsage,
                "parameter '" + key + "' names no component; keys start with an accelerator (" +
                    accels.names_joined() + ") or integrator (" + integrators.names_joined() +
                    ") name and a dot, e.g. bvh.max_leaf_size",
                ErrorLocation{{}, 0, "--set"});
  }
  for (const auto& component : in_use) {
    const auto unused = params.unused_with_prefix(component.name + ".");
    if (!unused.empty()) {
      throw Error(ErrorKind::kUsage,
                  std::string(unused.size() == 1 ? "unknown parameter '" : "unknown parameters '") +
                      join(unused, "', '") + "' for " + component.kind + " '" + component.name +
                      "' (its parameters: `prism list`)",
                  ErrorLocation{{}, 0, "--set"});
    }
  }
  for (const auto& key : ignored) {
    std::fprintf(stderr, "prism: warning: --set %s ignored: '%s' is not in use\n", key.c_str(),
                 key.substr(0, key.find('.')).c_str());
  }
}

}  // namespace prism
