#include "solver/dynamics/time_stepping.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "solver/dynamics/simulate.h"
#include "tests/timestepping/cases.h"

namespace skewbridge::dynamics {
namespace {

using timestepping_test::Case;

// The event-driven reference at tolerances far below the time-stepping errors.
RunResult Reference(const Case& c) {
  model::RunControl control = c.file.run;
  control.relative_tolerance = 1e-11;
  control.absolute_tolerance = 1e-13;
  SimulationWorkspace ws(c.file.model);
  return Simulate(c.file.model, *c.excitation, control, ws);
}

RunResult Stepped(const Case& c, double h_s, TimeSteppingWorkspace& ws) {
  model::RunControl control = c.file.run;
  control.time_step_s = h_s;
  return SimulateTimeStepping(c.file.model, *c.excitation, control, ws);
}

// Rotation in the sense of docs/theory.md §4: theta_m rho above 1e-3 of the largest translation.
bool Rotates(const RunResult& r, double rho_m) {
  return r.max_abs_q[2] * rho_m > 1e-3 * std::max(r.max_abs_q[0], r.max_abs_q[1]);
}

TEST(MeanAcceleration, EqualsTheIntegralOfACosinePulseAcrossItsEnd) {
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 2.0, 4.0);
  const double T = 2.0 * M_PI / 4.0;
  // Mean over [T - 0.1, T + 0.1]: (1/0.2) int_{T-0.1}^{T} 2 cos(4 t) dt = sin(0.4) / 0.4.
  const Eigen::Vector2d mean = MeanAcceleration(pulse, T - 0.1, T + 0.1);
  EXPECT_NEAR(mean.x(), std::sin(0.4) / 0.4, 1e-13);
  EXPECT_EQ(mean.y(), 0.0);
}

TEST(TimeStepping, ContactFreeRunConvergesAtSecondOrderToTheExactFlow) {
  // subsystem.toml with a gap the deck never closes: the event-driven run is the exact
  // transition, the trapezoidal rule is second order.
  std::string text =
      timestepping_test::ReadText(timestepping_test::ExamplesDir() + "/subsystem.toml");
  timestepping_test::Replace(text, "gap_m = 0.03", "gap_m = 1.0");
  Case c{"free", model::ParseModelString(text, "subsystem.toml"), nullptr};
  c.excitation = std::make_unique<records::PulseExcitation>(records::PulseShape::kCosine,
                                                            c.file.excitation.amplitude_mps2,
                                                            c.file.excitation.omega_radps);
  const RunResult reference = Reference(c);
  ASSERT_EQ(reference.impacts, 0);
  const double rho = timestepping_test::Rho(c.file.model);
  TimeSteppingWorkspace ws(c.file.model);
  std::vector<double> errors;
  for (double h : {1e-3, 5e-4, 2.5e-4}) {
    const RunResult r = Stepped(c, h, ws);
    ASSERT_EQ(r.status, RunStatus::kOk);
    EXPECT_EQ(r.impacts, 0);
    errors.push_back(timestepping_test::HistoryError(reference, r, rho));
  }
  for (std::size_t j = 1; j < errors.size(); ++j) {
    const double order = std::log2(errors[j - 1] / errors[j]);
    EXPECT_NEAR(order, 2.0, 0.1) << "h halving " << j;
  }
  EXPECT_LT(errors[0], 1e-3);
}

TEST(TimeStepping, EnergyLedgerBalancesToRoundingForTheTrapezoidalRule) {
  // With theta = 1/2 the discrete energy change equals the theta-point work exactly, impacts
  // and friction included [Acary and Brogliato 2008, §10.1].
  const Case c = timestepping_test::SubsystemCase(0.3, 2.0, true);
  TimeSteppingWorkspace ws(c.file.model);
  const RunResult r = Stepped(c, 2e-4, ws);
  ASSERT_EQ(r.status, RunStatus::kOk);
  ASSERT_GT(r.impacts, 0);
  const EnergyLedger& e = r.energy;
  EXPECT_GT(e.impact_J, 0.0);
  EXPECT_GE(e.friction_J, 0.0);
  EXPECT_LT(std::abs(e.balance_error_J), 1e-9 * (e.input_J + e.initial_J + e.damping_J));
}

class CanonicalCase : public ::testing::TestWithParam<int> {};

TEST_P(CanonicalCase, MaximaConvergeToTheEventDrivenResultAndAgreeOnRotation) {
  std::vector<Case> cases = timestepping_test::CanonicalCases();
  const Case& c = cases[static_cast<std::size_t>(GetParam())];
  SCOPED_TRACE(c.name);
  const RunResult reference = Reference(c);
  ASSERT_EQ(reference.status, RunStatus::kOk);
  ASSERT_GT(reference.impacts, 0);
  const double rho = timestepping_test::Rho(c.file.model);
  TimeSteppingWorkspace ws(c.file.model);
  // The grid's phase against the impact instants makes the error at one h fluctuate between 0
  // and its first-order envelope, so each nominal h is represented by the worst error over
  // the band h 2^(j/4), j = 0..3: that envelope halves with h. The error at h itself must be
  // below 1 % at h = 1e-4 s.
  std::vector<double> envelope;
  double error_at_h = 0.0;
  for (double h : {1.6e-3, 8e-4, 4e-4, 2e-4, 1e-4}) {
    double worst = 0.0;
    for (int j = 0; j < 4; ++j) {
      const double step = h * std::exp2(0.25 * j);
      const RunResult r = Stepped(c, step, ws);
      ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
      const double error = timestepping_test::MaximaError(reference, r, rho);
      worst = std::max(worst, error);
      error_at_h = j == 0 ? error : error_at_h;
      EXPECT_EQ(Rotates(r, rho), Rotates(reference, rho)) << "h = " << step;
    }
    envelope.push_back(worst);
  }
  for (std::size_t j = 1; j < envelope.size(); ++j) {
    EXPECT_LT(envelope[j], envelope[j - 1])
        << "halving " << j << ", envelope " << envelope[j - 1] << " -> " << envelope[j];
  }
  EXPECT_LT(error_at_h, 0.01);
}

INSTANTIATE_TEST_SUITE_P(MuEta0Shape, CanonicalCase, ::testing::Range(0, 8));

}  // namespace
}  // namespace skewbridge::dynamics
