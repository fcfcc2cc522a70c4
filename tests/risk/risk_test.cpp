// The risk integral (spectra/risk.h) against independent numbers: Baker's worked example
// (Baker et al. 2021, ch. 9, script risk_metrics: lambda = 0.0114 /yr, P(1 yr) = 0.0113), the
// risk-targeted medians of his risk_target script (0.253, 0.274, 0.300 g for beta 0.6, 0.7, 0.8
// at 2e-4 /yr), Cornell's closed form on a power-law hazard, a brute-force quadrature of the
// log-log interpolated curve, the delta method for the spread, and an OpenQuake CSV written by
// hand read back to the same rates.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "spectra/hazard_curve.h"
#include "spectra/risk.h"

namespace skewbridge::spectra::risk_test {
namespace {

namespace fs = std::filesystem;

HazardPoints Points(std::vector<double> im, std::vector<double> rate) {
  return UsableHazard(im, rate);
}

double Phi(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

// Baker et al. (2021, ch. 9, "Exceedance Probability simple example" of risk_metrics.m).
TEST(Risk, BakersWorkedExampleWithTheDiscreteConvention) {
  const HazardPoints h = Points({0.1, 0.2, 0.3}, {0.06, 0.016, 0.003});
  const std::vector<double> p = {0.1, 0.4, 0.6};
  const RiskIntegral r = DiscreteRisk(h, p, UpperTail::kLumped);
  // 0.1 x 0.044 + 0.4 x 0.013 + 0.6 x 0.003, by hand.
  EXPECT_NEAR(r.rate_per_yr, 0.0114, 1e-15);
  EXPECT_NEAR(r.by_interval[0], 0.0044, 1e-15);
  EXPECT_NEAR(r.beyond_last, 0.0018, 1e-15);
  const double p1 = ProbabilityInYears(r.rate_per_yr, 1.0);
  EXPECT_NEAR(p1, 0.0113, 0.5e-4);  // the published value, 3 significant digits
  EXPECT_NEAR(p1, 1.0 - std::exp(-0.0114), 1e-16);
  // With the tail dropped (risk_target's convention) the last point contributes nothing.
  EXPECT_NEAR(DiscreteRisk(h, p, UpperTail::kNone).rate_per_yr, 0.0096, 1e-15);
}

// The same example as an OpenQuake CSV written by hand: the probabilities in 50 years of the
// three rates, read back to the rates and to the same lambda.
TEST(Risk, OpenQuakeCsvOfTheWorkedExampleReadsBackToTheSameRate) {
  const fs::path p = fs::temp_directory_path() / "sb_risk_oq_worked.csv";
  {
    std::ofstream out(p);
    out.precision(17);
    out << "#,,,,,\"generated_by='hand', kind='mean', investigation_time=50.0, imt='SA(1.0)'\"\n"
        << "lon,lat,depth,poe-0.1,poe-0.2,poe-0.3\n0.0,0.0,0.0";
    for (double rate : {0.06, 0.016, 0.003}) out << "," << -std::expm1(-rate * 50.0);
    out << "\n";
  }
  const HazardCurve c = ReadHazardCurve(p, {});
  fs::remove(p);
  ASSERT_EQ(c.rate_per_yr.size(), 3u);
  EXPECT_NEAR(c.rate_per_yr[0], 0.06, 1e-15);
  EXPECT_NEAR(c.rate_per_yr[1], 0.016, 1e-15);
  EXPECT_NEAR(c.rate_per_yr[2], 0.003, 1e-15);
  const HazardPoints h = UsableHazard(c.im, c.rate_per_yr);
  const std::vector<double> pls = {0.1, 0.4, 0.6};
  EXPECT_NEAR(DiscreteRisk(h, pls, UpperTail::kLumped).rate_per_yr, 0.0114, 1e-14);
}

// Baker's risk_target: the median theta for which lambda_LS = 2e-4 /yr, found as his script
// finds it (lambda on theta = 0.10, 0.11, ..., 0.60 g, then linear interpolation), with the
// discrete sum and the tail dropped; and the exact root, which rounds to the same.
TEST(Risk, BakersRiskTargetedMedians) {
  const HazardCurve c =
      ReadHazardCurve(fs::path(SKEWBRIDGE_TEST_DATA_DIR) / "hazard" / "baker2021-mean-sa1.txt", {});
  ASSERT_EQ(c.im.size(), 100u);
  const HazardPoints h = UsableHazard(c.im, c.rate_per_yr);
  const RiskOptions discrete{RiskRule::kDiscrete, UpperTail::kNone};
  const double published[] = {0.253, 0.274, 0.300};
  const double betas[] = {0.6, 0.7, 0.8};
  constexpr double kTarget = 2e-4;
  for (int j = 0; j < 3; ++j) {
    const double beta = betas[j];
    std::vector<double> thetas, rates;
    for (int i = 0; i <= 50; ++i) {
      thetas.push_back(0.1 + 0.01 * i);
      rates.push_back(IntegrateRisk(h, thetas.back(), beta, discrete).rate_per_yr);
    }
    // The rate falls as theta grows: interpolate theta linearly in the rate.
    double theta_interp = NAN;
    for (int i = 0; i < 50; ++i) {
      if (rates[i] >= kTarget && rates[i + 1] <= kTarget) {
        theta_interp = thetas[i] + (kTarget - rates[i]) / (rates[i + 1] - rates[i]) * 0.01;
      }
    }
    EXPECT_NEAR(theta_interp, published[j], 0.5e-3) << "beta " << beta;
    double lo = 0.1, hi = 0.6;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (IntegrateRisk(h, mid, beta, discrete).rate_per_yr > kTarget ? lo : hi) = mid;
    }
    EXPECT_NEAR(0.5 * (lo + hi), published[j], 0.5e-3) << "beta " << beta;
    // The log-log integral with the power-law tail puts each interval's rate at the fragility
    // inside it, not at its lower level: the medians move up about 5 %, to those a numpy
    // trapezoidal quadrature of the same interpolant (201 points per interval) gives,
    // 0.2651, 0.2871, 0.3142 g.
    const double loglog[] = {0.2651, 0.2871, 0.3142};
    lo = 0.1;
    hi = 0.6;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (IntegrateRisk(h, mid, beta, RiskOptions{}).rate_per_yr > kTarget ? lo : hi) = mid;
    }
    EXPECT_NEAR(0.5 * (lo + hi), loglog[j], 1e-4) << "beta " << beta;
  }
}

// The log-log integral on the same curve against a brute-force quadrature of the same
// interpolant: P(LS | x) |d lambda / d ln x| = P k_i lambda(x) by the trapezoidal rule on 4000
// points per interval in ln x, and the power-law tail out to 1000 x_n.
TEST(Risk, LogLogIntegralAgreesWithBruteForceQuadrature) {
  const HazardCurve c =
      ReadHazardCurve(fs::path(SKEWBRIDGE_TEST_DATA_DIR) / "hazard" / "baker2021-mean-sa1.txt", {});
  const HazardPoints h = UsableHazard(c.im, c.rate_per_yr);
  for (const double beta : {0.1, 0.4, 0.8}) {
    for (const double theta : {0.05, 0.3, 1.5}) {
      auto integrand_segment = [&](double a, double b, double lambda_a, double k) {
        constexpr int kN = 4000;
        double sum = 0.0;
        for (int s = 0; s <= kN; ++s) {
          const double lx = std::log(a) + (std::log(b) - std::log(a)) * s / kN;
          const double x = std::exp(lx);
          const double f = Phi(std::log(x / theta) / beta) * k * lambda_a * std::pow(x / a, -k);
          sum += (s == 0 || s == kN ? 0.5 : 1.0) * f;
        }
        return sum * (std::log(b) - std::log(a)) / kN;
      };
      double brute = 0.0;
      std::vector<double> per(h.im.size());
      for (std::size_t i = 0; i + 1 < h.im.size(); ++i) {
        const double k =
            std::log(h.rate_per_yr[i] / h.rate_per_yr[i + 1]) / std::log(h.im[i + 1] / h.im[i]);
        per[i] = integrand_segment(h.im[i], h.im[i + 1], h.rate_per_yr[i], k);
        brute += per[i];
      }
      const std::size_t n = h.im.size();
      const double k_last = std::log(h.rate_per_yr[n - 2] / h.rate_per_yr[n - 1]) /
                            std::log(h.im[n - 1] / h.im[n - 2]);
      per[n - 1] = 0.0;
      for (int d = 0; d < 30; ++d) {  // [x_n, 1000 x_n] in 30 pieces of a factor 10^0.1
        const double a = h.im[n - 1] * std::pow(10.0, 0.1 * d);
        per[n - 1] +=
            integrand_segment(a, a * std::pow(10.0, 0.1),
                              h.rate_per_yr[n - 1] * std::pow(a / h.im[n - 1], -k_last), k_last);
      }
      brute += per[n - 1];
      const RiskIntegral r = IntegrateRisk(h, theta, beta, RiskOptions{});
      EXPECT_NEAR(r.rate_per_yr / brute, 1.0, 1e-6) << "theta " << theta << " beta " << beta;
      double sum = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        sum += r.by_interval[i];
        EXPECT_NEAR(r.by_interval[i], per[i], 1e-6 * brute + 1e-20) << i;
      }
      EXPECT_NEAR(sum, r.rate_per_yr, 1e-14 * r.rate_per_yr);
      // Split anywhere, the parts add up; from x_1 on, the part is the whole.
      const double cut = 0.37 * theta;
      const RiskOptions o;
      EXPECT_NEAR(
          RiskBetween(h, theta, beta, o, 0.0, cut) + RiskBetween(h, theta, beta, o, cut, INFINITY),
          r.rate_per_yr, 1e-13 * r.rate_per_yr);
      EXPECT_NEAR(RiskBetween(h, theta, beta, o, h.im[0], INFINITY), r.rate_per_yr,
                  1e-13 * r.rate_per_yr);
      EXPECT_NEAR(RiskBetween(h, theta, beta, o, h.im[n - 1], INFINITY), r.beyond_last,
                  1e-13 * r.rate_per_yr);
    }
  }
}

// Cornell et al. (2002, eq. 8): a hazard k0 x^-k and a lognormal fragility give
// lambda_LS = k0 theta^-k exp(k^2 beta^2 / 2). The integral on points of that hazard (every
// ratio of 2 from 0.005 to 5 g, the power-law tail beyond) recovers it; the lower end, where
// P(LS | 0.005 g) is below 1e-12, is all that is missing.
TEST(Risk, CornellClosedFormRecoveredOnAPowerLawHazard) {
  const double k0 = 4e-4, k = 2.7;
  std::vector<double> im, rate;
  for (double x = 0.005; x < 5.1; x *= 2.0) {
    im.push_back(x);
    rate.push_back(k0 * std::pow(x, -k));
  }
  const HazardPoints h = UsableHazard(im, rate);
  for (const double theta : {0.4, 1.0}) {
    for (const double beta : {0.2, 0.5}) {
      const double exact = CornellRate(k0, k, theta, beta);
      const RiskIntegral r = IntegrateRisk(h, theta, beta, RiskOptions{});
      EXPECT_NEAR(r.rate_per_yr / exact, 1.0, 1e-3);
      EXPECT_NEAR(r.rate_per_yr / exact, 1.0, 1e-10) << "exact per interval";
      const PowerLawFit fit = FitPowerLaw(h, theta, beta);
      EXPECT_EQ(fit.reason, "");
      EXPECT_NEAR(fit.k, k, 1e-10);
      EXPECT_NEAR(fit.k0 / k0, 1.0, 1e-9);
      EXPECT_NEAR(CornellRate(fit.k0, fit.k, theta, beta) / exact, 1.0, 1e-9);
      // Baker's discrete sum on the same points is a left Riemann sum of an increasing P: low.
      const double discrete =
          IntegrateRisk(h, theta, beta, RiskOptions{RiskRule::kDiscrete, UpperTail::kLumped})
              .rate_per_yr;
      EXPECT_LT(discrete, exact);
    }
  }
  // A band outside the hazard's points has no fit.
  EXPECT_NE(FitPowerLaw(h, 100.0, 0.3).reason, "");
}

// Tails: lumped counts lambda_n at P(x_n) (a lower bound), none drops it, the power law extends
// it; on a power-law hazard the power-law tail is exact.
TEST(Risk, TailConventionsOrderAsTheyShould) {
  const HazardPoints h = Points({0.1, 0.2, 0.4}, {1e-2, 2e-3, 3e-4});
  const double theta = 0.5, beta = 0.4;
  const double none =
      IntegrateRisk(h, theta, beta, {RiskRule::kLogLog, UpperTail::kNone}).rate_per_yr;
  const double lumped =
      IntegrateRisk(h, theta, beta, {RiskRule::kLogLog, UpperTail::kLumped}).rate_per_yr;
  const RiskIntegral power =
      IntegrateRisk(h, theta, beta, {RiskRule::kLogLog, UpperTail::kPowerLaw});
  EXPECT_LT(none, lumped);
  EXPECT_LT(lumped, power.rate_per_yr);
  EXPECT_NEAR(lumped - none, Phi(std::log(0.4 / theta) / beta) * 3e-4, 1e-15);
  // The power-law tail alone: int_0.4^inf Phi(ln(x/theta)/beta) k lambda_n (x/x_n)^-k dx/x,
  // by the closed form per piece and by parts, equals lambda_n P(0.4) + the moment term.
  const double k = std::log(2e-3 / 3e-4) / std::log(2.0);
  const double moment = 3e-4 * std::pow(0.4 / theta, k) * std::exp(0.5 * k * k * beta * beta) *
                        (1.0 - Phi(std::log(0.4 / theta) / beta + k * beta));
  EXPECT_NEAR(power.beyond_last, 3e-4 * Phi(std::log(0.4 / theta) / beta) + moment, 1e-15);
  EXPECT_NEAR(power.p_at_first, Phi(std::log(0.1 / theta) / beta), 1e-15);
}

TEST(Risk, HazardRateAtInterpolatesLogLogAndFollowsTheTail) {
  const HazardPoints h = Points({0.1, 0.2, 0.4}, {1e-2, 2e-3, 3e-4});
  // Between 0.1 and 0.2 the slope is ln 5 / ln 2: at the geometric middle, the geometric mean.
  EXPECT_NEAR(HazardRateAt(h, UpperTail::kPowerLaw, std::sqrt(0.02)), std::sqrt(2e-5), 1e-15);
  EXPECT_DOUBLE_EQ(HazardRateAt(h, UpperTail::kPowerLaw, 0.2), 2e-3);
  EXPECT_DOUBLE_EQ(HazardRateAt(h, UpperTail::kPowerLaw, 0.05), 1e-2);
  const double k = std::log(2e-3 / 3e-4) / std::log(2.0);
  EXPECT_NEAR(HazardRateAt(h, UpperTail::kPowerLaw, 0.8), 3e-4 * std::pow(2.0, -k), 1e-18);
  EXPECT_EQ(HazardRateAt(h, UpperTail::kLumped, 0.8), 0.0);
  EXPECT_EQ(HazardRateAt(h, UpperTail::kNone, 0.8), 0.0);
}

TEST(Risk, UsableHazardDropsInfiniteAndZeroRates) {
  const std::vector<double> im = {0.01, 0.1, 0.2, 0.5, 1.0};
  const std::vector<double> rate = {INFINITY, 0.1, 0.01, 0.001, 0.0};
  const HazardPoints h = UsableHazard(im, rate, 1.5);
  EXPECT_EQ(h.dropped_infinite, 1);
  EXPECT_EQ(h.dropped_zero, 1);
  ASSERT_EQ(h.im.size(), 3u);
  EXPECT_DOUBLE_EQ(h.im[0], 0.15);
  const std::vector<double> one = {0.1, 0.0};
  EXPECT_TRUE(UsableHazard(std::vector<double>{0.1, 0.2}, one).im.empty());
}

// The spread of lambda from (ln theta, beta) against the delta method on Cornell's form:
// ln lambda = ln k0 - k ln theta + k^2 beta^2 / 2 has gradient (-k, k^2 beta), so
// sd(ln lambda)^2 = k^2 var(ln theta) - 2 k^3 beta cov + k^4 beta^2 var(beta), and the 16 and
// 84 % of lambda are exp(-/+ 0.9945 sd) about the median.
TEST(Risk, SpreadMatchesTheDeltaMethodForSmallUncertainty) {
  const double k0 = 4e-4, k = 2.7, theta = 1.0, beta = 0.3;
  std::vector<double> im, rate;
  for (double x = 0.005; x < 5.1; x *= 1.5) {
    im.push_back(x);
    rate.push_back(k0 * std::pow(x, -k));
  }
  const HazardPoints h = UsableHazard(im, rate);
  const double s1 = 0.04, s2 = 0.02, cov = 0.3 * s1 * s2;
  const RiskSpread s = SpreadOfRisk(h, theta, beta, s1, s2, cov, RiskOptions{});
  EXPECT_EQ(s.reason, "");
  EXPECT_EQ(s.used, s.draws);
  const double sd = std::sqrt(k * k * s1 * s1 - 2.0 * k * k * k * beta * cov +
                              k * k * k * k * beta * beta * s2 * s2);
  const double exact = CornellRate(k0, k, theta, beta);
  constexpr double kZ84 = 0.994457883209753;
  EXPECT_NEAR(std::log(s.p50 / exact), 0.0, 0.05 * sd);
  EXPECT_NEAR(std::log(s.p84 / s.p50), kZ84 * sd, 0.06 * sd);
  EXPECT_NEAR(std::log(s.p50 / s.p16), kZ84 * sd, 0.06 * sd);
  // Deterministic: the same seed, the same numbers.
  const RiskSpread again = SpreadOfRisk(h, theta, beta, s1, s2, cov, RiskOptions{});
  EXPECT_EQ(again.p16, s.p16);
  EXPECT_EQ(again.p84, s.p84);
  EXPECT_NE(SpreadOfRisk(h, theta, beta, NAN, s2, cov, RiskOptions{}).reason, "");
}

TEST(Risk, ProbabilityInYearsIsPoisson) {
  EXPECT_NEAR(ProbabilityInYears(1e-3, 50.0), 1.0 - std::exp(-0.05), 1e-16);
  EXPECT_NEAR(ProbabilityInYears(1e-12, 1.0), 1e-12, 1e-24);
}

}  // namespace
}  // namespace skewbridge::spectra::risk_test
