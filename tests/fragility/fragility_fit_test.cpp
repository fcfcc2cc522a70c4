// The lognormal fragility fits of spectra/fragility.h against what they must recover: known
// (theta, beta) from synthetic binomial stripes within the standard errors the fit reports,
// over many seeds; a closed form for two stripes; the degenerate stripes refused with a reason.
#include "spectra/fragility.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace skewbridge::spectra {
namespace {

double Phi(double u) { return 0.5 * std::erfc(-u / std::numbers::sqrt2); }

struct Stripes {
  std::vector<double> im, n, z;
};

// Ten stripes 0.1..1.5 g, `per` records each, exceedances drawn from the lognormal fragility.
Stripes Draw(double theta, double beta, int per, std::mt19937_64& gen) {
  Stripes s;
  for (int j = 0; j < 10; ++j) {
    const double x = 0.1 + 0.15 * j;
    std::binomial_distribution<int> draw(per, Phi(std::log(x / theta) / beta));
    s.im.push_back(x);
    s.n.push_back(per);
    s.z.push_back(draw(gen));
  }
  return s;
}

TEST(FragilityMle, RecoversMedianAndDispersionWithinTheirStandardErrors) {
  const double theta = 0.55, beta = 0.45;
  int inside_theta = 0, inside_beta = 0, fitted = 0;
  double mean_z = 0.0;
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    std::mt19937_64 gen(seed);
    const Stripes s = Draw(theta, beta, 40, gen);
    const LognormalFit f = FitLognormalMle(s.im, s.n, s.z);
    ASSERT_TRUE(f.reason.empty()) << "seed " << seed << ": " << f.reason;
    ++fitted;
    const double z = (std::log(f.theta) - std::log(theta)) / f.se_ln_theta;
    mean_z += z;
    inside_theta += std::abs(z) < 1.959964 ? 1 : 0;
    inside_beta += std::abs(f.beta - beta) < 1.959964 * f.se_beta ? 1 : 0;
  }
  // The Wald intervals cover the truth about 95 % of the time (binomial sd of 400 draws: 1.1 %).
  EXPECT_GT(inside_theta, 0.91 * fitted);
  EXPECT_LT(inside_theta, 0.99 * fitted);
  EXPECT_GT(inside_beta, 0.90 * fitted);
  EXPECT_LT(inside_beta, 0.99 * fitted);
  EXPECT_LT(std::abs(mean_z / fitted), 0.15);  // unbiased to a fraction of its standard error
}

TEST(FragilityMle, TwoStripesMatchTheProbitOfTheirFractions) {
  // With two stripes the maximum reproduces both fractions exactly:
  // ln x_j = ln theta + beta Phi^-1(p_j), two equations in (ln theta, beta).
  const std::vector<double> im{0.2, 0.8}, n{10, 10}, z{2, 7};
  const LognormalFit f = FitLognormalMle(im, n, z);
  ASSERT_TRUE(f.reason.empty()) << f.reason;
  EXPECT_NEAR(Phi(std::log(0.2 / f.theta) / f.beta), 0.2, 1e-10);
  EXPECT_NEAR(Phi(std::log(0.8 / f.theta) / f.beta), 0.7, 1e-10);
}

TEST(FragilityMle, PerCellTrialsGiveTheSameFitAsTheirStripes) {
  std::mt19937_64 gen(7);
  const Stripes s = Draw(0.6, 0.4, 12, gen);
  std::vector<double> im, n, z;
  for (std::size_t j = 0; j < s.im.size(); ++j) {
    for (int k = 0; k < s.n[j]; ++k) {
      im.push_back(s.im[j]);
      n.push_back(1);
      z.push_back(k < s.z[j] ? 1 : 0);
    }
  }
  const LognormalFit a = FitLognormalMle(s.im, s.n, s.z), b = FitLognormalMle(im, n, z);
  ASSERT_TRUE(a.reason.empty() && b.reason.empty());
  EXPECT_NEAR(a.theta, b.theta, 1e-9 * a.theta);
  EXPECT_NEAR(a.beta, b.beta, 1e-9 * a.beta);
  EXPECT_NEAR(a.se_ln_theta, b.se_ln_theta, 1e-8 * a.se_ln_theta);
}

TEST(FragilityMle, DegenerateStripesGiveAReasonNotANumber) {
  const std::vector<double> im{0.1, 0.2, 0.4}, n{5, 5, 5};
  struct Case {
    std::vector<double> im, n, z;
    const char* words;
  };
  const std::vector<Case> cases{
      {im, n, {0, 0, 0}, "no exceedance in 15 cells"},
      {im, n, {5, 5, 5}, "exceeded in all 15 cells"},
      {{0.3}, {10}, {4}, "one stripe"},
      {{0.3, 0.3}, {10, 10}, {4, 6}, "one stripe"},
      {im, n, {0, 0, 5}, "the stripes separate"},
      {im, n, {0, 2, 5}, "the stripes separate"},  // quasi-separation: beta still tends to 0
      {im, n, {5, 2, 0}, "does not grow"},
      {{}, {}, {}, "no cell"},
  };
  for (const Case& c : cases) {
    const LognormalFit f = FitLognormalMle(c.im, c.n, c.z);
    EXPECT_NE(f.reason.find(c.words), std::string::npos) << f.reason;
    EXPECT_TRUE(std::isnan(f.theta) && std::isnan(f.beta)) << c.words;
  }
}

TEST(FragilityMle, ASeparationSaysOnlyWhatLiesOnEachSide) {
  const std::vector<double> im{0.1, 0.2, 0.4}, n{5, 5, 5};
  EXPECT_EQ(FitLognormalMle(im, n, std::vector<double>{0, 0, 5}).reason,
            "the stripes separate (no exceedance up to IM = 0.2, every cell exceeded from IM = "
            "0.4 on): beta tends to 0 and the median is anywhere between them");
  // Exceedances only at the largest IM: nothing lies above it, so nothing is said of above.
  EXPECT_EQ(FitLognormalMle(im, n, std::vector<double>{0, 0, 2}).reason,
            "the stripes separate at IM = 0.4 (2 of 5 exceeded there, none below it): beta "
            "tends to 0 and the median is at that level");
  EXPECT_EQ(FitLognormalMle(im, n, std::vector<double>{0, 2, 5}).reason,
            "the stripes separate at IM = 0.2 (2 of 5 exceeded there, none below it, every cell "
            "above it): beta tends to 0 and the median is at that level");
  EXPECT_EQ(FitLognormalMle(im, n, std::vector<double>{3, 5, 5}).reason,
            "the stripes separate at IM = 0.1 (3 of 5 exceeded there, every cell above it): beta "
            "tends to 0 and the median is at that level");
}

TEST(FragilityCloud, RecoversAKnownLineAndItsFragility) {
  // ln(D / C) = a + b ln x + e, e ~ N(0, s): theta = exp(-a / b), beta = s / b.
  const double a = 0.3, b = 1.2, s = 0.35;
  std::mt19937_64 gen(11);
  std::normal_distribution<double> e(0.0, s);
  std::uniform_real_distribution<double> lx(std::log(0.05), std::log(2.0));
  std::vector<double> im, dc;
  for (int i = 0; i < 20000; ++i) {
    const double x = lx(gen);
    im.push_back(std::exp(x));
    dc.push_back(std::exp(a + b * x + e(gen)));
  }
  im.push_back(0.4);
  dc.push_back(0.0);  // a zero demand has no logarithm: left out and counted
  const CloudFit f = FitCloud(im, dc);
  ASSERT_TRUE(f.reason.empty()) << f.reason;
  EXPECT_EQ(f.excluded, 1);
  EXPECT_NEAR(f.slope, b, 0.02);
  EXPECT_NEAR(f.intercept, a, 0.02);
  EXPECT_NEAR(f.sigma, s, 0.01);
  EXPECT_NEAR(f.theta, std::exp(-a / b), 0.02);
  EXPECT_NEAR(f.beta, s / b, 0.01);
}

TEST(FragilityCloud, RefusesTooFewCellsAndAFallingDemand) {
  EXPECT_NE(
      FitCloud(std::vector<double>{0.1, 0.2}, std::vector<double>{1, 2}).reason.find("at least 3"),
      std::string::npos);
  const CloudFit falling =
      FitCloud(std::vector<double>{0.1, 0.2, 0.4}, std::vector<double>{3, 2, 1});
  EXPECT_NE(falling.reason.find("does not grow"), std::string::npos);
  EXPECT_TRUE(std::isnan(falling.theta));
}

// Every field of two fits, doubles bit for bit.
void ExpectSameFit(const LognormalFit& a, const LognormalFit& b, const std::string& where) {
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  EXPECT_EQ(a.reason, b.reason) << where;
  EXPECT_EQ(bits(a.theta), bits(b.theta)) << where;
  EXPECT_EQ(bits(a.beta), bits(b.beta)) << where;
  EXPECT_EQ(bits(a.se_ln_theta), bits(b.se_ln_theta)) << where;
  EXPECT_EQ(bits(a.se_beta), bits(b.se_beta)) << where;
  EXPECT_EQ(bits(a.cov_ln_theta_beta), bits(b.cov_ln_theta_beta)) << where;
  EXPECT_EQ(bits(a.log_likelihood), bits(b.log_likelihood)) << where;
  EXPECT_EQ(a.iterations, b.iterations) << where;
  EXPECT_EQ(a.trials, b.trials) << where;
  EXPECT_EQ(a.exceeded, b.exceeded) << where;
}

// A resample's fit from ResampledLognormalFits is FitLognormalMle of the cells it draws, each
// repeated: cells of 40 records at 12 stripes (a tenth of them an ulp off their stripe's IM, as
// scaled records land; some with no usable IM), drawn as a bootstrap over records and as random
// counts, fitted and refused alike (every cell exceeded, none, and separated stripes); and with
// an exceedance other than 0 or 1 it runs FitLognormalMle itself.
TEST(ResampledLognormalFits, AResampleIsTheBitsOfFitLognormalMleOfItsCells) {
  std::mt19937_64 gen(2033);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const int data : {0, 1, 2, 3, 4, 5}) {
    const int records = 40, stripes = 12;
    std::vector<double> im, z;
    for (int r = 0; r < records; ++r) {
      for (int j = 0; j < stripes; ++j) {
        double x = 0.1 * std::pow(1.35, j);
        if (unit(gen) < 0.1) x = std::nextafter(x, unit(gen) < 0.5 ? 0.0 : 10.0);
        if (data == 0 && unit(gen) < 0.02) x = unit(gen) < 0.5 ? -1.0 : std::nan("");
        double e = unit(gen) < Phi(std::log(x / 0.8) / 0.45) ? 1.0 : 0.0;
        if (data == 1) e = 1.0;                 // every cell exceeded
        if (data == 2) e = 0.0;                 // none
        if (data == 3) e = j >= 6 ? 1.0 : 0.0;  // the stripes separate
        if (data == 4 && j == 5) e = 0.5;       // not one trial's outcome
        im.push_back(x);
        z.push_back(e);
      }
    }
    const ResampledLognormalFits resampled(im, z);
    std::uniform_int_distribution<int> pick(0, records - 1);
    std::uniform_int_distribution<std::uint32_t> count(0, 3);
    for (int b = 0; b < 40; ++b) {
      std::vector<std::uint32_t> draws(im.size(), 0);
      if (b % 2 == 0) {
        for (int r = 0; r < records; ++r) {
          const int drawn = pick(gen);
          for (int j = 0; j < stripes; ++j) ++draws[static_cast<std::size_t>(drawn * stripes + j)];
        }
      } else {
        for (std::uint32_t& d : draws) d = count(gen);
      }
      std::vector<double> x, ones, e;
      for (std::size_t i = 0; i < im.size(); ++i) {
        for (std::uint32_t k = 0; k < draws[i]; ++k) {
          x.push_back(im[i]);
          e.push_back(z[i]);
        }
      }
      ones.assign(x.size(), 1.0);
      const LognormalFit expected = FitLognormalMle(x, ones, e);
      if (data == 0) {
        EXPECT_TRUE(expected.reason.empty()) << expected.reason;
      }
      if (data >= 1 && data <= 3) {
        EXPECT_FALSE(expected.reason.empty());
      }
      ExpectSameFit(resampled.Fit(draws), expected,
                    "data " + std::to_string(data) + ", resample " + std::to_string(b));
    }
  }
}

}  // namespace
}  // namespace skewbridge::spectra
