#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "accel/validation/double_oracle.h"
#include "core/hit.h"
#include "core/ray.h"

namespace prism {

/// How two backends' answers for one ray relate.
enum class HitAgreement {
  kSame,       ///< equal under the rule applied
  kTie,        ///< different primitives hit at the same t: shared edge/vertex, coplanar copies
  kAmbiguous,  ///< the ray grazes an edge, silhouette or interval end: rounding decides
  kHard,       ///< a real disagreement: a bug in one of the backends
};

std::string to_string(HitAgreement agreement);

/// The verdict on one ray and why.
struct HitComparison {
  HitAgreement agreement = HitAgreement::kSame;
  std::string reason;  ///< empty for kSame
};

/// Relative t tolerance of the bvh-vs-embree rule: |dt| <= kHitTimeTolerance * max(1, t).
inline constexpr double kHitTimeTolerance = 1e-4;

/// The rule for two backends sharing primitive tests and tie order (bvh vs brute): both miss,
/// or both hit with the same t bits, u, v bits and primitive. A different primitive at the
/// same t bits is kTie (an exact tie resolved differently); anything else is kHard.
HitComparison compare_exact(const std::optional<Hit>& a, const std::optional<Hit>& b);

/// The rule for independent backends (bvh vs embree), judged by `oracle`:
/// - hit/miss must agree, unless the hit primitive is grazed or its t is at tmin/tmax within
///   rounding (kAmbiguous);
/// - on the same primitive, |dt| <= kHitTimeTolerance * max(1, t), or within the oracle's
///   rounding for t on an ill-conditioned (grazing) hit (kAmbiguous);
/// - different primitives only where the oracle finds both at the same t within rounding
///   (kTie), or where the nearer of the two (in double) is grazed (kAmbiguous).
HitComparison compare_tolerant(const Ray& ray, const std::optional<Hit>& a,
                               const std::optional<Hit>& b, const DoubleOracle& oracle);

/// "miss" or "t=<hex> (<decimal>) u=.. v=.. geom=.. prim=.." for failure messages.
std::string format_hit(const std::optional<Hit>& hit);

/// Counts of each verdict over many rays, with the first non-kSame reason of each kind.
struct AgreementTally {
  size_t same = 0, tie = 0, ambiguous = 0, hard = 0;
  std::string first_tie, first_ambiguous, first_hard;

  /// Counts `c`; `context` (e.g. the formatted ray) is kept with the first reason of its kind.
  void add(const HitComparison& c, const std::string& context);
  size_t total() const { return same + tie + ambiguous + hard; }
  /// "same=.. tie=.. ambiguous=.. hard=..".
  std::string summary() const;
};

}  // namespace prism
