#include "spectra/ida.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace skewbridge::spectra::ida_test {
namespace {

// A search over a demand D(IM) = IM^1.5 with the limit state D > d_c: the capacity is exactly
// d_c^(1 / 1.5), monotone, so every bracket (below, im] must contain it.
IdaPoint PowerLaw(double im, double threshold) {
  IdaPoint p;
  const double d = std::pow(im, 1.5);
  p.demand = {d};
  p.exceeded = {d > threshold ? 1.0 : 0.0};
  return p;
}

IdaSpec Spec() {
  IdaSpec s;
  s.enabled = true;
  s.start = 0.1;
  s.step = 0.2;
  s.step_increase = 0.1;
  s.tolerance = 0.01;
  s.max_im = 5.0;
  s.max_runs = 14;
  return s;
}

TEST(Ida, HuntStepsGrowBySteppedIncrementsUntilTheFirstExceedance) {
  // Capacity 1.3: the hunt runs 0.1, 0.3 (+0.2), 0.6 (+0.3), 1.0 (+0.4), 1.5 (+0.5), stop.
  const double capacity = 1.3, threshold = std::pow(capacity, 1.5);
  const IdaTrace t = HuntAndFill(Spec(), 1, [&](double im) { return PowerLaw(im, threshold); });
  ASSERT_GE(t.im.size(), 5u);
  const std::vector<double> hunt{0.1, 0.3, 0.6, 1.0, 1.5};
  for (std::size_t k = 0; k < hunt.size(); ++k) EXPECT_NEAR(t.im[k], hunt[k], 1e-12) << k;
  // Bisection of (1.0, 1.5]: 1.25, 1.375, 1.3125, 1.28125, 1.296875, 1.3046875 (width < 0.01).
  const std::vector<double> bisect{1.25, 1.375, 1.3125, 1.28125, 1.296875, 1.3046875};
  for (std::size_t k = 0; k < bisect.size(); ++k) {
    EXPECT_NEAR(t.im[hunt.size() + k], bisect[k], 1e-12) << k;
  }
  ASSERT_EQ(t.capacity.size(), 1u);
  EXPECT_DOUBLE_EQ(t.capacity[0].im, 1.3046875);
  EXPECT_DOUBLE_EQ(t.capacity[0].below, 1.296875);
  EXPECT_LE(t.capacity[0].below, capacity);
  EXPECT_GE(t.capacity[0].im, capacity);
  // The three runs left fill the widest gaps below 1.3046875: (0.6, 1.0) of 0.4, then
  // (0.3, 0.6) of 0.3, then (1.0, 1.25) of 0.25 (ahead of (0.1, 0.3) and (0.8, 1.0) of 0.2).
  ASSERT_EQ(t.im.size(), 14u);
  EXPECT_NEAR(t.im[11], 0.8, 1e-12);
  EXPECT_NEAR(t.im[12], 0.45, 1e-12);
  EXPECT_NEAR(t.im[13], 1.125, 1e-12);
  EXPECT_EQ(t.status, kStatusOk);
}

TEST(Ida, CapacityOfAMonotoneDemandIsWithinTheToleranceForManyThresholds) {
  IdaSpec spec = Spec();
  spec.max_runs = 40;
  for (double capacity = 0.05; capacity < 4.9; capacity *= 1.37) {
    const double threshold = std::pow(capacity, 1.5);
    const IdaTrace t = HuntAndFill(spec, 1, [&](double im) { return PowerLaw(im, threshold); });
    const IdaCapacity& c = t.capacity[0];
    EXPECT_LE(c.below, capacity) << capacity;  // exceeded above d_c: a run at it is not
    EXPECT_GE(c.im, capacity) << capacity;
    EXPECT_LE(c.im - c.below, spec.tolerance) << capacity;
    EXPECT_LE(t.im.size(), 40u);
  }
}

TEST(Ida, AFillingRunThatExceedsBelowTheCapacityOpensABracketThatIsBisectedAgain) {
  // Exceeded from 2 on, and also in the window |IM - 0.8| < 0.01 that only the filling run at
  // 0.8 (the middle of the hunt's gap 0.6-1.0) finds: the capacity drops to the window's lower
  // edge 0.79, bracketed again within the tolerance.
  IdaSpec spec = Spec();
  spec.max_runs = 30;
  const IdaTrace t = HuntAndFill(spec, 1, [](double im) {
    IdaPoint p;
    p.demand = {im};
    p.exceeded = {im >= 2.0 || std::abs(im - 0.8) < 0.01 ? 1.0 : 0.0};
    return p;
  });
  EXPECT_GE(t.capacity[0].im, 0.79);
  EXPECT_LE(t.capacity[0].im, 0.8);
  EXPECT_LE(t.capacity[0].below, 0.79);
  EXPECT_LE(t.capacity[0].im - t.capacity[0].below, spec.tolerance);
}

TEST(Ida, TwoLimitStatesEachGetTheirBracketAndTheHuntGoesOnToTheLast) {
  IdaSpec spec = Spec();
  spec.max_runs = 30;
  const double c1 = 0.42, c2 = 2.2;
  auto run = [&](double im) {
    IdaPoint p;
    p.demand = {im, im};
    p.exceeded = {im >= c1 ? 1.0 : 0.0, im >= c2 ? 1.0 : 0.0};
    return p;
  };
  const IdaTrace t = HuntAndFill(spec, 2, run);
  EXPECT_GE(t.capacity[0].im, c1);
  EXPECT_LT(t.capacity[0].below, c1);
  EXPECT_LE(t.capacity[0].im - t.capacity[0].below, spec.tolerance);
  EXPECT_GE(t.capacity[1].im, c2);
  EXPECT_LT(t.capacity[1].below, c2);
  EXPECT_LE(t.capacity[1].im - t.capacity[1].below, spec.tolerance);
}

TEST(Ida, CapacityBeyondMaxImIsInfiniteAndAFirstRunExceedingBracketsFromZero) {
  IdaSpec spec = Spec();
  const IdaTrace never = HuntAndFill(spec, 1, [](double im) { return PowerLaw(im, 1e9); });
  EXPECT_TRUE(std::isinf(never.capacity[0].im));
  double top = 0.0;
  for (double im : never.im) top = std::max(top, im);
  EXPECT_DOUBLE_EQ(top, spec.max_im);  // the hunt reaches max_im exactly, never beyond
  const IdaTrace always = HuntAndFill(spec, 1, [](double im) { return PowerLaw(im, 1e-6); });
  EXPECT_DOUBLE_EQ(always.im.front(), spec.start);
  EXPECT_LT(always.capacity[0].im, spec.tolerance + 1e-12);  // bisected down towards 0
  EXPECT_EQ(always.capacity[0].below, 0.0);
}

TEST(Ida, AFailedRunEndsTheSearchWithItsStatus) {
  int runs = 0;
  const IdaTrace t = HuntAndFill(Spec(), 1, [&](double im) {
    if (++runs == 3) {
      IdaPoint p;
      p.ok = false;
      p.status = 4;
      p.status_text = "ray";
      return p;
    }
    return PowerLaw(im, 8.0);
  });
  EXPECT_EQ(t.status, 4);
  EXPECT_EQ(t.status_text, "ray");
  EXPECT_EQ(t.im.size(), 2u);
  EXPECT_EQ(runs, 3);
}

TEST(Ida, CapacityFitIsTheGeometricMeanAndTheSampleLogDeviation) {
  // ln of 1, e, e^2: mean 1, sample variance ((1)^2 + 0 + 1^2) / 2 = 1.
  const double e = std::exp(1.0), inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> caps{1.0, e, e * e, nan};
  const CapacityFit f = FitCapacities(caps);
  EXPECT_NEAR(f.theta, e, 1e-14);
  EXPECT_NEAR(f.beta, 1.0, 1e-14);
  EXPECT_EQ(f.n, 3);
  EXPECT_EQ(f.censored, 0);
  EXPECT_TRUE(f.reason.empty());
  // A record beyond the search without the intensity it was censored at: no number.
  const CapacityFit unknown = FitCapacities(std::vector<double>{1.0, e, e * e, inf});
  EXPECT_TRUE(std::isnan(unknown.theta) && std::isnan(unknown.beta));
  EXPECT_EQ(unknown.censored, 1);
  EXPECT_NE(unknown.reason.find("1 of 4 records never reach the limit state"), std::string::npos)
      << unknown.reason;
  const CapacityFit one = FitCapacities(std::vector<double>{2.0, nan});
  EXPECT_TRUE(std::isnan(one.theta));
  EXPECT_NE(one.reason.find("1 finite capacities"), std::string::npos) << one.reason;
}

TEST(Ida, CensoredCapacityFitMatchesAnIndependentMaximumLikelihood) {
  // Six capacities and three records censored at 2.0, 2.0, 1.8 g. Reference: scipy 1.10,
  // optimize.minimize (Nelder-Mead, xatol 1e-12) of -(norm.logpdf(ln c) + norm.logsf(ln u))
  // over (mu, ln sigma): theta = 1.1785385082160147, beta = 0.9186771870401322.
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> caps{0.3, 0.45, 0.6, 0.8, 1.1, 1.5, inf, inf, inf, nan};
  const std::vector<double> below{0.2, 0.4, 0.5, 0.7, 1.0, 1.4, 2.0, 2.0, 1.8, nan};
  const CapacityFit f = FitCapacities(caps, below);
  EXPECT_NEAR(f.theta, 1.1785385082160147, 1e-8);
  EXPECT_NEAR(f.beta, 0.9186771870401322, 1e-8);
  EXPECT_EQ(f.n, 6);
  EXPECT_EQ(f.censored, 3);
  EXPECT_TRUE(f.reason.empty()) << f.reason;
  EXPECT_NE(f.note.find("3 of 9 records never reach"), std::string::npos) << f.note;
  // Undefined fits: one finite capacity, all censored, equal finite capacities with censoring.
  const CapacityFit one = FitCapacities(std::vector<double>{1.0, inf}, std::vector<double>{0.5, 2});
  EXPECT_TRUE(std::isnan(one.theta));
  EXPECT_NE(one.reason.find("a fit needs 2"), std::string::npos) << one.reason;
  const CapacityFit all = FitCapacities(std::vector<double>{inf, inf}, std::vector<double>{2, 2});
  EXPECT_TRUE(std::isnan(all.theta));
  const CapacityFit flat =
      FitCapacities(std::vector<double>{1.0, 1.0, inf}, std::vector<double>{0.5, 0.5, 2});
  EXPECT_TRUE(std::isnan(flat.beta));
  EXPECT_NE(flat.reason.find("no maximum"), std::string::npos) << flat.reason;
}

TEST(Ida, CensoredCapacityFitRecoversAKnownLognormal) {
  // Capacities drawn from theta = 0.8 g, beta = 0.5, the search ending at 1.2 g (about 21 %
  // censored): the fit is within 4 standard errors (beta / sqrt(n), inflated 1.5 for the
  // censoring) over 20 seeds, while the finite capacities alone put the median low.
  constexpr int kRecords = 400;
  const double theta = 0.8, beta = 0.5, max_im = 1.2;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::mt19937_64 rng(seed);
    std::lognormal_distribution<double> draw(std::log(theta), beta);
    std::vector<double> caps, below;
    double finite_log_sum = 0.0;
    int finite = 0;
    for (int i = 0; i < kRecords; ++i) {
      const double c = draw(rng);
      caps.push_back(c > max_im ? std::numeric_limits<double>::infinity() : c);
      below.push_back(c > max_im ? max_im : 0.9 * c);
      if (c <= max_im) {
        finite_log_sum += std::log(c);
        ++finite;
      }
    }
    const CapacityFit f = FitCapacities(caps, below);
    const double se = 1.5 * beta / std::sqrt(static_cast<double>(kRecords));
    EXPECT_NEAR(std::log(f.theta), std::log(theta), 4.0 * se) << "seed " << seed;
    EXPECT_NEAR(f.beta, beta, 4.0 * se) << "seed " << seed;
    EXPECT_LT(finite_log_sum / finite, std::log(theta) - 2.0 * se) << "seed " << seed;
  }
}

}  // namespace
}  // namespace skewbridge::spectra::ida_test
