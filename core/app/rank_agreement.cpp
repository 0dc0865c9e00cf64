#include "core/app/rank_agreement.h"

#include "core/error.h"

namespace prism {
namespace {

using nlohmann::json;

/// The first key (depth first) whose values differ between `a` and `b`; "" when equal.
std::string first_difference(const json& a, const json& b, const std::string& prefix = "") {
  if (a.is_object() && b.is_object()) {
    for (const auto& [key, value] : a.items()) {
      if (!b.contains(key)) return prefix + key;
      const std::string inner = first_difference(value, b.at(key), prefix + key + ".");
      if (!inner.empty()) return inner;
    }
    for (const auto& [key, value] : b.items()) {
      if (!a.contains(key)) return prefix + key;
    }
    return "";
  }
  if (a == b) return "";
  return prefix.empty() ? "(all)" : prefix.substr(0, prefix.size() - 1);
}

}  // namespace

std::string rank_status_to_text(const RankStatus& status) {
  return json{{"exit_code", status.exit_code}, {"message", status.message}, {"data", status.data}}
      .dump();
}

RankStatus rank_status_from_text(const std::string& text) {
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  PRISM_CHECK(j.is_object() && j.contains("exit_code") && j.contains("message") &&
              j.contains("data"));
  return RankStatus{j.at("exit_code").get<int>(), j.at("message").get<std::string>(), j.at("data")};
}

std::optional<RankError> first_rank_error(const std::vector<RankStatus>& statuses,
                                          const std::string& subject) {
  for (size_t r = 0; r < statuses.size(); ++r) {
    if (statuses[r].exit_code != 0) {
      return RankError(int(r), statuses[r].exit_code, statuses[r].message);
    }
  }
  for (size_t r = 1; r < statuses.size(); ++r) {
    const std::string field = first_difference(statuses[0].data, statuses[r].data);
    if (field.empty()) continue;
    return RankError(int(r), kExitBadInput, subject + " differs from rank 0's: '" + field + "'");
  }
  return std::nullopt;
}

void agree_across_ranks(const RankStatus& mine, const std::string& subject) {
  if (mpi::size() <= 1) return;
  std::vector<RankStatus> statuses;
  for (const std::string& text : mpi::all_gather(rank_status_to_text(mine))) {
    statuses.push_back(rank_status_from_text(text));
  }
  if (auto error = first_rank_error(statuses, subject)) throw *error;
}

RankStatus take_rank0_status(const RankStatus& mine) {
  if (mpi::size() <= 1) return mine;
  RankStatus status = rank_status_from_text(mpi::broadcast(rank_status_to_text(mine)));
  if (status.exit_code != 0) throw RankError(0, status.exit_code, status.message);
  return status;
}

}  // namespace prism
