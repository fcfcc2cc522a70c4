#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "solver/lcp/lcp_check.h"
#include "solver/lcp/lemke.h"
#include "tests/lcp/lcp_oracles.h"

namespace skewbridge::lcp::lemke_test {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using testing::EnumerateSolutions;

/// Asserts the three LCP conditions directly (not through CheckSolution), with the scale of
/// the brief: z >= 0, w >= -tol s, |z^T w| <= tol |z| s, s = |M| |z| + |q| (2-norms).
void ExpectSolves(const MatrixXd& M, const VectorXd& q, const LcpSolution& s, double tol) {
  ASSERT_EQ(s.status, LcpStatus::kSolved) << s.message;
  const VectorXd w = M * s.z + q;
  const double scale = M.norm() * s.z.norm() + q.norm();
  EXPECT_GE(s.z.minCoeff(), 0.0);
  EXPECT_GE(w.minCoeff(), -tol * scale);
  EXPECT_LE(std::abs(s.z.dot(w)), tol * std::max(s.z.norm(), 1.0) * scale);
  EXPECT_LE((s.w - w).norm(), 1e-14 * scale) << "solution.w must be M z + q";
}

TEST(LemkeSolver, ReturnsZeroWithoutPivotsWhenQIsNonnegative) {
  LemkeSolver solver;
  LcpSolution s;
  const MatrixXd M = MatrixXd::Random(3, 3);
  const VectorXd q = (VectorXd(3) << 1.0, 0.0, 2.5).finished();
  EXPECT_EQ(solver.Solve(M, q, s), LcpStatus::kSolved);
  EXPECT_EQ(s.pivots, 0);
  EXPECT_EQ(s.z, VectorXd::Zero(3));
  EXPECT_EQ(s.w, q);
  EXPECT_TRUE(s.message.empty());
}

TEST(LemkeSolver, SolvesOneDimensionalProblemExactly) {
  // w = 4 z - 2: z = 1/2, w = 0.
  LemkeSolver solver;
  LcpSolution s;
  EXPECT_EQ(solver.Solve(MatrixXd::Constant(1, 1, 4.0), VectorXd::Constant(1, -2.0), s),
            LcpStatus::kSolved);
  EXPECT_EQ(s.z(0), 0.5);
  EXPECT_EQ(s.w(0), 0.0);
  EXPECT_EQ(s.pivots, 2);  // z0 in, then z_1 in and z0 out
}

TEST(LemkeSolver, SolvesRandomSymmetricPositiveDefiniteProblems) {
  std::mt19937 rng(20110301);
  LemkeSolver solver;  // reused across sizes: the workspace grows and is reused
  LcpSolution s;
  for (int n = 1; n <= 30; ++n) {
    const MatrixXd M = testing::RandomSpd(n, rng);
    for (int trial = 0; trial < 6; ++trial) {
      const VectorXd q = testing::RandomVector(n, rng);
      SCOPED_TRACE(::testing::Message() << "n = " << n << ", trial " << trial);
      solver.Solve(M, q, s);
      ExpectSolves(M, q, s, 1e-10);
      EXPECT_LE(s.worst_violation, 1e-12);
    }
  }
}

/// Lemke's result against the unique solution found by enumerating all 2^n bases.
void ExpectMatchesEnumeration(const MatrixXd& M, const VectorXd& q, LemkeSolver& solver) {
  const std::vector<VectorXd> all = EnumerateSolutions(M, q, 1e-12);
  ASSERT_EQ(all.size(), 1u) << "a P-matrix LCP has exactly one solution";
  LcpSolution s;
  ASSERT_EQ(solver.Solve(M, q, s), LcpStatus::kSolved) << s.message;
  EXPECT_LE((s.z - all[0]).cwiseAbs().maxCoeff(), 1e-10 * (1.0 + all[0].cwiseAbs().maxCoeff()))
      << "lemke z = " << s.z.transpose() << "\nenumerated z = " << all[0].transpose();
}

TEST(LemkeSolver, MatchesBruteForceEnumerationOnRandomPMatrices) {
  std::mt19937 rng(813);
  LemkeSolver solver;
  for (int n = 1; n <= 8; ++n) {
    for (int trial = 0; trial < 8; ++trial) {
      SCOPED_TRACE(::testing::Message() << "n = " << n << ", trial " << trial);
      ExpectMatchesEnumeration(testing::RandomSpd(n, rng), testing::RandomVector(n, rng), solver);
      ExpectMatchesEnumeration(testing::RandomDiagonallyDominant(n, rng),
                               testing::RandomVector(n, rng), solver);
      ExpectMatchesEnumeration(testing::RandomPositiveDefiniteNonsymmetric(n, rng),
                               testing::RandomVector(n, rng), solver);
    }
  }
}

TEST(LemkeSolver, MatchesBruteForceOnDegenerateIntegerProblems) {
  // Small-integer P-matrices and q in {-1, 0, 1}: many zero basic values, many equal ratios
  // and many equal entries of the inverse basis, the situation where the lexicographic rule
  // decides every pivot.
  std::mt19937 rng(575);
  std::uniform_int_distribution<int> entry(-1, 1);
  LemkeSolver solver;
  for (int n = 2; n <= 8; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      MatrixXd M(n, n);
      VectorXd q(n);
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) M(i, j) = entry(rng);
        M(i, i) = 0.0;
        M(i, i) = M.row(i).cwiseAbs().sum() + 1.0;  // integer, strictly dominant: P-matrix
        q(i) = entry(rng);
      }
      if (q.minCoeff() >= 0.0) q(trial % n) = -1.0;
      SCOPED_TRACE(::testing::Message() << "n = " << n << ", trial " << trial << "\nM =\n"
                                        << M << "\nq = " << q.transpose());
      ExpectMatchesEnumeration(M, q, solver);
    }
  }
}

TEST(LemkeSolver, SolvesMurtyTriangularMatrixWithAllRatiosTied) {
  // Murty's upper-triangular P-matrix (1 on the diagonal, 2 above), with q = -e as in the
  // Handbook of Test Problems in Local and Global Optimization (Floudas et al. 1999), problem
  // 10.2.1, n = 16: every row ties in the first ratio test. Unique solution z = e_16:
  // w_i = 2 - 1 = 1 for i < 16 and w_16 = 1 - 1 = 0.
  const int n = 16;
  MatrixXd M = MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) M(i, j) = 2.0;
  }
  const VectorXd q = VectorXd::Constant(n, -1.0);
  LemkeSolver solver;
  LcpSolution s;
  ASSERT_EQ(solver.Solve(M, q, s), LcpStatus::kSolved) << s.message;
  VectorXd expected = VectorXd::Zero(n);
  expected(n - 1) = 1.0;
  EXPECT_EQ(s.z, expected);
  ExpectSolves(M, q, s, 1e-14);
}

TEST(LemkeSolver, SolvesHandbookProblems) {
  LemkeSolver solver;
  LcpSolution s;
  {
    // Floudas et al. (1999) 10.2.3: a copositive-plus (skew-symmetric part plus PSD) 3 x 3
    // problem with the solution z = (0, 1, 3) given there.
    MatrixXd M(3, 3);
    // clang-format off
    M <<  0, -1,  2,
          2,  0, -2,
         -1,  1,  0;
    // clang-format on
    const VectorXd q = (VectorXd(3) << -3, 6, -1).finished();
    ASSERT_EQ(solver.Solve(M, q, s), LcpStatus::kSolved) << s.message;
    EXPECT_LE((s.z - VectorXd((VectorXd(3) << 0, 1, 3).finished())).norm(), 1e-12);
    ExpectSolves(M, q, s, 1e-12);
  }
  {
    // Floudas et al. (1999) 10.2.9 with q = (50, 50, l, -6), l in [0, 23]: the book's solution
    // z = ((l + 16)/13, (l + 16)/13, 2 (23 - l)/13, (1286 - 9 l)/13). (The book misprints
    // M(3, 3) as 1; it is 0, as in Drake's test of the same problem.)
    MatrixXd M(4, 4);
    // clang-format off
    M << 11,  0, 10, -1,
          0, 11, 10, -1,
         10, 10, 21, -1,
          1,  1,  1,  0;
    // clang-format on
    for (double l : {1.0, 16.0}) {
      const VectorXd q = (VectorXd(4) << 50, 50, l, -6).finished();
      const VectorXd expected =
          (VectorXd(4) << (l + 16) / 13, (l + 16) / 13, 2 * (23 - l) / 13, (1286 - 9 * l) / 13)
              .finished();
      ASSERT_EQ(solver.Solve(M, q, s), LcpStatus::kSolved) << s.message;
      EXPECT_LE((s.z - expected).norm(), 1e-11 * expected.norm()) << s.z.transpose();
    }
  }
}

TEST(LemkeSolver, SolvesFullyDegenerateRankOneProblems) {
  // M = e e^T (PSD, rank one), q = -e: every ratio ties at every pivot and the solutions form
  // the simplex {z >= 0, sum z = 1} (Floudas et al. 1999, 10.2.2 is n = 2). Termination and
  // the simplex condition are checked.
  LemkeSolver solver;
  LcpSolution s;
  for (int n = 1; n <= 12; ++n) {
    const MatrixXd M = MatrixXd::Ones(n, n);
    const VectorXd q = VectorXd::Constant(n, -1.0);
    ASSERT_EQ(solver.Solve(M, q, s), LcpStatus::kSolved) << "n = " << n << ": " << s.message;
    EXPECT_NEAR(s.z.sum(), 1.0, 1e-14);
    ExpectSolves(M, q, s, 1e-14);
  }
}

TEST(LemkeSolver, SolvesProblemsWithZeroEntriesInQ) {
  // q with zero entries makes the starting basis degenerate; P-matrices keep the answer unique.
  std::mt19937 rng(44);
  LemkeSolver solver;
  for (int n = 2; n <= 8; ++n) {
    for (int trial = 0; trial < 10; ++trial) {
      VectorXd q = testing::RandomVector(n, rng);
      for (int i = 0; i < n; i += 2) q(i) = 0.0;
      q(1) = -std::abs(q(1)) - 0.1;
      SCOPED_TRACE(::testing::Message() << "n = " << n << ", trial " << trial);
      ExpectMatchesEnumeration(testing::RandomSpd(n, rng), q, solver);
    }
  }
}

TEST(LemkeSolver, TerminatesWhereIndexTieBreakingCycles) {
  // Two degenerate problems on which Lemke's method with a naive tie-break of the ratio test
  // cycles forever in exact arithmetic: the path revisits a basis with the same entering
  // variable after 7 (resp. 5) pivots. Found and checked by tests/lcp/cycling_search.py
  // (seeded search, exact rationals). The lexicographic rule must end each of them.
  LemkeSolver solver;
  LcpSolution s;
  {
    // Cycles with "last tied row"; solutions (enumerated) include z = (0, 0, 1, 0).
    MatrixXd M(4, 4);
    // clang-format off
    M <<  1,  2,  2,  2,
         -1, -1,  1,  2,
          1,  1,  1,  0,
          2,  1,  2,  1;
    // clang-format on
    const VectorXd q = (VectorXd(4) << -1, 0, -1, -1).finished();
    ASSERT_FALSE(EnumerateSolutions(M, q, 1e-12).empty());
    ASSERT_EQ(solver.Solve(M, q, s), LcpStatus::kSolved) << s.message;
    EXPECT_LE(CheckSolution(M, q, s.z, 0.0).worst_violation, 1e-15);
  }
  {
    // Cycles with "first tied row"; enumeration of all 16 complementary bases finds no
    // solution, so the only correct outcome is a secondary ray.
    MatrixXd M(4, 4);
    // clang-format off
    M <<  1,  1,  1,  2,
          1,  1,  1,  1,
         -1,  2,  2,  1,
         -1,  0, -1, -1;
    // clang-format on
    const VectorXd q = (VectorXd(4) << 0, -1, -1, -1).finished();
    ASSERT_TRUE(EnumerateSolutions(M, q, 1e-12).empty());
    EXPECT_EQ(solver.Solve(M, q, s), LcpStatus::kSecondaryRay) << s.message;
  }
}

TEST(LemkeSolver, SolvesContactProblemWhoseQHasATinyNegativeEntry) {
  // A contact problem of one deck at rest: w_1 = 4.3e-6 z_1 + 8e-17, w_2 = 1.2e-5 z_2 + z_3 -
  // 2e-35, w_3 = -z_2. Exactly: w_3 >= 0 and z_2 >= 0 force z_2 = 0; then w_2 = z_3 - 2e-35 >= 0
  // makes z_3 > 0, so w_2 = 0 and z_3 = 2e-35; w_1 > 0 for z_1 >= 0, so z_1 = 0. The unique
  // solution is z* = (0, 0, 2e-35), w* = (8e-17, 0, 0). M is PSD (M + M^T = diag(8.6e-6,
  // 2.4e-5, 0)), hence copositive-plus, so a secondary ray would claim that no z >= 0 makes
  // w >= 0, which z* disproves. The tiny entry is 2.5e-19 max|q|: the solver may read it as 0,
  // and z = 0 then misses w* by that much.
  MatrixXd M(3, 3);
  // clang-format off
  M << 4.3e-6,  0.0,    0.0,
       0.0,     1.2e-5, 1.0,
       0.0,    -1.0,    0.0;
  // clang-format on
  const VectorXd q = (VectorXd(3) << 8e-17, -2e-35, 0.0).finished();
  const VectorXd z_exact = (VectorXd(3) << 0.0, 0.0, 2e-35).finished();
  const VectorXd w_exact = (VectorXd(3) << 8e-17, 0.0, 0.0).finished();
  ASSERT_EQ(CheckSolution(M, q, z_exact, 0.0).worst_violation, 0.0);
  LemkeSolver solver;
  LcpSolution s;
  for (double factor : {1.0, 1e10, 1e-200}) {  // the same problem in other units of q
    SCOPED_TRACE(::testing::Message() << "q scaled by " << factor);
    ASSERT_EQ(solver.Solve(M, factor * q, s), LcpStatus::kSolved) << s.message;
    EXPECT_LE(CheckSolution(M, factor * q, s.z, 1e-8).worst_violation, 1e-18);
    EXPECT_LE((s.z - factor * z_exact).cwiseAbs().maxCoeff(), factor * 1e-13 * q.norm());
    EXPECT_LE((s.w - factor * w_exact).cwiseAbs().maxCoeff(), factor * 1e-13 * q.norm());
    EXPECT_EQ(s.worst_violation, CheckSolution(M, factor * q, s.z, 0.0).worst_violation);
  }
  // When the negative entry is not negligible against max|q| (2.5e-4 of it), it is kept and
  // the exact solution z_3 = -q_2 is found.
  const VectorXd q_kept = (VectorXd(3) << 8e-17, -2e-20, 0.0).finished();
  ASSERT_EQ(solver.Solve(M, q_kept, s), LcpStatus::kSolved) << s.message;
  EXPECT_EQ(s.z(0), 0.0);
  EXPECT_EQ(s.z(1), 0.0);
  EXPECT_NEAR(s.z(2), 2e-20, 1e-13 * 2e-20);
}

/// A PSD contact-like matrix [[P, E], [-E^T, 0]] (P SPD of k rows with a random magnitude in
/// 1e-6 .. 1, E with entries in {0, 1} of k x m): the structure of the friction problems,
/// copositive-plus but not a P-matrix, so solutions need not be unique.
MatrixXd RandomContactLikeMatrix(int k, int m, std::mt19937& rng) {
  std::uniform_real_distribution<double> exponent(-6.0, 0.0);
  std::bernoulli_distribution one(0.6);
  MatrixXd M = MatrixXd::Zero(k + m, k + m);
  M.topLeftCorner(k, k) = std::pow(10.0, exponent(rng)) * testing::RandomSpd(k, rng);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < m; ++j) {
      const double e = one(rng) ? 1.0 : 0.0;
      M(i, k + j) = e;
      M(k + j, i) = -e;
    }
  }
  return M;
}

/// q = w* - M z* for a random complementary pair (z*, w*) in which about a third of the
/// indices are degenerate (z*_i = w*_i = 0) and, half the time, z* = 0 (at least one index is
/// not degenerate, so q != 0). Every degenerate q_i is then moved by dq_i of either sign with
/// |dq_i| = 10^u max|q|: u in [-35, -14] below the solver's tolerance (tiny = true), else u in
/// [-6, -3], which makes a different problem that the enumeration has to judge.
VectorXd PerturbedDegenerateQ(const MatrixXd& M, bool tiny, std::mt19937& rng) {
  const int n = static_cast<int>(M.rows());
  std::uniform_int_distribution<int> kind(0, 2);  // 0: z basic, 1: w basic, 2: degenerate
  std::uniform_real_distribution<double> value(0.1, 1.0);
  std::uniform_real_distribution<double> exponent(tiny ? -35.0 : -6.0, tiny ? -14.0 : -3.0);
  std::bernoulli_distribution coin(0.5);
  const bool z_zero = coin(rng);
  VectorXd z = VectorXd::Zero(n);
  VectorXd w = VectorXd::Zero(n);
  std::vector<int> degenerate;
  for (int i = 0; i < n; ++i) {
    const int k = (i == 0) ? 1 : kind(rng);
    if (k == 0 && !z_zero) z(i) = value(rng);
    if (k == 1 || (k == 0 && z_zero)) w(i) = value(rng);
    if (k == 2) degenerate.push_back(i);
  }
  VectorXd q = w - M * z;
  const double size = q.cwiseAbs().maxCoeff();
  for (int i : degenerate) {
    q(i) += (coin(rng) ? 1.0 : -1.0) * std::pow(10.0, exponent(rng)) * size;
  }
  return q;
}

TEST(LemkeSolver, MatchesBruteForceOnPerturbationsOfDegenerateProblems) {
  // Each problem is solved as given and in the units of the contact problems (q of order
  // 1e-16, as for a deck at rest). Perturbations below the solver's tolerance must give a
  // solution that passes the independent check and is, scaled back, one of the solutions the
  // enumeration of all complementary bases finds. Larger ones are judged by the enumeration:
  // both matrix classes are copositive-plus, so Lemke's method solves every solvable problem
  // and ends on a secondary ray only when none is solvable [Cottle, Pang and Stone 1992,
  // §4.4].
  std::mt19937 rng(20260121);
  LemkeSolver solver;
  LcpSolution s;
  int solved = 0;
  int rays = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const bool contact_like = trial % 2 == 0;
    const bool tiny = trial % 3 != 0;
    std::uniform_int_distribution<int> rows(1, 4);
    const int k = rows(rng);
    const int m = contact_like ? rows(rng) : 0;
    const MatrixXd M =
        contact_like ? RandomContactLikeMatrix(k, m, rng) : testing::RandomSpd(k + 2, rng);
    const VectorXd q = PerturbedDegenerateQ(M, tiny, rng);
    const std::vector<VectorXd> all = EnumerateSolutions(M, q, 1e-11);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << (tiny ? " (tiny)" : "") << "\nM =\n"
                                      << M << "\nq = " << q.transpose());
    if (tiny) {
      ASSERT_FALSE(all.empty()) << "a tiny perturbation keeps a near-solution";
    }
    for (double q_units : {1.0, 1e-16}) {
      if (all.empty()) {
        EXPECT_EQ(solver.Solve(M, q_units * q, s), LcpStatus::kSecondaryRay);
        ++rays;
        continue;
      }
      ASSERT_EQ(solver.Solve(M, q_units * q, s), LcpStatus::kSolved) << s.message;
      EXPECT_LE(CheckSolution(M, q_units * q, s.z, 1e-10).worst_violation, 1e-12);
      const VectorXd z = s.z / q_units;
      double nearest = std::numeric_limits<double>::infinity();
      for (const VectorXd& e : all) {
        nearest =
            std::min(nearest, (z - e).cwiseAbs().maxCoeff() / (1.0 + e.cwiseAbs().maxCoeff()));
      }
      EXPECT_LE(nearest, 1e-8) << "lemke z = " << z.transpose();
      ++solved;
    }
  }
  EXPECT_EQ(solved + rays, 1200);
  EXPECT_GT(rays, 0) << "the larger perturbations must also make unsolvable problems";
  EXPECT_GT(solved, 800);
}

TEST(LemkeSolver, ReportsRayForUnsolvableScalarProblem) {
  // w = -z - 1 < 0 for every z >= 0: no solution.
  LemkeSolver solver;
  LcpSolution s;
  EXPECT_EQ(solver.Solve(MatrixXd::Constant(1, 1, -1.0), VectorXd::Constant(1, -1.0), s),
            LcpStatus::kSecondaryRay);
  EXPECT_FALSE(s.message.empty());
}

TEST(LemkeSolver, ReportsRayForCopositivePlusProblemWithInfeasibleQ) {
  // M = [[0, 1], [-1, 0]] is skew-symmetric, so z^T M z = 0 >= 0 and (M + M^T) z = 0: it is
  // copositive-plus, and for such M Lemke's method ends on a secondary ray exactly when
  // {z >= 0 : M z + q >= 0} is empty [Cottle, Pang and Stone 1992, §4.4]. With q = (-1, -1),
  // w_2 = -z_1 - 1 < 0 for every z_1 >= 0: infeasible, so a ray and never a "solution".
  LemkeSolver solver;
  LcpSolution s;
  MatrixXd M(2, 2);
  M << 0, 1, -1, 0;
  EXPECT_EQ(solver.Solve(M, VectorXd::Constant(2, -1.0), s), LcpStatus::kSecondaryRay);

  // The PSD (hence copositive-plus) M = [[1, -1], [-1, 1]] with q = (-1, -1):
  // w_1 + w_2 = -2 < 0 for every z, infeasible.
  M << 1, -1, -1, 1;
  EXPECT_EQ(solver.Solve(M, VectorXd::Constant(2, -1.0), s), LcpStatus::kSecondaryRay);
}

TEST(LemkeSolver, SolvesFeasibleCopositivePlusProblem) {
  // Same skew-symmetric M with q = (-1, 1): w_1 = z_2 - 1, w_2 = 1 - z_1. z_2 >= 1 > 0 forces
  // w_2 = 0, so z_1 = 1 > 0 forces w_1 = 0, so z_2 = 1: the unique solution z = (1, 1), w = 0.
  LemkeSolver solver;
  LcpSolution s;
  MatrixXd M(2, 2);
  M << 0, 1, -1, 0;
  const VectorXd q = (VectorXd(2) << -1, 1).finished();
  ASSERT_EQ(solver.Solve(M, q, s), LcpStatus::kSolved) << s.message;
  EXPECT_EQ(s.z, VectorXd::Ones(2));
  EXPECT_EQ(s.w, VectorXd::Zero(2));
}

TEST(LemkeSolver, StopsAtThePivotLimit) {
  std::mt19937 rng(7);
  const int n = 12;
  const MatrixXd M = testing::RandomSpd(n, rng);
  const VectorXd q = VectorXd::Constant(n, -1.0);
  LemkeSolver solver;
  LcpSolution s;
  ASSERT_EQ(solver.Solve(M, q, s), LcpStatus::kSolved);
  const int needed = s.pivots;
  ASSERT_GT(needed, 2);
  // A budget of (n + 1) * per_unknown pivots below what the solve needs.
  LemkeOptions tight;
  tight.max_pivots_per_unknown = 0;
  LemkeSolver limited(tight);
  EXPECT_EQ(limited.Solve(M, q, s), LcpStatus::kPivotLimit);
  EXPECT_EQ(s.pivots, 1);
  EXPECT_NE(s.message.find("pivot limit"), std::string::npos) << s.message;
}

TEST(LemkeSolver, ReportsInaccurateWhenTheFinalCheckFails) {
  // With a zero acceptance tolerance any rounding in the terminal basis fails the independent
  // check: the status says so, and z, w are still the (rounded) solution.
  std::mt19937 rng(21);
  const MatrixXd M = testing::RandomSpd(20, rng);
  const VectorXd q = testing::RandomVector(20, rng);
  LemkeOptions strict;
  strict.acceptance_tolerance = 0.0;
  LemkeSolver solver(strict);
  LcpSolution s;
  ASSERT_EQ(solver.Solve(M, q, s), LcpStatus::kInaccurate);
  EXPECT_GT(s.worst_violation, 0.0);
  EXPECT_LE(s.worst_violation, 1e-12);
  EXPECT_NE(s.message.find("inaccurate"), std::string::npos) << s.message;
  EXPECT_LE(CheckSolution(M, q, s.z, 1e-12).worst_violation, 1e-12);
}

TEST(LemkeSolver, ScalingByPowersOfTwoIsExact) {
  // (2^20 M, 2^-10 q) has the solution 2^-30 z; the solver scales by powers of two, so the
  // pivots see the same numbers and the answer is bit-identical after rescaling.
  std::mt19937 rng(99);
  LemkeSolver solver;
  LcpSolution a;
  LcpSolution b;
  for (int n : {3, 7, 15}) {
    const MatrixXd M = testing::RandomDiagonallyDominant(n, rng);
    VectorXd q = testing::RandomVector(n, rng);
    if (n == 7) q /= q.cwiseAbs().maxCoeff();  // max|q| exactly 1: a power of two itself
    ASSERT_EQ(solver.Solve(M, q, a), LcpStatus::kSolved);
    // Scales near the ends of the normal range too: the solver's powers of two must be exact
    // there (its exponents read from the bits, its products by 2^e).
    for (const auto& [e_m, e_q] : {std::pair{20, -10}, {-300, -1000}, {600, 900}, {-500, 300}}) {
      SCOPED_TRACE(::testing::Message() << "M x 2^" << e_m << ", q x 2^" << e_q);
      ASSERT_EQ(solver.Solve(std::ldexp(1.0, e_m) * M, std::ldexp(1.0, e_q) * q, b),
                LcpStatus::kSolved);
      EXPECT_EQ(std::ldexp(1.0, e_q - e_m) * a.z, b.z);
      EXPECT_EQ(a.pivots, b.pivots);
    }
  }
}

TEST(LemkeSolver, SolutionIsInvariantUnderGeneralScaling) {
  // Scaling by non-powers of two changes rounding only: z scales as q / M.
  std::mt19937 rng(100);
  LemkeSolver solver;
  LcpSolution a;
  LcpSolution b;
  const MatrixXd M = testing::RandomSpd(10, rng);
  const VectorXd q = testing::RandomVector(10, rng);
  ASSERT_EQ(solver.Solve(M, q, a), LcpStatus::kSolved);
  ASSERT_EQ(solver.Solve(3.7e-7 * M, 0.31 * q, b), LcpStatus::kSolved);
  EXPECT_LE((b.z - (0.31 / 3.7e-7) * a.z).norm(), 1e-12 * b.z.norm());
}

TEST(LemkeSolver, RejectsInvalidInputWithAMessage) {
  LemkeSolver solver;
  LcpSolution s;
  auto expect_invalid = [&](const MatrixXd& M, const VectorXd& q, const std::string& needle) {
    EXPECT_EQ(solver.Solve(M, q, s), LcpStatus::kInvalidInput);
    EXPECT_EQ(s.status, LcpStatus::kInvalidInput);
    EXPECT_NE(s.message.find(needle), std::string::npos) << "message: " << s.message;
  };
  expect_invalid(MatrixXd::Identity(2, 3), VectorXd::Ones(2), "square");
  expect_invalid(MatrixXd::Identity(3, 3), VectorXd::Ones(2), "size");
  expect_invalid(MatrixXd(0, 0), VectorXd(0), "empty");
  MatrixXd M = MatrixXd::Identity(3, 3);
  M(1, 2) = std::numeric_limits<double>::quiet_NaN();
  expect_invalid(M, -VectorXd::Ones(3), "M(1, 2) is not finite");
  M(1, 2) = std::numeric_limits<double>::infinity();
  expect_invalid(M, -VectorXd::Ones(3), "M(1, 2) is not finite");
  VectorXd q = -VectorXd::Ones(3);
  q(2) = -std::numeric_limits<double>::infinity();
  expect_invalid(MatrixXd::Identity(3, 3), q, "q(2) is not finite");
  q(2) = std::numeric_limits<double>::quiet_NaN();
  expect_invalid(MatrixXd::Identity(3, 3), q, "q(2) is not finite");
}

TEST(LemkeSolver, FindsEveryNonFiniteEntryOfABlock) {
  // The finiteness check against std::isfinite entry by entry: a NaN or an infinity at any
  // position of M or q is invalid input, M read as a block of a larger matrix (its columns
  // further apart than its rows); with every entry finite the block solves to the bits of a
  // compact copy.
  std::mt19937 rng(11);
  LemkeSolver solver;
  LcpSolution s, compact;
  const double bad[3] = {std::numeric_limits<double>::quiet_NaN(),
                         std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity()};
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  for (int n = 1; n <= 7; ++n) {
    MatrixXd big = MatrixXd::Zero(n + 3, n + 1);
    big.topLeftCorner(n, n) = testing::RandomSpd(n, rng);
    big.bottomRows(3).setConstant(bad[0]);  // outside the block: never read
    const VectorXd q = testing::RandomVector(n, rng);
    const Eigen::Ref<const MatrixXd> block = big.topLeftCorner(n, n);
    ASSERT_EQ(solver.Solve(block, q, s), LcpStatus::kSolved) << n;
    ASSERT_EQ(solver.Solve(MatrixXd(block), q, compact), LcpStatus::kSolved) << n;
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(bits(s.z[i]), bits(compact.z[i])) << n << " " << i;
      EXPECT_EQ(bits(s.w[i]), bits(compact.w[i])) << n << " " << i;
    }
    for (const double v : bad) {
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          MatrixXd m = big;
          m(i, j) = v;
          EXPECT_EQ(solver.Solve(m.topLeftCorner(n, n), q, s), LcpStatus::kInvalidInput)
              << n << " M(" << i << ", " << j << ") = " << v;
        }
        VectorXd r = q;
        r(j) = v;
        EXPECT_EQ(solver.Solve(big.topLeftCorner(n, n), r, s), LcpStatus::kInvalidInput)
            << n << " q(" << j << ") = " << v;
      }
    }
  }
}

TEST(LemkeSolver, StatusNamesAreDistinct) {
  EXPECT_STREQ(ToString(LcpStatus::kSolved), "solved");
  EXPECT_STREQ(ToString(LcpStatus::kSecondaryRay), "secondary-ray");
  EXPECT_STREQ(ToString(LcpStatus::kPivotLimit), "pivot-limit");
  EXPECT_STREQ(ToString(LcpStatus::kInvalidInput), "invalid-input");
  EXPECT_STREQ(ToString(LcpStatus::kInaccurate), "inaccurate");
}

TEST(CheckSolution, MeasuresEachViolationOnItsOwnScale) {
  // M = I, q = (-1, 2): the solution is z = (1, 0), w = (0, 2).
  const MatrixXd M = MatrixXd::Identity(2, 2);
  const VectorXd q = (VectorXd(2) << -1, 2).finished();
  EXPECT_EQ(CheckSolution(M, q, (VectorXd(2) << 1, 0).finished(), 0.0).worst_violation, 0.0);
  // z = (1.5, 0): w = (0.5, 2), s_z = 1.5, s_w = 1.5 + 2; complementarity 0.75 / (1.5 * 3.5).
  const LcpCheck off = CheckSolution(M, q, (VectorXd(2) << 1.5, 0).finished(), 0.1);
  EXPECT_DOUBLE_EQ(off.worst_violation, 0.75 / (1.5 * 3.5));
  EXPECT_FALSE(off.is_solution);
  // z = (0.5, 0): w_1 = -0.5, scaled by s_w = 0.5 + 2.
  EXPECT_DOUBLE_EQ(CheckSolution(M, q, (VectorXd(2) << 0.5, 0).finished(), 0.1).worst_violation,
                   0.5 / 2.5);
  // z = (1, -0.25): z negative by 0.25 / s_z.
  EXPECT_DOUBLE_EQ(CheckSolution(M, q, (VectorXd(2) << 1, -0.25).finished(), 0.1).worst_violation,
                   0.25);
  VectorXd nan_z = VectorXd::Zero(2);
  nan_z(0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(CheckSolution(M, q, nan_z, 1.0).is_solution);
}

TEST(CheckSolution, IsItsDefinitionRowByRowBitForBit) {
  // The definition of the header evaluated row by row, w_i = q_i + M_i0 z_0 + M_i1 z_1 + ...,
  // against CheckSolution (which sums blocks of rows column by column) and CheckSolutionOfFinite
  // (given max|M| and max|q|): the same bits for random problems of 1 to 40 unknowns (more than
  // one block of rows), with negative, zero and complementarity violations.
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Index n = 1 + trial % 40;
    const MatrixXd M = MatrixXd::NullaryExpr(n, n, [&] { return unit(rng); });
    const VectorXd q = VectorXd::NullaryExpr(n, [&] { return unit(rng); });
    VectorXd z = VectorXd::NullaryExpr(n, [&] { return unit(rng); });
    z = z.cwiseMax(trial % 2 == 0 ? 0.0 : -0.1);
    const double max_z = z.cwiseAbs().maxCoeff();
    const double s_z = max_z > 0.0 ? max_z : 1.0;
    const double s_w_raw = M.cwiseAbs().maxCoeff() * max_z + q.cwiseAbs().maxCoeff();
    const double s_w = s_w_raw > 0.0 ? s_w_raw : 1.0;
    double worst = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      double w_i = q(i);
      for (Eigen::Index j = 0; j < n; ++j) w_i += M(i, j) * z(j);
      worst = std::max(worst, -z(i) / s_z);
      worst = std::max(worst, -w_i / s_w);
      worst = std::max(worst, std::abs(z(i) * w_i) / (s_z * s_w));
    }
    const LcpCheck check = CheckSolution(M, q, z, 1e-3);
    const LcpCheck given =
        CheckSolutionOfFinite(M, q, z, M.cwiseAbs().maxCoeff(), q.cwiseAbs().maxCoeff(), 1e-3);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(check.worst_violation),
              std::bit_cast<std::uint64_t>(worst))
        << "n " << n;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(given.worst_violation),
              std::bit_cast<std::uint64_t>(worst))
        << "n " << n;
    EXPECT_EQ(check.is_solution, worst <= 1e-3);
    EXPECT_EQ(given.is_solution, worst <= 1e-3);
  }
}

}  // namespace
}  // namespace skewbridge::lcp::lemke_test
