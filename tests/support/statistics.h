#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace prism::test {

/// Upper regularized incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a), a > 0, x >= 0.
double incomplete_gamma_q(double a, double x);

/// P(X >= statistic) for X chi-square distributed with `dof` degrees of freedom.
double chi_square_survival(double statistic, double dof);

/// Two-sided p-value of a standard normal z score.
double normal_two_sided_p(double z);

/// Result of a chi-square goodness-of-fit test.
struct ChiSquareResult {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 1.0;
  /// Observations in cells whose expected count is (numerically) zero: always a failure.
  size_t impossible_observations = 0;
  std::string summary() const;
};

/// Pearson's chi-square test of `observed` counts against `expected` counts (same total).
/// Cells expecting fewer than `min_expected` are pooled into one cell (Mitsuba's habit), which
/// is dropped if it still expects fewer. Cells expecting less than `zero_threshold` that
/// received samples are counted as impossible observations.
ChiSquareResult chi_square_test(std::span<const double> observed, std::span<const double> expected,
                                double min_expected = 5.0, double zero_threshold = 1e-9);

/// Per-test significance that keeps the family-wise error rate at `alpha` over `tests`
/// independent tests (Sidak correction).
double sidak_significance(double alpha, size_t tests);

/// Benjamini-Hochberg: which of the hypotheses with these p-values are rejected at false
/// discovery rate `q`.
std::vector<bool> benjamini_hochberg(std::span<const double> p_values, double q);

}  // namespace prism::test
