#include "solver/dynamics/runge_kutta.h"

#include <gtest/gtest.h>

#include <cmath>

namespace skewbridge::dynamics::runge_kutta_test {
namespace {

// y'' = -y as a first-order system; exact y = (sin t, cos t) from (0, 1).
void Oscillator(double, const Eigen::Ref<const Eigen::VectorXd>& y,
                Eigen::Ref<Eigen::VectorXd> dy) {
  dy[0] = y[1];
  dy[1] = -y[0];
}

struct FixedStepErrors {
  double end = 0.0;    // max error at t = 2
  double dense = 0.0;  // max error of the dense output at step mid-points
};

FixedStepErrors IntegrateOscillator(int steps) {
  DormandPrince45 rk(2);
  Eigen::VectorXd y(2), dy(2), mid(2);
  y << 0.0, 1.0;
  Oscillator(0.0, y, dy);
  const double h = 2.0 / steps;
  FixedStepErrors errors;
  for (int i = 0; i < steps; ++i) {
    const double t = i * h;
    rk.Step(Oscillator, t, y, dy, h);
    rk.Dense(0.5, mid);
    const double tm = t + 0.5 * h;
    errors.dense = std::max(errors.dense, std::abs(mid[0] - std::sin(tm)));
    errors.dense = std::max(errors.dense, std::abs(mid[1] - std::cos(tm)));
    y = rk.y_end();
    dy = rk.dy_end();
  }
  errors.end = std::max(std::abs(y[0] - std::sin(2.0)), std::abs(y[1] - std::cos(2.0)));
  return errors;
}

TEST(DormandPrince45, ObservedOrderAtMeshPointsIsFive) {
  const FixedStepErrors coarse = IntegrateOscillator(10);
  const FixedStepErrors fine = IntegrateOscillator(20);
  const double order = std::log2(coarse.end / fine.end);
  EXPECT_NEAR(order, 5.0, 0.3);
}

TEST(DormandPrince45, ObservedOrderOfDenseOutputIsAtLeastFour) {
  const FixedStepErrors coarse = IntegrateOscillator(10);
  const FixedStepErrors fine = IntegrateOscillator(20);
  const double order = std::log2(coarse.dense / fine.dense);
  EXPECT_GT(order, 3.8);
  EXPECT_LT(order, 5.5);
}

TEST(DormandPrince45, DenseOutputInterpolatesTheStepEnds) {
  DormandPrince45 rk(2);
  Eigen::VectorXd y(2), dy(2), out(2);
  y << 0.3, -0.2;
  Oscillator(0.0, y, dy);
  rk.Step(Oscillator, 0.0, y, dy, 0.4);
  rk.Dense(0.0, out);
  EXPECT_EQ((out - y).cwiseAbs().maxCoeff(), 0.0);
  rk.Dense(1.0, out);
  EXPECT_LT((out - rk.y_end()).cwiseAbs().maxCoeff(), 1e-16);
}

TEST(DormandPrince45, AdaptiveControlMeetsTheToleranceOnGaussian) {
  // y' = -2 t y, y(0) = 1: y = exp(-t^2).
  const auto f = [](double t, const Eigen::Ref<const Eigen::VectorXd>& y,
                    Eigen::Ref<Eigen::VectorXd> dy) { dy[0] = -2.0 * t * y[0]; };
  for (double rtol : {1e-6, 1e-9}) {
    DormandPrince45 rk(1);
    Eigen::VectorXd y = Eigen::VectorXd::Ones(1), dy(1), atol = Eigen::VectorXd::Constant(1, rtol);
    f(0.0, y, dy);
    double t = 0.0, h = 0.1, worst = 0.0;
    int rejected = 0;
    while (t < 3.0) {
      h = std::min(h, 3.0 - t);
      rk.Step(f, t, y, dy, h);
      const double err = rk.ErrorNorm(atol, rtol);
      if (err <= 1.0) {
        t += h;
        y = rk.y_end();
        dy = rk.dy_end();
        worst = std::max(worst, std::abs(y[0] - std::exp(-t * t)));
      } else {
        ++rejected;
      }
      h *= DormandPrince45::StepFactor(err);
    }
    EXPECT_LT(worst, 20.0 * rtol) << "rtol " << rtol;
    EXPECT_LT(rejected, 10);
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::runge_kutta_test
