// A record's run as a stripe of it (dynamics::RunScaledRecord: the record's contact-free response
// traced at 2^-40, scaled to the factor, and the event-driven run from the scaled state at the
// start of the first free step in which a gap may close), for the one-deck model of the
// record-scaling tests (abutments 20 mm away) under the real record NIS090.AT2 at factors with
// and without impacts:
// - recording histories and the energy ledger changes none of its results: maxima and their
//   times, end state, corner travels, counts and events have the bits of the run without them;
// - its history samples are the output grid 0, dt, 2 dt, ... without a gap or a repeat across
//   the restart, and they follow the run at the factor from rest (dynamics::Run) within 1e-9 of
//   the peak until the first impact;
// - the energy ledger, the trace's work over [0, t_s] (quadratic in the factor) and the restarted
//   run's after it, balances: |balance error| within 1e-9 of the input work (a conservation law
//   the stitch breaks by the whole energy at t_s if either part is left out);
// - against dynamics::Run at the same factor: the same status and impact count, the maxima
//   within 1e-12 without impacts, and at a power of two (the record's samples and the linear
//   flow scale exactly) the direct run's bits.
// And TraceStripes against a brute force over every free step of the trace, at 60 factors that
// straddle the first contact: the exact scaled gaps and normal rates at both ends of every step
// (no bound), and the corner travel scanned at every step on the scaled dense output, give the
// same step for each stripe's restart and the same bits of its corner travels.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "records/ground_motion.h"
#include "solver/contact/kinematics.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/linear_flow.h"
#include "solver/dynamics/run.h"
#include "solver/dynamics/stripes.h"
#include "solver/model/model_file.h"
#include "tests/dynamics/run_bits.h"

namespace skewbridge::dynamics::stripes_test {
namespace {

const std::string kDataDir = SKEWBRIDGE_TEST_DATA_DIR;
using testing::Bits;

// The record along x at `factor`, each sample times the factor as a sweep scales it.
records::SampledExcitation Scaled(const records::GroundMotion& motion, double factor) {
  records::GroundMotion scaled = motion;
  for (double& a : scaled.acc_mps2) a *= factor;
  return records::ToExcitation(scaled);
}

TEST(StripeRun, HistoriesAndLedgerObserveItAndTheLedgerBalancesAcrossTheRestart) {
  const model::ModelFile file = model::ParseModelFile(kDataDir + "/models/one-deck-records.toml");
  const records::GroundMotion motion = records::ReadRecord(kDataDir + "/records/NIS090.AT2");
  const model::Model& model = file.model;
  const records::SampledExcitation trace = Scaled(motion, kStripeTraceFactor);
  const RunPolicies policies;
  model::RunControl plain = file.run;
  plain.method = model::Method::kEventDriven;
  plain.output_interval_s = 0.0;
  plain.energy_ledger = false;
  model::RunControl recorded = plain;
  recorded.output_interval_s = 0.01;
  recorded.energy_ledger = true;
  const int n = model.n_dof();
  int with_impacts = 0, without = 0, powers_of_two = 0;
  for (const double factor : {0.02, 0.05, 0.5, 1.0, 2.7, 4.0, 6.3}) {
    SCOPED_TRACE("factor " + std::to_string(factor));
    const records::SampledExcitation excitation = Scaled(motion, factor);
    const RunResult stripe = RunScaledRecord(model, excitation, trace, factor, plain, policies);
    const RunResult full = RunScaledRecord(model, excitation, trace, factor, recorded, policies);
    testing::ExpectSameRunBits(full, stripe);

    // The output grid, whole across the restart.
    const Histories& h = full.histories;
    ASSERT_GE(h.t_s.size(), 2u);
    ASSERT_EQ(h.q.size(), h.t_s.size() * static_cast<std::size_t>(n));
    ASSERT_EQ(h.gap_m.size(), h.t_s.size() * static_cast<std::size_t>(model.n_contacts()));
    for (std::size_t k = 0; k < h.t_s.size(); ++k) {
      ASSERT_EQ(h.t_s[k], recorded.output_interval_s * static_cast<double>(k)) << "sample " << k;
    }
    EXPECT_GE(h.t_s.back(), full.end_time_s - recorded.output_interval_s);

    // The ledger stitched over the restart balances.
    const EnergyLedger& e = full.energy;
    ASSERT_TRUE(std::isfinite(e.input_J) && e.input_J > 0.0);
    EXPECT_LE(std::abs(e.balance_error_J), 1e-9 * e.input_J)
        << "input " << e.input_J << ", damping " << e.damping_J << ", impacts " << e.impact_J;

    // The run at the factor from rest.
    const RunResult own = dynamics::Run(model, excitation, recorded, policies);
    ASSERT_EQ(own.status, full.status);
    EXPECT_EQ(own.impacts, full.impacts);
    const double t_first = full.events.empty() ? full.end_time_s + 1.0 : full.events[0].t_s;
    const Histories& g = own.histories;
    ASSERT_EQ(g.t_s.size(), h.t_s.size());
    for (std::size_t k = 0; k < h.t_s.size() && h.t_s[k] < t_first; ++k) {
      for (int i = 0; i < n; ++i) {
        const std::size_t at = k * static_cast<std::size_t>(n) + static_cast<std::size_t>(i);
        EXPECT_LE(std::abs(h.q[at] - g.q[at]), 1e-9 * own.max_abs_q[i])
            << "sample " << k << ", q " << i;
      }
    }
    if (full.impacts == 0) {
      ++without;
      for (int i = 0; i < n; ++i) {
        EXPECT_LE(std::abs(full.max_abs_q[i] - own.max_abs_q[i]), 1e-12 * own.max_abs_q[i]);
      }
    } else {
      ++with_impacts;
    }
    if (factor == 1.0 || factor == 4.0) {
      ++powers_of_two;
      testing::ExpectSameRunBits(full, own);
    }
  }
  EXPECT_GE(with_impacts, 2);
  EXPECT_GE(without, 2);
  EXPECT_EQ(powers_of_two, 2);
}

// Keeps every free step of a run: its ends' times and states.
class StepLog final : public FreeStepObserver {
 public:
  struct Kept {
    double t0, t1;
    Eigen::VectorXd z0, z1;
  };
  bool Step(double t0, const Eigen::Ref<const Eigen::VectorXd>& z0, double /*h0*/, double t1,
            const Eigen::Ref<const Eigen::VectorXd>& z1, const RunResult& /*run*/) override {
    steps.push_back({t0, t1, z0, z1});
    return true;
  }
  std::vector<Kept> steps;
};

// TraceStripes of the model of `file` under NIS090 along x at 60 factors from 0.05 to 5, against
// the brute force.
void ExpectTraceIsTheBruteForce(const model::ModelFile& file) {
  const records::GroundMotion motion = records::ReadRecord(kDataDir + "/records/NIS090.AT2");
  const model::Model& model = file.model;
  const records::SampledExcitation trace = Scaled(motion, kStripeTraceFactor);
  const RunPolicies policies;
  model::RunControl control = file.run;
  control.method = model::Method::kEventDriven;
  control.output_interval_s = 0.0;
  control.energy_ledger = false;
  std::vector<double> factors;
  for (int i = 0; i < 60; ++i) factors.push_back(0.05 * std::pow(10.0, 2.0 * i / 59.0));
  const std::vector<StripeStart> starts =
      TraceStripes(model, trace, kStripeTraceFactor, control, policies, factors);

  // The trace's free steps, all of them (no observer stops it).
  ASSERT_EQ(starts.size(), factors.size());
  StepLog log;
  SimulationWorkspace workspace(model);
  const RunResult run = Simulate(model, trace, control, workspace, {}, policies.event, &log);
  ASSERT_EQ(run.status, RunStatus::kOk);
  ASSERT_TRUE(run.events.empty());
  ASSERT_GT(log.steps.size(), 1000u);

  const int n = model.n_dof(), nc = model.n_contacts();
  double length_m = 1.0;  // the integrator's length scale (SimulationWorkspace)
  for (const model::Body& body : model.bodies()) {
    length_m = std::max({length_m, body.geometry.length_m, body.geometry.width_m,
                         body.rest_position_m.norm() + body.geometry.length_m});
  }
  const EventPolicy& policy = policies.event;
  LinearFlow flow(model.M(), model.K(), model.C(), model.r(), FlowPath::kAuto, model.modes());
  FreeDenseOutput dense(flow.augmented_size());
  Eigen::VectorXd z_aug = Eigen::VectorXd::Zero(flow.augmented_size());
  contact::GapRateScratch scratch;
  scratch.Resize(model);
  int reached = 0, clear = 0;
  for (std::size_t s = 0; s < factors.size(); ++s) {
    SCOPED_TRACE("factor " + std::to_string(factors[s]));
    const double c = factors[s] / kStripeTraceFactor;
    CornerTravelTracker travel(model);
    Eigen::VectorXd max_travel;
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    travel.Start(zero, max_travel);
    Eigen::VectorXd g0(nc), gN0(nc), g1(nc), gN1(nc);
    contact::GapsAndRates(model, zero, zero, g0, gN0, scratch);
    double restart_s = -1.0;
    Eigen::VectorXd restart_z0;
    for (const StepLog::Kept& step : log.steps) {
      const Eigen::VectorXd q0 = c * step.z0.head(n), u0 = c * step.z0.segment(n, n);
      const Eigen::VectorXd q1 = c * step.z1.head(n), u1 = c * step.z1.segment(n, n);
      const double tau = step.t1 - step.t0;
      contact::GapsAndRates(model, q1, u1, g1, gN1, scratch);
      bool reach = false;
      for (int k = 0; k < nc; ++k) {
        const double gap = std::min(g0[k], g1[k]) - 1e-9 * length_m;
        const double dip =
            policy.dip_margin * 0.5 * std::max(std::abs(gN0[k]), std::abs(gN1[k])) * tau;
        if (!(gap > dip)) reach = true;
      }
      if (reach) {
        restart_s = step.t0;
        restart_z0 = step.z0;
        break;
      }
      const double tolerance = policy.maximum_time_tolerance * std::max(1.0, std::abs(step.t1)) +
                               policy.event_time_floor_s;
      bool built = false;
      const auto component_at = [&](double t, int i) {
        if (!built) {
          z_aug.head(2 * n) = step.z0;
          const ExcitationPiece piece = trace.PieceAt(step.t0);
          flow.SetGenerator(piece, step.t0, z_aug);
          dense.Build(flow, piece.omega, z_aug, tau);
          built = true;
        }
        return c * dense.EvaluateComponent(t - step.t0, i);
      };
      travel.Scan(step.t0, q0, u0, step.t1, q1, u1, tolerance, component_at, max_travel);
      std::swap(g0, g1);
      std::swap(gN0, gN1);
    }
    const StripeStart& start = starts[s];
    ASSERT_EQ(start.reaches_gap, restart_s >= 0.0);
    if (start.reaches_gap) {
      ++reached;
      EXPECT_EQ(Bits(start.state.t_s), Bits(restart_s));
      for (int i = 0; i < n; ++i) {
        EXPECT_EQ(Bits(start.state.q[i]), Bits(c * restart_z0[i])) << "q " << i;
      }
    } else {
      ++clear;
    }
    ASSERT_EQ(start.linear.max_travel_m.size(), max_travel.size());
    for (Eigen::Index d = 0; d < max_travel.size(); ++d) {
      EXPECT_EQ(Bits(start.linear.max_travel_m[d]), Bits(max_travel[d])) << "deck " << d;
    }
  }
  // The factors straddle the first contact, and many stripes restart late in the record.
  EXPECT_GE(reached, 10);
  EXPECT_GE(clear, 10);
}

TEST(StripeTrace, RestartsAndTravelsAreThoseOfTheExactGapsAtEveryStep) {
  // One deck on an uncoupled substructure (no rotation before an impact), and the pilot bridge,
  // whose deck turns under a record along x (the gaps' bound through |theta| |p|).
  {
    SCOPED_TRACE("one deck, uncoupled");
    ExpectTraceIsTheBruteForce(model::ParseModelFile(kDataDir + "/models/one-deck-records.toml"));
  }
  // The pilot bridge with its centre of rigidity 8 m from the mass centre: the deck turns by as
  // much as its corners translate, so that the gaps' bound through |theta| |p| decides.
  const std::string examples = kDataDir + "/../../docs/examples";
  std::ifstream in(examples + "/pilot-bridge.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string pilot = text.str();
  const std::size_t at = pilot.find("e_x = -0.24");
  ASSERT_NE(at, std::string::npos);
  pilot.replace(at, 11, "e_x = -8.00");
  SCOPED_TRACE("pilot bridge, eccentric");
  ExpectTraceIsTheBruteForce(model::ParseModelString(pilot, "pilot-bridge.toml", examples));
}

}  // namespace
}  // namespace skewbridge::dynamics::stripes_test
