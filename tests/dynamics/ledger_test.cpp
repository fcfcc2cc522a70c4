// The energy ledger is bookkeeping only: a run without it (RunControl::energy_ledger = false, what
// a sweep cell does) gives the same bits in every response, on the modal path and the general one.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/dynamics/simulate.h"
#include "tests/dynamics/benchmark_cases.h"

namespace skewbridge::dynamics::ledger_test {
namespace {

void ExpectSameResponses(const model::Model& m, const Excitation& ex, model::RunControl control) {
  control.energy_ledger = true;
  SimulationWorkspace ws_on(m);
  const RunResult on = Simulate(m, ex, control, ws_on);
  control.energy_ledger = false;
  SimulationWorkspace ws_off(m);
  const RunResult off = Simulate(m, ex, control, ws_off);
  ASSERT_EQ(on.status, RunStatus::kOk);
  EXPECT_EQ(on.status, off.status);
  EXPECT_TRUE(on.max_abs_q == off.max_abs_q);
  EXPECT_TRUE(on.time_of_max_s == off.time_of_max_s);
  EXPECT_TRUE(on.q_end == off.q_end);
  EXPECT_TRUE(on.u_end == off.u_end);
  EXPECT_EQ(on.end_time_s, off.end_time_s);
  EXPECT_EQ(on.impacts, off.impacts);
  EXPECT_EQ(on.free_steps, off.free_steps);
  EXPECT_EQ(on.rk_steps, off.rk_steps);
  EXPECT_EQ(on.min_impact_separation_s, off.min_impact_separation_s);
  ASSERT_EQ(on.events.size(), off.events.size());
  for (std::size_t i = 0; i < on.events.size(); ++i) {
    EXPECT_EQ(on.events[i].t_s, off.events[i].t_s);
    EXPECT_EQ(on.events[i].kind, off.events[i].kind);
    EXPECT_EQ(on.events[i].contact, off.events[i].contact);
    EXPECT_EQ(on.events[i].impulse_N_Ns, off.events[i].impulse_N_Ns);
    EXPECT_EQ(on.events[i].impulse_T_Ns, off.events[i].impulse_T_Ns);
    EXPECT_EQ(on.events[i].gamma_N_before_mps, off.events[i].gamma_N_before_mps);
  }
  // The impacts' share stays; the free steps' work is absent, and says so.
  EXPECT_EQ(on.energy.impact_J, off.energy.impact_J);
  EXPECT_TRUE(std::isnan(off.energy.input_J) && std::isnan(off.energy.damping_J) &&
              std::isnan(off.energy.balance_error_J));
  EXPECT_LT(std::abs(on.energy.balance_error_J), 1e-6 * on.energy.input_J);
}

TEST(EnergyLedger, ResponsesAreTheSameBitsWithoutIt) {
  const bench::Case pulse = bench::SubsystemCosinePulse(true);
  ExpectSameResponses(pulse.model, *pulse.excitation, pulse.control);
  const bench::Case record = bench::PilotBridgeRecord(true, bench::kPilotStudyGap_m);
  ExpectSameResponses(record.model, *record.excitation, record.control);
}

TEST(EnergyLedger, ResponsesAreTheSameBitsWithoutItOnTheGeneralPath) {
  // Dampers on x and y with a cross term and none on theta: not classical, so the augmented
  // exponential propagates.
  const bench::Case c = bench::SubsystemCosinePulse(true);
  const double c0 = 0.1 * c.model.M()(0, 0) * std::sqrt(c.model.K()(0, 0) / c.model.M()(0, 0));
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, 3);
  C(0, 0) = c0;
  C(1, 1) = 0.3 * c0;
  C(0, 1) = C(1, 0) = 0.2 * c0;
  const model::Model m(c.model.bodies(), c.model.K(), C, c.model.r(), c.model.contacts());
  ASSERT_FALSE(LinearFlow(m.M(), m.K(), m.C(), m.r()).modal());
  ExpectSameResponses(m, *c.excitation, c.control);
}

}  // namespace
}  // namespace skewbridge::dynamics::ledger_test
