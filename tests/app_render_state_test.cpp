// The render state a checkpoint or part file carries (core/app/render_state.*): it round-trips,
// and a number out of its field's range is a one-line input error naming the field, not an
// unchecked conversion (fuzzing found two: tests/fuzz/regressions/render_state/).

#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "core/app/render_state.h"
#include "core/error.h"

namespace prism {
namespace {

using nlohmann::json;

RenderStateRecord example_record() {
  RenderStateRecord record;
  record.identity = json{{"prism", "test"}};
  record.options.scene = "scene.dae";
  record.window = PixelRect{{0, 0}, {8, 4}};
  record.samples = SampleRange{0, 16};
  record.pass_samples = 4;
  record.width = 8;
  record.height = 4;
  record.spp = 16;
  record.render_ms = 12.5;
  return record;
}

TEST(AppRenderState, RoundTrips) {
  const RenderStateRecord back =
      render_state_from_text(render_state_to_text(example_record()), "ck.exr");
  EXPECT_EQ(back.window.begin.x, 0);
  EXPECT_EQ(back.window.end.x, 8);
  EXPECT_EQ(back.window.end.y, 4);
  EXPECT_EQ(back.samples.first, 0u);
  EXPECT_EQ(back.samples.last, 16u);
  EXPECT_EQ(back.pass_samples, 4u);
  EXPECT_EQ(back.width, 8);
  EXPECT_EQ(back.spp, 16);
  EXPECT_EQ(back.render_ms, 12.5);
  EXPECT_EQ(back.options.scene, "scene.dae");
}

/// Each field set to a value of the right JSON kind but beyond its C++ type, or of the wrong
/// size: Error(kInput) naming the file and the field.
TEST(AppRenderState, NumbersBeyondTheirFieldAreInputErrorsNamingTheField) {
  const json good = json::parse(render_state_to_text(example_record()));
  struct Case {
    const char* field;
    json value;
  };
  const Case cases[] = {
      {"window", json::array({0, 0, 8, 1.1e30})},
      {"window", json::array({0, 0, 8, 4294967296LL})},
      {"window", json::array({0, 0, 8})},
      {"samples", json::array({-1, 16})},
      {"samples", json::array({0, 1e20})},
      {"resolution", json::array({8, 1e30})},
      {"spp", 3e9},
      {"pass_samples", -4},
      {"render_ms", "12"},
  };
  for (const Case& c : cases) {
    json damaged = good;
    damaged[c.field] = c.value;
    try {
      render_state_from_text(damaged.dump(), "ck.exr");
      ADD_FAILURE() << c.field << " = " << c.value.dump() << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInput);
      const std::string what = e.what();
      EXPECT_NE(what.find("ck.exr"), std::string::npos) << what;
      EXPECT_NE(what.find(std::string("'") + c.field + "' has the wrong type or is out of range"),
                std::string::npos)
          << what;
    }
  }
}

}  // namespace
}  // namespace prism
