// A workspace refitted from model to model (dynamics::RunReuse, SimulationWorkspace::Refit) gives
// the bits of a new workspace built for each model: over single decks with two and four
// abutment contacts (skews, frequencies, gaps, restitution and friction that differ from model to
// model), a deck with non-classical damping (the augmented flow, no gap bound) and three- and
// five-span bridges (joint contacts between decks), each run under a cosine pulse, in the order
// listed and in a shuffled order with repeats, so that every shape follows every other. The
// reference is Simulate in a workspace built for that model alone; the results compared bit for
// bit are the maxima and their times, the end state, the corner travels, the counts of steps and
// events and every event's time, also when each result is given back to the next run's storage.

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <random>
#include <vector>

#include "records/excitations.h"
#include "solver/common/error.h"
#include "solver/dynamics/run.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/builders.h"
#include "solver/model/multispan.h"
#include "tests/dynamics/run_bits.h"

namespace skewbridge::dynamics::run_reuse_test {
namespace {

// One deck of the subsystem's kind (10 m long, eta0-like proportions) against the +x abutment
// (or both), its frequencies, skew, gap and contact laws varied by `k`.
model::Model Deck(int k, model::AbutmentSet set, bool non_classical) {
  model::DeckSpec d;
  d.mass_kg = 1.0e6;
  d.geometry = {30.0, 10.0 + 2.0 * k, (10.0 + 9.0 * k) * std::numbers::pi / 180.0};
  d.w0x_radps = 6.0 + 1.3 * k;
  d.w0y_radps = 5.0 + 0.7 * k;
  d.W0_radps = 7.5 + 0.9 * k;
  d.xi = 0.02 + 0.01 * k;
  d.abutments = set;
  d.gap_plus_m = d.gap_minus_m = 0.004 + 0.002 * k;
  d.restitution = 0.3 + 0.1 * k;
  d.friction = 0.1 * (k % 3);
  if (non_classical) {
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    C.diagonal() << 2.0e5, 3.0e5, 4.0e7;
    C(0, 2) = C(2, 0) = 1.0e6;  // couples x and theta: Phi^T C Phi is not diagonal
    d.C = C;
  }
  return model::BuildDeckModel(d, "deck");
}

model::Model Spans(int n, int k) {
  model::MultiSpanSpec b;
  b.n_spans = n;
  b.span_lengths_m = {30.0 + 3.0 * k};
  b.width_m = 12.0;
  b.skew_rad = (20.0 + 5.0 * k) * std::numbers::pi / 180.0;
  b.mass_per_length_kgpm = 3.0e4;
  b.w0x_radps = b.w0y_radps = 6.0 + k;
  b.W0_radps = 8.0 + k;
  b.abutment_gap_m = 0.01;
  b.joint_gap_m = 0.005;
  return model::BuildMultiSpanBridge(b, "spans");
}

TEST(RunReuse, RefittedWorkspaceGivesTheBitsOfANewOneOverShapesInOrderAndShuffled) {
  std::vector<model::Model> models;
  for (int k = 0; k < 4; ++k) {
    models.push_back(Deck(k, model::AbutmentSet::kPlusX, false));
    models.push_back(Deck(k, model::AbutmentSet::kBoth, false));
  }
  models.push_back(Deck(1, model::AbutmentSet::kPlusX, true));
  models.push_back(Deck(2, model::AbutmentSet::kPlusX, true));
  models.push_back(Spans(3, 0));
  models.push_back(Spans(3, 1));
  models.push_back(Spans(5, 0));

  const records::PulseExcitation pulse(records::PulseShape::kCosine, 4.0, 2.0 * std::numbers::pi);
  model::RunControl control;
  control.end_time_s = 3.0;
  control.energy_ledger = false;

  std::vector<RunResult> fresh;
  long impacts = 0;
  for (const model::Model& m : models) {
    SimulationWorkspace ws(m);
    fresh.push_back(Simulate(m, pulse, control, ws));
    ASSERT_EQ(fresh.back().status, RunStatus::kOk) << fresh.back().message;
    impacts += fresh.back().impacts;
  }
  // The runs strike their abutments: the contact problems' storage is used, not only the flow.
  ASSERT_GT(impacts, 10);

  std::vector<int> order;
  for (int i = 0; i < static_cast<int>(models.size()); ++i) order.push_back(i);
  std::vector<int> shuffled;
  std::mt19937 rng(20261129);
  for (int round = 0; round < 3; ++round) {
    std::vector<int> o = order;
    std::shuffle(o.begin(), o.end(), rng);
    shuffled.insert(shuffled.end(), o.begin(), o.end());
  }
  for (const std::vector<int>* sequence : {&order, &shuffled}) {
    RunReuse reuse;
    for (int i : *sequence) {
      SCOPED_TRACE(i);
      testing::ExpectSameRunBits(reuse.Run(models[static_cast<std::size_t>(i)], pulse, control),
                                 fresh[static_cast<std::size_t>(i)]);
    }
  }
  // And through Run, whose thread keeps one RunReuse for every caller.
  for (int i : shuffled) {
    SCOPED_TRACE(i);
    testing::ExpectSameRunBits(dynamics::Run(models[static_cast<std::size_t>(i)], pulse, control),
                               fresh[static_cast<std::size_t>(i)]);
  }
  // A model moved into the workspace (a sweep's cell) instead of copied, in both entries.
  for (int i : shuffled) {
    SCOPED_TRACE(i);
    model::Model copy = models[static_cast<std::size_t>(i)];
    testing::ExpectSameRunBits(dynamics::Run(std::move(copy), pulse, control),
                               fresh[static_cast<std::size_t>(i)]);
  }
  RunReuse moved;
  for (int i : shuffled) {
    SCOPED_TRACE(i);
    model::Model copy = models[static_cast<std::size_t>(i)];
    testing::ExpectSameRunBits(moved.Run(std::move(copy), pulse, control),
                               fresh[static_cast<std::size_t>(i)]);
  }
  // Each result given back once read (a sweep's cell): the next run's result, of another shape
  // or the same, takes its storage and still has the bits of a new workspace's, its event log
  // that run's alone.
  RunReuse recycled;
  for (int i : shuffled) {
    SCOPED_TRACE(i);
    RunResult run = recycled.Run(models[static_cast<std::size_t>(i)], pulse, control);
    testing::ExpectSameRunBits(run, fresh[static_cast<std::size_t>(i)]);
    recycled.Recycle(std::move(run));
  }
  for (int i : shuffled) {
    SCOPED_TRACE(i);
    model::Model copy = models[static_cast<std::size_t>(i)];
    RunResult run = dynamics::Run(std::move(copy), pulse, control);
    testing::ExpectSameRunBits(run, fresh[static_cast<std::size_t>(i)]);
    RecycleResult(std::move(run));
  }
}

// The workspace checks a policy once for runs that bring the same bytes: a policy outside its
// ranges after a valid one in the same workspace is still refused (each time), and a valid one
// after it runs with the bits of a new workspace.
TEST(RunReuse, AWorkspaceStillRefusesABadPolicyAfterAGoodOne) {
  const model::Model model = Deck(1, model::AbutmentSet::kPlusX, false);
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 4.0, 2.0 * std::numbers::pi);
  model::RunControl control;
  control.end_time_s = 3.0;
  EventPolicy bad;
  bad.finite_check_steps = 3;  // not a power of two
  EventPolicy other;
  other.finite_check_steps = 32;  // valid, other bytes
  SimulationWorkspace fresh_ws(model);
  const RunResult fresh = Simulate(model, pulse, control, fresh_ws);
  SimulationWorkspace ws(model);
  for (int round = 0; round < 2; ++round) {
    testing::ExpectSameRunBits(Simulate(model, pulse, control, ws), fresh);
    EXPECT_THROW(Simulate(model, pulse, control, ws, {}, bad), InputError);
    EXPECT_THROW(Simulate(model, pulse, control, ws, {}, bad), InputError);
    EXPECT_EQ(Simulate(model, pulse, control, ws, {}, other).status, RunStatus::kOk);
  }
  testing::ExpectSameRunBits(Simulate(model, pulse, control, ws), fresh);
}

// The contact problems and active systems of a workspace take a policy's thresholds when the run
// validates it: runs that alternate two valid policies whose contact thresholds and rank
// threshold differ (and whose runs end differently) give each policy's bits of a new workspace.
TEST(RunReuse, AWorkspaceTakesEachPolicysThresholdsWhenThePolicyChanges) {
  const model::Model model = Deck(1, model::AbutmentSet::kBoth, false);
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 4.0, 2.0 * std::numbers::pi);
  model::RunControl control;
  control.end_time_s = 3.0;
  EventPolicy other;
  other.contact.tie_tolerance *= 1e4;
  other.contact.contact_compliance *= 1e4;
  other.contact.impact_compliance *= 1e4;
  other.rank_threshold = 1e-3;
  SimulationWorkspace fresh_ws(model), fresh_other_ws(model);
  const RunResult fresh = Simulate(model, pulse, control, fresh_ws);
  const RunResult fresh_other = Simulate(model, pulse, control, fresh_other_ws, {}, other);
  ASSERT_EQ(fresh.status, RunStatus::kOk) << fresh.message;
  // Under the coarser thresholds the run ends otherwise (an event cascade at its first strike).
  ASSERT_NE(fresh_other.status, RunStatus::kOk);
  SimulationWorkspace ws(model);
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE(round);
    testing::ExpectSameRunBits(Simulate(model, pulse, control, ws), fresh);
    testing::ExpectSameRunBits(Simulate(model, pulse, control, ws, {}, other), fresh_other);
  }
}

// A run's energies at its ends are their definitions, 1/2 u^T M u + 1/2 q^T K q, with or without
// the ledger and in a reused workspace: +0.0 from rest (every form of a zero state), the forms'
// bits from a state given at the start, and the strain 1/2 q^T K q of the end state.
TEST(RunReuse, TheEnergiesAtTheRunsEndsAreTheirForms) {
  const model::Model model = Deck(2, model::AbutmentSet::kPlusX, false);
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 4.0, 2.0 * std::numbers::pi);
  InitialState moving;
  moving.q = Eigen::Vector3d(1.0e-3, -2.0e-3, 3.0e-5);
  moving.u = Eigen::Vector3d(-4.0e-2, 5.0e-3, -6.0e-4);
  const auto forms = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
    const Eigen::VectorXd Mu = model.M() * u, Kq = model.K() * q;
    return 0.5 * u.dot(Mu) + 0.5 * q.dot(Kq);
  };
  RunReuse reuse;
  for (const bool ledger : {false, true}) {
    model::RunControl control;
    control.end_time_s = 2.0;
    control.energy_ledger = ledger;
    for (int round = 0; round < 2; ++round) {
      const RunResult rest = reuse.Run(model, pulse, control);
      ASSERT_EQ(rest.status, RunStatus::kOk);
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
      EXPECT_EQ(testing::Bits(rest.energy.initial_J), testing::Bits(forms(zero, zero)));
      EXPECT_EQ(testing::Bits(rest.energy.strain_J), testing::Bits(forms(rest.q_end, zero)));
      const RunResult run = reuse.Run(model, pulse, control, {}, moving);
      ASSERT_EQ(run.status, RunStatus::kOk);
      EXPECT_EQ(testing::Bits(run.energy.initial_J), testing::Bits(forms(moving.q, moving.u)));
      EXPECT_EQ(testing::Bits(run.energy.strain_J), testing::Bits(forms(run.q_end, zero)));
    }
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::run_reuse_test
