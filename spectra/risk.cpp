#include "spectra/risk.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "solver/common/error.h"

namespace skewbridge::spectra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double Phi(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

// Phi(z2) - Phi(z1) for z1 <= z2, from the upper tails when both are positive so that a
// difference of numbers near 1 keeps its digits.
double PhiBetween(double z1, double z2) {
  if (z1 > 0.0)
    return 0.5 * (std::erfc(z1 / std::numbers::sqrt2) - std::erfc(z2 / std::numbers::sqrt2));
  return Phi(z2) - Phi(z1);
}

// The fragility P(LS | x), 0 at x = 0 and 1 at x = inf.
double Fragility(double x, double theta, double beta) {
  if (x <= 0.0) return 0.0;
  if (std::isinf(x)) return 1.0;
  return Phi(std::log(x / theta) / beta);
}

// The log-log slope k_i of interval i: lambda(x) = lambda_i (x / x_i)^-k_i.
double Slope(const HazardPoints& h, std::size_t i) {
  return std::log(h.rate_per_yr[i] / h.rate_per_yr[i + 1]) / std::log(h.im[i + 1] / h.im[i]);
}

// int_a^b Phi(ln(x / theta) / beta) |d lambda(x)| for the power law lambda(x) = lambda_a
// (x / a)^-k, a < b <= inf. By parts, with f the lognormal density of the capacity:
//   = F(a) lambda(a) - F(b) lambda(b) + int_a^b lambda(x) f(x) dx,
// and int_a^b (x / a)^-k f(x) dx = (a / theta)^k exp(k^2 beta^2 / 2)
//   [Phi(ln(b / theta) / beta + k beta) - Phi(ln(a / theta) / beta + k beta)]
// (the lognormal's moment of order -k over [a, b]; Cornell et al. 2002, eq. 8, is the whole
// line a = 0, b = inf).
double PowerLawPiece(double a, double b, double lambda_a, double k, double theta, double beta) {
  if (!(b > a)) return 0.0;
  const double fa = Fragility(a, theta, beta);
  const double lambda_b = std::isinf(b) ? 0.0 : lambda_a * std::pow(b / a, -k);
  const double fb = Fragility(b, theta, beta);
  const double za = std::log(a / theta) / beta + k * beta;
  const double zb = std::isinf(b) ? kInf : std::log(b / theta) / beta + k * beta;
  const double dphi =
      std::isinf(zb) ? 0.5 * std::erfc(za / std::numbers::sqrt2) : PhiBetween(za, zb);
  double moment = 0.0;
  if (dphi > 0.0) {
    moment = std::exp(std::log(lambda_a) + k * std::log(a / theta) + 0.5 * k * k * beta * beta +
                      std::log(dphi));
  }
  return std::max(fa * lambda_a - fb * lambda_b + moment, 0.0);
}

// The tail beyond x_n within [a, b) (a >= x_n), by the options' tail.
double TailBetween(const HazardPoints& h, double theta, double beta, UpperTail tail, double a,
                   double b) {
  const std::size_t n = h.im.size();
  const double xn = h.im[n - 1];
  const double ln = h.rate_per_yr[n - 1];
  switch (tail) {
    case UpperTail::kNone:
      return 0.0;
    case UpperTail::kLumped:
      return (a <= xn && xn < b) ? Fragility(xn, theta, beta) * ln : 0.0;
    case UpperTail::kPowerLaw: {
      const double k = Slope(h, n - 2);
      if (!(k > 0.0)) return 0.0;  // a flat last interval: no decay to extend
      const double lo = std::max(a, xn);
      if (!(b > lo)) return 0.0;
      return PowerLawPiece(lo, b, ln * std::pow(lo / xn, -k), k, theta, beta);
    }
  }
  return 0.0;
}

// The rate from IM in [a, b) of interval i (x_i <= a < b <= x_i+1) by the options' rule.
double IntervalBetween(const HazardPoints& h, std::size_t i, double theta, double beta,
                       RiskRule rule, double a, double b) {
  const double lo = std::max(a, h.im[i]);
  const double hi = std::min(b, h.im[i + 1]);
  if (!(hi > lo)) return 0.0;
  if (rule == RiskRule::kDiscrete) {
    // A point mass at x_i: counted when x_i lies in [a, b).
    return lo == h.im[i]
               ? Fragility(h.im[i], theta, beta) * (h.rate_per_yr[i] - h.rate_per_yr[i + 1])
               : 0.0;
  }
  const double k = Slope(h, i);
  return PowerLawPiece(lo, hi, h.rate_per_yr[i] * std::pow(lo / h.im[i], -k), k, theta, beta);
}

// The p-quantile of sorted values, linear between order statistics (numpy's default).
double Quantile(const std::vector<double>& sorted, double p) {
  const double at = p * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (at - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

void DemandUsable(const HazardPoints& h, double theta, double beta) {
  SB_DEMAND(h.im.size() >= 2 && h.im.size() == h.rate_per_yr.size(),
            "a risk integral needs at least two hazard points");
  SB_DEMAND(theta > 0.0 && beta > 0.0, "a lognormal fragility needs theta > 0 and beta > 0");
}

}  // namespace

std::string RiskRuleName(RiskRule rule) {
  return rule == RiskRule::kLogLog ? "loglog" : "discrete";
}

std::string UpperTailName(UpperTail tail) {
  switch (tail) {
    case UpperTail::kPowerLaw:
      return "power-law";
    case UpperTail::kLumped:
      return "lumped";
    case UpperTail::kNone:
      return "none";
  }
  return "";
}

HazardPoints UsableHazard(std::span<const double> im, std::span<const double> rate_per_yr,
                          double im_factor) {
  SB_DEMAND(im.size() == rate_per_yr.size(), "hazard levels and rates of unequal lengths");
  HazardPoints h;
  for (std::size_t i = 0; i < im.size(); ++i) {
    const double r = rate_per_yr[i];
    if (std::isinf(r)) {
      ++h.dropped_infinite;
    } else if (r == 0.0) {
      ++h.dropped_zero;
    } else {
      h.im.push_back(im[i] * im_factor);
      h.rate_per_yr.push_back(r);
    }
  }
  if (h.im.size() < 2) {
    h.im.clear();
    h.rate_per_yr.clear();
  }
  return h;
}

RiskIntegral IntegrateRisk(const HazardPoints& hazard, double theta, double beta,
                           const RiskOptions& options) {
  DemandUsable(hazard, theta, beta);
  const std::size_t n = hazard.im.size();
  RiskIntegral r;
  r.by_interval.resize(n);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    r.by_interval[i] =
        IntervalBetween(hazard, i, theta, beta, options.rule, hazard.im[i], hazard.im[i + 1]);
  }
  r.beyond_last = TailBetween(hazard, theta, beta, options.tail, hazard.im[n - 1], kInf);
  r.by_interval[n - 1] = r.beyond_last;
  for (double v : r.by_interval) r.rate_per_yr += v;
  r.p_at_first = Fragility(hazard.im[0], theta, beta);
  return r;
}

RiskIntegral DiscreteRisk(const HazardPoints& hazard, std::span<const double> p_ls,
                          UpperTail tail) {
  SB_DEMAND(hazard.im.size() >= 2 && p_ls.size() == hazard.im.size(),
            "one fragility value per hazard point");
  SB_DEMAND(tail != UpperTail::kPowerLaw, "the discrete sum of given values has no power-law tail");
  const std::size_t n = hazard.im.size();
  RiskIntegral r;
  r.by_interval.resize(n);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    r.by_interval[i] = p_ls[i] * (hazard.rate_per_yr[i] - hazard.rate_per_yr[i + 1]);
  }
  r.beyond_last = tail == UpperTail::kLumped ? p_ls[n - 1] * hazard.rate_per_yr[n - 1] : 0.0;
  r.by_interval[n - 1] = r.beyond_last;
  for (double v : r.by_interval) r.rate_per_yr += v;
  r.p_at_first = p_ls[0];
  return r;
}

double RiskBetween(const HazardPoints& hazard, double theta, double beta,
                   const RiskOptions& options, double lo, double hi) {
  DemandUsable(hazard, theta, beta);
  SB_DEMAND(lo <= hi, "RiskBetween needs lo <= hi");
  const std::size_t n = hazard.im.size();
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    sum += IntervalBetween(hazard, i, theta, beta, options.rule, lo, hi);
  }
  return sum + TailBetween(hazard, theta, beta, options.tail, lo, hi);
}

double HazardRateAt(const HazardPoints& hazard, UpperTail tail, double x) {
  SB_DEMAND(hazard.im.size() >= 2 && x > 0.0, "HazardRateAt needs a hazard and x > 0");
  const std::size_t n = hazard.im.size();
  if (x <= hazard.im[0]) return hazard.rate_per_yr[0];
  if (x > hazard.im[n - 1]) {
    if (tail != UpperTail::kPowerLaw) return 0.0;
    return hazard.rate_per_yr[n - 1] * std::pow(x / hazard.im[n - 1], -Slope(hazard, n - 2));
  }
  const std::size_t i = static_cast<std::size_t>(
      std::upper_bound(hazard.im.begin(), hazard.im.end(), x) - hazard.im.begin() - 1);
  if (i >= n - 1) return hazard.rate_per_yr[n - 1];
  return hazard.rate_per_yr[i] * std::pow(x / hazard.im[i], -Slope(hazard, i));
}

double CornellRate(double k0, double k, double theta, double beta) {
  return k0 * std::pow(theta, -k) * std::exp(0.5 * k * k * beta * beta);
}

PowerLawFit FitPowerLaw(const HazardPoints& hazard, double theta, double beta) {
  DemandUsable(hazard, theta, beta);
  PowerLawFit fit;
  const double first = hazard.im.front(), last = hazard.im.back();
  fit.lo = std::max(theta * std::exp(-beta), first);
  fit.hi = std::min(theta * std::exp(beta), last);
  if (!(fit.hi > fit.lo)) {
    fit.reason = fmt::format(
        "the band theta e^-beta .. theta e^beta = {:.4g} .. {:.4g} lies "
        "outside the hazard's points {:.4g} .. {:.4g}",
        theta * std::exp(-beta), theta * std::exp(beta), first, last);
    fit.k0 = fit.k = kNaN;
    return fit;
  }
  // ln lambda at 21 points equally spaced in ln x, on the log-log interpolated curve.
  constexpr int kPoints = 21;
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  std::size_t seg = 0;
  for (int j = 0; j < kPoints; ++j) {
    const double lx = std::log(fit.lo) + (std::log(fit.hi) - std::log(fit.lo)) * j / (kPoints - 1);
    const double x = std::exp(lx);
    while (seg + 2 < hazard.im.size() && x > hazard.im[seg + 1]) ++seg;
    const double k = Slope(hazard, seg);
    const double ly = std::log(hazard.rate_per_yr[seg]) - k * (lx - std::log(hazard.im[seg]));
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double slope = (kPoints * sxy - sx * sy) / (kPoints * sxx - sx * sx);
  fit.k = -slope;
  fit.k0 = std::exp((sy - slope * sx) / kPoints);
  return fit;
}

RiskSpread SpreadOfRisk(const HazardPoints& hazard, double theta, double beta, double se_ln_theta,
                        double se_beta, double cov_ln_theta_beta, const RiskOptions& options,
                        int draws, std::uint64_t seed) {
  DemandUsable(hazard, theta, beta);
  RiskSpread s;
  s.draws = draws;
  s.p16 = s.p50 = s.p84 = kNaN;
  if (!(std::isfinite(se_ln_theta) && std::isfinite(se_beta) && std::isfinite(cov_ln_theta_beta) &&
        se_ln_theta >= 0.0 && se_beta >= 0.0)) {
    s.reason = "the fragility has no covariance of (ln theta, beta)";
    return s;
  }
  // (ln theta, beta) = mean + L z with L the Cholesky factor of the covariance.
  const double l11 = se_ln_theta;
  const double l21 = l11 > 0.0 ? cov_ln_theta_beta / l11 : 0.0;
  const double l22 = std::sqrt(std::max(se_beta * se_beta - l21 * l21, 0.0));
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> rates;
  rates.reserve(static_cast<std::size_t>(draws));
  for (int d = 0; d < draws; ++d) {
    const double z1 = normal(gen);
    const double z2 = normal(gen);
    const double t = theta * std::exp(l11 * z1);
    const double b = beta + l21 * z1 + l22 * z2;
    if (!(b > 0.0)) continue;
    rates.push_back(IntegrateRisk(hazard, t, b, options).rate_per_yr);
  }
  s.used = static_cast<int>(rates.size());
  if (s.used < draws / 2) {
    s.reason = fmt::format("only {} of {} draws have beta > 0", s.used, draws);
    return s;
  }
  std::sort(rates.begin(), rates.end());
  s.p16 = Quantile(rates, 0.16);
  s.p50 = Quantile(rates, 0.50);
  s.p84 = Quantile(rates, 0.84);
  return s;
}

double ProbabilityInYears(double rate_per_yr, double years) {
  return -std::expm1(-rate_per_yr * years);
}

}  // namespace skewbridge::spectra
