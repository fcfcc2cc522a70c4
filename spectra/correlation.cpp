#include "spectra/correlation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace skewbridge::spectra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Statistic NotANumber(std::string reason) { return {kNaN, std::move(reason)}; }

double Mean(std::span<const double> v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

}  // namespace

Statistic Pearson(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) return NotANumber("x and y differ in length");
  if (x.size() < 2) return NotANumber("fewer than 2 points");
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) return NotANumber("a value is not finite");
  }
  // Two passes (means first) keep the sums of squares free of cancellation.
  const double x_mean = Mean(x);
  const double y_mean = Mean(y);
  double sxy = 0.0;
  double sxx = 0.0;
  double syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = x[i] - x_mean;
    const double dy = y[i] - y_mean;
    sxy += dx * dy;
    sxx += dx * dx;
    syy += dy * dy;
  }
  if (sxx == 0.0) return NotANumber("x is constant");
  if (syy == 0.0) return NotANumber("y is constant");
  return {std::clamp(sxy / std::sqrt(sxx * syy), -1.0, 1.0), ""};
}

std::vector<double> AverageRanks(std::span<const double> values) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<double> ranks(values.size());
  std::size_t first = 0;
  while (first < order.size()) {
    std::size_t last = first;
    while (last + 1 < order.size() && values[order[last + 1]] == values[order[first]]) ++last;
    // Positions first..last (0-based) hold equal values: each gets the mean of ranks
    // first + 1 .. last + 1.
    const double rank = 0.5 * static_cast<double>(first + last) + 1.0;
    for (std::size_t k = first; k <= last; ++k) ranks[order[k]] = rank;
    first = last + 1;
  }
  return ranks;
}

Statistic Spearman(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) return NotANumber("x and y differ in length");
  if (x.size() < 2) return NotANumber("fewer than 2 points");
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) return NotANumber("a value is not finite");
  }
  const std::vector<double> rx = AverageRanks(x);
  const std::vector<double> ry = AverageRanks(y);
  return Pearson(rx, ry);
}

LogLogFit FitLogLog(std::span<const double> x, std::span<const double> y) {
  LogLogFit fit;
  std::vector<double> lx;
  std::vector<double> ly;
  const std::size_t n = std::min(x.size(), y.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i]) && x[i] > 0.0 && y[i] > 0.0) {
      lx.push_back(std::log10(x[i]));
      ly.push_back(std::log10(y[i]));
    }
  }
  fit.n = lx.size();
  if (x.size() != y.size()) {
    fit.slope = fit.intercept = fit.r2 = NotANumber("x and y differ in length");
    return fit;
  }
  if (fit.n < 2) {
    fit.slope = fit.intercept = fit.r2 = NotANumber("fewer than 2 positive points");
    return fit;
  }
  const double x_mean = Mean(lx);
  const double y_mean = Mean(ly);
  double sxy = 0.0;
  double sxx = 0.0;
  double syy = 0.0;
  for (std::size_t i = 0; i < fit.n; ++i) {
    const double dx = lx[i] - x_mean;
    const double dy = ly[i] - y_mean;
    sxy += dx * dy;
    sxx += dx * dx;
    syy += dy * dy;
  }
  if (sxx == 0.0) {
    fit.slope = fit.intercept = fit.r2 = NotANumber("log10 x is constant");
    return fit;
  }
  const double slope = sxy / sxx;
  const double intercept = y_mean - slope * x_mean;
  fit.slope = {slope, ""};
  fit.intercept = {intercept, ""};
  if (syy == 0.0) {
    fit.r2 = NotANumber("log10 y is constant");
    return fit;
  }
  double ss_res = 0.0;
  for (std::size_t i = 0; i < fit.n; ++i) {
    const double e = ly[i] - (intercept + slope * lx[i]);
    ss_res += e * e;
  }
  fit.r2 = {1.0 - ss_res / syy, ""};
  return fit;
}

}  // namespace skewbridge::spectra
