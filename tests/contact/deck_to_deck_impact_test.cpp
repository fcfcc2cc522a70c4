// Deck-to-deck impacts (no substructure) against the two-body Newton impact solution: an impulse
// Lambda n through the contact arms r_0 = P - c_0, r_1 = P - c_1 of the two mass centres,
// Lambda = -(1 + eps) gamma_N,A m_eff with 1/m_eff = 1/m_0 + 1/m_1 + (r_0 x n)^2 / I_0 +
// (r_1 x n)^2 / I_1, computed from positions alone (not from the contact Jacobians), and against
// conservation of linear and angular momentum.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "solver/contact/impact_problem.h"
#include "solver/contact/kinematics.h"
#include "solver/model/multispan.h"

namespace skewbridge::contact::deck_to_deck_impact_test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Two free decks of different lengths (hence masses) with a joint of zero gap, frictionless.
model::Model TwoFreeDecks(double skew_deg, double eps) {
  model::MultiSpanSpec spec;
  spec.n_spans = 2;
  spec.span_lengths_m = {30.0, 22.0};
  spec.width_m = 12.0;
  spec.skew_rad = skew_deg * kDeg;
  spec.mass_per_length_kgpm = 2.0e4;
  spec.xi = 0.0;
  spec.abutment_gap_m = 0.05;
  spec.joint_gap_m = 0.0;
  spec.restitution = eps;
  spec.friction = 0.0;
  return model::BuildMultiSpanBridge(spec, "two-free-decks");
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Linear momentum (x, y) and angular momentum about the origin of the two decks at (q, u).
Eigen::Vector3d Momentum(const model::Model& model, const Eigen::VectorXd& q,
                         const Eigen::VectorXd& u) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int b = 0; b < model.n_bodies(); ++b) {
    const model::Body& body = model.body(b);
    const Eigen::Vector2d c = body.rest_position_m + q.segment<2>(3 * b);
    const Eigen::Vector2d v = u.segment<2>(3 * b);
    p.head<2>() += body.mass_kg * v;
    p(2) += body.mass_kg * Cross(c, v) + body.inertia_kgm2 * u(3 * b + 2);
  }
  return p;
}

TEST(DeckToDeckImpact, JointContactsCloseTheZeroGapAtRestAlongTheSkewedFace) {
  for (double a : {0.0, 30.0}) {
    const model::Model model = TwoFreeDecks(a, 0.5);
    ASSERT_EQ(model.n_contacts(), 6);
    for (int c = 2; c < 4; ++c) {
      EXPECT_EQ(model.contact(c).body, 0);
      EXPECT_EQ(model.contact(c).face.body, 1);
      EXPECT_NEAR(Gap(model, c, Eigen::VectorXd::Zero(6)), 0.0, 1e-12);
    }
    // Moving deck 1 by s along x opens the joint by s cos a.
    Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
    q(3) = 0.01;
    EXPECT_NEAR(Gap(model, 2, q), 0.01 * std::cos(a * kDeg), 1e-14);
  }
}

TEST(DeckToDeckImpact, FullEdgeImpactOfUnskewedDecksIsTheOneDimensionalNewtonCollision) {
  for (double eps : {0.0, 0.5, 1.0}) {
    const model::Model model = TwoFreeDecks(0.0, eps);
    const double m0 = model.body(0).mass_kg;
    const double m1 = model.body(1).mass_kg;
    Eigen::VectorXd q = Eigen::VectorXd::Zero(6), u = Eigen::VectorXd::Zero(6);
    u(0) = 0.8;
    u(3) = -0.3;
    ContactKinematics kin;
    kin.Resize(model);
    Evaluate(model, q, u, kin);
    ImpactProblem problem(model);
    ImpactResult result = problem.MakeResult();
    const std::vector<int> joint{2, 3};
    ASSERT_EQ(problem.Solve(kin, joint, u, result), lcp::LcpStatus::kSolved);
    const double V = (m0 * u(0) + m1 * u(3)) / (m0 + m1);
    const double approach = u(0) - u(3);
    EXPECT_NEAR(result.u_E(0), V - eps * m1 * approach / (m0 + m1), 1e-12);
    EXPECT_NEAR(result.u_E(3), V + eps * m0 * approach / (m0 + m1), 1e-12);
    for (int k : {1, 2, 4, 5}) {
      EXPECT_NEAR(result.u_E(k), 0.0, 1e-12) << "dof " << k;
    }
  }
}

TEST(DeckToDeckImpact, SingleCornerImpactMatchesTheTwoBodyNewtonSolutionAndConservesMomentum) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (double a : {0.0, 35.0}) {
    const model::Model model = TwoFreeDecks(a, 0.6);
    for (int trial = 0; trial < 50; ++trial) {
      Eigen::VectorXd q(6), u(6);
      for (int k = 0; k < 6; ++k) {
        q(k) = (k % 3 == 2 ? 0.01 : 0.05) * unit(rng);
        u(k) = (k % 3 == 2 ? 0.02 : 0.5) * unit(rng);
      }
      const int c = trial % 2 == 0 ? 2 : 3;
      const model::Contact& contact = model.contact(c);
      // The closed form from positions: world n, the arms, the approach velocity.
      const Eigen::Vector2d c0 = model.body(0).rest_position_m + q.segment<2>(0);
      const Eigen::Vector2d c1 = model.body(1).rest_position_m + q.segment<2>(3);
      const Eigen::Vector2d P = c0 + Rotation(q(2)) * contact.point_m;
      const Eigen::Vector2d n = Rotation(q(5)) * contact.face.normal;
      const Eigen::Vector2d r0 = P - c0, r1 = P - c1;
      const Eigen::Vector2d v0 = u.segment<2>(0) + u(2) * Eigen::Vector2d(-r0.y(), r0.x());
      const Eigen::Vector2d v1 = u.segment<2>(3) + u(5) * Eigen::Vector2d(-r1.y(), r1.x());
      double gamma_A = n.dot(v0 - v1);
      if (gamma_A > 0.0) {
        // Make it an approach: reverse every velocity.
        u = -u;
        gamma_A = -gamma_A;
      }
      const model::Body& b0 = model.body(0);
      const model::Body& b1 = model.body(1);
      const double inverse_m_eff = 1.0 / b0.mass_kg + 1.0 / b1.mass_kg +
                                   Cross(r0, n) * Cross(r0, n) / b0.inertia_kgm2 +
                                   Cross(r1, n) * Cross(r1, n) / b1.inertia_kgm2;
      const double Lambda = -(1.0 + 0.6) * gamma_A / inverse_m_eff;
      Eigen::VectorXd u_E = u;
      u_E.segment<2>(0) += Lambda * n / b0.mass_kg;
      u_E(2) += Lambda * Cross(r0, n) / b0.inertia_kgm2;
      u_E.segment<2>(3) -= Lambda * n / b1.mass_kg;
      u_E(5) -= Lambda * Cross(r1, n) / b1.inertia_kgm2;

      ContactKinematics kin;
      kin.Resize(model);
      Evaluate(model, q, u, kin);
      ImpactProblem problem(model);
      ImpactResult result = problem.MakeResult();
      const std::vector<int> one{c};
      ASSERT_EQ(problem.Solve(kin, one, u, result), lcp::LcpStatus::kSolved);
      EXPECT_NEAR(result.Lambda_N(0), Lambda, 1e-9 * std::abs(Lambda) + 1e-9);
      for (int k = 0; k < 6; ++k) {
        EXPECT_NEAR(result.u_E(k), u_E(k), 1e-10 * (1.0 + u.cwiseAbs().maxCoeff()))
            << "a " << a << " trial " << trial << " dof " << k;
      }
      const Eigen::Vector3d before = Momentum(model, q, u);
      const Eigen::Vector3d after = Momentum(model, q, result.u_E);
      EXPECT_NEAR((after - before).head<2>().norm(), 0.0, 1e-9 * before.head<2>().norm() + 1e-6);
      EXPECT_NEAR(after(2), before(2), 1e-9 * std::abs(before(2)) + 1e-4);
    }
  }
}

}  // namespace
}  // namespace skewbridge::contact::deck_to_deck_impact_test
