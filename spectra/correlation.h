#pragma once
/// @file
/// Correlation statistics of a response against an excitation measure over a set of records
/// (theta_m against the persistency L_e in [Dimitrakopoulos 2011, §4]): Pearson's r, Spearman's
/// rho with average ranks for ties, and the least-squares line through (log10 x, log10 y).
/// A statistic that cannot be computed is NaN with a one-line reason, never an exception.

#include <span>
#include <string>
#include <vector>

namespace skewbridge::spectra {

/// A statistic and, when it is NaN, why.
struct Statistic {
  double value = 0.0;  ///< NaN when it cannot be computed.
  std::string reason;  ///< "" when value is a number.
};

/// Pearson's correlation coefficient
/// r = sum (x_i - xbar)(y_i - ybar) / sqrt(sum (x_i - xbar)^2 sum (y_i - ybar)^2).
/// NaN when n < 2, the sizes differ, a value is not finite, or a column is constant.
Statistic Pearson(std::span<const double> x, std::span<const double> y);

/// Ranks 1..n of the values, ties given the average of the ranks they span (1-based), so
/// {10, 20, 20, 30} -> {1, 2.5, 2.5, 4}. @pre every value finite.
std::vector<double> AverageRanks(std::span<const double> values);

/// Spearman's rank correlation: Pearson's r of AverageRanks(x) and AverageRanks(y) (the tie-
/// corrected form; equals 1 - 6 sum d_i^2 / (n (n^2 - 1)) without ties).
/// NaN as Pearson (a column of equal values has constant ranks).
Statistic Spearman(std::span<const double> x, std::span<const double> y);

/// The line log10 y = intercept + slope log10 x fitted by least squares, and its coefficient
/// of determination r2 = 1 - SS_res / SS_tot in log space.
struct LogLogFit {
  std::size_t n = 0;  ///< points used: x and y finite and positive
  Statistic slope;
  Statistic intercept;
  Statistic r2;
};

/// Fits LogLogFit over the pairs with x > 0 and y > 0 (both finite); the others are skipped
/// (a zero rotation has no logarithm). slope and intercept are NaN with fewer than 2 such
/// points or a constant log10 x; r2 is NaN also when log10 y is constant (SS_tot = 0).
/// For y = c x^p exactly: slope = p, intercept = log10 c, r2 = 1.
LogLogFit FitLogLog(std::span<const double> x, std::span<const double> y);

}  // namespace skewbridge::spectra
