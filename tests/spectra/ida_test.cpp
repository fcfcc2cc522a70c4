#include "spectra/ida.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace skewbridge::spectra {
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
  // A record beyond the search: no number, the reason instead.
  const CapacityFit censored = FitCapacities(std::vector<double>{1.0, e, e * e, inf});
  EXPECT_TRUE(std::isnan(censored.theta) && std::isnan(censored.beta));
  EXPECT_EQ(censored.censored, 1);
  EXPECT_NE(censored.reason.find("1 of 4 records never reach the limit state"), std::string::npos)
      << censored.reason;
  const CapacityFit one = FitCapacities(std::vector<double>{2.0, nan});
  EXPECT_TRUE(std::isnan(one.theta));
  EXPECT_NE(one.reason.find("1 finite capacities"), std::string::npos) << one.reason;
}

}  // namespace
}  // namespace skewbridge::spectra
