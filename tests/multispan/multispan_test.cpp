// Multi-span bridges through both integrators: one span from the generator runs bit for bit as
// the single-deck model; two identical decks with a closed frictionless joint under uniform
// excitation move as one rigid deck of twice the length (a second, independent model); the
// three-span example and 10- and 20-span bridges have the same maxima under both integrators; the
// sparse and dense linear algebra of the time-stepping scheme agree on 2, 5 and 20 spans.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/common/error.h"
#include "solver/dynamics/simulate.h"
#include "solver/dynamics/time_stepping.h"
#include "solver/model/model_file.h"
#include "solver/model/multispan.h"

namespace skewbridge::multispan_test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

model::MultiSpanSpec Bridge(int n_spans, double skew_deg, double joint_gap_m, double mu) {
  model::MultiSpanSpec spec;
  spec.n_spans = n_spans;
  spec.span_lengths_m = {30.0};
  spec.width_m = 10.0;
  spec.skew_rad = skew_deg * kDeg;
  spec.mass_per_length_kgpm = 20e3;
  spec.w0x_radps = spec.w0y_radps = 8.0;
  spec.W0_radps = 10.0;
  spec.xi = 0.05;
  spec.abutment_gap_m = 0.02;
  spec.joint_gap_m = joint_gap_m;
  spec.restitution = 0.5;
  spec.friction = mu;
  return spec;
}

// A one-cycle cosine pulse along x, a_g = 0.5 g, T = 0.6 s.
records::PulseExcitation Pulse() {
  return records::PulseExcitation(records::PulseShape::kCosine, 0.5 * 9.80665,
                                  2.0 * std::numbers::pi / 0.6, Eigen::Vector2d::UnitX());
}

void ExpectIdentical(const dynamics::RunResult& a, const dynamics::RunResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.impacts, b.impacts);
  EXPECT_EQ(a.events.size(), b.events.size());
  ASSERT_EQ(a.max_abs_q.size(), b.max_abs_q.size());
  for (int i = 0; i < a.max_abs_q.size(); ++i) {
    EXPECT_EQ(a.max_abs_q(i), b.max_abs_q(i)) << "dof " << i;
    EXPECT_EQ(a.time_of_max_s(i), b.time_of_max_s(i)) << "dof " << i;
    EXPECT_EQ(a.q_end(i), b.q_end(i)) << "dof " << i;
    EXPECT_EQ(a.u_end(i), b.u_end(i)) << "dof " << i;
  }
  EXPECT_EQ(a.histories.q, b.histories.q);
  EXPECT_EQ(a.energy.impact_J, b.energy.impact_J);
}

TEST(MultiSpan, OneSpanFromTheGeneratorRunsBitForBitAsTheSingleDeckModel) {
  const model::MultiSpanSpec spec = Bridge(1, 30.0, 0.0, 0.2);
  const model::Model generated = model::BuildMultiSpanBridge(spec);
  model::DeckSpec deck;
  deck.mass_kg = 20e3 * 30.0;
  deck.geometry = {30.0, 10.0, 30.0 * kDeg};
  deck.w0x_radps = deck.w0y_radps = 8.0;
  deck.W0_radps = 10.0;
  deck.xi = 0.05;
  deck.abutments = model::AbutmentSet::kBoth;
  deck.gap_plus_m = deck.gap_minus_m = 0.02;
  deck.restitution = 0.5;
  deck.friction = 0.2;
  const model::Model single = model::BuildDeckModel(deck);

  const records::PulseExcitation pulse = Pulse();
  model::RunControl control;
  control.tail_s = 1.0;
  control.output_interval_s = 0.01;
  dynamics::SimulationWorkspace ws_generated(generated), ws_single(single);
  const dynamics::RunResult a = dynamics::Simulate(generated, pulse, control, ws_generated);
  const dynamics::RunResult b = dynamics::Simulate(single, pulse, control, ws_single);
  ASSERT_EQ(a.status, dynamics::RunStatus::kOk) << a.message;
  EXPECT_GT(a.impacts, 0);
  ExpectIdentical(a, b);

  control.time_step_s = 1e-3;
  dynamics::TimeSteppingWorkspace ts_generated(generated), ts_single(single);
  ExpectIdentical(dynamics::SimulateTimeStepping(generated, pulse, control, ts_generated),
                  dynamics::SimulateTimeStepping(single, pulse, control, ts_single));
}

// Two decks of length L, mass m against one deck of length 2 L, mass 2 m on a support of twice
// the stiffness (the same frequencies): with a = 0, a closed joint and no friction, the pair
// bounces off each abutment as one body, so x_0 = x_1 = x of the long deck and nothing rotates.
TEST(MultiSpan, TwoIdenticalDecksWithAClosedFrictionlessJointMoveAsOneRigidDeck) {
  const model::Model pair = model::BuildMultiSpanBridge(Bridge(2, 0.0, 0.0, 0.0));
  model::MultiSpanSpec long_spec = Bridge(1, 0.0, 0.0, 0.0);
  long_spec.span_lengths_m = {60.0};
  const model::Model one = model::BuildMultiSpanBridge(long_spec);

  const records::PulseExcitation pulse = Pulse();
  model::RunControl control;
  // The whole pulse and its default tail: the joint stays closed with a force that is zero up to
  // rounding, which is neither a detachment nor an event.
  control.output_interval_s = 0.005;
  dynamics::SimulationWorkspace ws_pair(pair), ws_one(one);
  const dynamics::RunResult a = dynamics::Simulate(pair, pulse, control, ws_pair);
  const dynamics::RunResult b = dynamics::Simulate(one, pulse, control, ws_one);
  ASSERT_EQ(a.status, dynamics::RunStatus::kOk) << a.message;
  ASSERT_EQ(b.status, dynamics::RunStatus::kOk) << b.message;
  EXPECT_GE(b.impacts, 3);
  const std::size_t n_samples = a.histories.t_s.size();
  ASSERT_EQ(n_samples, b.histories.t_s.size());
  const double scale = b.max_abs_q(0);
  for (std::size_t s = 0; s < n_samples; ++s) {
    const double* q = &a.histories.q[6 * s];
    EXPECT_NEAR(q[0], q[3], 1e-12 * scale) << "t = " << a.histories.t_s[s];
    EXPECT_NEAR(q[0], b.histories.q[3 * s], 1e-8 * scale) << "t = " << a.histories.t_s[s];
    for (int k : {1, 2, 4, 5}) {
      EXPECT_NEAR(q[k], 0.0, 1e-12 * scale) << "dof " << k << " t = " << a.histories.t_s[s];
    }
  }
  // The joint (contacts 2, 3) never opens, so it never strikes again: it takes part in the
  // abutment impacts as a closed contact (gamma_N,A = 0) that passes the impulse on.
  for (const dynamics::EventRecord& e : a.events) {
    if ((e.contact == 2 || e.contact == 3) && e.kind == dynamics::EventKind::kImpact) {
      EXPECT_NEAR(e.gamma_N_before_mps, 0.0, 1e-12) << "joint closure at t = " << e.t_s;
      EXPECT_NEAR(e.gamma_N_after_mps, 0.0, 1e-12) << "joint opened at t = " << e.t_s;
    }
  }
}

TEST(MultiSpan, SparseAndDenseTimeSteppingAgreeOnTwoFiveAndTwentySpans) {
  const records::PulseExcitation pulse = Pulse();
  for (int n_spans : {2, 5, 20}) {
    const model::Model model = model::BuildMultiSpanBridge(Bridge(n_spans, 30.0, 0.01, 0.2));
    model::RunControl control;
    control.tail_s = 0.6;
    control.output_interval_s = 0.01;
    control.time_step_s = 1e-3;
    dynamics::TimeSteppingWorkspace ws(model);
    control.linear_algebra = "dense";
    const dynamics::RunResult dense = dynamics::SimulateTimeStepping(model, pulse, control, ws);
    control.linear_algebra = "sparse";
    const dynamics::RunResult sparse = dynamics::SimulateTimeStepping(model, pulse, control, ws);
    ASSERT_EQ(dense.status, dynamics::RunStatus::kOk) << dense.message;
    ASSERT_EQ(sparse.status, dynamics::RunStatus::kOk) << sparse.message;
    EXPECT_GT(dense.impacts, n_spans) << "the joints must pound for the test to mean anything";
    EXPECT_EQ(dense.impacts, sparse.impacts);
    const double scale = dense.max_abs_q.maxCoeff();
    for (int i = 0; i < model.n_dof(); ++i) {
      EXPECT_NEAR(dense.max_abs_q(i), sparse.max_abs_q(i), 1e-10 * scale) << "dof " << i;
      EXPECT_NEAR(dense.q_end(i), sparse.q_end(i), 1e-10 * scale) << "dof " << i;
    }
    ASSERT_EQ(dense.histories.q.size(), sparse.histories.q.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < dense.histories.q.size(); ++k) {
      worst = std::max(worst, std::abs(dense.histories.q[k] - sparse.histories.q[k]));
    }
    EXPECT_LE(worst, 1e-10 * scale) << n_spans << " spans";
    EXPECT_NEAR(dense.energy.impact_J, sparse.energy.impact_J,
                1e-10 * std::abs(dense.energy.impact_J));
  }
}

// The three-span example through both integrators: time-stepping with h = 1e-4 s converges to
// the event-driven motion (first order with impacts), so every deck's maxima agree to 1 %.
TEST(MultiSpan, ThreeSpanExampleHasTheSameMaximaUnderBothIntegrators) {
  const model::ModelFile file = model::ParseModelFile(std::string(SKEWBRIDGE_TEST_DATA_DIR) +
                                                      "/../../docs/examples/three-span.toml");
  const model::ExcitationSpec& ex = file.excitation;
  const records::PulseExcitation pulse(records::PulseShape::kCosine, ex.amplitude_mps2,
                                       ex.omega_radps, ex.direction);
  model::RunControl control = file.run;
  control.output_interval_s = 0.0;
  dynamics::SimulationWorkspace ws(file.model);
  const dynamics::RunResult event_driven = dynamics::Simulate(file.model, pulse, control, ws);
  control.time_step_s = 1e-4;
  dynamics::TimeSteppingWorkspace ts(file.model);
  const dynamics::RunResult stepped =
      dynamics::SimulateTimeStepping(file.model, pulse, control, ts);
  ASSERT_EQ(event_driven.status, dynamics::RunStatus::kOk) << event_driven.message;
  ASSERT_EQ(stepped.status, dynamics::RunStatus::kOk) << stepped.message;
  EXPECT_GT(event_driven.impacts, 3);
  for (int i = 0; i < file.model.n_dof(); ++i) {
    EXPECT_NEAR(stepped.max_abs_q(i), event_driven.max_abs_q(i), 0.01 * event_driven.max_abs_q(i))
        << "dof " << i;
  }
}

// Ten and twenty spans (22 and 42 contacts, beyond the 24-row fixed-capacity active set)
// through both integrators: the event-driven run reaches the end, and time-stepping with
// h = 1e-4 s agrees on every deck's maxima within 3 % (first-order convergence with impacts,
// checked to 1 % on three spans above; more joints pound here, so the bound is looser).
TEST(MultiSpan, TenAndTwentySpansRunEventDrivenToTheEndWithTheTimeSteppingMaxima) {
  const records::PulseExcitation pulse = Pulse();
  for (int n_spans : {10, 20}) {
    const model::Model model = model::BuildMultiSpanBridge(Bridge(n_spans, 30.0, 0.01, 0.2));
    ASSERT_GT(2 * model.n_contacts(), 24);
    model::RunControl control;
    control.tail_s = 0.6;
    dynamics::SimulationWorkspace ws(model);
    const dynamics::RunResult event_driven = dynamics::Simulate(model, pulse, control, ws);
    control.time_step_s = 1e-4;
    dynamics::TimeSteppingWorkspace ts(model);
    const dynamics::RunResult stepped = dynamics::SimulateTimeStepping(model, pulse, control, ts);
    ASSERT_EQ(event_driven.status, dynamics::RunStatus::kOk) << event_driven.message;
    ASSERT_EQ(stepped.status, dynamics::RunStatus::kOk) << stepped.message;
    EXPECT_GT(event_driven.impacts, n_spans) << "the joints must pound for the test to mean "
                                                "anything";
    const double scale = event_driven.max_abs_q.maxCoeff();
    for (int i = 0; i < model.n_dof(); ++i) {
      EXPECT_NEAR(stepped.max_abs_q(i), event_driven.max_abs_q(i),
                  0.03 * std::max(event_driven.max_abs_q(i), 0.1 * scale))
          << n_spans << " spans, dof " << i;
    }
  }
}

TEST(MultiSpan, AutoLinearAlgebraSwitchesToSparseAtTheThreshold) {
  model::RunControl control;
  const model::Model small = model::BuildMultiSpanBridge(Bridge(1, 30.0, 0.01, 0.2));
  const int big_spans = (dynamics::kSparseThresholdDof + 2) / 3;
  const model::Model big = model::BuildMultiSpanBridge(Bridge(big_spans, 30.0, 0.01, 0.2));
  EXPECT_FALSE(dynamics::UsesSparseLinearAlgebra(small, control));
  EXPECT_TRUE(dynamics::UsesSparseLinearAlgebra(big, control));
  control.linear_algebra = "sparse";
  EXPECT_TRUE(dynamics::UsesSparseLinearAlgebra(small, control));
  control.linear_algebra = "dense";
  EXPECT_FALSE(dynamics::UsesSparseLinearAlgebra(big, control));
  control.linear_algebra = "cholesky";
  EXPECT_THROW(dynamics::UsesSparseLinearAlgebra(big, control), InputError);
}

}  // namespace
}  // namespace skewbridge::multispan_test
