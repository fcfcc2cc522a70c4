#include "solver/dynamics/root_finding.h"

#include <gtest/gtest.h>

#include <cmath>

namespace skewbridge::dynamics::root_finding_test {
namespace {

TEST(FindRootBrent, ConvergesToDottieNumberWithinTolerance) {
  const auto f = [](double x) { return std::cos(x) - x; };
  const RootResult root = FindRootBrent(f, 0.0, 1.0, f(0.0), f(1.0), 1e-15);
  ASSERT_TRUE(root.bracketed);
  EXPECT_NEAR(root.x, 0.739085133215160641655, 2e-15);
  EXPECT_LT(root.evaluations, 15);  // superlinear, far fewer than bisection's 50
}

TEST(FindRootBrent, FindsTripleRootBySafeguardedBisection) {
  const auto f = [](double x) { return std::pow(x - 0.3, 3); };
  const RootResult root = FindRootBrent(f, -1.0, 2.0, f(-1.0), f(2.0), 1e-12);
  EXPECT_NEAR(root.x, 0.3, 1e-11);
  EXPECT_LE(root.lower, 0.3 + 1e-15);
  EXPECT_GE(root.upper, 0.3 - 1e-15);
}

TEST(FindRootBrent, KeepsTheBracketAroundTheRootOfAStepLikeFunction) {
  // tanh with a steep front: interpolation overshoots, the bracket must still hold.
  const auto f = [](double x) { return std::tanh(1e4 * (x - 0.123456789)); };
  const RootResult root = FindRootBrent(f, 0.0, 1.0, f(0.0), f(1.0), 1e-14);
  EXPECT_NEAR(root.x, 0.123456789, 1e-13);
}

TEST(FindRootBrent, BisectsOnceABracketIsFlatAtTheFunctionsResolution) {
  // Flat at +1e-20 up to x0, then -1 (a slow approach's gap in its rounding band, against the
  // far end of the bracket): every interpolation puts the root within the tolerance of the flat
  // side, and plain Brent alternates those minimal steps with bisections, 72 evaluations here.
  // Bisecting once a minimal step stays on its side takes one evaluation per halving:
  // log2(1 / 2e-15) = 49, plus the first steps.
  const double x0 = 0.7071067811865476;
  const auto f = [x0](double x) { return x < x0 ? 1e-20 : -1.0; };
  const RootResult root = FindRootBrent(f, 0.0, 1.0, f(0.0), f(1.0), 1e-15);
  EXPECT_LE(root.evaluations, 55);
  EXPECT_LE(root.lower, x0);
  EXPECT_GE(root.upper, x0);
  EXPECT_LE(root.upper - root.lower, 2e-15);
}

TEST(FindRootBrent, ReportsMissingSignChange) {
  const auto f = [](double x) { return 1.0 + x * x; };
  const RootResult root = FindRootBrent(f, -1.0, 1.0, f(-1.0), f(1.0), 1e-12);
  EXPECT_FALSE(root.bracketed);
  EXPECT_EQ(root.evaluations, 0);
}

}  // namespace
}  // namespace skewbridge::dynamics::root_finding_test
