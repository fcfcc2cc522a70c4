/// The free step's gap bound (solver/dynamics/gap_bound.h) [docs/theory.md §3.18] against a dense
/// evaluation of every corner's gap along the exact flow, propagated on the augmented path (the
/// matrix exponential, no modal code): random states and inputs, forcing alone, resonant
/// harmonics, an undamped deck, long steps, and grazing steps whose smallest gap is a hair above
/// zero, which the bound must never call open.

#include "solver/dynamics/gap_bound.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "solver/contact/kinematics.h"
#include "solver/dynamics/gap_floors.h"
#include "solver/dynamics/linear_flow.h"
#include "solver/model/builders.h"
#include "solver/model/multispan.h"
#include "tests/dynamics/eccentric_deck.h"

namespace skewbridge::dynamics::gap_bound_test {
namespace {

struct Step {
  Eigen::VectorXd z;  // (q, u, a, slope, p, k) at the step's start
  double tau_s = 0.01;
  double omega_radps = 0.0;
};

// Per contact, the smallest g(s) - g(0) over 256 points of the step along the augmented flow.
Eigen::VectorXd DenseDrop(const model::Model& model, LinearFlow& augmented, const Step& step) {
  constexpr int kPoints = 256;
  const int n = model.n_dof();
  const FreePropagator& p = augmented.Propagator(step.tau_s / kPoints, step.omega_radps, false);
  Eigen::VectorXd z = step.z, z_next = z;
  Eigen::VectorXd g0(model.n_contacts()), worst = Eigen::VectorXd::Zero(model.n_contacts());
  for (int c = 0; c < model.n_contacts(); ++c) g0[c] = contact::Gap(model, c, z.head(n));
  for (int i = 1; i <= kPoints; ++i) {
    augmented.Apply(p, z, z_next);
    z.swap(z_next);
    for (int c = 0; c < model.n_contacts(); ++c) {
      worst[c] = std::min(worst[c], contact::Gap(model, c, z.head(n)) - g0[c]);
    }
  }
  return worst;
}

// Per contact, the bound's closure sum_k W_ck D_k of the step, from the modal path's coordinates.
Eigen::VectorXd BoundDrop(const model::Model& model, LinearFlow& modal, const Step& step) {
  const ModalGapBound bound(model, modal.modal_flow());
  EXPECT_TRUE(bound.applies());
  const FreePropagator& p = modal.Propagator(step.tau_s, step.omega_radps, false);
  Eigen::VectorXd z_next = step.z;
  modal.Apply(p, step.z, z_next);
  Eigen::VectorXd drift(model.n_dof()), out(model.n_contacts());
  ModalDrift(bound, modal.modal_coordinates().data(), step.tau_s, drift.data());
  for (int c = 0; c < model.n_contacts(); ++c) out[c] = GapClosureBound(bound, c, drift.data());
  return out;
}

// Random steps of one kind; each contact's dense drop must lie within the bound.
void CheckSteps(double xi, int count, unsigned seed, double q_scale, double u_scale, double a_scale,
                double tau_s, bool resonant) {
  const model::Model model = testing::EccentricDeck(xi);
  LinearFlow modal(model.M(), model.K(), model.C(), model.r());
  LinearFlow augmented(model.M(), model.K(), model.C(), model.r(), FlowPath::kAugmented);
  ASSERT_TRUE(modal.modal());
  const int n = model.n_dof();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double tightest = 0.0;  // the largest dense drop / bound seen
  for (int s = 0; s < count; ++s) {
    Step step;
    step.tau_s = tau_s;
    step.z = Eigen::VectorXd::Zero(modal.augmented_size());
    for (int i = 0; i < n; ++i) {
      const double length = i % 3 == 2 ? 1.0 / 15.0 : 1.0;  // theta in rad, x and y in m
      step.z[i] = q_scale * length * unit(rng);
      step.z[n + i] = u_scale * length * unit(rng);
    }
    for (int j = 0; j < 8; ++j) step.z[2 * n + j] = a_scale * unit(rng);
    step.z[2 * n + 2] *= 50.0;  // slopes of a record: the acceleration changes by 0.5 a per 0.01 s
    step.z[2 * n + 3] *= 50.0;
    if (resonant) {
      const int k = s % n;
      step.omega_radps = std::sqrt(modal.modal_flow().w2()[k]);
    } else {
      step.omega_radps = s % 2 == 0 ? 0.0 : 40.0 * std::abs(unit(rng));
    }
    const Eigen::VectorXd dense = DenseDrop(model, augmented, step);
    const Eigen::VectorXd bound = BoundDrop(model, modal, step);
    for (int c = 0; c < model.n_contacts(); ++c) {
      // The bound is exact arithmetic of the flow; the dense gaps carry the rounding of the
      // deck's world coordinates (about 1e-15 m) on top.
      ASSERT_GE(dense[c], -bound[c] - 1e-13) << "step " << s << " contact " << c;
      if (bound[c] > 0.0) tightest = std::max(tightest, -dense[c] / bound[c]);
    }
  }
  // A bound of no use (orders of magnitude above the motion) would pass the check above too.
  EXPECT_GT(tightest, 0.05);
}

TEST(GapBound, HoldsOnRandomStepsOfADampedDeck) {
  CheckSteps(0.05, 300, 1, 0.05, 0.5, 5.0, 0.01, false);
}

TEST(GapBound, HoldsOnAnUndampedDeckAndLongSteps) {
  CheckSteps(0.0, 150, 2, 0.05, 0.5, 5.0, 0.05, false);
}

TEST(GapBound, HoldsUnderForcingAloneFromRest) {
  // Zero state: the whole closure is the input's tau^2 F / 2 term.
  CheckSteps(0.05, 150, 3, 0.0, 0.0, 5.0, 0.02, false);
}

TEST(GapBound, HoldsAtResonance) { CheckSteps(0.02, 150, 4, 0.01, 0.1, 5.0, 0.04, true); }

TEST(GapBound, HoldsOnFreeVibrationOfLargeRotation) {
  // No input, rotation dominant: the arm's term carries the closure.
  CheckSteps(0.05, 150, 5, 0.3, 3.0, 0.0, 0.01, false);
}

TEST(GapBound, ADecksDriftsWithoutHarmonicColumnsAreTheBitsOfTheGeneralLoop) {
  // A record's piece (omega 0, no harmonic generator): ModalDrift3<false> leaves out the
  // harmonic columns' magnitudes, which are +0; its drifts must be the bits of ModalDrift's
  // general loop and of ModalDrift3<true>, and GapFloors must take the same decisions and sums.
  const model::Model model = testing::EccentricDeck(0.05);
  LinearFlow modal(model.M(), model.K(), model.C(), model.r());
  ASSERT_TRUE(modal.modal());
  const ModalGapBound bound(model, modal.modal_flow());
  ASSERT_EQ(bound.n_modes, 3);
  const int n = model.n_dof();
  std::mt19937 rng(71u);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  GapFloors with(bound), without(bound);
  const Eigen::VectorXd gaps = Eigen::VectorXd::Constant(model.n_contacts(), 0.05);
  with.Restart(gaps);
  without.Restart(gaps);
  int open_steps = 0;
  for (int s = 0; s < 600; ++s) {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(modal.augmented_size()), z_next = z;
    for (int i = 0; i < 2 * n; ++i) z[i] = 1e-4 * unit(rng);
    for (int j = 0; j < 4; ++j) z[2 * n + j] = (j < 2 ? 1.0 : 50.0) * unit(rng);
    if (s % 7 == 0) z[2 * n] = -0.0;  // signed zeros of the forcing
    modal.Apply(modal.Propagator(0.01, 0.0, false), z, z_next);
    const double* Y = modal.modal_coordinates().data();
    double general[3], plain[3], harmonic[3], lanes[3];
    ModalDrift(bound, Y, 0.01, general);
    ModalDrift3<false>(bound, Y, 0.01, plain);
    ModalDrift3<true>(bound, Y, 0.01, harmonic);
    ModalDrift3Lanes(bound, Y, 0.01, lanes);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(std::signbit(plain[k]), std::signbit(general[k])) << "step " << s;
      EXPECT_EQ(plain[k], general[k]) << "step " << s << " mode " << k;
      EXPECT_EQ(harmonic[k], general[k]) << "step " << s << " mode " << k;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(lanes[k]), std::bit_cast<std::uint64_t>(plain[k]))
          << "step " << s << " mode " << k;
    }
    const bool a = with.StaysOpen(Y, 0.01, 1e-6, true);
    const bool b = without.StaysOpen(Y, 0.01, 1e-6, false);
    ASSERT_EQ(a, b) << "step " << s;
    if (!a) {
      with.Restart(gaps);
      without.Restart(gaps);
    } else {
      ++open_steps;
    }
  }
  // Both answers occur: runs of open steps long enough to fold, and steps the sums close.
  EXPECT_GT(open_steps, 256);
  EXPECT_LT(open_steps, 600);
}

TEST(GapBound, NeverCallsAGrazingStepOpen) {
  // Each step's faces moved so that the smallest gap inside it is 1e-9 m: the start's gap minus
  // the bound must not stay above zero (the rule then searches the step).
  const model::Model model = testing::EccentricDeck(0.05);
  LinearFlow modal(model.M(), model.K(), model.C(), model.r());
  LinearFlow augmented(model.M(), model.K(), model.C(), model.r(), FlowPath::kAugmented);
  const int n = model.n_dof();
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int grazes = 0;
  for (int s = 0; s < 200; ++s) {
    Step step;
    step.z = Eigen::VectorXd::Zero(modal.augmented_size());
    for (int i = 0; i < n; ++i) {
      step.z[i] = 0.02 * unit(rng);
      step.z[n + i] = 0.3 * unit(rng) / (i % 3 == 2 ? 15.0 : 1.0);
    }
    step.z[2 * n] = 3.0 * unit(rng);
    step.z[2 * n + 1] = 3.0 * unit(rng);
    const Eigen::VectorXd dense = DenseDrop(model, augmented, step);
    const Eigen::VectorXd bound = BoundDrop(model, modal, step);
    for (int c = 0; c < model.n_contacts(); ++c) {
      // A face shifted so that min g = 1e-9 m has g(0) = 1e-9 - dense[c] at the start.
      const double g0 = 1e-9 - dense[c];
      EXPECT_LE(g0 - bound[c], 1e-9) << "step " << s << " contact " << c;
      ++grazes;
    }
  }
  EXPECT_EQ(grazes, 800);
}

// Two 30 m spans of a 12 m wide deck at 0.5 rad skew, 20 rad/s in every direction, 50 mm gaps:
// the corners of one deck strike a face on the other, where the modal gap bound does not apply.
model::Model TwoSpans() {
  model::MultiSpanSpec spec;
  spec.n_spans = 2;
  spec.span_lengths_m = {30.0};
  spec.width_m = 12.0;
  spec.skew_rad = 0.5;
  spec.mass_per_length_kgpm = 5e4;
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = 20.0;
  spec.abutment_gap_m = spec.joint_gap_m = 0.05;
  return model::BuildMultiSpanBridge(spec);
}

TEST(GapBound, DoesNotApplyToAJointBetweenBodiesOrNegativeDamping) {
  model::Model deck = testing::EccentricDeck(0.05);
  LinearFlow modal(deck.M(), deck.K(), deck.C(), deck.r());
  EXPECT_TRUE(ModalGapBound(deck, modal.modal_flow()).applies());
  // A model whose C is the negative of a classical damping (an energy source).
  LinearFlow source(deck.M(), deck.K(), -deck.C(), deck.r());
  ASSERT_TRUE(source.modal());
  EXPECT_FALSE(ModalGapBound(deck, source.modal_flow()).applies());
  // Two spans: the corners of one deck against a face on the other.
  const model::Model spans = TwoSpans();
  LinearFlow spans_flow(spans.M(), spans.K(), spans.C(), spans.r());
  ASSERT_TRUE(spans_flow.modal());
  EXPECT_FALSE(ModalGapBound(spans, spans_flow.modal_flow()).applies());
}

// One bound assigned model after model (a deck, the same deck with negative damping, two spans,
// the deck again) holds each time what the definition gives for that model alone: the weights
// W_ck = |n_x Phi_xk + n_y Phi_yk| + |n| |p| |Phi_theta,k| and w_k = sqrt(w_k^2) bit for bit
// where the bound applies, nothing where it does not.
TEST(GapBound, AnAssignedBoundIsTheDefinitionOfEachModelInTurn) {
  const model::Model deck = testing::EccentricDeck(0.05);
  const model::Model spans = TwoSpans();
  const LinearFlow deck_flow(deck.M(), deck.K(), deck.C(), deck.r());
  const LinearFlow source_flow(deck.M(), deck.K(), -deck.C(), deck.r());
  const LinearFlow spans_flow(spans.M(), spans.K(), spans.C(), spans.r());
  struct Case {
    const model::Model& model;
    const LinearFlow& flow;
    bool applies;
  };
  const Case cases[] = {{deck, deck_flow, true},
                        {deck, source_flow, false},
                        {spans, spans_flow, false},
                        {deck, deck_flow, true}};
  ModalGapBound bound;
  for (const Case& c : cases) {
    bound.Assign(c.model, c.flow.modal_flow());
    const ModalFlow& modal = c.flow.modal_flow();
    ASSERT_EQ(bound.applies(), c.applies);
    if (!c.applies) {
      EXPECT_TRUE(bound.weights.empty());
      continue;
    }
    const int n = modal.n_modes();
    ASSERT_EQ(bound.n_modes, n);
    ASSERT_EQ(bound.n_contacts, c.model.n_contacts());
    ASSERT_EQ(bound.weights.size(), static_cast<std::size_t>(n * c.model.n_contacts()));
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(bound.w_radps[static_cast<std::size_t>(k)]),
                std::bit_cast<std::uint64_t>(std::sqrt(modal.w2()[k])));
    }
    const Eigen::MatrixXd& Phi = modal.Phi();
    for (int j = 0; j < c.model.n_contacts(); ++j) {
      const model::Contact& contact = c.model.contact(j);
      const Eigen::Vector2d& nrm = contact.face.normal;
      const int r = 3 * contact.body;
      for (int k = 0; k < n; ++k) {
        const double expected = std::abs(nrm.x() * Phi(r, k) + nrm.y() * Phi(r + 1, k)) +
                                nrm.norm() * contact.point_m.norm() * std::abs(Phi(r + 2, k));
        EXPECT_EQ(std::bit_cast<std::uint64_t>(bound.weights[static_cast<std::size_t>(j * n + k)]),
                  std::bit_cast<std::uint64_t>(expected))
            << "contact " << j << " mode " << k;
      }
    }
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::gap_bound_test
