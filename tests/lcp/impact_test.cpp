// The impact LCP of docs/theory.md §3, built from its formulas in tests/lcp/impact_problem.h and
// solved by LemkeSolver, must reproduce the physical facts of docs/theory.md §4 (facts 1, 2, 6).
//
// Derivations the checks rely on (translating deck, theta = thetadot = 0, contacts P1, P2 at
// the +x abutment, n = (-cos a, sin a), t = (sin a, cos a)):
//   w_N,i = (-cos a, sin a, r_i), w_T,i = (sin a, cos a, r_T) (the same for both corners),
//   r_1 = (L sin a + W / cos a) / 2 > 0, r_2 = (L sin a - W / cos a) / 2, r_T = L cos a / 2.
//   r_2 <= 0  <=>  L sin a cos a <= W  <=>  eta0 = sin 2a / (2 W / L) <= 1.
// If both corners slide through the impact with friction along sigma t (Lambda_T,i = sigma mu
// Lambda_N,i), the generalised impulse is sum_i Lambda_N,i (w_N,i + sigma mu w_T,i), whose
// moment is Lambda_N,1 (r_1 + sigma mu r_T) + Lambda_N,2 (r_2 + sigma mu r_T). With r_1 +
// sigma mu r_T > 0 it can vanish with Lambda >= 0 only if r_2 + sigma mu r_T <= 0, i.e.
// eta0 (1 + sigma mu / tan a) <= 1; the threshold is mu* = -r_2 / (sigma r_T). Then the deck
// leaves without rotating and both corners share the impulse. Otherwise corner P1 carries no
// impulse and P2 alone gives, from gamma_N2,E = -eps gamma_N2,A,
//   Lambda_N,2 = -(1 + eps) gamma_N2,A / (1/m + r_2 (r_2 + sigma mu r_T) / I_m),
//   thetadot_E = Lambda_N,2 (r_2 + sigma mu r_T) / I_m        (n . t = 0).
// Which sigma: gamma_T = w_T^T u. A purely longitudinal approach u_A = (v, 0, 0), v > 0, has
// gamma_N,A = -v cos a < 0 (approach) and gamma_T,A = v sin a > 0: slip along +t, friction
// along -t, sigma = -1. An approach u_A = v (-n) + v (-t) has gamma_N,A = -v and gamma_T,A =
// -v: slip along -t, friction along +t, sigma = +1 (the paper's eta1 = eta0 (1 + mu / tan a)).
// Each case also checks that the slip keeps its sign after the impact, as the fact assumes.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <random>
#include <vector>

#include "solver/lcp/lcp_check.h"
#include "solver/lcp/lemke.h"
#include "tests/lcp/impact_problem.h"

namespace skewbridge::lcp::impact_test {
namespace {

using testing::BuildImpactProblem;
using testing::Deck;
using testing::ImpactProblem;
using testing::KineticEnergy;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kV = 0.4;  // approach speed, m/s

/// Lever arms of docs/theory.md §2 for the +x abutment.
struct Arms {
  double r1, r2, rT;
};
Arms LeverArms(const Deck& d) {
  return {0.5 * (d.L * std::sin(d.a) + d.W / std::cos(d.a)),
          0.5 * (d.L * std::sin(d.a) - d.W / std::cos(d.a)), 0.5 * d.L * std::cos(d.a)};
}

/// The two decks every fact is checked on: unit data, and the pilot bridge's mass and length
/// (m = 1547 t, L = 89.14 m), whose LCP mixes entries of order 1/m with entries of order 1.
std::vector<Deck> Decks(double a, double eta0) {
  return {Deck::WithSkewRatio(1.0, a, eta0, 1.0), Deck::WithSkewRatio(89.14, a, eta0, 1.547e6)};
}

struct Outcome {
  LcpSolution solution;
  Eigen::Vector3d u_E;
  Eigen::VectorXd lambda_n;
  Eigen::VectorXd lambda_t;
  Eigen::VectorXd gamma_t_E;
};

Outcome SolveImpact(const ImpactProblem& p) {
  LemkeSolver solver;
  Outcome o;
  solver.Solve(p.A, p.b, o.solution);
  EXPECT_EQ(o.solution.status, LcpStatus::kSolved) << o.solution.message;
  o.u_E = p.PostImpactVelocity(o.solution.z);
  o.lambda_n = p.LambdaN(o.solution.z);
  o.lambda_t = p.LambdaT(o.solution.z);
  o.gamma_t_E = p.W_T.transpose() * o.u_E;
  return o;
}

void ExpectNoEnergyCreated(const Deck& d, const ImpactProblem& p, const Outcome& o) {
  const double before = KineticEnergy(d, p.u_A);
  EXPECT_LE(KineticEnergy(d, o.u_E), before * (1.0 + 1e-12));
}

TEST(ImpactProblemHelper, JacobiansMatchTheClosedFormsOfMethodSection2) {
  const Deck d = Deck::WithSkewRatio(30.0, 25 * kDeg, 1.3, 2.0);
  const Arms arms = LeverArms(d);
  for (double theta : {0.0, 0.03, -0.2}) {
    const ImpactProblem p = BuildImpactProblem(d, {1, 2}, theta, Eigen::Vector3d::Zero(), 0, 0);
    for (int i = 0; i < 2; ++i) {
      const double r = i == 0 ? arms.r1 : arms.r2;
      const Eigen::Vector3d w_n(
          -std::cos(d.a), std::sin(d.a),
          0.5 * (d.L * std::cos(d.a) * std::sin(theta) + 2 * r * std::cos(theta)));
      const Eigen::Vector3d w_t(std::sin(d.a), std::cos(d.a),
                                -r * std::sin(theta) + arms.rT * std::cos(theta));
      EXPECT_LE((p.W_N.col(i) - w_n).norm(), 1e-13 * d.L);
      EXPECT_LE((p.W_T.col(i) - w_t).norm(), 1e-13 * d.L);
    }
  }
}

TEST(ImpactFact1, FrictionlessFullEdgeImpactRotatesIffSkewRatioExceedsOne) {
  for (double a_deg : {20.0, 30.0, 45.0}) {
    for (double eta0 : {0.95, 1.0, 1.05}) {
      for (const Deck& d : Decks(a_deg * kDeg, eta0)) {
        for (double eps : {0.0, 0.5, 1.0}) {
          SCOPED_TRACE(::testing::Message() << "a = " << a_deg << " deg, eta0 = " << eta0
                                            << ", m = " << d.m << ", eps = " << eps);
          const Eigen::Vector3d u_A(kV, 0.0, 0.0);
          const ImpactProblem p = BuildImpactProblem(d, {1, 2}, 0.0, u_A, 0.0, eps);
          const Outcome o = SolveImpact(p);
          const Arms arms = LeverArms(d);
          const double rho = d.Rho();
          const double gamma_n_A = -kV * std::cos(d.a);
          if (eta0 <= 1.0) {
            EXPECT_LE(std::abs(o.u_E(2)) * rho / kV, 1e-12) << "thetadot_E = " << o.u_E(2);
            // Shared impulse: total S = m (1 + eps) v cos a, moments cancel.
            const double total = -d.m * (1.0 + eps) * gamma_n_A;
            EXPECT_NEAR(o.lambda_n(0), -arms.r2 * total / (arms.r1 - arms.r2), 1e-12 * total);
            EXPECT_NEAR(o.lambda_n(1), arms.r1 * total / (arms.r1 - arms.r2), 1e-12 * total);
          } else {
            EXPECT_EQ(o.lambda_n(0), 0.0) << "the acute corner P1 must carry no impulse";
            const double lambda2 =
                -(1.0 + eps) * gamma_n_A / (1.0 / d.m + arms.r2 * arms.r2 / d.Inertia());
            const double thetadot = lambda2 * arms.r2 / d.Inertia();
            EXPECT_GT(thetadot * rho / kV, 1e-3);
            EXPECT_NEAR(o.u_E(2), thetadot, 1e-12 * std::abs(thetadot));
            EXPECT_NEAR(o.lambda_n(1), lambda2, 1e-12 * lambda2);
          }
          EXPECT_LE(o.lambda_t.cwiseAbs().maxCoeff(), 1e-12 * o.lambda_n.sum());
          ExpectNoEnergyCreated(d, p, o);
        }
      }
    }
  }
}

/// One frictional case of fact 2: approach velocity, sigma, and the predicted outcome.
struct FrictionCase {
  double a_deg;
  double eta0;
  double sigma;
  double mu;
};

Eigen::Vector3d ApproachFor(const Deck& d, double sigma) {
  // sigma = -1: purely longitudinal; sigma = +1: v (-n) + v (-t) (see the file comment).
  if (sigma < 0) return {kV, 0.0, 0.0};
  const double c = std::cos(d.a);
  const double s = std::sin(d.a);
  return {kV * (c - s), kV * (-s - c), 0.0};
}

void CheckFrictionCase(const FrictionCase& fc, double eps) {
  for (const Deck& d : Decks(fc.a_deg * kDeg, fc.eta0)) {
    SCOPED_TRACE(::testing::Message()
                 << "a = " << fc.a_deg << ", eta0 = " << fc.eta0 << ", sigma = " << fc.sigma
                 << ", mu = " << fc.mu << ", m = " << d.m << ", eps = " << eps);
    const Eigen::Vector3d u_A = ApproachFor(d, fc.sigma);
    const ImpactProblem p = BuildImpactProblem(d, {1, 2}, 0.0, u_A, fc.mu, eps);
    const Eigen::VectorXd gamma_n_A = p.W_N.transpose() * u_A;
    const Eigen::VectorXd gamma_t_A = p.W_T.transpose() * u_A;
    ASSERT_LT(gamma_n_A.maxCoeff(), 0.0);
    ASSERT_GT((-fc.sigma * gamma_t_A).minCoeff(), 0.0) << "slip must be along -sigma t";
    const Outcome o = SolveImpact(p);
    // Sliding persists with the same sign, so friction is sigma mu Lambda_N at both corners.
    EXPECT_GT((-fc.sigma * o.gamma_t_E).minCoeff(), 0.0) << "gamma_T,E = " << o.gamma_t_E;
    EXPECT_LE((o.lambda_t - fc.sigma * fc.mu * o.lambda_n).cwiseAbs().maxCoeff(),
              1e-12 * o.lambda_n.sum());

    const Arms arms = LeverArms(d);
    const double moment_arm_2 = arms.r2 + fc.sigma * fc.mu * arms.rT;
    const double rho = d.Rho();
    if (moment_arm_2 <= 0.0) {
      EXPECT_LE(std::abs(o.u_E(2)) * rho / kV, 1e-12) << "thetadot_E = " << o.u_E(2);
      EXPECT_GT(o.lambda_n(0), 0.0);
    } else {
      EXPECT_EQ(o.lambda_n(0), 0.0) << "the acute corner P1 must carry no impulse";
      const double lambda2 =
          -(1.0 + eps) * gamma_n_A(1) / (1.0 / d.m + arms.r2 * moment_arm_2 / d.Inertia());
      const double thetadot = lambda2 * moment_arm_2 / d.Inertia();
      EXPECT_GT(std::abs(thetadot) * rho / kV, 1e-4);
      EXPECT_NEAR(o.u_E(2), thetadot, 1e-12 * std::abs(thetadot));
    }
    ExpectNoEnergyCreated(d, p, o);
  }
}

TEST(ImpactFact2, PaperExampleRotatesOnlyAboveTheFrictionalSkewRatio) {
  // a = 30 deg, eta0 = 0.87: eta1 = eta0 (1 + mu / tan a) is 0.99 for mu = 0.08 and 1.02 for
  // mu = 0.10 (docs/theory.md §4 fact 2), with friction along +t (sigma = +1).
  const double tan_a = std::tan(30 * kDeg);
  EXPECT_NEAR(0.87 * (1 + 0.08 / tan_a), 0.99, 0.005);
  EXPECT_NEAR(0.87 * (1 + 0.10 / tan_a), 1.02, 0.005);
  for (double eps : {0.0, 0.5}) {
    CheckFrictionCase({30, 0.87, +1, 0.08}, eps);
    CheckFrictionCase({30, 0.87, +1, 0.10}, eps);
  }
}

TEST(ImpactFact2, LongitudinalApproachFrictionInhibitsRotation) {
  // sigma = -1: eta0 (1 - mu / tan a) <= 1 decides; a = 30 deg, eta0 = 1.1 gives the threshold
  // mu* = tan a (1 - 1 / eta0) = 0.0525: mu = 0.04 rotates, mu = 0.07 does not, mu = 0 rotates
  // (fact 1).
  for (double eps : {0.0, 0.5}) {
    CheckFrictionCase({30, 1.1, -1, 0.0}, eps);
    CheckFrictionCase({30, 1.1, -1, 0.04}, eps);
    CheckFrictionCase({30, 1.1, -1, 0.07}, eps);
  }
}

/// Bisection on mu for the onset of rotation, judged by whether corner P1 carries impulse,
/// down to an interval of 1e-10. (At mu* itself the problem is doubly degenerate: Lambda_N,1
/// and the moment arm r_2 + sigma mu r_T vanish together. With the pilot deck's mass, probes
/// within about 1e-12 of mu* can end on a secondary ray in floating point although exact
/// Lemke solves them; a ray is reported, never a wrong solution.) The threshold is resolved
/// to about the pivot tolerance times the growth of the inverse basis (1e-13 x 1e6 with the
/// pilot mass): closer to mu*, Lambda_N,1 is below what rounding can separate from zero.
double BisectRotationThreshold(const Deck& d, double sigma, double mu_lo, double mu_hi,
                               bool rotates_at_hi) {
  LemkeSolver solver;
  LcpSolution s;
  auto p1_loaded = [&](double mu) {
    const ImpactProblem p = BuildImpactProblem(d, {1, 2}, 0.0, ApproachFor(d, sigma), mu, 0.5);
    EXPECT_EQ(solver.Solve(p.A, p.b, s), LcpStatus::kSolved)
        << "mu = " << std::setprecision(17) << mu << ", m = " << d.m << ": " << s.message;
    return s.z(0) > 0.0;
  };
  EXPECT_EQ(p1_loaded(mu_lo), rotates_at_hi);
  EXPECT_EQ(p1_loaded(mu_hi), !rotates_at_hi);
  while (mu_hi - mu_lo > 1e-10) {
    const double mid = 0.5 * (mu_lo + mu_hi);
    (p1_loaded(mid) == rotates_at_hi ? mu_lo : mu_hi) = mid;
  }
  return 0.5 * (mu_lo + mu_hi);
}

TEST(ImpactFact2, BisectedFrictionThresholdMatchesClosedForm) {
  for (const Deck& d : Decks(30 * kDeg, 0.87)) {
    const Arms arms = LeverArms(d);
    const double closed_form = -arms.r2 / (+1 * arms.rT);
    EXPECT_NEAR(closed_form, std::tan(d.a) * (1 / 0.87 - 1), 1e-12);
    EXPECT_NEAR(BisectRotationThreshold(d, +1, 0.08, 0.10, true), closed_form, 1e-7);
  }
  for (const Deck& d : Decks(30 * kDeg, 1.1)) {
    const Arms arms = LeverArms(d);
    const double closed_form = -arms.r2 / (-1 * arms.rT);
    EXPECT_NEAR(closed_form, std::tan(d.a) * (1 - 1 / 1.1), 1e-12);
    EXPECT_NEAR(BisectRotationThreshold(d, -1, 0.04, 0.07, false), closed_form, 1e-7);
  }
}

TEST(ImpactProblem, FourCornerImpactsOfTheRotatingPilotDeckSolveWithoutCreatingEnergy) {
  // The pilot deck (a = 20 deg, eta0 = 1.48) spinning clockwise with a small drift: all four
  // corners approach their faces (gamma_N = r omega + drift with r_1, r_2 > 0), a 12 x 12 LCP.
  std::mt19937 rng(1548);
  std::uniform_real_distribution<double> drift(-0.02, 0.02);
  const Deck d = Deck::WithSkewRatio(89.14, 20 * kDeg, 1.48, 1.547e6);
  for (double mu : {0.0, 0.3}) {
    for (int trial = 0; trial < 20; ++trial) {
      const double omega = -kV / d.Rho();
      const Eigen::Vector3d u_A(drift(rng), drift(rng), omega);
      const ImpactProblem p = BuildImpactProblem(d, {1, 2, 3, 4}, 0.0, u_A, mu, 0.5);
      ASSERT_LT((p.W_N.transpose() * u_A).maxCoeff(), 0.0);
      const Outcome o = SolveImpact(p);
      EXPECT_LE(o.solution.worst_violation, 1e-12);
      EXPECT_LE((o.lambda_t.cwiseAbs() - mu * o.lambda_n).maxCoeff(), 1e-9 * o.lambda_n.sum())
          << "inside the friction cone";
      ExpectNoEnergyCreated(d, p, o);
    }
  }
}

}  // namespace
}  // namespace skewbridge::lcp::impact_test
