// core/param_set.h: "--set key=value" parsing, the typed getters and their errors, and the
// bookkeeping of which keys were read.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/param_set.h"

namespace prism {
namespace {

/// Runs `read` expecting an Error of kind kUsage whose message contains every one of `parts`.
void expect_usage_error(const std::function<void()>& read, const std::vector<std::string>& parts) {
  try {
    read();
    ADD_FAILURE() << "expected Error(kUsage)";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage) << e.what();
    for (const auto& part : parts) {
      EXPECT_NE(e.message().find(part), std::string::npos) << "'" << part << "' in " << e.what();
    }
  }
}

/// A ParamSet holding the single assignment key=value.
ParamSet with(const std::string& key, const std::string& value) {
  ParamSet p;
  p.set(key, value);
  return p;
}

TEST(CoreParamSet, AddAssignmentSplitsAtTheFirstEquals) {
  ParamSet p;
  p.add_assignment("bvh.max_leaf_size=4");
  p.add_assignment("output.note=a=b=c");
  p.add_assignment("output.empty=");
  EXPECT_TRUE(p.has("bvh.max_leaf_size"));
  EXPECT_EQ(p.get_string("bvh.max_leaf_size", ""), "4");
  EXPECT_EQ(p.get_string("output.note", ""), "a=b=c");
  EXPECT_TRUE(p.has("output.empty"));
  EXPECT_EQ(p.get_string("output.empty", "fallback"), "");
  EXPECT_FALSE(p.has("output.note=a"));
  EXPECT_FALSE(p.has("output"));
}

TEST(CoreParamSet, AddAssignmentRejectsMissingEqualsOrKey) {
  for (const std::string bad : {"bvh.max_leaf_size", "=4", "=", ""}) {
    SCOPED_TRACE(bad);
    ParamSet p;
    expect_usage_error([&] { p.add_assignment(bad); }, {"key=value", "'" + bad + "'"});
    EXPECT_TRUE(p.keys().empty());
  }
}

TEST(CoreParamSet, LaterAssignmentsReplaceEarlierOnes) {
  ParamSet p;
  p.add_assignment("a=1");
  p.add_assignment("a=2");
  EXPECT_EQ(p.keys(), std::vector<std::string>{"a"});
  EXPECT_EQ(p.get_int("a", 0, 0, 10), 2);
}

TEST(CoreParamSet, GetIntParsesWholeIntegersInRange) {
  EXPECT_EQ(with("k", "42").get_int("k", 0, 0, 100), 42);
  EXPECT_EQ(with("k", "-3").get_int("k", 0, -10, 10), -3);
  EXPECT_EQ(with("k", "0").get_int("k", 5, 0, 10), 0);
  // The range is closed.
  EXPECT_EQ(with("k", "1").get_int("k", 5, 1, 8), 1);
  EXPECT_EQ(with("k", "8").get_int("k", 5, 1, 8), 8);
  const long long big = std::numeric_limits<long long>::max();
  EXPECT_EQ(with("k", std::to_string(big)).get_int("k", 0, 0, big), big);
}

TEST(CoreParamSet, GetIntRejectsOutOfRange) {
  expect_usage_error([] { with("bvh.max_leaf_size", "0").get_int("bvh.max_leaf_size", 4, 1, 8); },
                     {"'bvh.max_leaf_size'", "'0'", "[1, 8]"});
  expect_usage_error([] { with("bvh.max_leaf_size", "9").get_int("bvh.max_leaf_size", 4, 1, 8); },
                     {"'bvh.max_leaf_size'", "'9'", "[1, 8]"});
  expect_usage_error([] { with("k", "-1").get_int("k", 4, 0, 8); }, {"'k'"});
}

TEST(CoreParamSet, GetIntRejectsGarbage) {
  for (const std::string bad :
       {"", "abc", "12abc", "4.5", "1e3", " 5", "5 ", "0x10", "--1", "99999999999999999999"}) {
    SCOPED_TRACE("'" + bad + "'");
    expect_usage_error(
        [&] { with("bvh.max_leaf_size", bad).get_int("bvh.max_leaf_size", 4, 0, 100); },
        {"'bvh.max_leaf_size'", "'" + bad + "'", "integer"});
  }
}

TEST(CoreParamSet, GetFloatParsesFiniteNumbersInRange) {
  EXPECT_DOUBLE_EQ(with("k", "0.5").get_float("k", 0.0, 0.0, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(with("k", "1e-3").get_float("k", 0.0, 0.0, 1.0), 1e-3);
  EXPECT_DOUBLE_EQ(with("k", "-2.25").get_float("k", 0.0, -10.0, 10.0), -2.25);
  EXPECT_DOUBLE_EQ(with("k", "3").get_float("k", 0.0, 0.0, 10.0), 3.0);
  // The range is closed.
  EXPECT_DOUBLE_EQ(with("k", "0").get_float("k", 0.5, 0.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(with("k", "1.0").get_float("k", 0.5, 0.0, 1.0), 1.0);
}

TEST(CoreParamSet, GetFloatRejectsOutOfRange) {
  expect_usage_error([] { with("sah.cost", "1.5").get_float("sah.cost", 0.5, 0.0, 1.0); },
                     {"'sah.cost'", "'1.5'"});
  expect_usage_error([] { with("sah.cost", "-0.001").get_float("sah.cost", 0.5, 0.0, 1.0); },
                     {"'sah.cost'", "'-0.001'"});
}

TEST(CoreParamSet, GetFloatRejectsNonFiniteAndGarbage) {
  for (const std::string bad :
       {"nan", "NaN", "inf", "-inf", "infinity", "1e999", "", "abc", "0.5x", "1,5", "0.5 "}) {
    SCOPED_TRACE("'" + bad + "'");
    const double lowest = std::numeric_limits<double>::lowest();
    const double highest = std::numeric_limits<double>::max();
    expect_usage_error([&] { with("sah.cost", bad).get_float("sah.cost", 0.5, lowest, highest); },
                       {"'sah.cost'", "'" + bad + "'", "finite"});
  }
}

TEST(CoreParamSet, GetBoolAcceptsTheDocumentedSpellings) {
  for (const char* yes : {"true", "1", "yes", "on"}) {
    EXPECT_TRUE(with("embree.robust", yes).get_bool("embree.robust", false)) << yes;
  }
  for (const char* no : {"false", "0", "no", "off"}) {
    EXPECT_FALSE(with("embree.robust", no).get_bool("embree.robust", true)) << no;
  }
}

TEST(CoreParamSet, GetBoolRejectsOtherValues) {
  for (const std::string bad : {"", "maybe", "2", "-1", "y", "truee", " true"}) {
    SCOPED_TRACE("'" + bad + "'");
    expect_usage_error([&] { with("embree.robust", bad).get_bool("embree.robust", false); },
                       {"'embree.robust'", "'" + bad + "'", "boolean"});
  }
}

TEST(CoreParamSet, AbsentKeysGiveTheFallback) {
  ParamSet p;
  p.set("other", "garbage");
  EXPECT_EQ(p.get_string("k", "dflt"), "dflt");
  EXPECT_EQ(p.get_int("k", 17, 0, 100), 17);
  EXPECT_DOUBLE_EQ(p.get_float("k", 0.25, 0.0, 1.0), 0.25);
  EXPECT_TRUE(p.get_bool("k", true));
  EXPECT_FALSE(p.get_bool("k", false));
  EXPECT_FALSE(p.has("k"));
  // Reading absent keys adds nothing.
  EXPECT_EQ(p.keys(), std::vector<std::string>{"other"});
  EXPECT_EQ(p.unused_with_prefix(""), std::vector<std::string>{"other"});
}

TEST(CoreParamSet, UnusedWithPrefixListsKeysNoGetterRead) {
  ParamSet p;
  p.add_assignment("bvh.max_leaf_size=4");
  p.add_assignment("bvh.sah_bins=16");
  p.add_assignment("bvh.typo=1");
  p.add_assignment("embree.robust=on");
  p.add_assignment("bvhx=1");
  EXPECT_EQ(p.unused_with_prefix("bvh."),
            (std::vector<std::string>{"bvh.max_leaf_size", "bvh.sah_bins", "bvh.typo"}));

  EXPECT_EQ(p.get_int("bvh.max_leaf_size", 8, 1, 64), 4);
  EXPECT_EQ(p.get_string("bvh.sah_bins", ""), "16");
  // has() is not a read.
  EXPECT_TRUE(p.has("bvh.typo"));
  EXPECT_EQ(p.unused_with_prefix("bvh."), std::vector<std::string>{"bvh.typo"});
  EXPECT_EQ(p.unused_with_prefix("embree."), std::vector<std::string>{"embree.robust"});
  EXPECT_EQ(p.unused_with_prefix(""),
            (std::vector<std::string>{"bvh.typo", "bvhx", "embree.robust"}));
  EXPECT_TRUE(p.unused_with_prefix("sobol.").empty());

  // A read that fails still counts as a read: the key is known, its value is wrong.
  p.add_assignment("embree.robust=perhaps");
  EXPECT_THROW(p.get_bool("embree.robust", false), Error);
  EXPECT_TRUE(p.unused_with_prefix("embree.").empty());
}

TEST(CoreParamSet, KeysAndToStringAreInKeyOrder) {
  ParamSet p;
  EXPECT_TRUE(p.keys().empty());
  EXPECT_EQ(p.to_string(), "");
  p.set("sobol.seed", "7");
  p.set("bvh.max_leaf_size", "4");
  p.set("embree.robust", "on");
  p.set("output.note", "a b=c");
  EXPECT_EQ(p.keys(), (std::vector<std::string>{"bvh.max_leaf_size", "embree.robust", "output.note",
                                                "sobol.seed"}));
  EXPECT_EQ(p.to_string(), "bvh.max_leaf_size=4 embree.robust=on output.note=a b=c sobol.seed=7");

  ParamSet one;
  one.set("k", "");
  EXPECT_EQ(one.to_string(), "k=");
}

}  // namespace
}  // namespace prism
