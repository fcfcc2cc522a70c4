#include "solver/lcp/enumeration.h"

#include <Eigen/QR>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "solver/lcp/lcp_check.h"

namespace skewbridge::lcp {

LcpStatus SolveByEnumeration(const Eigen::Ref<const Eigen::MatrixXd>& M,
                             const Eigen::Ref<const Eigen::VectorXd>& q, LcpSolution& solution,
                             double tolerance) {
  const Eigen::Index n = q.size();
  solution.pivots = 0;
  solution.message.clear();
  if (M.rows() != n || M.cols() != n || n == 0 || n > kMaxEnumerationSize || !M.allFinite() ||
      !q.allFinite()) {
    solution.status = LcpStatus::kInvalidInput;
    solution.message = "enumeration: square finite problem of 1 to " +
                       std::to_string(kMaxEnumerationSize) + " unknowns expected";
    return solution.status;
  }
  Eigen::VectorXd z(n), best_z = Eigen::VectorXd::Zero(n);
  double best = std::numeric_limits<double>::infinity();
  Eigen::VectorXi index(n);
  const std::uint32_t subsets = 1u << static_cast<unsigned>(n);
  for (std::uint32_t mask = 0; mask < subsets; ++mask) {
    Eigen::Index k = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (mask & (1u << static_cast<unsigned>(i))) {
        index[k++] = static_cast<int>(i);
      }
    }
    z.setZero();
    if (k > 0) {
      Eigen::MatrixXd Maa(k, k);
      Eigen::VectorXd qa(k);
      for (Eigen::Index r = 0; r < k; ++r) {
        qa[r] = -q[index[r]];
        for (Eigen::Index c = 0; c < k; ++c) {
          Maa(r, c) = M(index[r], index[c]);
        }
      }
      const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(Maa);
      const Eigen::VectorXd za = cod.solve(qa);
      for (Eigen::Index r = 0; r < k; ++r) {
        z[index[r]] = za[r];
      }
    }
    const LcpCheck check = CheckSolution(M, q, z, tolerance);
    if (check.worst_violation < best) {
      best = check.worst_violation;
      best_z = z;
    }
    if (check.is_solution) {
      solution.z = z;
      solution.w = M * z + q;
      solution.worst_violation = check.worst_violation;
      solution.complementarity = solution.z.cwiseMin(solution.w).cwiseAbs().maxCoeff();
      solution.status = LcpStatus::kSolved;
      return solution.status;
    }
  }
  solution.z = best_z;
  solution.w = M * best_z + q;
  solution.worst_violation = best;
  solution.status = LcpStatus::kSecondaryRay;
  solution.message = "enumeration: no complementary basis solves the problem";
  return solution.status;
}

}  // namespace skewbridge::lcp
