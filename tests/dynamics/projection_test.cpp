/// ProjectOntoContacts (solver/dynamics/projection.h) on its postconditions [docs/theory.md
/// §3.10]: after the projection every closed contact's gap is within gap_tol and its normal
/// velocity zero, every open contact at its face approaches no faster than v_tol, and the change
/// is the least-squares one in the mass metric: the state change equals the solution of the
/// constrained least-squares problem solved independently by Eigen (the KKT system by full-pivot
/// LU), and the multipliers of the open contacts that joined the velocity projection push.

#include "solver/dynamics/projection.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <random>

#include "solver/model/builders.h"

namespace skewbridge::dynamics::projection_test {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kGapTol = 1e-9;  // m
constexpr double kVTol = 1e-6;    // m/s

// A 30 deg skew deck, 30 m x 10 m, between both abutments (P1, P2 at +x, P3, P4 at -x).
model::Model MakeDeck(double friction) {
  model::DeckSpec spec;
  spec.mass_kg = 1.0e5;
  spec.geometry = {30.0, 10.0, 30.0 * std::numbers::pi / 180.0};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = 2.0 * std::numbers::pi;
  spec.abutments = model::AbutmentSet::kBoth;
  spec.gap_plus_m = spec.gap_minus_m = 0.01;
  spec.friction = friction;
  return model::BuildDeckModel(spec);
}

// The position at which contacts 0 (P1) and 1 (P2) have the gaps g0 and g1 (m), found by Newton
// on (x, theta) with finite-difference slopes (the gaps are smooth; y is left at y).
VectorXd PlaceAt(const model::Model& m, double g0, double g1, double y) {
  VectorXd q = VectorXd::Zero(3);
  q[1] = y;
  for (int it = 0; it < 20; ++it) {
    Eigen::Vector2d r(contact::Gap(m, 0, q) - g0, contact::Gap(m, 1, q) - g1);
    Eigen::Matrix2d J;
    for (int k = 0; k < 2; ++k) {
      VectorXd dq = q;
      dq[k == 0 ? 0 : 2] += 1e-6;
      J(0, k) = (contact::Gap(m, 0, dq) - contact::Gap(m, 0, q)) / 1e-6;
      J(1, k) = (contact::Gap(m, 1, dq) - contact::Gap(m, 1, q)) / 1e-6;
    }
    const Eigen::Vector2d d = J.fullPivLu().solve(r);
    q[0] -= d[0];
    q[2] -= d[1];
  }
  return q;
}

// The minimum of dz^T M dz subject to A^T dz = b, by the KKT system [M A; A^T 0] and Eigen's
// full-pivot LU: returns (dz, multipliers).
std::pair<VectorXd, VectorXd> LeastChange(const VectorXd& mass, const MatrixXd& A,
                                          const VectorXd& b) {
  const int n = static_cast<int>(mass.size());
  const int m = static_cast<int>(A.cols());
  MatrixXd K = MatrixXd::Zero(n + m, n + m);
  K.topLeftCorner(n, n) = mass.asDiagonal();
  K.topRightCorner(n, m) = A;
  K.bottomLeftCorner(m, n) = A.transpose();
  VectorXd rhs = VectorXd::Zero(n + m);
  rhs.tail(m) = b;
  const VectorXd s = K.fullPivLu().solve(rhs);
  // M dz + A mu = 0: the projection's multipliers are x = -mu.
  return {s.head(n), -s.tail(m)};
}

struct Fixture {
  explicit Fixture(const model::Model& m)
      : model(m), modes(m.n_contacts()), ws(m, policy.rank_threshold), joined(ws.projection_rows) {}
  void Project(VectorXd& q, VectorXd& u) {
    ProjectOntoContacts(model, modes, policy, {30.0, kGapTol, kVTol}, q, u, ws);
  }
  const model::Model& model;
  EventPolicy policy;
  ContactModes modes;
  ProjectionWorkspace ws;
  const std::vector<int>& joined;  ///< per contact: 1 when an open contact joined
};

// Positions, one pass (closed gaps below one_pass_gap L_d = 4.5e-7 m): the change is the
// minimum-M-norm dq with W_N(q0)^T dq = -g(q0) over the closed contacts, and the gaps close.
TEST(Projection, OnePassPositionChangeIsTheLeastSquaresOneInTheMassMetric) {
  const model::Model m = MakeDeck(0.3);
  Fixture f(m);
  f.modes.Set(0, ContactMode::kStick);
  f.modes.Set(1, ContactMode::kSlidePositive);
  const VectorXd q0 = PlaceAt(m, -2e-7, 1.5e-7, 0.004);
  VectorXd q = q0;
  VectorXd u = VectorXd::Zero(3);
  contact::ContactKinematics k0;
  k0.Resize(m);
  contact::Evaluate(m, q0, u, k0);
  MatrixXd A(3, 2);
  A << k0.W_N.col(0), k0.W_N.col(1);
  const VectorXd b = -Eigen::Vector2d(k0.gap_m[0], k0.gap_m[1]);
  const VectorXd dq = LeastChange(m.mass_diagonal(), A, b).first;
  f.Project(q, u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(q[i] - q0[i], dq[i], 1e-12 * dq.cwiseAbs().maxCoeff() + 1e-18) << "dof " << i;
  }
  EXPECT_LE(std::abs(contact::Gap(m, 0, q)), kGapTol);
  EXPECT_LE(std::abs(contact::Gap(m, 1, q)), kGapTol);
  EXPECT_GT(dq.cwiseAbs().maxCoeff(), 1e-8);  // the test moved something
}

// Positions, two passes from gaps far above one_pass_gap L_d: the residual of the second
// Gauss-Newton pass is far below gap_tol; velocities of a sticking contact vanish in both
// directions.
TEST(Projection, TwoPassesCloseLargeGapsAndStopTheStickingContact) {
  const model::Model m = MakeDeck(0.3);
  Fixture f(m);
  f.modes.Set(0, ContactMode::kStick);
  VectorXd q = PlaceAt(m, 3e-4, 0.02, -0.01);
  VectorXd u(3);
  u << -0.3, 0.2, 0.01;
  const VectorXd q_before = q;
  f.Project(q, u);
  EXPECT_LE(std::abs(contact::Gap(m, 0, q)), kGapTol);
  EXPECT_GT((q - q_before).norm(), 3e-5);
  // One pass alone leaves a residual of the order of g^2 / L_d, above gap_tol: the second pass
  // is what closes the gap.
  Fixture one(m);
  one.policy.position_passes = 1;
  one.modes.Set(0, ContactMode::kStick);
  VectorXd q1 = q_before;
  VectorXd u1(3);
  u1 << -0.3, 0.2, 0.01;
  one.Project(q1, u1);
  EXPECT_GT(std::abs(contact::Gap(m, 0, q1)), kGapTol);
  contact::ContactKinematics k;
  k.Resize(m);
  contact::Evaluate(m, q, u, k);
  EXPECT_NEAR(k.gamma_N[0], 0.0, 1e-14);
  EXPECT_NEAR(k.gamma_T[0], 0.0, 1e-14);
}

// Velocities over random states with P1 closed and sliding and P2, P4 open at their face: the
// closed normal velocity vanishes, no open contact at its face approaches faster than v_tol,
// the change equals the least-squares one over the final active set (closed plus joined rows),
// and every joined contact's multiplier pushes (>= 0). Some draws must join a contact, or the
// active set was never exercised.
TEST(Projection, VelocityActiveSetMeetsItsPostconditions) {
  const model::Model m = MakeDeck(0.0);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> speed(-0.5, 0.5);
  int joined_draws = 0;
  for (int draw = 0; draw < 400; ++draw) {
    Fixture f(m);
    f.modes.Set(0, ContactMode::kFrictionless);
    VectorXd q = PlaceAt(m, 0.0, 0.0, 0.0);  // P1 and P2 both at their +x face
    VectorXd u(3);
    u << speed(rng), speed(rng), speed(rng) / 10.0;
    const VectorXd u0 = u;
    f.Project(q, u);
    contact::ContactKinematics k;
    k.Resize(m);
    contact::Evaluate(m, q, u, k);
    ASSERT_NEAR(k.gamma_N[0], 0.0, 1e-13) << "draw " << draw;
    for (int c = 1; c < m.n_contacts(); ++c) {
      if (k.gap_m[c] <= kGapTol) {
        EXPECT_GE(k.gamma_N[c], -kVTol) << "draw " << draw << " contact " << c;
      }
    }
    // The final active set, and the least-squares change over it at the projected positions.
    std::vector<int> set = {0};
    for (int c = 1; c < m.n_contacts(); ++c) {
      if (f.joined[static_cast<std::size_t>(c)] != 0) {
        set.push_back(c);
      }
    }
    joined_draws += set.size() > 1 ? 1 : 0;
    MatrixXd A(3, static_cast<int>(set.size()));
    for (std::size_t i = 0; i < set.size(); ++i) {
      A.col(static_cast<int>(i)) = k.W_N.col(set[i]);
    }
    const auto [du, x] = LeastChange(m.mass_diagonal(), A, -A.transpose() * u0);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(u[i] - u0[i], du[i], 1e-12 * (1.0 + du.cwiseAbs().maxCoeff())) << "draw " << draw;
    }
    for (std::size_t i = 1; i < set.size(); ++i) {
      EXPECT_GE(x[static_cast<int>(i)], 0.0) << "draw " << draw << " contact " << set[i];
    }
  }
  EXPECT_GT(joined_draws, 20);
  EXPECT_LT(joined_draws, 400);
}

// The rule switched off (EventPolicy::open_contacts_in_projection = false): the velocity change
// is the least-squares one over the closed contact alone, whatever the open contacts at the face
// do, and in the draws where the rule (on) made an open contact join, that contact is left
// approaching its face faster than v_tol, what the rule exists to prevent (§3.10).
TEST(Projection, WithoutOpenContactsInTheProjectionOnlyTheClosedSetIsProjected) {
  const model::Model m = MakeDeck(0.0);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> speed(-0.5, 0.5);
  int left_approaching = 0;
  for (int draw = 0; draw < 400; ++draw) {
    VectorXd u0(3);
    u0 << speed(rng), speed(rng), speed(rng) / 10.0;
    const VectorXd q0 = PlaceAt(m, 0.0, 0.0, 0.0);
    Fixture on(m), off(m);
    off.policy.open_contacts_in_projection = false;
    VectorXd q_on = q0, u_on = u0, q_off = q0, u_off = u0;
    for (Fixture* f : {&on, &off}) {
      f->modes.Set(0, ContactMode::kFrictionless);
    }
    on.Project(q_on, u_on);
    off.Project(q_off, u_off);
    for (int c = 0; c < m.n_contacts(); ++c) {
      EXPECT_EQ(off.joined[static_cast<std::size_t>(c)], 0) << "draw " << draw;
    }
    contact::ContactKinematics k;
    k.Resize(m);
    contact::Evaluate(m, q_off, u_off, k);
    MatrixXd A = k.W_N.col(0);
    const VectorXd du = LeastChange(m.mass_diagonal(), A, -A.transpose() * u0).first;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(u_off[i] - u0[i], du[i], 1e-12 * (1.0 + du.cwiseAbs().maxCoeff()))
          << "draw " << draw;
    }
    EXPECT_NEAR(k.gamma_N[0], 0.0, 1e-13) << "draw " << draw;
    bool joined_on = false;
    for (int c = 1; c < m.n_contacts(); ++c) {
      joined_on = joined_on || on.joined[static_cast<std::size_t>(c)] != 0;
    }
    if (joined_on) {
      // Contact 1 (P2) is the only other one at a face; it approaches without the rule.
      EXPECT_LT(k.gamma_N[1], -kVTol) << "draw " << draw;
      left_approaching += k.gamma_N[1] < -kVTol ? 1 : 0;
    } else {
      EXPECT_EQ((u_on - u_off).cwiseAbs().maxCoeff(), 0.0) << "draw " << draw;
    }
  }
  EXPECT_GT(left_approaching, 20);
}

}  // namespace
}  // namespace skewbridge::dynamics::projection_test
