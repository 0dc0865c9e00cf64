// core/registry.h: the explicit table of named implementations, on a test interface.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/param_set.h"
#include "core/registry.h"

namespace prism {
namespace {

struct Shape {
  virtual ~Shape() = default;
  virtual std::string name() const = 0;
  long long size = 0;
};

struct Square : Shape {
  std::string name() const override { return "square"; }
};
struct Circle : Shape {
  std::string name() const override { return "circle"; }
};
struct Triangle : Shape {
  std::string name() const override { return "triangle"; }
};

/// A factory for T that reads "shape.size" and counts its calls in `calls`.
template <typename T>
Registry<Shape>::Factory factory(int* calls) {
  return [calls](const ParamSet& params) -> std::unique_ptr<Shape> {
    ++*calls;
    auto shape = std::make_unique<T>();
    shape->size = params.get_int("shape.size", 1, 1, 100);
    return shape;
  };
}

/// Names deliberately not in alphabetical order, so that table order is observable.
class CoreRegistry : public ::testing::Test {
 protected:
  int square_calls = 0, circle_calls = 0, triangle_calls = 0;
  Registry<Shape> registry{"shape",
                           {{"square", "four sides", factory<Square>(&square_calls)},
                            {"circle", "no sides", factory<Circle>(&circle_calls)},
                            {"triangle", "three sides", factory<Triangle>(&triangle_calls)}}};
};

TEST_F(CoreRegistry, CreatesByNameWithTheParameters) {
  ParamSet params;
  params.set("shape.size", "7");
  params.set("shape.colour", "red");
  const auto circle = registry.create("circle", params);
  ASSERT_NE(circle, nullptr);
  EXPECT_EQ(circle->name(), "circle");
  EXPECT_EQ(circle->size, 7);
  EXPECT_EQ(circle_calls, 1);
  EXPECT_EQ(square_calls, 0);
  EXPECT_EQ(triangle_calls, 0);
  // The factory read the caller's ParamSet itself (not a copy): its read is recorded there.
  EXPECT_EQ(params.unused_with_prefix("shape."), std::vector<std::string>{"shape.colour"});

  const auto square = registry.create("square", ParamSet{});
  EXPECT_EQ(square->name(), "square");
  EXPECT_EQ(square->size, 1);  // the factory's fallback
  EXPECT_EQ(square_calls, 1);
}

TEST_F(CoreRegistry, FactoryErrorsPropagate) {
  ParamSet params;
  params.set("shape.size", "1000");
  try {
    registry.create("triangle", params);
    FAIL() << "an out-of-range parameter must be rejected";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_NE(std::string(e.what()).find("shape.size"), std::string::npos) << e.what();
  }
}

TEST_F(CoreRegistry, UnknownNameListsTheValidNamesInTableOrder) {
  try {
    registry.create("hexagon", ParamSet{});
    FAIL() << "an unknown name must be rejected";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_EQ(e.message(), "unknown shape 'hexagon'; available: square, circle, triangle");
  }
  // Names are matched exactly: no case folding, no prefixes.
  EXPECT_THROW(registry.create("Square", ParamSet{}), Error);
  EXPECT_THROW(registry.create("squ", ParamSet{}), Error);
  EXPECT_THROW(registry.create("", ParamSet{}), Error);
  EXPECT_EQ(square_calls + circle_calls + triangle_calls, 0);
}

TEST_F(CoreRegistry, ContainsOnlyTheTableNames) {
  EXPECT_TRUE(registry.contains("square"));
  EXPECT_TRUE(registry.contains("circle"));
  EXPECT_TRUE(registry.contains("triangle"));
  EXPECT_FALSE(registry.contains("hexagon"));
  EXPECT_FALSE(registry.contains("Circle"));
  EXPECT_FALSE(registry.contains(""));
  // Looking does not build anything.
  EXPECT_EQ(square_calls + circle_calls + triangle_calls, 0);
}

TEST_F(CoreRegistry, ListsNamesAndEntriesInTableOrder) {
  EXPECT_EQ(registry.kind(), "shape");
  EXPECT_EQ(registry.names(), (std::vector<std::string>{"square", "circle", "triangle"}));
  EXPECT_EQ(registry.names_joined(), "square, circle, triangle");
  const auto& entries = registry.entries();
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].name, "square");
  EXPECT_EQ(entries[0].description, "four sides");
  EXPECT_EQ(entries[1].name, "circle");
  EXPECT_EQ(entries[1].description, "no sides");
  EXPECT_EQ(entries[2].name, "triangle");
  EXPECT_EQ(entries[2].description, "three sides");
  // Each entry's factory is the one registered under its name.
  for (const auto& e : entries) EXPECT_EQ(e.factory(ParamSet{})->name(), e.name);
  EXPECT_EQ(square_calls, 1);
  EXPECT_EQ(circle_calls, 1);
  EXPECT_EQ(triangle_calls, 1);
}

TEST_F(CoreRegistry, AnEmptyTableHasNoNames) {
  const Registry<Shape> empty("widget", {});
  EXPECT_TRUE(empty.names().empty());
  EXPECT_EQ(empty.names_joined(), "");
  EXPECT_FALSE(empty.contains("square"));
  try {
    empty.create("square", ParamSet{});
    FAIL() << "an empty registry creates nothing";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_NE(e.message().find("unknown widget 'square'"), std::string::npos) << e.message();
  }
}

}  // namespace
}  // namespace prism
