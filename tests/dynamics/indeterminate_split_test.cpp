/// SplitIndeterminateForces (solver/dynamics/indeterminate_split.h) on its postconditions
/// [docs/theory.md §3.13], on the active sets of a skew deck's corners against its abutments:
/// the split forces still satisfy the equations of motion of the active set (A x = b), push, stay
/// inside the friction cones, carry no squeeze, and are the deepest split inside the cones found
/// by a brute-force scan along the kernel; a determinate system keeps its unique solution.

#include "solver/dynamics/indeterminate_split.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <cmath>
#include <numbers>

#include "solver/contact/kinematics.h"
#include "solver/model/builders.h"

namespace skewbridge::dynamics::indeterminate_split_test {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// A 30 deg skew deck, 30 m x 10 m, between both abutments at zero gap (P1, P2 on the +x face,
// P3, P4 on the -x face), friction mu.
model::Model ClampedDeck(double mu) {
  model::DeckSpec spec;
  spec.mass_kg = 1.0e5;
  spec.geometry = {30.0, 10.0, 30.0 * std::numbers::pi / 180.0};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = 2.0 * std::numbers::pi;
  spec.abutments = model::AbutmentSet::kBoth;
  spec.friction = mu;
  return model::BuildDeckModel(spec);
}

// The active set of the closed contacts `closed` (modes as given) at q = 0, u = 0 under the
// generalized load h (N, N, N m): rows W_N of the closed contacts in ascending order, then W_T
// of the sticking ones; the system is solved by ActiveSystem and split. Also returns A, b.
struct Case {
  MatrixXd A;
  VectorXd b, x;
  int k = 0, m = 0;
  bool rank_deficient = false;
};

Case SolveAndSplit(const model::Model& model, const ContactModes& modes, const VectorXd& h) {
  const int nc = model.n_contacts();
  contact::ContactKinematics kin;
  kin.Resize(model);
  const VectorXd zero = VectorXd::Zero(model.n_dof());
  contact::Evaluate(model, zero, zero, kin);
  std::vector<VectorXd> rows;
  for (int c = 0; c < nc; ++c) {
    if (modes.closed(c)) {
      rows.push_back(kin.W_N.col(c));
    }
  }
  Case out;
  out.k = static_cast<int>(rows.size());
  for (int c = 0; c < nc; ++c) {
    if (modes[c] == ContactMode::kStick) {
      rows.push_back(kin.W_T.col(c));
    }
  }
  out.m = static_cast<int>(rows.size());
  const VectorXd& inv_m = model.inverse_mass_diagonal();
  EventPolicy policy;
  ActiveSystem sys(2 * nc, policy.rank_threshold);
  out.A.resize(out.m, out.m);
  out.b.resize(out.m);
  sys.Start(out.m);
  for (int i = 0; i < out.m; ++i) {
    out.b[i] = -rows[i].dot(inv_m.cwiseProduct(h));
    sys.b(i) = out.b[i];
    for (int j = 0; j < out.m; ++j) {
      out.A(i, j) = rows[i].dot(inv_m.cwiseProduct(rows[j]));
      sys.A(i, j) = out.A(i, j);
    }
  }
  sys.SolveSymmetric();
  out.rank_deficient = sys.rank_deficient();
  const int cap = sys.capacity();
  MatrixXd kernel = MatrixXd::Zero(cap, cap);
  std::vector<int> normal_of(static_cast<std::size_t>(nc), 0);
  std::vector<int> tangent_of(static_cast<std::size_t>(nc), -1);
  VectorXd x_bal = VectorXd::Zero(cap), x_try = VectorXd::Zero(cap);
  lcp::SmallLp lp;
  MatrixXd lp_G = MatrixXd::Zero(3 * nc + 2, cap + 1);
  VectorXd lp_h = VectorXd::Zero(3 * nc + 2);
  VectorXd lp_c = VectorXd::Zero(cap + 1), lp_y = VectorXd::Zero(cap + 1);
  SplitWorkspace ws{kernel, normal_of, tangent_of, x_bal, x_try, lp, lp_G, lp_h, lp_c, lp_y};
  SplitIndeterminateForces(model, modes, policy, 1e-6, out.k, out.m, sys, ws);
  out.x.resize(out.m);
  for (int j = 0; j < out.m; ++j) {
    out.x[j] = sys.x(j);
  }
  return out;
}

// The smallest friction margin mu lambda_N - |lambda_T| over the sticking unknowns (N).
double SmallestMargin(const VectorXd& x, int k, double mu) {
  double least = INFINITY;
  for (int t = k; t < x.size(); ++t) {
    least = std::min(least, mu * x[t - k] - std::abs(x[t]));
  }
  return least;
}

// A deck clamped between both faces, all four corners sticking, pushed into the +x face: the
// system is singular (8 unknowns, 3 degrees of freedom) and the split satisfies A x = b, every
// normal force pushes, and the unloaded -x face carries nothing (no squeeze). (The cones are
// checked in the one-face case: with three corners at zero normal force, friction alone at the
// fourth cannot hold the deck, and the slip event is the rigid model's answer.)
TEST(IndeterminateSplit, ClampedDeckPushesWithoutSqueeze) {
  const double mu = 0.5;
  const model::Model model = ClampedDeck(mu);
  ContactModes modes(4);
  for (int c = 0; c < 4; ++c) {
    modes.Set(c, ContactMode::kStick);
  }
  // Into the +x face along its normal, a little along it, and a small torque (2e4 N m).
  contact::ContactKinematics kin;
  kin.Resize(model);
  const VectorXd zero = VectorXd::Zero(3);
  contact::Evaluate(model, zero, zero, kin);
  VectorXd h = VectorXd::Zero(3);
  h.head(2) = -2.0e5 * kin.W_N.col(0).head(2) + 2.0e4 * kin.W_T.col(0).head(2);
  h[2] = 2.0e4;
  const Case s = SolveAndSplit(model, modes, h);
  ASSERT_EQ(s.m, 8);
  ASSERT_TRUE(s.rank_deficient);
  const double scale = s.x.cwiseAbs().maxCoeff();
  EXPECT_LE((s.A * s.x - s.b).norm(), 1e-9 * s.b.norm());
  for (int j = 0; j < 4; ++j) {
    EXPECT_GE(s.x[j], -1e-9 * scale) << "contact " << j;
  }
  // The -x face (P3, P4) is unloaded, and the +x face carries the push.
  EXPECT_NEAR(s.x[2] + s.x[3], 0.0, 1e-9 * scale);
  EXPECT_GT(s.x[0] + s.x[1], 0.1 * scale);
}

// Two corners sticking on one face: the kernel trades one corner's friction against the
// other's and leaves the normal forces unique. The split keeps the normal forces of the
// minimum-norm solution (Eigen's complete orthogonal decomposition), satisfies A x = b, and its
// smallest friction margin is the largest along the kernel (a brute-force scan).
TEST(IndeterminateSplit, OneFaceSplitIsTheDeepestInsideTheCones) {
  const double mu = 0.4;
  const model::Model model = ClampedDeck(mu);
  ContactModes modes(4);
  modes.Set(0, ContactMode::kStick);
  modes.Set(1, ContactMode::kStick);
  VectorXd h(3);
  h << 3.0e5, -8.0e4, 4.0e5;
  const Case s = SolveAndSplit(model, modes, h);
  ASSERT_EQ(s.m, 4);
  ASSERT_TRUE(s.rank_deficient);
  const double scale = s.x.cwiseAbs().maxCoeff();
  EXPECT_LE((s.A * s.x - s.b).norm(), 1e-9 * s.b.norm());
  const VectorXd x0 = s.A.completeOrthogonalDecomposition().solve(s.b);
  const MatrixXd kernel = s.A.fullPivLu().kernel();
  ASSERT_EQ(kernel.cols(), 1);
  EXPECT_LT(kernel.col(0).head(2).norm(), 1e-9);  // tangential only
  EXPECT_NEAR(s.x[0], x0[0], 1e-9 * scale);
  EXPECT_NEAR(s.x[1], x0[1], 1e-9 * scale);
  double best = -INFINITY;
  const VectorXd dir = kernel.col(0) / kernel.col(0).norm();
  for (int i = -200000; i <= 200000; ++i) {
    const double t = 4.0 * scale * i / 200000.0;
    best = std::max(best, SmallestMargin(x0 + t * dir, 2, mu));
  }
  const double split = SmallestMargin(s.x, 2, mu);
  EXPECT_GE(split, best - 1e-9 * scale);
  EXPECT_LE(split, best + 1e-4 * scale);  // the scan's resolution is 2e-5 scale
}

// A determinate active set (P1 frictionless, P2 sticking: 3 unknowns, full rank) is left at its
// unique solution.
TEST(IndeterminateSplit, DeterminateSystemKeepsItsUniqueSolution) {
  const model::Model model = ClampedDeck(0.3);
  ContactModes modes(4);
  modes.Set(0, ContactMode::kFrictionless);
  modes.Set(1, ContactMode::kStick);
  VectorXd h(3);
  h << 1.0e5, 2.0e4, -3.0e4;
  const Case s = SolveAndSplit(model, modes, h);
  ASSERT_EQ(s.m, 3);
  EXPECT_FALSE(s.rank_deficient);
  const VectorXd unique = s.A.fullPivLu().solve(s.b);
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(s.x[j], unique[j], 1e-10 * unique.cwiseAbs().maxCoeff()) << "unknown " << j;
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::indeterminate_split_test
