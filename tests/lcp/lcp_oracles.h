#pragma once
/// @file
/// Independent references for the LCP tests: enumeration of complementary bases and seeded
/// generators of matrix classes with known LCP theory.

#include <Eigen/Core>
#include <Eigen/LU>
#include <cstdint>
#include <random>
#include <vector>

namespace skewbridge::lcp::testing {

/// Every solution of w = M z + q, w, z >= 0, w^T z = 0 found by trying all 2^n complementary
/// bases: z_S = -M_SS^-1 q_S for the index set S of basic z, kept when z_S >= -tol and
/// w = M z + q >= -tol (tolerances absolute); solutions closer than tol are merged. Singular
/// M_SS are skipped. Only for n <= 12.
inline std::vector<Eigen::VectorXd> EnumerateSolutions(const Eigen::MatrixXd& M,
                                                       const Eigen::VectorXd& q, double tol) {
  const int n = static_cast<int>(q.size());
  std::vector<Eigen::VectorXd> solutions;
  for (std::uint32_t mask = 0; mask < (1u << n); ++mask) {
    std::vector<int> basic;
    for (int i = 0; i < n; ++i) {
      if (mask & (1u << i)) basic.push_back(i);
    }
    const int k = static_cast<int>(basic.size());
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
    if (k > 0) {
      Eigen::MatrixXd m_ss(k, k);
      Eigen::VectorXd q_s(k);
      for (int a = 0; a < k; ++a) {
        q_s(a) = q(basic[a]);
        for (int b = 0; b < k; ++b) m_ss(a, b) = M(basic[a], basic[b]);
      }
      Eigen::FullPivLU<Eigen::MatrixXd> lu(m_ss);
      if (lu.rank() < k) continue;
      const Eigen::VectorXd z_s = lu.solve(-q_s);
      for (int a = 0; a < k; ++a) z(basic[a]) = z_s(a);
    }
    const Eigen::VectorXd w = M * z + q;
    if (z.minCoeff() < -tol || w.minCoeff() < -tol) continue;
    // A degenerate solution (some z_i = w_i = 0) is reached from several bases: keep it once.
    bool seen = false;
    for (const Eigen::VectorXd& s : solutions) seen = seen || (s - z).cwiseAbs().maxCoeff() <= tol;
    if (!seen) solutions.push_back(z);
  }
  return solutions;
}

/// Uniform matrix with entries in [-1, 1].
inline Eigen::MatrixXd RandomMatrix(int rows, int cols, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd a(rows, cols);
  for (int j = 0; j < cols; ++j) {
    for (int i = 0; i < rows; ++i) a(i, j) = u(rng);
  }
  return a;
}

/// Uniform vector with entries in [-1, 1].
inline Eigen::VectorXd RandomVector(int n, std::mt19937& rng) { return RandomMatrix(n, 1, rng); }

/// Symmetric positive definite: A A^T + 0.1 I (a P-matrix).
inline Eigen::MatrixXd RandomSpd(int n, std::mt19937& rng) {
  const Eigen::MatrixXd a = RandomMatrix(n, n, rng);
  return a * a.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
}

/// Non-symmetric P-matrix: positive diagonal strictly dominating each row (every principal
/// submatrix is then row diagonally dominant with positive diagonal, so its determinant > 0).
inline Eigen::MatrixXd RandomDiagonallyDominant(int n, std::mt19937& rng) {
  Eigen::MatrixXd m = RandomMatrix(n, n, rng);
  std::uniform_real_distribution<double> margin(0.05, 1.0);
  for (int i = 0; i < n; ++i) {
    m(i, i) = 0.0;
    m(i, i) = m.row(i).cwiseAbs().sum() + margin(rng);
  }
  return m;
}

/// Non-symmetric positive definite (z^T M z > 0): SPD plus skew-symmetric, a P-matrix.
inline Eigen::MatrixXd RandomPositiveDefiniteNonsymmetric(int n, std::mt19937& rng) {
  const Eigen::MatrixXd s = RandomMatrix(n, n, rng);
  return RandomSpd(n, rng) + (s - s.transpose());
}

}  // namespace skewbridge::lcp::testing
