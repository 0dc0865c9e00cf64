#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/app/mpi_world.h"

namespace prism {

/// How one rank's step of a distributed command went, as the ranks exchange it.
struct RankStatus {
  int exit_code = 0;    ///< 0: the step succeeded
  std::string message;  ///< the one-line error when exit_code != 0
  nlohmann::json data;  ///< what the step produced, to compare or share (when it succeeded)
};

std::string rank_status_to_text(const RankStatus& status);
/// Throws Error(kInternal) on text rank_status_to_text() did not make.
RankStatus rank_status_from_text(const std::string& text);

/// The error of the first rank (in rank order) that failed, or else of the first whose data
/// differs from rank 0's: "<subject> differs from rank 0's: '<first differing field>'" (exit
/// 2); nothing when every rank succeeded with rank 0's data.
std::optional<RankError> first_rank_error(const std::vector<RankStatus>& statuses,
                                          const std::string& subject);

/// Collective: every rank's `mine`; throws first_rank_error() on every rank when there is one.
/// With one rank: throws nothing (its own errors propagate as they are).
void agree_across_ranks(const RankStatus& mine, const std::string& subject);

/// Collective: rank 0's `mine` on every rank (the others' are ignored); throws RankError(0, ...)
/// on every rank when rank 0's step failed. With one rank: `mine`.
RankStatus take_rank0_status(const RankStatus& mine);

}  // namespace prism
