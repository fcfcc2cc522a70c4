/// @file
/// A single deck of zero skew held against its abutment (gap 0, mu = 0.3) under a cosine
/// pulse, integrated by the Moreau-Jean scheme: its velocity-level LCP at t = 0.7042 s (two
/// active contacts) ended on a secondary ray, and the run stopped with lcp-failure, until
/// Lemke's method read entries of q within its tolerance of zero as zero (solver/lcp). The
/// same deck under the event-driven integrator is the reference.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <numbers>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "solver/dynamics/time_stepping.h"
#include "solver/model/builders.h"

namespace skewbridge::zero_skew_time_stepping_test {
namespace {

/// docs/examples/subsystem.toml with a = 0 (W = 6.495 m), gap 0 and mu = 0.3.
model::Model ZeroSkewDeckAgainstItsAbutment() {
  model::DeckSpec deck;
  deck.mass_kg = 500e3;
  deck.geometry = {30.0, 6.495, 0.0};
  deck.stiffness = model::DeckSpec::StiffnessKind::kUncoupled;
  deck.w0x_radps = 12.0;
  deck.w0y_radps = 12.0;
  deck.W0_radps = 12.0;
  deck.xi = 0.05;
  deck.abutments = model::AbutmentSet::kPlusX;
  deck.gap_plus_m = 0.0;
  deck.restitution = 0.5;
  deck.friction = 0.3;
  return model::BuildDeckModel(deck, "zero-skew");
}

TEST(ZeroSkewTimeStepping, RunsThroughAndMatchesTheEventDrivenMaximum) {
  const model::Model model = ZeroSkewDeckAgainstItsAbutment();
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 0.5 * 9.80665,
                                       2.0 * std::numbers::pi / 0.5);
  model::RunControl control;
  control.end_time_s = 2.5;
  control.time_step_s = 1e-4;

  dynamics::SimulationWorkspace exact_workspace(model);
  const dynamics::RunResult exact = dynamics::Simulate(model, pulse, control, exact_workspace);
  ASSERT_EQ(exact.status, dynamics::RunStatus::kOk) << exact.message;
  ASSERT_GT(exact.impacts, 0);

  dynamics::TimeSteppingWorkspace workspace(model);
  const dynamics::RunResult run = dynamics::SimulateTimeStepping(model, pulse, control, workspace);
  ASSERT_EQ(run.status, dynamics::RunStatus::kOk) << run.message;
  EXPECT_DOUBLE_EQ(run.end_time_s, 2.5);
  // The time-stepping maximum is within 2 % of the event-driven one, as for the example
  // subsystem in docs/validation.md; a deck without skew does not turn [docs/theory.md §4 fact 3].
  EXPECT_NEAR(run.max_abs_q(0), exact.max_abs_q(0), 0.02 * exact.max_abs_q(0));
  EXPECT_LE(run.max_abs_q(2), 1e-12);
}

}  // namespace
}  // namespace skewbridge::zero_skew_time_stepping_test
