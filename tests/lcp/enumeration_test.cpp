// lcp::SolveByEnumeration, the second method behind a Painleve status: it agrees with Lemke's
// algorithm where the solution is unique, finds the solution of the degenerate contact problem
// on which Lemke ended on a ray (two corners of one face, identical tangent rows), and proves
// the scalar Painleve problem unsolvable.

#include <gtest/gtest.h>

#include <random>

#include "solver/lcp/enumeration.h"
#include "solver/lcp/lcp_check.h"
#include "solver/lcp/lemke.h"

namespace skewbridge::lcp::enumeration_test {
namespace {

TEST(LcpEnumeration, AgreesWithLemkeOnRandomPMatrices) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  LemkeSolver lemke;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 8;
    Eigen::MatrixXd B(n, n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        B(i, j) = normal(rng);
      }
    }
    // Positive definite (a P-matrix): the solution is unique, so both methods must find it.
    const Eigen::MatrixXd M = B * B.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) {
      q[i] = normal(rng);
    }
    LcpSolution by_lemke, by_enumeration;
    ASSERT_EQ(lemke.Solve(M, q, by_lemke), LcpStatus::kSolved);
    ASSERT_EQ(SolveByEnumeration(M, q, by_enumeration), LcpStatus::kSolved);
    EXPECT_LE((by_lemke.z - by_enumeration.z).cwiseAbs().maxCoeff(),
              1e-9 * (1.0 + by_lemke.z.cwiseAbs().maxCoeff()))
        << "trial " << trial;
  }
}

TEST(LcpEnumeration, SolvesTheDegenerateContactProblemLemkeLeftOnARay) {
  // The contact problem of a robustness-grid cell (Pi_delta = 0, eps_N = 0.5, mu = 0.6, a = 5
  // deg, eta0 = 0.5, W0/w0 = 0.5, w0/w_g = 10, sine) at t = 2.4541 s, two sticking corners of
  // one face: rows 3 and 4 differ only in the identity block (docs/theory.md §3, contact problem).
  Eigen::MatrixXd A(6, 6);
  // clang-format off
  A << 7.44023e-07,  4.78626e-07,  7.58374e-07,  7.58374e-07,  0, 0,
       1.08533e-06,  1.17379e-06, -2.52791e-07, -2.52791e-07,  0, 0,
      -1.57528e-06, -2.58644e-06,  3.88942e-06,  3.88942e-06,  1, 0,
      -1.57528e-06, -2.58644e-06,  3.88942e-06,  3.88942e-06,  0, 1,
       1.2,          0,           -1,           0,            0, 0,
       0,            1.2,          0,          -1,            0, 0;
  // clang-format on
  Eigen::VectorXd b(6);
  b << -2.31786e-12, -3.11898e-12, 0.00017192, 0.00017192, 0, 0;
  LcpSolution s;
  ASSERT_EQ(SolveByEnumeration(A, b, s), LcpStatus::kSolved) << s.message;
  EXPECT_TRUE(CheckSolution(A, b, s.z, 1e-9).is_solution);
  EXPECT_GT(s.z[0], 0.0);  // the first corner carries the load
}

TEST(LcpEnumeration, ProvesTheScalarPainleveProblemUnsolvable) {
  // w = A lambda + b with A < 0 (a sliding corner whose friction pulls it into the face) and
  // b < 0 (pushed into it): w >= 0 needs lambda <= b / A < 0, so no lambda >= 0 exists.
  Eigen::MatrixXd A(1, 1);
  A << -2.0;
  Eigen::VectorXd b(1);
  b << -1.0;
  LcpSolution s;
  EXPECT_EQ(SolveByEnumeration(A, b, s), LcpStatus::kSecondaryRay);
  LemkeSolver lemke;
  LcpSolution r;
  EXPECT_EQ(lemke.Solve(A, b, r), LcpStatus::kSecondaryRay);
}

TEST(LcpEnumeration, RefusesProblemsTooLargeToEnumerate) {
  const int n = kMaxEnumerationSize + 1;
  LcpSolution s;
  EXPECT_EQ(SolveByEnumeration(Eigen::MatrixXd::Identity(n, n), Eigen::VectorXd::Ones(n), s),
            LcpStatus::kInvalidInput);
}

}  // namespace
}  // namespace skewbridge::lcp::enumeration_test
