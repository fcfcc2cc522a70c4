#pragma once
/// @file
/// The annual rate of a limit state from a hazard curve and a lognormal fragility, the risk
/// integral lambda_LS = int P(LS | IM = x) |d lambda_IM(x)| [Cornell et al. 2002, J. Struct.
/// Eng. 128(4):526-533, eq. 3; Baker et al. 2021, Seismic Hazard and Risk Analysis, ch. 9],
/// its deaggregation by IM, the closed form of Cornell et al. (2002, eq. 8) for a power-law
/// hazard, the rate's spread from the fragility's parameter uncertainty, and the probability in
/// t years under Poisson occurrence. Pure functions of their inputs: no state, no printing.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace skewbridge::spectra {

/// How the integral reads the hazard between its points.
enum class RiskRule {
  /// lambda(x) interpolated as a straight line in ln lambda against ln x between points, and the
  /// integral of Phi(ln(x / theta) / beta) |d lambda| over each interval exact for that power
  /// law (docs/risk.md gives the closed form per interval).
  kLogLog,
  /// The discrete sum of Baker et al. (2021, ch. 9): sum_i P(LS | x_i) (lambda_i - lambda_i+1),
  /// each interval's rate assigned to the fragility at its lower level.
  kDiscrete,
};

/// What the integral takes beyond the last hazard point x_n.
enum class UpperTail {
  /// The last interval's power law lambda_n (x / x_n)^-k extended to infinity (k its log-log
  /// slope; nothing when k = 0): an upper bound where the hazard falls faster, as a truncated
  /// ground-motion model makes it.
  kPowerLaw,
  /// All of lambda_n counted at P(LS | x_n), the convention of Baker's risk_metrics script
  /// (diff([rates 0])): a lower bound, since P grows beyond x_n.
  kLumped,
  /// Nothing beyond x_n, the convention of Baker's risk_target script (diff then 0).
  kNone,
};

/// The rule and the tail of one integral.
struct RiskOptions {
  RiskRule rule = RiskRule::kLogLog;      ///< between the points
  UpperTail tail = UpperTail::kPowerLaw;  ///< beyond the last
};

/// "loglog" / "discrete", and "power-law" / "lumped" / "none", as cubes and options spell them.
std::string RiskRuleName(RiskRule rule);
/// As RiskRuleName, for the tail.
std::string UpperTailName(UpperTail tail);

/// The points of a hazard curve the integral uses: levels x_i (> 0, increasing) and annual rates
/// lambda_i (finite, > 0, non-increasing), at least two.
struct HazardPoints {
  std::vector<double> im;           ///< x_i, in the unit of the fragility's theta
  std::vector<double> rate_per_yr;  ///< lambda_i (1/yr)
  int dropped_infinite = 0;         ///< leading levels dropped: rate +inf (OpenQuake poe = 1)
  int dropped_zero = 0;             ///< trailing levels dropped: rate 0 (beyond the tail's reach)
};

/// The usable points of a curve: leading infinite rates and trailing zero rates dropped, the
/// levels multiplied by `im_factor` (a component conversion). Empty `im` when fewer than two
/// finite positive rates remain.
/// @pre im and rate_per_yr have equal sizes; levels increasing, rates non-increasing
HazardPoints UsableHazard(std::span<const double> im, std::span<const double> rate_per_yr,
                          double im_factor = 1.0);

/// The result of one risk integral.
struct RiskIntegral {
  double rate_per_yr = 0.0;  ///< lambda_LS, the annual rate of the limit state (1/yr)
  /// The deaggregation by IM: entry i < n - 1 the rate from IM in [x_i, x_i+1), entry n - 1 the
  /// rate from IM beyond x_n (the tail); they sum to rate_per_yr.
  std::vector<double> by_interval;
  double beyond_last = 0.0;  ///< the tail's rate (= by_interval.back())
  double p_at_first = 0.0;   ///< P(LS | x_1): the fragility where the hazard starts, whose
                             ///< lower IM the integral does not see
};

/// The risk integral of the lognormal fragility Phi(ln(x / theta) / beta) over the hazard.
/// @pre theta > 0, beta > 0; hazard as UsableHazard makes it (>= 2 points)
RiskIntegral IntegrateRisk(const HazardPoints& hazard, double theta, double beta,
                           const RiskOptions& options);

/// Baker's discrete sum for a fragility given by its values at the hazard's points:
/// lambda_LS = sum_i p_i (lambda_i - lambda_i+1), with lambda_n+1 = 0 for the kLumped tail (his
/// risk_metrics script) or lambda_n+1 = lambda_n for kNone (his risk_target script).
/// @pre p_ls has one value in [0, 1] per hazard point; tail is kLumped or kNone
RiskIntegral DiscreteRisk(const HazardPoints& hazard, std::span<const double> p_ls, UpperTail tail);

/// The part of the integral from IM in [lo, hi) (hi may be +inf), by the same rule and tail:
/// the rate that intensities between lo and hi contribute.
/// @pre as IntegrateRisk; lo <= hi
double RiskBetween(const HazardPoints& hazard, double theta, double beta,
                   const RiskOptions& options, double lo, double hi);

/// The hazard lambda(x) as the integral reads it: log-log between the points, lambda_1 below
/// x_1 (the least it can be), and beyond x_n the tail's: the power law for kPowerLaw, 0 for
/// kLumped and kNone (their rate beyond x_n is counted at x_n or not at all).
/// @pre hazard as UsableHazard makes it; x > 0
double HazardRateAt(const HazardPoints& hazard, UpperTail tail, double x);

/// The closed form of Cornell et al. (2002, eq. 8) for a power-law hazard lambda(x) = k0 x^-k
/// and a lognormal fragility: lambda_LS = k0 theta^-k exp(k^2 beta^2 / 2).
double CornellRate(double k0, double k, double theta, double beta);

/// A power law fitted to the hazard around a median: least squares of ln lambda on ln x over
/// 21 points equally spaced in ln x across [theta e^-beta, theta e^beta] (clipped to the
/// hazard's range) on the log-log interpolated curve.
struct PowerLawFit {
  std::string reason;  ///< "" when fitted; else why not (the band outside the hazard's points)
  double k0 = 0.0;     ///< lambda = k0 x^-k, in 1/yr with x in the IM unit
  double k = 0.0;      ///< the log-log slope (> 0 for a falling hazard)
  double lo = 0.0;     ///< the band's ends actually used
  double hi = 0.0;
};

/// Fits k0 and k around theta over +-1 beta.
/// @pre hazard as UsableHazard makes it; theta > 0, beta > 0
PowerLawFit FitPowerLaw(const HazardPoints& hazard, double theta, double beta);

/// The spread of lambda_LS from the fragility's parameter uncertainty: (ln theta, beta) drawn
/// from the bivariate normal of the fit's covariance (std::mt19937_64 with `seed`), draws with
/// beta <= 0 discarded, lambda_LS integrated for each, and the 16, 50 and 84 % quantiles (linear
/// between order statistics, numpy's default).
struct RiskSpread {
  std::string reason;  ///< "" or why no spread (no covariance, too few usable draws)
  int draws = 0;       ///< draws asked for
  int used = 0;        ///< draws with beta > 0
  double p16 = 0.0;    ///< 16 % quantile of lambda_LS (1/yr)
  double p50 = 0.0;    ///< median of the draws' lambda_LS
  double p84 = 0.0;    ///< 84 % quantile
};

/// The draws' default count and seed.
inline constexpr int kRiskDraws = 2000;
inline constexpr std::uint64_t kRiskSeed = 20021101;

/// Draws the spread of lambda_LS.
/// @pre as IntegrateRisk; se_ln_theta, se_beta >= 0 and the covariance positive semi-definite
RiskSpread SpreadOfRisk(const HazardPoints& hazard, double theta, double beta, double se_ln_theta,
                        double se_beta, double cov_ln_theta_beta, const RiskOptions& options,
                        int draws = kRiskDraws, std::uint64_t seed = kRiskSeed);

/// P(at least one occurrence in t years) = 1 - exp(-lambda t), Poisson occurrence.
double ProbabilityInYears(double rate_per_yr, double years);

}  // namespace skewbridge::spectra
