/// ActiveSystem (solver/dynamics/active_system.h) against Eigen's complete orthogonal
/// decomposition, the minimum-norm least-squares solution, on every path: the written-out
/// elimination (up to 6 rows), LU and LDL^T beyond, the decomposition of a singular A, heap
/// storage above 24 rows; and the kernel of a singular A on its postconditions.

#include "solver/dynamics/active_system.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <random>

namespace skewbridge::dynamics::active_system_test {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kRank = 1e-10;  // EventPolicy::rank_threshold

// Fills `sys` with A and b and solves (symmetric: SolveSymmetric); returns x.
VectorXd SolveWith(ActiveSystem& sys, const MatrixXd& A, const VectorXd& b, bool symmetric) {
  const int m = static_cast<int>(A.rows());
  sys.Start(m);
  for (int i = 0; i < m; ++i) {
    sys.b(i) = b[i];
    for (int j = 0; j < m; ++j) {
      sys.A(i, j) = A(i, j);
    }
  }
  if (symmetric) {
    sys.SolveSymmetric();
  } else {
    sys.Solve();
  }
  VectorXd x(m);
  for (int j = 0; j < m; ++j) {
    x[j] = sys.x(j);
  }
  return x;
}

VectorXd Reference(const MatrixXd& A, const VectorXd& b) {
  Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(A);
  cod.setThreshold(kRank);
  return cod.solve(b);
}

// A Gram matrix W^T D W of n x m random rows W (rank min(n, m)), D diagonal positive.
MatrixXd Gram(int n, int m, std::mt19937& rng) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> d(0.5, 2.0);
  MatrixXd W(n, m);
  VectorXd D(n);
  for (int i = 0; i < n; ++i) {
    D[i] = d(rng);
    for (int j = 0; j < m; ++j) {
      W(i, j) = g(rng);
    }
  }
  return W.transpose() * D.asDiagonal() * W;
}

TEST(ActiveSystem, RegularSystemsMatchTheOrthogonalDecomposition) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (int capacity : {12, 40}) {  // fixed-capacity storage, heap storage
    ActiveSystem sys(capacity, kRank);
    for (int m = 1; m <= 10; ++m) {
      for (bool symmetric : {false, true}) {
        const MatrixXd A = symmetric ? Gram(m + 3, m, rng)
                                     : MatrixXd::NullaryExpr(m, m, [&] { return g(rng); }).eval() +
                                           3.0 * MatrixXd::Identity(m, m);
        const VectorXd b = VectorXd::NullaryExpr(m, [&] { return g(rng); });
        const VectorXd x = SolveWith(sys, A, b, symmetric);
        const VectorXd ref = Reference(A, b);
        EXPECT_LE((x - ref).norm(), 1e-12 * (1.0 + ref.norm()))
            << "m " << m << " symmetric " << symmetric << " capacity " << capacity;
        EXPECT_FALSE(sys.rank_deficient());
      }
    }
  }
}

TEST(ActiveSystem, SingularSystemsGiveTheMinimumNormSolutionAndTheKernel) {
  // Redundant constraints: m rows of which only r are independent (as four corners of two
  // aligned decks on one straight face), b in the range of A.
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  ActiveSystem sys(24, kRank);
  for (int m = 2; m <= 9; ++m) {
    for (int r = 1; r < m; ++r) {
      for (bool symmetric : {false, true}) {
        MatrixXd A;
        if (symmetric) {
          A = Gram(r, m, rng);  // rank r
        } else {
          const MatrixXd L = MatrixXd::NullaryExpr(m, r, [&] { return g(rng); });
          const MatrixXd R = MatrixXd::NullaryExpr(r, m, [&] { return g(rng); });
          A = L * R;
        }
        const VectorXd b = A * VectorXd::NullaryExpr(m, [&] { return g(rng); });
        const VectorXd x = SolveWith(sys, A, b, symmetric);
        const VectorXd ref = Reference(A, b);
        const std::string where =
            "m " + std::to_string(m) + " r " + std::to_string(r) + (symmetric ? " sym" : "");
        EXPECT_TRUE(sys.rank_deficient()) << where;
        EXPECT_LE((x - ref).norm(), 1e-9 * (1.0 + ref.norm())) << where;
        EXPECT_LE((A * x - b).norm(), 1e-9 * (1.0 + b.norm())) << where;
        // The kernel: m - r orthonormal columns that A maps to zero, orthogonal to x (the
        // minimum-norm solution has no kernel component).
        MatrixXd K = MatrixXd::Zero(24, 24);
        const int d = sys.Kernel(K, 24);
        ASSERT_EQ(d, m - r) << where;
        const MatrixXd Kd = K.topLeftCorner(m, d);
        EXPECT_LE((A * Kd).norm(), 1e-9 * A.norm()) << where;
        EXPECT_LE((Kd.transpose() * Kd - MatrixXd::Identity(d, d)).norm(), 1e-9) << where;
        EXPECT_LE((Kd.transpose() * x).norm(), 1e-9 * (1.0 + x.norm())) << where;
      }
    }
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::active_system_test
