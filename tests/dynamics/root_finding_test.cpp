#include "solver/dynamics/root_finding.h"

#include <gtest/gtest.h>

#include <cmath>

namespace skewbridge::dynamics {
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

TEST(FindRootBrent, ReportsMissingSignChange) {
  const auto f = [](double x) { return 1.0 + x * x; };
  const RootResult root = FindRootBrent(f, -1.0, 1.0, f(-1.0), f(1.0), 1e-12);
  EXPECT_FALSE(root.bracketed);
  EXPECT_EQ(root.evaluations, 0);
}

}  // namespace
}  // namespace skewbridge::dynamics
