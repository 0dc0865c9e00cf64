#include "tests/support/statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace prism::test {
namespace {

/// P(a, x) by its power series; converges quickly for x < a + 1.
double gamma_p_series(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < 10000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-15) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

/// Q(a, x) by Lentz's evaluation of its continued fraction; for x >= a + 1.
double gamma_q_fraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double incomplete_gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  if (x < a + 1.0) return std::clamp(1.0 - gamma_p_series(a, x), 0.0, 1.0);
  return std::clamp(gamma_q_fraction(a, x), 0.0, 1.0);
}

double chi_square_survival(double statistic, double dof) {
  if (dof <= 0.0) return 1.0;
  return incomplete_gamma_q(0.5 * dof, 0.5 * statistic);
}

double normal_two_sided_p(double z) { return std::erfc(std::abs(z) / std::sqrt(2.0)); }

std::string ChiSquareResult::summary() const {
  std::ostringstream out;
  out << "chi2 = " << statistic << ", dof = " << dof << ", p = " << p_value
      << ", samples in zero-probability cells = " << impossible_observations;
  return out.str();
}

ChiSquareResult chi_square_test(std::span<const double> observed, std::span<const double> expected,
                                double min_expected, double zero_threshold) {
  ChiSquareResult result;
  double pooled_observed = 0.0, pooled_expected = 0.0;
  int cells = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < zero_threshold) {
      if (observed[i] > 0.0) result.impossible_observations += size_t(observed[i]);
      continue;
    }
    if (expected[i] < min_expected) {
      pooled_observed += observed[i];
      pooled_expected += expected[i];
      continue;
    }
    const double d = observed[i] - expected[i];
    result.statistic += d * d / expected[i];
    ++cells;
  }
  if (pooled_expected >= min_expected) {
    const double d = pooled_observed - pooled_expected;
    result.statistic += d * d / pooled_expected;
    ++cells;
  }
  result.dof = std::max(0, cells - 1);
  result.p_value = chi_square_survival(result.statistic, result.dof);
  return result;
}

double sidak_significance(double alpha, size_t tests) {
  if (tests <= 1) return alpha;
  return 1.0 - std::pow(1.0 - alpha, 1.0 / double(tests));
}

std::vector<bool> benjamini_hochberg(std::span<const double> p_values, double q) {
  const size_t m = p_values.size();
  std::vector<size_t> order(m);
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return p_values[a] < p_values[b]; });
  // The largest rank k with p_(k) <= k q / m: every hypothesis up to it is rejected.
  size_t cutoff = 0;
  for (size_t k = 1; k <= m; ++k) {
    if (p_values[order[k - 1]] <= double(k) * q / double(m)) cutoff = k;
  }
  std::vector<bool> rejected(m, false);
  for (size_t k = 0; k < cutoff; ++k) rejected[order[k]] = true;
  return rejected;
}

}  // namespace prism::test
