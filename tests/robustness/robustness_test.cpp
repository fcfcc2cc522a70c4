// The robustness grid of the event-driven integrator (robustness_grid.h) and runs that exercise
// the rules of the mode decision [docs/theory.md §3.1-§3.15]: every run ends ok, makes progress
// in time (no decision repeated at one instant), and agrees with Moreau-Jean time-stepping, the
// independent method [docs/theory.md §3].

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>

#include "records/excitations.h"
#include "records/measures.h"
#include "records/synthetic.h"
#include "solver/dynamics/simulate.h"
#include "solver/dynamics/time_stepping.h"
#include "solver/model/model_file.h"
#include "tests/robustness/robustness_grid.h"

namespace skewbridge::robustness::robustness_test {
namespace {

// |a - b| within 1 % of |b|, or within `floor` (normalised by L_e) where both are near zero.
void ExpectAgree(double event_driven, double time_stepping, double floor, const std::string& what) {
  EXPECT_LE(std::abs(event_driven - time_stepping), std::max(0.01 * std::abs(time_stepping), floor))
      << what << ": event-driven " << event_driven << ", time-stepping " << time_stepping;
}

// No contact takes the same kind of event twice at one instant: each decision is reached once.
void ExpectEachDecisionOnce(const dynamics::RunResult& r) {
  std::map<std::tuple<double, int, int>, int> seen;
  for (const dynamics::EventRecord& e : r.events) {
    const int n = ++seen[{e.t_s, e.contact, static_cast<int>(e.kind)}];
    EXPECT_EQ(n, 1) << dynamics::ToString(e.kind) << " of contact " << e.contact
                    << " repeated at t = " << e.t_s;
  }
}

// The event-driven maxima of x, y and theta against Moreau-Jean at h = h_over_Tg T_g, each within
// 1 % or 1e-6 L_e (criterion 4 of the robustness work, docs/validation.md).
void ExpectMaximaAgreeWithTimeStepping(const spectra::PointParameters& p, double h_over_Tg) {
  const spectra::PointResult ed = Evaluate(p, spectra::Method::kEventDriven);
  const spectra::PointResult ts = Evaluate(p, spectra::Method::kTimeStepping, h_over_Tg);
  ASSERT_EQ(ts.status, dynamics::RunStatus::kOk) << ts.message;
  ExpectAgree(ed.x_norm, ts.x_norm, 1e-6, "x_norm");
  ExpectAgree(ed.y_norm, ts.y_norm, 1e-6, "y_norm");
  ExpectAgree(ed.theta_norm, ts.theta_norm, 1e-6, "theta_norm");
}

TEST(RobustnessGrid, SeededSampleEndsOkEverywhere) {
  const GridAxes grid;
  ASSERT_EQ(grid.size(), 28800);
  int failed = 0;
  for (std::int64_t c : SampleCells(grid, 600, 2024)) {
    const spectra::PointResult r = Evaluate(grid.Cell(c), spectra::Method::kEventDriven);
    if (r.status != dynamics::RunStatus::kOk) {
      ++failed;
      ADD_FAILURE() << "cell " << c << " (" << Describe(grid.Cell(c)) << "): " << r.message;
    }
  }
  EXPECT_EQ(failed, 0);
}

// Cells that end in an event cascade, a step limit, a false Painleve ray or a false impact-LCP
// ray without the consistent decision of docs/theory.md §3.1-§3.15 (enumeration of a degenerate
// LCP: §3.15), each against time-stepping at h = 1e-6 of the excitation period.
// One test per cell, so that the shards of the test program (tests/robustness/CMakeLists.txt)
// share them.
class FormerlyFailingCell : public ::testing::TestWithParam<std::int64_t> {};

TEST_P(FormerlyFailingCell, EndsOkAndAgreesWithTimeStepping) {
  const GridAxes grid;
  const std::int64_t c = GetParam();
  const spectra::PointParameters p = grid.Cell(c);
  SCOPED_TRACE("cell " + std::to_string(c) + " (" + Describe(p) + ")");
  const dynamics::RunResult run = RunEventDriven(p);
  ASSERT_EQ(run.status, dynamics::RunStatus::kOk) << run.message;
  ExpectEachDecisionOnce(run);
  // h = 1e-6 T_g: at 1e-5 T_g the Moreau-Jean answer of cell 1178 is still 12 % off its
  // converged value in y (near-simultaneous impacts merged by the step), at 1e-6 within 2e-6.
  // A cell with w0/w_g < 1 runs for 2 natural periods of >= 10 T_g: 1e-5 T_g keeps it within
  // the step budget.
  ExpectMaximaAgreeWithTimeStepping(p, p.w0_over_wg < 1.0 ? 1e-5 : 1e-6);
}

INSTANTIATE_TEST_SUITE_P(RobustnessGrid, FormerlyFailingCell,
                         ::testing::Values(429, 465, 637, 1178, 1792, 3369, 3449, 11871));

// A deck rocking between the two corners of one face at a closed joint, its impacts alternating
// every 40-80 us at about 1.4 times the accumulation threshold (1e-6 of the response's velocity
// scale), a speed the loads sustain: resolved impact by impact it takes 134 impacts and 153
// detachments, and rounding-level changes of its event times (another root search, other
// compiler flags) turn the same rocking into tens of thousands of events or an event cascade.
// It settles into both corners closed [docs/theory.md §3.5, settling and the rocking
// exception], and the maxima agree with Moreau-Jean. Cell 3568 rocks above that speed and
// decays by itself: it keeps its impacts but must end ok and agree.
TEST(RobustnessGrid, RockingBetweenTwoCornersSettlesAndAgreesWithTimeStepping) {
  const GridAxes grid;
  for (const auto& [c, max_impacts] : {std::pair<std::int64_t, long>{2957, 40}, {3568, 300}}) {
    const spectra::PointParameters p = grid.Cell(c);
    SCOPED_TRACE("cell " + std::to_string(c) + " (" + Describe(p) + ")");
    const dynamics::RunResult run = RunEventDriven(p);
    ASSERT_EQ(run.status, dynamics::RunStatus::kOk) << run.message;
    ExpectEachDecisionOnce(run);
    EXPECT_LE(run.impacts, max_impacts);
    ExpectMaximaAgreeWithTimeStepping(p, 1e-5);
  }
}

// The grid's most event-rich cell: a deck pressed onto one face rocks between its two corners
// there for 0.4 s, each impact (eps_N 0.5) lifting the other corner, and the striking corner
// rebounds for about 13 us (1e-4 of the shortest period) after each rock. The bounce is closed
// at its first impact [docs/theory.md §3.6, the predicted bounce]; closed by the Zeno rule at
// its second (§3.4) it costs 372 impacts, 173 of them returns within 0.1 ms of the same corner's
// impact. The maxima agree with Moreau-Jean.
TEST(RobustnessGrid, ShortBounceOfARockingCornerClosesAtOnceAndAgreesWithTimeStepping) {
  const GridAxes grid;
  const spectra::PointParameters p = grid.Cell(3599);
  const dynamics::RunResult run = RunEventDriven(p);
  ASSERT_EQ(run.status, dynamics::RunStatus::kOk) << run.message;
  ExpectEachDecisionOnce(run);
  EXPECT_LE(run.impacts, 250);
  std::map<int, double> last_impact_s;
  int quick_returns = 0;
  for (const dynamics::EventRecord& e : run.events) {
    if (e.kind != dynamics::EventKind::kImpact) {
      continue;
    }
    const auto it = last_impact_s.find(e.contact);
    quick_returns += it != last_impact_s.end() && e.t_s - it->second < 1e-4 ? 1 : 0;
    last_impact_s[e.contact] = e.t_s;
  }
  EXPECT_LE(quick_returns, 10);
  ExpectMaximaAgreeWithTimeStepping(p, 1e-5);
}

// A closed joint with plastic impacts and friction. Slow closures are plastic impacts
// [docs/theory.md §3.3], and the stick or slip of P1 at t = 0.274155 s starts at zero slip or on
// the cone, where the event-function bands and the tie bands decide it once (§3.7, §3.12);
// without them stick and slip alternate dozens of times at that instant, and a slow closure
// repeats at t = 1.3097 s until an event cascade. It reaches 3 s, decides each stick or slip
// once, and matches Moreau-Jean at h = 1e-5 s.
TEST(ClosedJointReproduction, RunsThroughWithOneDecisionPerInstantAndMatchesTimeStepping) {
  const model::ModelFile file = model::ParseModelFile(
      std::string(SKEWBRIDGE_TEST_DATA_DIR) + "/robustness/closed-joint-plastic-friction.toml");
  const model::ExcitationSpec& spec = file.excitation;
  const records::PulseExcitation pulse(records::PulseShape::kCosine, spec.amplitude_mps2,
                                       spec.omega_radps);
  dynamics::SimulationWorkspace ws(file.model);
  const dynamics::RunResult ed = dynamics::Simulate(file.model, pulse, file.run, ws);
  ASSERT_EQ(ed.status, dynamics::RunStatus::kOk) << ed.message;
  EXPECT_NEAR(ed.end_time_s, 3.0, 1e-12);
  ExpectEachDecisionOnce(ed);
  int near_0274 = 0;  // the stick-slip decisions of P1 around t = 0.274155 s
  for (const dynamics::EventRecord& e : ed.events) {
    if (e.contact == 0 && std::abs(e.t_s - 0.274155) < 1e-5 &&
        (e.kind == dynamics::EventKind::kStick || e.kind == dynamics::EventKind::kSlip)) {
      ++near_0274;
    }
  }
  EXPECT_LE(near_0274, 1);
  model::RunControl ts_control = file.run;
  ts_control.time_step_s = 1e-5;
  dynamics::TimeSteppingWorkspace tws(file.model);
  const dynamics::RunResult ts = dynamics::SimulateTimeStepping(file.model, pulse, ts_control, tws);
  ASSERT_EQ(ts.status, dynamics::RunStatus::kOk) << ts.message;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(ed.max_abs_q[i], ts.max_abs_q[i], 1e-4 * ts.max_abs_q[i]) << "DOF " << i;
  }
}

// The pilot bridge clamped between both abutments (Pi_delta = 0: four closed corners on two
// parallel faces, a singular active set with a squeeze among its kernel) under records of the
// 62-record synthetic suite (seed 2011), as the sweep runs them. The indeterminate forces take
// the three-LP split [docs/theory.md §3.13], degenerate LCPs the compliance retry (§3.15) and a
// wedged deck the jam (§3.9); without them every record ends in an event cascade within its
// first 0.01 s. Each run ends ok, and agrees with Moreau-Jean at h = 1e-5 T_m (tolerances in
// docs/validation.md, "Robustness").
spectra::PointResult EvaluatePilotRecord(int index, double Pi_delta, spectra::Method method) {
  records::SynthOptions options;
  options.count = 62;
  options.seed = 2011;
  const records::GroundMotion motion = records::SynthesizeRecord(options, index);
  const records::IntensityMeasures measures = records::ComputeMeasures(motion);
  spectra::PointParameters p;
  p.family = spectra::Family::kPilotBridge;
  p.mu = 0.3;  // the published pilot bridge, as the sweep sets it
  p.Pi_delta = Pi_delta;
  p.method = method;
  // Moreau-Jean at h = 1e-5 s (1e-5 to 5e-5 T_m): 3.2 million steps over the 32 s run.
  p.time_step_over_Tg = 1e-5 * measures.omega_g_radps / (2.0 * std::numbers::pi);
  const spectra::ExcitationScales scales{measures.pga_mps2, measures.omega_g_radps};
  return spectra::EvaluatePoint(spectra::ToDimensional(p, scales), records::ToExcitation(motion));
}

// Every sixth record of the suite at Pi_delta = 0 (all 62 in the sweep of
// jobs/specs/robustness/pilot-closed-joints.toml, docs/validation.md), one test per record.
class PilotClosedJointRecord : public ::testing::TestWithParam<int> {};

TEST_P(PilotClosedJointRecord, EndsOk) {
  const int index = GetParam();
  const spectra::PointResult ed = EvaluatePilotRecord(index, 0.0, spectra::Method::kEventDriven);
  EXPECT_EQ(ed.status, dynamics::RunStatus::kOk)
      << "record synth-2011-" << index << ": " << ed.message;
  EXPECT_GT(ed.x_norm, 0.0) << "record synth-2011-" << index << ": the deck slides";
}

INSTANTIATE_TEST_SUITE_P(PilotClosedJoints, PilotClosedJointRecord, ::testing::Range(0, 62, 6));

// (record, Pi_delta): the closed joints on record 7, whose Moreau-Jean maxima at h = 1e-5 s and
// 1e-6 s agree; at Pi_delta = 0.1 records 2 and 5. On other records of the clamped deck
// Moreau-Jean itself has not converged at 1e-5 s (docs/validation.md, "Robustness").
class PilotClosedJointAgreement : public ::testing::TestWithParam<std::pair<int, double>> {};

TEST_P(PilotClosedJointAgreement, AgreesWithTimeSteppingWhereItHasConverged) {
  const auto [index, Pi_delta] = GetParam();
  SCOPED_TRACE("record synth-2011-" + std::to_string(index) +
               ", Pi_delta = " + std::to_string(Pi_delta));
  const spectra::PointResult ed =
      EvaluatePilotRecord(index, Pi_delta, spectra::Method::kEventDriven);
  ASSERT_EQ(ed.status, dynamics::RunStatus::kOk) << ed.message;
  const spectra::PointResult ts =
      EvaluatePilotRecord(index, Pi_delta, spectra::Method::kTimeStepping);
  ASSERT_EQ(ts.status, dynamics::RunStatus::kOk) << ts.message;
  std::printf("record %d Pi_delta %g: x %.6e / %.6e  y %.6e / %.6e  theta %.6e / %.6e\n", index,
              Pi_delta, ed.x_norm, ts.x_norm, ed.y_norm, ts.y_norm, ed.theta_norm, ts.theta_norm);
  // The clamped deck (Pi_delta = 0) is ill-conditioned in the event-driven method too: its
  // maxima on record 7 moved by up to 1 % under changes of the event logic at rounding level
  // (x_norm 1.1517e-2, 1.1580e-2, 1.1591e-2, 1.1611e-2, 1.1630e-2, 1.1635e-2, 1.1536e-2 against
  // Moreau-Jean's 1.1531e-2): there the bound is 2 %, at Pi_delta = 0.1 the 1 % of the grid.
  const double tolerance = Pi_delta == 0.0 ? 0.02 : 0.01;
  for (const auto& [name, e, t] :
       {std::tuple{"x_norm", ed.x_norm, ts.x_norm}, std::tuple{"y_norm", ed.y_norm, ts.y_norm},
        std::tuple{"theta_norm", ed.theta_norm, ts.theta_norm}}) {
    EXPECT_LE(std::abs(e - t), std::max(tolerance * std::abs(t), 1e-6))
        << name << ": event-driven " << e << ", time-stepping " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(PilotClosedJoints, PilotClosedJointAgreement,
                         ::testing::Values(std::pair{7, 0.0}, std::pair{2, 0.1},
                                           std::pair{5, 0.1}));

}  // namespace
}  // namespace skewbridge::robustness::robustness_test
