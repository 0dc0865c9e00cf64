#pragma once

#include <string>
#include <vector>

#include "core/param_set.h"

namespace prism {

/// A component built from the registries: its table ("accelerator", "integrator") and name.
struct ComponentInUse {
  std::string kind;
  std::string name;
};

/// Checks the --set keys after the components in `in_use` have been constructed from `params`,
/// so that typos never pass silently. A key scoped by an in-use component ("bvh.max_leaf_size")
/// that the component did not read, a key without a component prefix, and a key naming no
/// registered component are Error(kUsage). A key of a registered component that is not in use
/// (embree.* while rendering with bvh) is ignored with a warning on stderr.
void check_component_params(const ParamSet& params, const std::vector<ComponentInUse>& in_use);

}  // namespace prism
