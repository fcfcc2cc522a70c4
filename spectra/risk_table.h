#pragma once
/// @file
/// The annual rates of a sweep's limit states over a site's hazard curve, per limit state and
/// combination of the fragility's axes (spectra/fragility_table.h): lambda_LS by the risk
/// integral (spectra/risk.h) with its deaggregation by IM, the Cornell closed form beside it,
/// the 16 and 84 % of lambda from the fit's covariance, P in 1 and 50 years, the return
/// period, the shares of the rate from beyond the hazard's last point and from outside the
/// stripes, and the flags that say what the number assumes. Pure: the jobs layer reads the cube
/// and writes the table (docs/hdf5-layout.md, risk/).

#include <cstdint>
#include <string>
#include <vector>

#include "spectra/risk.h"

namespace skewbridge::spectra {

/// One limit state's fragility as the cube stores it, per combination (row-major).
struct RiskFragility {
  std::string name;                          ///< the limit state
  std::vector<double> theta, beta;           ///< median (IM unit) and dispersion; NaN: no fit
  std::vector<double> se_ln_theta, se_beta;  ///< standard errors; NaN: none (e.g. IDA fits)
  std::vector<double> cov_ln_theta_beta;     ///< their covariance
  std::vector<std::string> reason;           ///< why theta is NaN, per combination
  /// The smallest and largest stripe IM with cells, per combination (NaN without stripes: the
  /// fitted cells' IM range then).
  std::vector<double> im_lo, im_hi;
};

/// What the records of each combination were asked to do, for the honesty flags.
struct RiskRecordFacts {
  bool selected_for_site = false;  ///< the user states the records were selected for it
  double max_scale = 0.0;          ///< the scale-factor limit (0: none set)
  std::vector<std::int64_t> cells_beyond_max_scale;  ///< per combination
  std::vector<double> largest_scale;                 ///< per combination; NaN for unscaled records
};

/// The thresholds of the flags: a share of the rate from outside the data, or a fragility
/// already this likely at the hazard's first level, is flagged. Above the largest stripe s the
/// fragility lies between P(LS | s) and 1, so the part of the rate its extrapolation can move
/// is at most (1 - P(LS | s)) lambda_IM(s): that bound is what is compared with kFlagShare.
inline constexpr double kFlagShare = 0.05;
inline constexpr double kFlagFirstLevelP = 1e-3;

/// One limit state's rates, per combination (row-major, as RiskFragility).
struct RiskRates {
  std::string name;
  std::vector<double> rate_per_yr;         ///< lambda_LS (1/yr); NaN where there is no fit
  std::vector<double> rate_p16, rate_p84;  ///< from the fit's covariance; NaN without one
  std::vector<double> p_1yr, p_50yr;       ///< 1 - exp(-lambda t)
  std::vector<double> return_period_yr;    ///< 1 / lambda
  std::vector<double> cornell_rate;        ///< k0 theta^-k exp(k^2 beta^2 / 2) with the local fit
  std::vector<double> cornell_k, cornell_k0;  ///< the local power law around theta
  std::vector<double> share_beyond_hazard;    ///< of lambda, from IM beyond the last hazard point
  std::vector<double> share_above_stripes;    ///< from IM above the largest stripe (im_hi)
  /// (1 - P(LS | im_hi)) lambda_IM(im_hi) / lambda_LS: the most the lognormal's extrapolation
  /// above the stripes can move the rate, as a share of it
  std::vector<double> share_above_stripes_movable;
  std::vector<double> share_below_stripes;  ///< from IM below the smallest stripe (im_lo)
  std::vector<double> p_at_first_level;     ///< P(LS | first hazard level)
  std::vector<double> deaggregation;        ///< [combination][hazard interval]: the rate's share
  std::vector<std::string> reason;          ///< "" or why there is no rate (the fit's reason)
  std::vector<std::string> flags;           ///< what the rate assumes, sentences joined by "; "
};

/// The rates of every limit state over one hazard.
struct RiskTable {
  RiskOptions options;             ///< the rule and tail used
  HazardPoints hazard;             ///< the points integrated (after conversion)
  std::vector<std::string> notes;  ///< flags common to every rate (measure match, records)
  std::vector<RiskRates> limit_states;
};

/// Computes the table. `match_notes` are the measure check's notes (period gap, conversion).
/// @pre hazard has >= 2 points; every per-combination vector of a fragility has one size, and
/// records' vectors that size too
RiskTable ComputeRiskTable(const HazardPoints& hazard, const RiskOptions& options,
                           const std::vector<RiskFragility>& fragilities,
                           const RiskRecordFacts& records,
                           const std::vector<std::string>& match_notes);

}  // namespace skewbridge::spectra
