// The impact problem through the contact layer, end to end: facts 1 and 2 of [docs/theory.md §4]
// against their lever-arm criteria, single-contact impacts against the closed form
// Lambda = -(1 + eps) gamma_N,A / (w_N^T M^-1 w_N), and, over 1000 seeded random impacts,
// energy never created, Newton's law on active contacts and Coulomb's cone; the closed form of a
// single contact's frictional impact against Lemke on the same LCP.
#include "solver/contact/impact_problem.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <vector>

#include "tests/contact/test_models.h"

namespace skewbridge::contact {
namespace {

using testing::kDeg;

// The deck translating towards the +x abutment with both P1 and P2 touching (x = delta,
// theta = 0), velocity u_A; returns the result of the two-contact impact.
ImpactResult FullEdgeImpact(const model::Model& model, const Eigen::Vector3d& u_A) {
  const double delta = model.contact(0).face.point_m.x() - 0.5 * model.body(0).geometry.length_m;
  const Eigen::Vector3d q(delta, 0.0, 0.0);
  ContactKinematics kin;
  kin.Resize(model);
  Evaluate(model, q, u_A, kin);
  EXPECT_NEAR(kin.gap_m(0), 0.0, 1e-14 * model.body(0).geometry.length_m);
  EXPECT_NEAR(kin.gap_m(1), 0.0, 1e-14 * model.body(0).geometry.length_m);
  ImpactProblem problem(model);
  ImpactResult result = problem.MakeResult();
  const std::vector<int> both{0, 1};
  EXPECT_EQ(problem.Solve(kin, both, u_A, result), lcp::LcpStatus::kSolved);
  return result;
}

TEST(ImpactProblem, FrictionlessFullEdgeImpactLeavesWithoutRotationIffEta0AtMostOne) {
  // [docs/theory.md §4 fact 1] at a = 20, 30, 45 deg.
  for (double a_deg : {20.0, 30.0, 45.0}) {
    for (double eta0 : {0.5, 0.9, 1.0, 1.1, 1.5, 2.5}) {
      const model::Model model = testing::FreeDeck(a_deg, eta0, 30.0, 0.05, 0.5, 0.0);
      const double v = 0.8;
      const ImpactResult r = FullEdgeImpact(model, Eigen::Vector3d(v, 0.0, 0.0));
      const double rho = std::sqrt(model.body(0).inertia_kgm2 / model.body(0).mass_kg);
      const double a = a_deg * kDeg;
      if (eta0 <= 1.0) {
        EXPECT_LE(std::abs(r.u_E(2)), 1e-12 * v / rho) << "a " << a_deg << " eta0 " << eta0;
        // Closed form: a pure translation u_E = u_A + (1 + eps) v cos a n.
        const Eigen::Vector3d n(-std::cos(a), std::sin(a), 0.0);
        const Eigen::Vector3d expected = Eigen::Vector3d(v, 0.0, 0.0) + 1.5 * v * std::cos(a) * n;
        EXPECT_LT((r.u_E - expected).norm(), 1e-12 * v);
      } else {
        EXPECT_GT(std::abs(r.u_E(2)), 1e-3 * v / rho) << "a " << a_deg << " eta0 " << eta0;
        // The acute corner P1 takes no impulse; P2 alone: the single-contact closed form.
        EXPECT_LE(r.Lambda_N(0), 1e-12 * r.Lambda_N(1));
        const Eigen::Vector3d w = model.inverse_mass_diagonal();
        ContactKinematics kin;
        kin.Resize(model);
        const double delta = 0.05;
        Evaluate(model, Eigen::Vector3d(delta, 0, 0), Eigen::Vector3d(v, 0, 0), kin);
        const Eigen::Vector3d w_N = kin.W_N.col(1);
        const double Lambda =
            -(1.5) * w_N.dot(Eigen::Vector3d(v, 0, 0)) / w_N.dot(w.asDiagonal() * w_N);
        EXPECT_NEAR(r.Lambda_N(1), Lambda, 1e-12 * Lambda);
        EXPECT_NEAR(r.gamma_N_E(1), -0.5 * r.gamma_N_A(1), 1e-12 * v);
      }
    }
  }
}

TEST(ImpactProblem, FrictionalFullEdgeImpactRotatesIffR2PlusSigmaMuRTIsPositive) {
  // [docs/theory.md §4 fact 2]: a = 30 deg, eta0 = 0.87. sigma = +1 (slip along -t: a transverse
  // approach) gives eta1 = eta0 (1 + mu / tan a): mu = 0.08 -> 0.99, no rotation; mu = 0.10 ->
  // 1.02, rotation. sigma = -1 (a longitudinal approach, slip along +t) inhibits rotation, even
  // at eta0 = 1.1 where eta0 (1 - mu / tan a) = 0.91.
  struct Case {
    double eta0, mu;
    Eigen::Vector3d u_A;
    int sigma;
  };
  const std::vector<Case> cases = {
      {0.87, 0.08, {1.0, -6.0, 0.0}, +1}, {0.87, 0.10, {1.0, -6.0, 0.0}, +1},
      {0.87, 0.08, {1.0, 0.0, 0.0}, -1},  {0.87, 0.10, {1.0, 0.0, 0.0}, -1},
      {1.10, 0.10, {1.0, 0.0, 0.0}, -1},  {1.10, 0.0, {1.0, 0.0, 0.0}, -1},
  };
  const double a = 30.0 * kDeg;
  for (const Case& k : cases) {
    const model::Model model = testing::FreeDeck(30.0, k.eta0, 30.0, 0.05, 0.5, k.mu);
    const ImpactResult r = FullEdgeImpact(model, k.u_A);
    const model::LeverArms arms = model::ComputeLeverArms(model.body(0).geometry);
    const Eigen::Vector3d t(std::sin(a), std::cos(a), 0.0);
    // The deck slips through the impact: the slip keeps its sign, so sigma = -sign(slip).
    const double slip_A = t.dot(k.u_A);
    ASSERT_EQ(-std::copysign(1.0, slip_A), k.sigma);
    ASSERT_GT(slip_A * r.gamma_T_E(0), 0.0) << "slip stopped during the impact";
    const double rho = std::sqrt(model.body(0).inertia_kgm2 / model.body(0).mass_kg);
    const bool rotates = arms.r2_m + k.sigma * k.mu * arms.rT_m > 0.0;
    if (rotates) {
      EXPECT_GT(std::abs(r.u_E(2)), 1e-4 / rho) << "eta0 " << k.eta0 << " mu " << k.mu;
    } else {
      EXPECT_LE(std::abs(r.u_E(2)), 1e-12 * k.u_A.norm() / rho)
          << "eta0 " << k.eta0 << " mu " << k.mu;
      // Both corners take impulses, each on the edge of the cone with friction along sigma t.
      for (int c = 0; c < 2; ++c) {
        EXPECT_GT(r.Lambda_N(c), 0.0);
        EXPECT_NEAR(r.Lambda_T(c), k.sigma * k.mu * r.Lambda_N(c), 1e-12 * r.Lambda_N(c));
      }
    }
  }
  // The worked example's classification: mu = 0.08 does not rotate, 0.10 does.
  const model::Model m08 = testing::FreeDeck(30.0, 0.87, 30.0, 0.05, 0.5, 0.08);
  const model::Model m10 = testing::FreeDeck(30.0, 0.87, 30.0, 0.05, 0.5, 0.10);
  EXPECT_LT(std::abs(FullEdgeImpact(m08, {1.0, -6.0, 0.0}).u_E(2)), 1e-12);
  EXPECT_GT(std::abs(FullEdgeImpact(m10, {1.0, -6.0, 0.0}).u_E(2)), 1e-5);
}

// Whether w = A z + b, w, z >= 0, w^T z = 0 has a solution, by enumerating the 2^n choices of
// which of z_i, w_i may be nonzero (an oracle independent of Lemke's pivoting).
bool HasSolutionByEnumeration(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(b.size());
  const double tol = 1e-9 * (1.0 + b.cwiseAbs().maxCoeff());
  for (int mask = 0; mask < (1 << n); ++mask) {
    std::vector<int> basic;
    for (int i = 0; i < n; ++i) {
      if ((mask >> i) & 1) {
        basic.push_back(i);
      }
    }
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
    if (!basic.empty()) {
      const int k = static_cast<int>(basic.size());
      Eigen::MatrixXd A_SS(k, k);
      Eigen::VectorXd b_S(k);
      for (int r = 0; r < k; ++r) {
        b_S(r) = b(basic[r]);
        for (int c = 0; c < k; ++c) {
          A_SS(r, c) = A(basic[r], basic[c]);
        }
      }
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(A_SS);
      if (!lu.isInvertible()) {
        continue;
      }
      const Eigen::VectorXd z_S = lu.solve(-b_S);
      for (int r = 0; r < k; ++r) {
        z(basic[r]) = z_S(r);
      }
    }
    const Eigen::VectorXd w = A * z + b;
    if (z.minCoeff() >= -tol && w.minCoeff() >= -tol) {
      return true;
    }
  }
  return false;
}

// Statistics of a batch of seeded random impacts of a free deck at one abutment.
struct ImpactBatch {
  int impacts = 0;
  int unsolved = 0;                // Lemke ended without a solution
  int unsolved_but_solvable = 0;   // ... although enumeration finds one
  int energy_gains = 0;            // T_E > T_A (1 + 1e-12)
  int gains_without_friction = 0;  // ... with mu = 0 or eps = 0
  double largest_gain = 0.0;       // max (T_E - T_A) / T_A
};

// Random skew, eta0, size and state; eps and mu drawn in [0, eps_max] and [0, mu_max]. Checks on
// every impact: Newton's law on contacts with an impulse, no penetration velocity below
// Newton's elsewhere, Coulomb's cone, and the energy identity
// T_E - T_A = 1/2 sum (Lambda_N (gamma_N,A + gamma_N,E) + Lambda_T (gamma_T,A + gamma_T,E)).
ImpactBatch RandomImpacts(std::uint64_t seed, int trials, double eps_max, double mu_max) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ImpactBatch batch;
  for (int trial = 0; trial < trials; ++trial) {
    const double a_deg = 5.0 + 60.0 * unit(rng);
    const double eta0 = 0.3 + 2.7 * unit(rng);
    const double eps = eps_max * unit(rng);
    const double mu = mu_max * unit(rng);
    const model::Model model =
        testing::FreeDeck(a_deg, eta0, 10.0 + 40.0 * unit(rng), 0.05, eps, mu,
                          model::AbutmentSet::kBoth, 1.0 + 1e3 * unit(rng));
    const Eigen::Vector3d q(0.2 * (unit(rng) - 0.5), 0.2 * (unit(rng) - 0.5),
                            0.1 * (unit(rng) - 0.5));
    Eigen::Vector3d u_A(2.0 * unit(rng) - 1.0, 2.0 * unit(rng) - 1.0, 0.2 * (unit(rng) - 0.5));
    ContactKinematics kin;
    kin.Resize(model);
    Evaluate(model, q, u_A, kin);
    // One abutment at a time (its two corners strike the same face); in a third of the trials
    // one corner is in persistent contact: u_A is made tangent to it (gamma_N,A = 0).
    const int first = trial % 2 == 0 ? 0 : 2;
    std::vector<int> persistent;
    if (trial % 3 == 0) {
      const int c = first + static_cast<int>(2 * unit(rng)) % 2;
      const Eigen::Vector3d w = kin.W_N.col(c);
      u_A -= (w.dot(u_A) / w.dot(w)) * w;
      Evaluate(model, q, u_A, kin);
      persistent.push_back(c);
    }
    std::vector<int> index_set = persistent;
    for (int c = first; c < first + 2; ++c) {
      if (kin.gamma_N(c) < 0.0 && (persistent.empty() || persistent[0] != c)) {
        index_set.push_back(c);
      }
    }
    if (index_set.size() == persistent.size()) {
      continue;
    }
    ImpactProblem problem(model);
    ImpactResult r = problem.MakeResult();
    if (problem.Solve(kin, index_set, u_A, r, persistent) != lcp::LcpStatus::kSolved) {
      ++batch.unsolved;
      if (HasSolutionByEnumeration(problem.last_A(), problem.last_b())) {
        ++batch.unsolved_but_solvable;
      }
      continue;
    }
    ++batch.impacts;
    const Eigen::VectorXd& m = model.mass_diagonal();
    const double T_A = 0.5 * u_A.dot(m.asDiagonal() * u_A);
    const double T_E = 0.5 * r.u_E.dot(m.asDiagonal() * r.u_E);
    // Velocity scale of the contacts: |w_N| |u| bounds every gamma.
    const double v = 3.0 * kin.W_N.cwiseAbs().maxCoeff() * u_A.cwiseAbs().maxCoeff();
    const double Lambda_scale = r.Lambda_N.head(r.k).cwiseAbs().maxCoeff() + 1e-300;
    double work = 0.0;
    for (int j = 0; j < r.k; ++j) {
      const int c = index_set[static_cast<std::size_t>(j)];
      EXPECT_LE(std::abs(r.Lambda_T(j)), mu * r.Lambda_N(j) + 1e-12 * Lambda_scale);
      EXPECT_GE(r.Lambda_N(j), -1e-12 * Lambda_scale);
      if (r.Lambda_N(j) > 1e-9 * Lambda_scale) {
        EXPECT_NEAR(r.gamma_N_E(j), -eps * r.gamma_N_A(j), 1e-9 * v) << "trial " << trial;
      } else {
        EXPECT_GE(r.gamma_N_E(j) + eps * r.gamma_N_A(j), -1e-9 * v) << "trial " << trial;
      }
      work += 0.5 * (r.Lambda_N(j) * (kin.gamma_N(c) + r.gamma_N_E(j)) +
                     r.Lambda_T(j) * (kin.gamma_T(c) + r.gamma_T_E(j)));
    }
    EXPECT_NEAR(T_E - T_A, work, 1e-10 * T_A) << "trial " << trial;
    if (T_E > T_A * (1.0 + 1e-12)) {
      ++batch.energy_gains;
      batch.largest_gain = std::max(batch.largest_gain, (T_E - T_A) / T_A);
      if (mu == 0.0 || eps == 0.0) {
        ++batch.gains_without_friction;
      }
    }
  }
  return batch;
}

TEST(ImpactProblem, FrictionlessImpactsNeverCreateEnergy) {
  // 1000 seeded impacts, eps in [0, 1], mu = 0 [docs/theory.md §4 fact 6].
  const ImpactBatch batch = RandomImpacts(1000, 1000, 1.0, 0.0);
  EXPECT_GT(batch.impacts, 500);
  EXPECT_EQ(batch.unsolved, 0);
  EXPECT_EQ(batch.energy_gains, 0) << "largest relative gain " << batch.largest_gain;
}

TEST(ImpactProblem, PlasticFrictionalImpactsNeverCreateEnergy) {
  // 1000 seeded impacts, eps = 0, mu in [0, 1].
  const ImpactBatch batch = RandomImpacts(2000, 1000, 0.0, 1.0);
  EXPECT_GT(batch.impacts, 500);
  EXPECT_EQ(batch.unsolved, 0);
  EXPECT_EQ(batch.energy_gains, 0) << "largest relative gain " << batch.largest_gain;
}

TEST(ImpactProblem, RandomImpactsObeyNewtonAndCoulombAndReportEnergyGains) {
  // 1000 seeded impacts, eps and mu in [0, 1]. Newton's kinematic restitution combined with
  // Coulomb friction can create kinetic energy when the normal impulse drives the slip
  // (the paradox of Kane and Levinson 1985, analysed by Stronge 2000 and Glocker 2013): the
  // law of docs/theory.md §3 is assembled exactly, so such gains are reported here, not hidden.
  // With friction and restitution the impact LCP may also have no solution at all; Lemke must
  // then end without one, never miss an existing one.
  const ImpactBatch batch = RandomImpacts(3000, 1000, 1.0, 1.0);
  EXPECT_GT(batch.impacts, 500);
  EXPECT_EQ(batch.unsolved_but_solvable, 0);
  EXPECT_EQ(batch.gains_without_friction, 0);
  std::cout << "random frictional impacts: " << batch.impacts << " solved, " << batch.energy_gains
            << " gain energy (largest " << batch.largest_gain * 100.0 << " % of T_A), "
            << batch.unsolved << " without a solution\n";
}

TEST(ImpactProblem, SingleContactClosedFormEqualsLemke) {
  // A single contact is solved in closed form where its LCP has a unique solution
  // (G_nn - mu |G_nt| > 0); Lemke on the same LCP (last_A, last_b) is the second method. 1000
  // seeded impacts of one corner, eps in [0, 1], mu in [0, 1] or [0, 3]: the impulses agree to
  // 1e-10, and where the closed form does not apply the status is Lemke's.
  std::mt19937_64 rng(4000);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int closed_form = 0, by_lemke = 0, stick = 0, slip = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    // Every third trial with mu up to 3: some of those are not unique (G_nn < mu |G_nt|).
    const double mu = trial % 10 == 0 ? 0.0 : (trial % 3 == 0 ? 3.0 : 1.0) * unit(rng);
    const model::Model model =
        testing::FreeDeck(5.0 + 70.0 * unit(rng), 0.3 + 3.7 * unit(rng), 10.0 + 40.0 * unit(rng),
                          0.05, unit(rng), mu, model::AbutmentSet::kBoth, 1.0 + 1e3 * unit(rng));
    const Eigen::Vector3d q(0.2 * (unit(rng) - 0.5), 0.2 * (unit(rng) - 0.5),
                            0.1 * (unit(rng) - 0.5));
    const Eigen::Vector3d u_A(2.0 * unit(rng) - 1.0, 2.0 * unit(rng) - 1.0,
                              0.2 * (unit(rng) - 0.5));
    ContactKinematics kin;
    kin.Resize(model);
    Evaluate(model, q, u_A, kin);
    const int c = static_cast<int>(rng() % 4);
    if (!(kin.gamma_N(c) < 0.0)) {
      continue;
    }
    ImpactProblem problem(model);
    ImpactResult r = problem.MakeResult();
    const std::vector<int> one{c};
    const lcp::LcpStatus status = problem.Solve(kin, one, u_A, r);
    lcp::LemkeSolver lemke;
    lcp::LcpSolution reference;
    const lcp::LcpStatus expected = lemke.Solve(problem.last_A(), problem.last_b(), reference);
    if (r.pivots > 0 || status != lcp::LcpStatus::kSolved) {
      ++by_lemke;
      EXPECT_EQ(status, expected) << "trial " << trial;
      continue;
    }
    ++closed_form;
    ASSERT_EQ(expected, lcp::LcpStatus::kSolved) << "trial " << trial;
    const double Lambda_N = reference.z(0), Lambda_T = reference.z(1) - mu * reference.z(0);
    const double scale = std::abs(Lambda_N) + std::abs(Lambda_T);
    EXPECT_NEAR(r.Lambda_N(0), Lambda_N, 1e-10 * scale) << "trial " << trial;
    EXPECT_NEAR(r.Lambda_T(0), Lambda_T, 1e-10 * scale) << "trial " << trial;
    // The post-impact velocities as the general path forms them.
    const Eigen::Vector3d u_E =
        u_A + model.inverse_mass_diagonal().asDiagonal() *
                  (kin.W_N.col(c) * r.Lambda_N(0) + kin.W_T.col(c) * r.Lambda_T(0));
    EXPECT_LT((r.u_E - u_E).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + u_A.cwiseAbs().maxCoeff()));
    EXPECT_NEAR(r.gamma_N_E(0), kin.W_N.col(c).dot(r.u_E), 1e-12);
    (std::abs(r.Lambda_T(0)) < mu * r.Lambda_N(0) * (1.0 - 1e-12) ? stick : slip) += 1;
  }
  EXPECT_GT(closed_form, 300);
  EXPECT_GT(stick, 30);
  EXPECT_GT(slip, 30);
  EXPECT_GT(by_lemke, 5);
  std::cout << "single-contact impacts: " << closed_form << " in closed form (" << stick
            << " stick, " << slip << " slip), " << by_lemke << " by Lemke\n";
}

// Bit for bit: equal as doubles and with the same sign (a zero's sign included).
bool SameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

TEST(ImpactProblem, TwoContactPathIsTheBitsOfTheDenseProducts) {
  // A single deck's impacts (kAuto: fixed-size sums) against the dense Eigen products of the
  // same LCP (kDense), over seeded random decks, states and sets of its four corners, with and
  // without friction, persistent contacts and exact zeros in u_A: the LCP, the impulses and the
  // velocities after are the same bits. A sum taken in another order differs in its last bits
  // within a few trials.
  std::mt19937_64 rng(5000);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double mu = trial % 4 == 0 ? 0.0 : unit(rng);
    const model::Model model =
        testing::FreeDeck(5.0 + 60.0 * unit(rng), 0.3 + 2.7 * unit(rng), 10.0 + 40.0 * unit(rng),
                          0.05, unit(rng), mu, model::AbutmentSet::kBoth, 1.0 + 1e3 * unit(rng));
    const Eigen::Vector3d q(0.2 * (unit(rng) - 0.5), 0.2 * (unit(rng) - 0.5),
                            trial % 5 == 0 ? 0.0 : 0.1 * (unit(rng) - 0.5));
    Eigen::Vector3d u_A(2.0 * unit(rng) - 1.0, 2.0 * unit(rng) - 1.0, 0.2 * (unit(rng) - 0.5));
    if (trial % 7 == 0) u_A(1 + trial % 2) = 0.0;
    ContactKinematics kin;
    kin.Resize(model);
    Evaluate(model, q, u_A, kin);
    const int first = static_cast<int>(4 * unit(rng)) % 4;
    // Mostly pairs (AssemblePair), also one contact (SolveOne) and three or four (Eigen's
    // products on both sides, after the deck's own copies of the columns).
    const int size = trial % 8 == 1 ? 1 : trial % 8 == 3 ? 3 : trial % 8 == 5 ? 4 : 2;
    std::vector<int> index_set{first};
    for (int j = 1; j < size; ++j)
      index_set.push_back((first + j + (size == 2 ? trial % 3 : 0)) % 4);
    std::vector<int> persistent;
    if (trial % 3 == 0) persistent.push_back(index_set.back());
    const bool frictionless = trial % 11 == 0;
    ImpactProblem fixed(model), dense(model, {}, Assembly::kDense);
    ImpactResult a = fixed.MakeResult(), b = dense.MakeResult();
    const lcp::LcpStatus status_a = fixed.Solve(kin, index_set, u_A, a, persistent, frictionless);
    const lcp::LcpStatus status_b = dense.Solve(kin, index_set, u_A, b, persistent, frictionless);
    ASSERT_EQ(status_a, status_b) << "trial " << trial;
    ASSERT_EQ(a.pivots, b.pivots) << "trial " << trial;
    const Eigen::Index n = fixed.last_A().rows();
    ASSERT_EQ(n, 3 * size);
    ASSERT_EQ(dense.last_A().rows(), n);
    ++compared;
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index i = 0; i < n; ++i) {
        ASSERT_TRUE(SameBits(fixed.last_A()(i, j), dense.last_A()(i, j)))
            << "trial " << trial << " A(" << i << ", " << j << ")";
      }
      ASSERT_TRUE(SameBits(fixed.last_b()(j), dense.last_b()(j))) << "trial " << trial;
    }
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(SameBits(a.u_E(i), b.u_E(i))) << "trial " << trial << " u_E(" << i << ")";
    }
    for (int j = 0; j < size; ++j) {
      ASSERT_TRUE(SameBits(a.Lambda_N(j), b.Lambda_N(j))) << "trial " << trial;
      ASSERT_TRUE(SameBits(a.Lambda_T(j), b.Lambda_T(j))) << "trial " << trial;
      ASSERT_TRUE(SameBits(a.gamma_N_A(j), b.gamma_N_A(j))) << "trial " << trial;
      ASSERT_TRUE(SameBits(a.gamma_N_E(j), b.gamma_N_E(j))) << "trial " << trial;
      ASSERT_TRUE(SameBits(a.gamma_T_E(j), b.gamma_T_E(j))) << "trial " << trial;
    }
  }
  EXPECT_EQ(compared, 2000);
}

TEST(ImpactProblem, EmptyIndexSetLeavesTheVelocityUnchanged) {
  const model::Model model = testing::FreeDeck(30.0, 1.0, 10.0, 0.05, 0.5, 0.2);
  ContactKinematics kin;
  kin.Resize(model);
  const Eigen::Vector3d u(1.0, 2.0, 3.0);
  Evaluate(model, Eigen::Vector3d::Zero(), u, kin);
  ImpactProblem problem(model);
  ImpactResult r = problem.MakeResult();
  EXPECT_EQ(problem.Solve(kin, {}, u, r), lcp::LcpStatus::kSolved);
  EXPECT_EQ(r.u_E, u);
}

}  // namespace
}  // namespace skewbridge::contact
