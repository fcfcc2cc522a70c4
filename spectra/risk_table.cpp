#include "spectra/risk_table.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "solver/common/error.h"
#include "spectra/fragility.h"

namespace skewbridge::spectra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string Join(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

}  // namespace

RiskTable ComputeRiskTable(const HazardPoints& hazard, const RiskOptions& options,
                           const std::vector<RiskFragility>& fragilities,
                           const RiskRecordFacts& records,
                           const std::vector<std::string>& match_notes) {
  SB_DEMAND(hazard.im.size() >= 2, "a risk table needs a hazard of at least two points");
  RiskTable t;
  t.options = options;
  t.hazard = hazard;
  t.notes = match_notes;
  if (!records.selected_for_site) {
    t.notes.push_back(
        "the records were not selected for this site's hazard (no conditional spectrum, "
        "magnitude or distance): the rate assumes the fragility holds whatever the spectral "
        "shape of the site's motions at each level");
  }
  if (hazard.dropped_infinite > 0) {
    t.notes.push_back(
        fmt::format("{} hazard level(s) with probability 1 (an infinite rate) left "
                    "out below {:.4g}",
                    hazard.dropped_infinite, hazard.im.front()));
  }
  if (hazard.dropped_zero > 0) {
    t.notes.push_back(
        fmt::format("{} hazard level(s) with rate 0 left out above {:.4g}: the "
                    "tail is extended from the last positive rate",
                    hazard.dropped_zero, hazard.im.back()));
  }
  const std::size_t n = hazard.im.size();
  for (const RiskFragility& f : fragilities) {
    const std::size_t combos = f.theta.size();
    SB_DEMAND(f.beta.size() == combos && f.reason.size() == combos && f.im_lo.size() == combos &&
                  f.im_hi.size() == combos && f.se_ln_theta.size() == combos &&
                  f.se_beta.size() == combos && f.cov_ln_theta_beta.size() == combos &&
                  records.cells_beyond_max_scale.size() == combos &&
                  records.largest_scale.size() == combos,
              "risk inputs of unequal sizes");
    RiskRates r;
    r.name = f.name;
    auto fill = [combos](auto&... v) { (v.assign(combos, kNaN), ...); };
    fill(r.rate_per_yr, r.rate_p16, r.rate_p84, r.p_1yr, r.p_50yr, r.return_period_yr,
         r.cornell_rate, r.cornell_k, r.cornell_k0, r.share_beyond_hazard, r.share_above_stripes,
         r.share_above_stripes_movable, r.share_below_stripes, r.p_at_first_level);
    r.deaggregation.assign(combos * n, kNaN);
    r.reason.assign(combos, "");
    r.flags.assign(combos, "");
    for (std::size_t c = 0; c < combos; ++c) {
      std::vector<std::string> flags;
      if (records.cells_beyond_max_scale[c] > 0) {
        flags.push_back(fmt::format(
            "{} cell(s) scaled beyond the limit of {:g} (largest factor "
            "{:.3g}), kept in the fit",
            records.cells_beyond_max_scale[c], records.max_scale, records.largest_scale[c]));
      } else if (std::isfinite(records.largest_scale[c])) {
        flags.push_back(fmt::format("largest scale factor {:.3g}{}", records.largest_scale[c],
                                    records.max_scale > 0.0
                                        ? fmt::format(" (limit {:g})", records.max_scale)
                                        : std::string(" (no limit set)")));
      }
      const double theta = f.theta[c], beta = f.beta[c];
      if (!(std::isfinite(theta) && std::isfinite(beta) && theta > 0.0 && beta > 0.0)) {
        r.reason[c] =
            "no fragility fit: " + (f.reason[c].empty() ? "theta or beta missing" : f.reason[c]);
        flags.push_back("no rate: " + r.reason[c]);
        r.flags[c] = Join(flags);
        continue;
      }
      const RiskIntegral integral = IntegrateRisk(hazard, theta, beta, options);
      const double lambda = integral.rate_per_yr;
      r.rate_per_yr[c] = lambda;
      r.p_1yr[c] = ProbabilityInYears(lambda, 1.0);
      r.p_50yr[c] = ProbabilityInYears(lambda, 50.0);
      r.return_period_yr[c] = lambda > 0.0 ? 1.0 / lambda : kInf;
      r.p_at_first_level[c] = integral.p_at_first;
      for (std::size_t i = 0; i < n; ++i) {
        r.deaggregation[c * n + i] = lambda > 0.0 ? integral.by_interval[i] / lambda : kNaN;
      }
      const PowerLawFit fit = FitPowerLaw(hazard, theta, beta);
      if (fit.reason.empty()) {
        r.cornell_k[c] = fit.k;
        r.cornell_k0[c] = fit.k0;
        r.cornell_rate[c] = CornellRate(fit.k0, fit.k, theta, beta);
      } else {
        flags.push_back("no closed form: " + fit.reason);
      }
      const RiskSpread spread = SpreadOfRisk(hazard, theta, beta, f.se_ln_theta[c], f.se_beta[c],
                                             f.cov_ln_theta_beta[c], options);
      r.rate_p16[c] = spread.p16;
      r.rate_p84[c] = spread.p84;
      if (!spread.reason.empty()) flags.push_back("no 16-84 % of lambda: " + spread.reason);
      if (lambda > 0.0) {
        r.share_beyond_hazard[c] = integral.beyond_last / lambda;
        if (std::isfinite(f.im_hi[c])) {
          r.share_above_stripes[c] =
              RiskBetween(hazard, theta, beta, options, f.im_hi[c], kInf) / lambda;
          const double p_top = LognormalFragility(f.im_hi[c], theta, beta);
          r.share_above_stripes_movable[c] =
              (1.0 - p_top) * HazardRateAt(hazard, options.tail, f.im_hi[c]) / lambda;
        }
        if (std::isfinite(f.im_lo[c])) {
          r.share_below_stripes[c] =
              RiskBetween(hazard, theta, beta, options, 0.0, f.im_lo[c]) / lambda;
        }
      }
      if (r.share_beyond_hazard[c] > kFlagShare) {
        flags.push_back(fmt::format(
            "{:.0f} % of the rate from beyond the hazard's last point "
            "{:.4g} ({} tail)",
            100.0 * r.share_beyond_hazard[c], hazard.im.back(), UpperTailName(options.tail)));
      }
      if (r.share_above_stripes_movable[c] > kFlagShare) {
        flags.push_back(fmt::format(
            "{:.0f} % of the rate from IM above the largest stripe "
            "{:.4g}, where the lognormal is extrapolated from P(LS) = "
            "{:.2g} (up to {:.0f} % of the rate hangs on it)",
            100.0 * r.share_above_stripes[c], f.im_hi[c],
            LognormalFragility(f.im_hi[c], theta, beta), 100.0 * r.share_above_stripes_movable[c]));
      }
      if (r.share_below_stripes[c] > kFlagShare) {
        flags.push_back(
            fmt::format("{:.0f} % of the rate from IM below the smallest stripe "
                        "{:.4g}, where the lognormal is extrapolated",
                        100.0 * r.share_below_stripes[c], f.im_lo[c]));
      }
      if (integral.p_at_first > kFlagFirstLevelP) {
        flags.push_back(
            fmt::format("P(LS) = {:.2g} already at the hazard's first level {:.4g}: "
                        "the rate from lower intensities is not counted",
                        integral.p_at_first, hazard.im.front()));
      }
      r.flags[c] = Join(flags);
    }
    t.limit_states.push_back(std::move(r));
  }
  return t;
}

}  // namespace skewbridge::spectra
