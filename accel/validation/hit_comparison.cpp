#include "accel/validation/hit_comparison.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

namespace prism {
namespace {

std::string fmt_double(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

std::string describe_probe(const std::string& who, const PrimitiveProbe& p) {
  return who + ": double " + (p.hit ? "hit" : "miss") + " t=" + fmt_double(p.t) + " (+-" +
         fmt_double(p.t_tolerance) + "), boundary " + fmt_double(p.boundary_distance) +
         " away (rounding " + fmt_double(p.boundary_tolerance) + ")";
}

/// Hit or miss of this primitive is a rounding decision.
bool borderline(const PrimitiveProbe& p, const Ray& ray) {
  return p.grazes() || p.near_interval_end(ray);
}

double time_tolerance(double t) { return kHitTimeTolerance * std::max(1.0, std::abs(t)); }

}  // namespace

std::string to_string(HitAgreement agreement) {
  switch (agreement) {
    case HitAgreement::kSame:
      return "same";
    case HitAgreement::kTie:
      return "tie";
    case HitAgreement::kAmbiguous:
      return "ambiguous";
    case HitAgreement::kHard:
      return "HARD";
  }
  return "?";
}

std::string format_hit(const std::optional<Hit>& hit) {
  if (!hit) return "miss";
  char buf[200];
  std::snprintf(buf, sizeof buf, "t=%a (%.9g) u=%a v=%a geom=%u prim=%u", double(hit->t),
                double(hit->t), double(hit->u), double(hit->v), hit->geom_id, hit->prim_id);
  return buf;
}

HitComparison compare_exact(const std::optional<Hit>& a, const std::optional<Hit>& b) {
  if (!a && !b) return {};
  const std::string both = "[" + format_hit(a) + "] vs [" + format_hit(b) + "]";
  if (!a || !b) return {HitAgreement::kHard, "hit/miss differ: " + both};
  const auto bits = [](float x) { return std::bit_cast<uint32_t>(x); };
  const bool same_prim = a->geom_id == b->geom_id && a->prim_id == b->prim_id;
  if (bits(a->t) != bits(b->t)) return {HitAgreement::kHard, "t bits differ: " + both};
  if (!same_prim) return {HitAgreement::kTie, "exact tie resolved differently: " + both};
  if (bits(a->u) != bits(b->u) || bits(a->v) != bits(b->v)) {
    return {HitAgreement::kHard, "u, v differ: " + both};
  }
  return {};
}

HitComparison compare_tolerant(const Ray& ray, const std::optional<Hit>& a,
                               const std::optional<Hit>& b, const DoubleOracle& oracle) {
  if (!a && !b) return {};
  const std::string both = "[" + format_hit(a) + "] vs [" + format_hit(b) + "]";
  if (!a || !b) {
    const Hit& h = a ? *a : *b;
    const PrimitiveProbe p = oracle.probe(ray, h.geom_id, h.prim_id);
    const std::string why = "hit/miss differ: " + both + "; " + describe_probe("hit prim", p);
    return {borderline(p, ray) ? HitAgreement::kAmbiguous : HitAgreement::kHard, why};
  }
  const double dt = std::abs(double(a->t) - double(b->t));
  if (a->geom_id == b->geom_id && a->prim_id == b->prim_id) {
    if (dt <= time_tolerance(a->t)) return {};
    const PrimitiveProbe p = oracle.probe(ray, a->geom_id, a->prim_id);
    const std::string why =
        "t differs on the same primitive: " + both + "; " + describe_probe("prim", p);
    return {dt <= 2.0 * p.t_tolerance ? HitAgreement::kAmbiguous : HitAgreement::kHard, why};
  }
  const PrimitiveProbe pa = oracle.probe(ray, a->geom_id, a->prim_id);
  const PrimitiveProbe pb = oracle.probe(ray, b->geom_id, b->prim_id);
  const std::string why = "different primitives: " + both + "; " + describe_probe("a", pa) + "; " +
                          describe_probe("b", pb);
  const double rounding = pa.t_tolerance + pb.t_tolerance;
  const bool same_t = std::abs(pa.t - pb.t) <= rounding;  // false when either t is NaN
  const bool both_touched = (pa.hit || pa.grazes()) && (pb.hit || pb.grazes());
  if (same_t && both_touched && (dt <= time_tolerance(a->t) || dt <= rounding)) {
    return {HitAgreement::kTie, why};
  }
  // The backend that returned the farther primitive missed the nearer one, or the other one
  // hit it by mistake: either is fine only if hitting the nearer one is a rounding decision.
  const bool a_nearer = std::isnan(pb.t) || (!std::isnan(pa.t) && pa.t <= pb.t);
  const PrimitiveProbe& nearer = a_nearer ? pa : pb;
  return {borderline(nearer, ray) ? HitAgreement::kAmbiguous : HitAgreement::kHard, why};
}

void AgreementTally::add(const HitComparison& c, const std::string& context) {
  const auto keep = [&](std::string& slot) {
    if (slot.empty()) slot = c.reason + (context.empty() ? "" : "\n  ray: " + context);
  };
  switch (c.agreement) {
    case HitAgreement::kSame:
      ++same;
      break;
    case HitAgreement::kTie:
      ++tie;
      keep(first_tie);
      break;
    case HitAgreement::kAmbiguous:
      ++ambiguous;
      keep(first_ambiguous);
      break;
    case HitAgreement::kHard:
      ++hard;
      keep(first_hard);
      break;
  }
}

std::string AgreementTally::summary() const {
  return "same=" + std::to_string(same) + " tie=" + std::to_string(tie) +
         " ambiguous=" + std::to_string(ambiguous) + " hard=" + std::to_string(hard);
}

}  // namespace prism
