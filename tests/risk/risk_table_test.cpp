// The table of rates over a sweep's combinations (spectra/risk_table.h): each rate is the risk
// integral of its own fit, the derived numbers follow from it (P in t years, return period,
// deaggregation summing to 1), a combination without a fit gets its reason and no number, and
// every flag of what a rate assumes is there when its condition holds and absent when not.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "spectra/risk_table.h"

namespace skewbridge::spectra::risk_table_test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

HazardPoints PowerLawHazard() {
  std::vector<double> im, rate;
  for (double x = 0.05; x < 3.3; x *= 1.25) {
    im.push_back(x);
    rate.push_back(1e-3 * std::pow(x, -2.5));
  }
  return UsableHazard(im, rate);
}

RiskFragility TwoCombinations() {
  RiskFragility f;
  f.name = "unseating";
  f.theta = {1.5, NAN};
  f.beta = {0.3, NAN};
  f.se_ln_theta = {0.05, NAN};
  f.se_beta = {0.04, NAN};
  f.cov_ln_theta_beta = {0.0, NAN};
  f.reason = {"", "no exceedance in 228 cells: the median lies above the largest IM, 6"};
  f.im_lo = {0.5, 0.5};
  f.im_hi = {6.0, 6.0};
  return f;
}

TEST(RiskTable, EachRateIsItsFitsIntegralWithItsDerivedNumbers) {
  const HazardPoints h = PowerLawHazard();
  RiskRecordFacts records;
  records.max_scale = 10.0;
  records.cells_beyond_max_scale = {20, 0};
  records.largest_scale = {55.0, 8.0};
  const RiskTable t = ComputeRiskTable(h, RiskOptions{}, {TwoCombinations()}, records, {});
  ASSERT_EQ(t.limit_states.size(), 1u);
  const RiskRates& r = t.limit_states[0];
  const double lambda = IntegrateRisk(h, 1.5, 0.3, RiskOptions{}).rate_per_yr;
  EXPECT_EQ(r.rate_per_yr[0], lambda);
  EXPECT_NEAR(r.p_50yr[0], 1.0 - std::exp(-50.0 * lambda), 1e-15);
  EXPECT_NEAR(r.return_period_yr[0] * lambda, 1.0, 1e-15);
  // The hazard is a power law: the local fit is exact and the closed form agrees to 1e-9.
  EXPECT_NEAR(r.cornell_k[0], 2.5, 1e-10);
  EXPECT_NEAR(r.cornell_rate[0] / lambda, 1.0, 1e-6);
  EXPECT_LT(r.rate_p16[0], lambda);
  EXPECT_GT(r.rate_p84[0], lambda);
  double sum = 0.0;
  for (std::size_t i = 0; i < h.im.size(); ++i) sum += r.deaggregation[i];
  EXPECT_NEAR(sum, 1.0, 1e-13);
  EXPECT_NEAR(r.share_below_stripes[0] + r.share_above_stripes[0] +
                  RiskBetween(h, 1.5, 0.3, RiskOptions{}, 0.5, 6.0) / lambda,
              1.0, 1e-12);
  EXPECT_THAT(r.flags[0],
              HasSubstr("20 cell(s) scaled beyond the limit of 10 (largest factor 55)"));
  // No fit: no number, the reason instead.
  EXPECT_TRUE(std::isnan(r.rate_per_yr[1]));
  EXPECT_THAT(r.reason[1], HasSubstr("no exceedance in 228 cells"));
  EXPECT_THAT(r.flags[1], HasSubstr("no rate: no fragility fit: no exceedance"));
  EXPECT_THAT(r.flags[1], HasSubstr("largest scale factor 8 (limit 10)"));
  EXPECT_THAT(t.notes[0], HasSubstr("not selected for this site's hazard"));
}

TEST(RiskTable, FlagsAppearExactlyWhenTheirConditionHolds) {
  const HazardPoints h = PowerLawHazard();  // 0.05 .. 3.05 g
  RiskRecordFacts records;
  records.selected_for_site = true;
  records.cells_beyond_max_scale = {0};
  records.largest_scale = {NAN};
  RiskFragility f;
  f.name = "ls";
  f.se_ln_theta = {0.05};
  f.se_beta = {0.04};
  f.cov_ln_theta_beta = {0.0};
  f.reason = {""};
  // A median inside the stripes and the hazard, small dispersion: no flag.
  f.theta = {0.8};
  f.beta = {0.2};
  f.im_lo = {0.3};
  f.im_hi = {2.0};
  RiskTable t = ComputeRiskTable(h, RiskOptions{}, {f}, records, {"a note of the match"});
  EXPECT_EQ(t.notes.size(), 1u);
  EXPECT_EQ(t.limit_states[0].flags[0], "");
  // Events above the largest stripe cause 9 % of this rate, but P(LS | 2 g) is 1 - 2e-6 there:
  // nothing of it hangs on the extrapolation.
  EXPECT_NEAR(t.limit_states[0].share_above_stripes[0], 0.09, 0.01);
  EXPECT_LT(t.limit_states[0].share_above_stripes_movable[0], 1e-4);
  // A median beyond the hazard's last point: most of the rate from the tail.
  f.theta = {5.0};
  f.im_hi = {6.0};
  t = ComputeRiskTable(h, RiskOptions{}, {f}, records, {});
  EXPECT_THAT(t.limit_states[0].flags[0],
              HasSubstr("of the rate from beyond the hazard's last point"));
  EXPECT_GT(t.limit_states[0].share_beyond_hazard[0], 0.5);
  // Stripes far above the median: most of the rate from below them.
  f.theta = {0.8};
  f.im_lo = {1.5};
  f.im_hi = {3.0};
  t = ComputeRiskTable(h, RiskOptions{}, {f}, records, {});
  EXPECT_THAT(t.limit_states[0].flags[0], HasSubstr("from IM below the smallest stripe 1.5"));
  EXPECT_THAT(t.limit_states[0].flags[0], Not(HasSubstr("above the largest stripe")));
  // A fragility already likely at the first hazard level.
  f.theta = {0.06};
  f.im_lo = {0.01};
  f.im_hi = {0.07};
  t = ComputeRiskTable(h, RiskOptions{}, {f}, records, {});
  EXPECT_THAT(t.limit_states[0].flags[0], HasSubstr("already at the hazard's first level 0.05"));
  EXPECT_THAT(
      t.limit_states[0].flags[0],
      HasSubstr(
          "above the largest stripe 0.07, where the lognormal is extrapolated from P(LS) = 0.78"));
  // No covariance: no interval, said so.
  f.se_ln_theta = {NAN};
  t = ComputeRiskTable(h, RiskOptions{}, {f}, records, {});
  EXPECT_THAT(t.limit_states[0].flags[0], HasSubstr("no 16-84 % of lambda"));
  EXPECT_TRUE(std::isnan(t.limit_states[0].rate_p16[0]));
}

}  // namespace
}  // namespace skewbridge::spectra::risk_table_test
