#pragma once
/// @file
/// Lognormal fragility functions P(C | IM = x) = Phi(ln(x / theta) / beta): the maximum-
/// likelihood fit of exceedance counts over intensity levels (binomial likelihood, multiple-
/// stripe analysis [Baker 2015, Earthquake Spectra 31(1):579-599, eq. 11]) and the cloud fit of
/// ln(demand / capacity) on ln(IM) [Cornell et al. 2002, J. Struct. Eng. 128(4):526-533].
/// Pure functions of their inputs: no state, no printing.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace skewbridge::spectra {

/// The lognormal fragility Phi(ln(im / theta) / beta) [Baker 2015, eq. 1]; im and theta in the
/// same unit. @pre theta > 0, beta > 0
double LognormalFragility(double im, double theta, double beta);

/// A maximum-likelihood lognormal fragility with the likelihood's own standard errors.
/// When `reason` is not empty the data cannot identify the function and every number is NaN.
struct LognormalFit {
  std::string reason;              ///< "" when fitted; else why not (all 0, all 1, one stripe, ...)
  double theta = 0.0;              ///< median capacity, in the unit of the IM
  double beta = 0.0;               ///< logarithmic standard deviation (dispersion), 1
  double se_ln_theta = 0.0;        ///< standard error of ln theta from the observed information
  double se_beta = 0.0;            ///< standard error of beta
  double cov_ln_theta_beta = 0.0;  ///< covariance of (ln theta, beta)
  double log_likelihood = 0.0;     ///< at the maximum
  int iterations = 0;              ///< Newton steps taken
  std::int64_t trials = 0;         ///< total number of trials used
  std::int64_t exceeded = 0;       ///< total number of exceedances used
};

/// Fits theta and beta by maximising the binomial log-likelihood
///   l = sum_j z_j ln Phi(u_j) + (n_j - z_j) ln Phi(-u_j),  u_j = (ln x_j - ln theta) / beta,
/// [Baker 2015, eq. 11] by Newton's method with step halving on the concave probit form
/// u_j = a + b ln x_j (b = 1 / beta, a = -ln theta / beta); the covariance is the inverse of the
/// observed information, carried to (ln theta, beta) by the delta method. A stripe may be one
/// cell (n_j = 1), so records of different intensity (cloud data) fit too. Observations of
/// equal im are pooled into one (their n_j and z_j summed), which leaves l unchanged: a stripe
/// of R cells costs one term of the sums, not R.
/// Observations with a non-finite or non-positive im, or n_j = 0, are skipped.
/// Refused with a reason, never a number: no trials; fewer than two distinct im; no exceedance;
/// exceedance in every trial; stripes that separate (every exceedance at an im at least as
/// large as every non-exceedance: beta would tend to 0); a fraction that falls with im (b <= 0).
/// @pre im, trials, exceeded have equal sizes; 0 <= exceeded_j <= trials_j, whole numbers
LognormalFit FitLognormalMle(std::span<const double> im, std::span<const double> trials,
                             std::span<const double> exceeded);

/// One-trial observations (im_i, exceeded_i) made ready for FitLognormalMle of many resamples of
/// them (a bootstrap): each observation's ln im and its place among the distinct ones are found
/// once, so a resample, given as how many times it draws each observation, costs no logarithm
/// and no sort. Its fit is FitLognormalMle of the observations so repeated, bit for bit: the
/// pooled points are the same, in the same order, and their sums are whole numbers.
class ResampledLognormalFits {
 public:
  /// @pre im and exceeded have equal sizes; 0 <= exceeded_i <= 1
  ResampledLognormalFits(std::span<const double> im, std::span<const double> exceeded);
  /// FitLognormalMle(x, ones, e) of the arrays x, e holding observation i draws[i] times.
  /// @pre draws.size() equals the number of observations
  LognormalFit Fit(std::span<const std::uint32_t> draws) const;

 private:
  std::vector<double> im_;
  std::vector<double> exceeded_;
  std::vector<double> ln_im_;         ///< the distinct ln im of usable observations, ascending
  std::vector<std::uint32_t> level_;  ///< per observation, its ln im's index in ln_im_
  bool whole_ = true;  ///< every usable exceeded_i is 0 or 1 (else Fit runs FitLognormalMle)
  static constexpr std::uint32_t kSkipped = 0xffffffffu;  ///< a level_ of a skipped observation
};

/// The cloud fit: least squares of ln(D / C) = intercept + slope ln(IM) over the cells, sigma
/// the standard error of the residuals (n - 2 degrees of freedom); the fragility
/// P(D > C | IM) = Phi((intercept + slope ln IM) / sigma) is lognormal with
/// theta = exp(-intercept / slope), beta = sigma / slope [Cornell et al. 2002, eq. 8].
struct CloudFit {
  std::string reason;         ///< "" when fitted; else why not
  std::int64_t n = 0;         ///< cells used: im > 0 and demand_over_capacity > 0, finite
  std::int64_t excluded = 0;  ///< cells left out: a zero, negative or non-finite D / C or im
  double intercept = 0.0;     ///< of ln(D / C) against ln(im)
  double slope = 0.0;         ///< b
  double sigma = 0.0;         ///< dispersion of ln(D / C) given im
  double theta = 0.0;         ///< median IM of D = C, in the unit of the IM
  double beta = 0.0;          ///< sigma / slope
};

/// Fits the cloud of (im, D / C). Needs at least 3 cells, a non-constant ln(im), and a positive
/// slope (a demand that grows with the intensity), else a reason and NaN numbers.
/// @pre im and demand_over_capacity have equal sizes
CloudFit FitCloud(std::span<const double> im, std::span<const double> demand_over_capacity);

}  // namespace skewbridge::spectra
