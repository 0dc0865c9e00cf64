// accelerator_registry() (accel/accelerator_registry.cpp): the backends it lists, its errors
// for unknown names and bad parameter values, and the parameters it consumes.

#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "accel/accelerator.h"
#include "core/error.h"
#include "core/param_set.h"

namespace prism {
namespace {

TEST(AccelRegistry, ListsEveryBackendWithADescription) {
  const auto& entries = accelerator_registry().entries();
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(accelerator_registry().names_joined(), "brute, bvh, embree");
  for (const auto& e : entries) {
    EXPECT_FALSE(e.description.empty()) << e.name;
    EXPECT_EQ(e.factory(ParamSet{})->name(), e.name);
  }
}

TEST(AccelRegistry, UnknownNameListsTheAvailableOnes) {
  try {
    accelerator_registry().create("bhv", ParamSet{});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_NE(
        std::string(e.what()).find("unknown accelerator 'bhv'; available: brute, bvh, embree"),
        std::string::npos)
        << e.what();
  }
}

/// The ErrorKind that creating `name` with key=value throws, or nothing.
std::optional<ErrorKind> creation_error(const std::string& name, const std::string& key,
                                        const std::string& value) {
  ParamSet params;
  params.set(key, value);
  try {
    accelerator_registry().create(name, params);
  } catch (const Error& e) {
    return e.kind();
  }
  return std::nullopt;
}

TEST(AccelRegistry, BadParameterValuesAreUsageErrors) {
  EXPECT_EQ(creation_error("bvh", "bvh.max_leaf_size", "0"), ErrorKind::kUsage);
  EXPECT_EQ(creation_error("bvh", "bvh.max_leaf_size", "four"), ErrorKind::kUsage);
  EXPECT_EQ(creation_error("bvh", "bvh.max_leaf_size", "1000"), ErrorKind::kUsage);
  EXPECT_EQ(creation_error("embree", "embree.quality", "ultra"), ErrorKind::kUsage);
  EXPECT_EQ(creation_error("embree", "embree.robust", "maybe"), ErrorKind::kUsage);
  EXPECT_EQ(creation_error("bvh", "bvh.max_leaf_size", "1"), std::nullopt);
  EXPECT_EQ(creation_error("embree", "embree.quality", "high"), std::nullopt);
}

TEST(AccelRegistry, ParametersAreMarkedUsed) {
  ParamSet params;
  params.set("bvh.max_leaf_size", "8");
  params.set("embree.robust", "true");
  params.set("embree.quality", "low");
  accelerator_registry().create("bvh", params);
  accelerator_registry().create("embree", params);
  EXPECT_TRUE(params.unused_with_prefix("bvh.").empty());
  EXPECT_TRUE(params.unused_with_prefix("embree.").empty());
}

}  // namespace
}  // namespace prism
