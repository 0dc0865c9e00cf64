// core/app/rank_agreement.h: which rank's error every rank of an MPI run exits with.
#include <gtest/gtest.h>

#include <vector>

#include "core/app/rank_agreement.h"
#include "core/error.h"

namespace prism {
namespace {

using nlohmann::json;

RankStatus ready(json data) { return RankStatus{0, "", std::move(data)}; }

TEST(AppRankAgreement, AllReadyWithTheSameDataAgree) {
  const json frame = {{"scene", "ab12"}, {"spp", 8}};
  EXPECT_FALSE(first_rank_error({ready(frame), ready(frame), ready(frame)}, "the frame"));
  EXPECT_FALSE(first_rank_error({ready(frame)}, "the frame"));
}

TEST(AppRankAgreement, TheFirstFailingRankIsReportedWithItsCode) {
  const json frame = {{"scene", "ab12"}};
  const auto error = first_rank_error(
      {ready(frame), RankStatus{3, "out of memory", nullptr}, RankStatus{2, "bad", nullptr}},
      "the frame");
  ASSERT_TRUE(error);
  EXPECT_EQ(error->rank(), 1);
  EXPECT_EQ(error->code(), 3);
  EXPECT_STREQ(error->what(), "rank 1: out of memory");
}

TEST(AppRankAgreement, FailuresComeBeforeDifferences) {
  const auto error = first_rank_error(
      {ready({{"scene", "a"}}), ready({{"scene", "b"}}), RankStatus{2, "missing", nullptr}},
      "the frame");
  ASSERT_TRUE(error);
  EXPECT_EQ(error->rank(), 2);
}

TEST(AppRankAgreement, ADifferentFrameNamesTheRankAndTheField) {
  const json frame = {{"scene", "ab12"}, {"color", {{"view", "sRGB"}}}};
  json other = frame;
  other["color"]["view"] = "Filmic";
  const auto error =
      first_rank_error({ready(frame), ready(frame), ready(other)}, "the frame to render");
  ASSERT_TRUE(error);
  EXPECT_EQ(error->rank(), 2);
  EXPECT_EQ(error->code(), kExitBadInput);
  EXPECT_STREQ(error->what(), "rank 2: the frame to render differs from rank 0's: 'color.view'");
  const auto missing = first_rank_error({ready(frame), ready({{"scene", "ab12"}})}, "it");
  ASSERT_TRUE(missing);
  EXPECT_STREQ(missing->what(), "rank 1: it differs from rank 0's: 'color'");
}

TEST(AppRankAgreement, StatusesRoundTripAsText) {
  const RankStatus status{2, "scene.json: not found", {{"a", 1}}};
  const RankStatus back = rank_status_from_text(rank_status_to_text(status));
  EXPECT_EQ(back.exit_code, 2);
  EXPECT_EQ(back.message, status.message);
  EXPECT_EQ(back.data, status.data);
  EXPECT_THROW(rank_status_from_text("not json"), Error);
}

TEST(AppRankAgreement, OneRankAgreesWithItself) {
  // Without mpirun there is one rank: nothing is exchanged and nothing thrown.
  EXPECT_NO_THROW(agree_across_ranks(RankStatus{2, "bad", nullptr}, "the frame"));
  EXPECT_EQ(take_rank0_status(ready({{"x", 1}})).data, json({{"x", 1}}));
}

}  // namespace
}  // namespace prism
