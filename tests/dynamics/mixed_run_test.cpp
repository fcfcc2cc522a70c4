// A deck with one rigid abutment and one compliant (SimulateMixed, solver/dynamics/compliant_run.h)
// against the two laws alone: springs out of reach give the rigid run bit for bit, a rigid wall out
// of reach gives the compliant run to the Runge-Kutta tolerance, and with both walls struck the
// energy ledger (a conservation law) closes to 1e-6 of the input.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/compliant_run.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"
#include "tests/dynamics/benchmark_cases.h"
#include "tests/dynamics/run_bits.h"

namespace skewbridge::dynamics::mixed_run_test {
namespace {

// The pilot bridge of docs/examples/pilot-bridge.toml with rigid contacts at the +x wall only, its
// gap `gap_plus_m`.
model::Model RigidPlusX(double gap_plus_m) {
  const model::ModelFile file = model::ParseModelFile(std::string(SKEWBRIDGE_TEST_DATA_DIR) +
                                                      "/../../docs/examples/pilot-bridge.toml");
  model::DeckSpec spec = file.deck;
  spec.abutments = model::AbutmentSet::kPlusX;
  spec.gap_plus_m = gap_plus_m;
  return model::BuildDeckModel(spec);
}

// Wilson and Elgamal's per-metre backfill over the skewed backwall (5 springs from P3 to P4) at the
// -x wall of the pilot bridge, its gap `gap_minus_m`.
std::vector<CompliantSpring> MinusXBackfill(double gap_minus_m) {
  const model::ModelFile file = model::ParseModelFile(std::string(SKEWBRIDGE_TEST_DATA_DIR) +
                                                      "/../../docs/examples/pilot-bridge.toml");
  model::DeckSpec spec = file.deck;
  spec.abutments = model::AbutmentSet::kBoth;
  spec.gap_minus_m = gap_minus_m;
  const model::Model both = model::BuildDeckModel(spec);
  const model::DeckGeometry& g = both.body(0).geometry;
  const double wall_m = g.width_m / std::cos(g.skew_rad);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  return WallSprings(both, 2, 3, wall, 5, "-x");
}

TEST(MixedRun, SpringsOutOfReachGiveTheRigidRunBitForBit) {
  const model::Model rigid = RigidPlusX(bench::kPilotStudyGap_m);
  const std::vector<CompliantSpring> far = MinusXBackfill(10.0);
  records::SampledExcitation ex(0.01, bench::RecordLikeSignal());
  for (const bool ledger : {true, false}) {
    SCOPED_TRACE(ledger ? "with the ledger" : "without the ledger");
    model::RunControl control;
    control.end_time_s = 40.0;
    control.energy_ledger = ledger;
    SimulationWorkspace ws(rigid);
    const RunResult alone = Simulate(rigid, ex, control, ws);
    ASSERT_EQ(alone.status, RunStatus::kOk) << alone.message;
    ASSERT_GT(alone.impacts, 5) << "the rigid wall is struck";
    const CompliantRunResult mixed = SimulateMixed(rigid, far, ex, control);
    ASSERT_EQ(mixed.run.status, RunStatus::kOk) << mixed.run.message;
    EXPECT_EQ(mixed.max_spring_force_N.maxCoeff(), 0.0);
    testing::ExpectSameRunAndLedgerBits(alone, mixed.run);
  }
}

TEST(MixedRun, ARigidWallOutOfReachGivesTheCompliantRun) {
  const model::Model far = RigidPlusX(10.0);
  const std::vector<CompliantSpring> springs = MinusXBackfill(bench::kPilotStudyGap_m);
  records::SampledExcitation ex(0.01, bench::RecordLikeSignal());
  model::RunControl control;
  control.end_time_s = 40.0;
  const CompliantRunResult compliant =
      SimulateCompliant(WithoutContacts(far), springs, ex, control);
  ASSERT_EQ(compliant.run.status, RunStatus::kOk) << compliant.run.message;
  ASSERT_GT(compliant.run.impacts, 5) << "the backfill is struck";
  const CompliantRunResult mixed = SimulateMixed(far, springs, ex, control);
  ASSERT_EQ(mixed.run.status, RunStatus::kOk) << mixed.run.message;
  EXPECT_EQ(mixed.run.impacts, compliant.run.impacts);
  // The step controls differ (the rigid integrator's first step and scales): the responses agree
  // to the Runge-Kutta tolerance's order, relative to each response (9e-11 and 2e-11 measured).
  const double tol = 1e-8;
  for (int i = 0; i < far.n_dof(); ++i) {
    EXPECT_NEAR(mixed.run.max_abs_q[i], compliant.run.max_abs_q[i],
                tol * compliant.run.max_abs_q[i])
        << "dof " << i;
  }
  for (int j = 0; j < static_cast<int>(springs.size()); ++j) {
    EXPECT_NEAR(mixed.max_spring_force_N[j], compliant.max_spring_force_N[j],
                tol * compliant.max_spring_force_N.maxCoeff())
        << "spring " << j;
  }
  EXPECT_NEAR(mixed.joint_dissipated_J, compliant.joint_dissipated_J,
              1e-6 * compliant.joint_dissipated_J);
}

TEST(MixedRun, EnergyLedgerClosesWithBothWallsStruck) {
  const model::Model rigid = RigidPlusX(bench::kPilotStudyGap_m);
  const std::vector<CompliantSpring> springs = MinusXBackfill(bench::kPilotStudyGap_m);
  records::SampledExcitation ex(0.01, bench::RecordLikeSignal());
  model::RunControl control;
  control.end_time_s = 40.0;
  const CompliantRunResult mixed = SimulateMixed(rigid, springs, ex, control);
  const RunResult& r = mixed.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  long contact_impacts = 0;
  for (const EventRecord& e : r.events) contact_impacts += e.kind == EventKind::kImpact ? 1 : 0;
  EXPECT_GT(contact_impacts, 0) << "the rigid wall is struck";
  EXPECT_GT(mixed.max_spring_force_N.maxCoeff(), 0.0) << "the backfill is struck";
  EXPECT_GT(r.energy.impact_J, 0.0);
  EXPECT_GT(mixed.joint_dissipated_J, 1e-4 * r.energy.input_J);
  EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-6 * r.energy.input_J)
      << "input " << r.energy.input_J << " impact " << r.energy.impact_J << " dissipated "
      << mixed.joint_dissipated_J << " stored " << mixed.joint_stored_J;
}

}  // namespace
}  // namespace skewbridge::dynamics::mixed_run_test
