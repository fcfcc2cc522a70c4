// The correlation statistics of spectra/correlation.h against hand-computed closed forms.

#include "spectra/correlation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace skewbridge::spectra::correlation_test {
namespace {

TEST(Pearson, IsOneForAnIncreasingLineAndMinusOneForADecreasingOne) {
  const std::vector<double> x{0.1, 0.4, 0.5, 2.0, 3.5};
  std::vector<double> up;
  std::vector<double> down;
  for (double v : x) {
    up.push_back(3.0 * v + 2.0);
    down.push_back(-0.5 * v + 7.0);
  }
  EXPECT_NEAR(Pearson(x, up).value, 1.0, 1e-15);
  EXPECT_NEAR(Pearson(x, down).value, -1.0, 1e-15);
  EXPECT_EQ(Pearson(x, up).reason, "");
}

// x = 1, 2, 3, 4 and y = 1, 3, 2, 4: deviations (-1.5, -0.5, 0.5, 1.5) and
// (-1.5, 0.5, -0.5, 1.5), so sxy = 4, sxx = syy = 5 and r = 0.8.
TEST(Pearson, MatchesTheHandComputedValueOfFourPoints) {
  EXPECT_NEAR(Pearson(std::vector<double>{1, 2, 3, 4}, std::vector<double>{1, 3, 2, 4}).value, 0.8,
              1e-15);
}

TEST(Spearman, IsOneForAMonotoneCurveWherePearsonIsBelowOne) {
  std::vector<double> x;
  std::vector<double> y;
  for (int i = 1; i <= 6; ++i) {
    x.push_back(i);
    y.push_back(std::exp(static_cast<double>(i)));
  }
  EXPECT_DOUBLE_EQ(Spearman(x, y).value, 1.0);
  const double r = Pearson(x, y).value;
  EXPECT_LT(r, 0.95);
  EXPECT_GT(r, 0.8);
}

// Without ties rho = 1 - 6 sum d^2 / (n (n^2 - 1)): ranks of y are 2, 1, 4, 3, 5 against
// 1..5, sum d^2 = 4, so rho = 1 - 24 / 120 = 0.8.
TEST(Spearman, EqualsTheRankDifferenceFormulaWithoutTies) {
  const std::vector<double> x{0.3, 1.1, 2.0, 5.0, 9.0};
  const std::vector<double> y{20.0, 10.0, 400.0, 300.0, 1000.0};
  EXPECT_NEAR(Spearman(x, y).value, 0.8, 1e-15);
}

TEST(AverageRanks, GivesTiedValuesTheMeanOfTheRanksTheySpan) {
  EXPECT_EQ(AverageRanks(std::vector<double>{10, 20, 20, 30}),
            (std::vector<double>{1, 2.5, 2.5, 4}));
  EXPECT_EQ(AverageRanks(std::vector<double>{5, 5, 5}), (std::vector<double>{2, 2, 2}));
  EXPECT_EQ(AverageRanks(std::vector<double>{3, 1, 2, 1}), (std::vector<double>{4, 1.5, 3, 1.5}));
}

// x = 1, 2, 2, 3 ranks as 1, 2.5, 2.5, 4; against y ranks 1..4: sxy = 4.5, sxx = 4.5, syy = 5,
// rho = 4.5 / sqrt(22.5) = sqrt(0.9).
TEST(Spearman, UsesAverageRanksForTies) {
  EXPECT_NEAR(Spearman(std::vector<double>{1, 2, 2, 3}, std::vector<double>{1, 2, 3, 4}).value,
              std::sqrt(0.9), 1e-15);
}

TEST(FitLogLog, RecoversTheExponentAndFactorOfAPowerLaw) {
  const double c = 2.5e-3;
  const double p = 1.7;
  std::vector<double> x{0.01, 0.1, 0.3, 2.0, 7.0};
  std::vector<double> y;
  for (double v : x) y.push_back(c * std::pow(v, p));
  const LogLogFit fit = FitLogLog(x, y);
  EXPECT_EQ(fit.n, 5U);
  EXPECT_NEAR(fit.slope.value, p, 1e-13);
  EXPECT_NEAR(fit.intercept.value, std::log10(c), 1e-13);
  EXPECT_NEAR(fit.r2.value, 1.0, 1e-14);
}

// log10 points (0, 0), (1, 2), (2, 3): slope 3 / 2, intercept 5/3 - 3/2 = 1/6, residuals
// -1/6, 1/3, -1/6 so SS_res = 1/6, SS_tot = 14/3 and R^2 = 1 - 1/28 = 27/28. The points with
// x <= 0 or y <= 0 have no logarithm and are skipped.
TEST(FitLogLog, MatchesTheHandComputedFitAndSkipsNonPositivePoints) {
  const LogLogFit fit = FitLogLog(std::vector<double>{1, 0, 10, -1, 100, 3},
                                  std::vector<double>{1, 5, 100, 2, 1000, 0});
  EXPECT_EQ(fit.n, 3U);
  EXPECT_NEAR(fit.slope.value, 1.5, 1e-15);
  EXPECT_NEAR(fit.intercept.value, 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(fit.r2.value, 27.0 / 28.0, 1e-15);
}

TEST(Correlation, DegenerateInputsGiveNaNWithAReason) {
  const std::vector<double> one{1.0};
  const Statistic few = Pearson(one, one);
  EXPECT_TRUE(std::isnan(few.value));
  EXPECT_EQ(few.reason, "fewer than 2 points");
  const std::vector<double> flat{2.0, 2.0, 2.0};
  const std::vector<double> rising{1.0, 2.0, 3.0};
  EXPECT_EQ(Pearson(flat, rising).reason, "x is constant");
  EXPECT_EQ(Pearson(rising, flat).reason, "y is constant");
  EXPECT_TRUE(std::isnan(Spearman(rising, flat).value));
  EXPECT_EQ(Spearman(rising, flat).reason, "y is constant");
  EXPECT_EQ(Pearson(rising, std::vector<double>{1.0, 2.0}).reason, "x and y differ in length");
  EXPECT_EQ(Pearson(rising, std::vector<double>{1.0, NAN, 2.0}).reason, "a value is not finite");

  const LogLogFit none = FitLogLog(std::vector<double>{0.0, 1.0}, std::vector<double>{1.0, 0.0});
  EXPECT_EQ(none.n, 0U);
  EXPECT_TRUE(std::isnan(none.slope.value));
  EXPECT_EQ(none.slope.reason, "fewer than 2 positive points");
  const LogLogFit vertical = FitLogLog(flat, rising);
  EXPECT_TRUE(std::isnan(vertical.slope.value));
  EXPECT_EQ(vertical.slope.reason, "log10 x is constant");
  // A horizontal line has slope 0 and no R^2 (SS_tot = 0).
  const LogLogFit horizontal = FitLogLog(rising, flat);
  EXPECT_EQ(horizontal.slope.value, 0.0);
  EXPECT_NEAR(horizontal.intercept.value, std::log10(2.0), 1e-15);
  EXPECT_TRUE(std::isnan(horizontal.r2.value));
  EXPECT_EQ(horizontal.r2.reason, "log10 y is constant");
}

}  // namespace
}  // namespace skewbridge::spectra::correlation_test
