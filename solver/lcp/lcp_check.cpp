#include "solver/lcp/lcp_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/common/error.h"

namespace skewbridge::lcp {

LcpCheck CheckSolution(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::VectorXd>& q,
                       const Eigen::Ref<const Eigen::VectorXd>& z, double tolerance) {
  SB_DEMAND(M.rows() == M.cols(), "CheckSolution: M must be square");
  SB_DEMAND(q.size() == M.rows() && z.size() == M.rows(), "CheckSolution: size mismatch");
  const Eigen::Index n = M.rows();
  LcpCheck check;
  if (n == 0) {
    check.is_solution = true;
    return check;
  }
  if (!M.allFinite() || !q.allFinite()) {
    check.worst_violation = std::numeric_limits<double>::infinity();
    return check;
  }
  return CheckSolutionOfFinite(M, q, z, M.cwiseAbs().maxCoeff(), q.cwiseAbs().maxCoeff(),
                               tolerance);
}

LcpCheck CheckSolutionOfFinite(const Eigen::Ref<const Eigen::MatrixXd>& M,
                               const Eigen::Ref<const Eigen::VectorXd>& q,
                               const Eigen::Ref<const Eigen::VectorXd>& z, double max_abs_M,
                               double max_abs_q, double tolerance) {
  SB_DEMAND(M.rows() == M.cols(), "CheckSolution: M must be square");
  SB_DEMAND(q.size() == M.rows() && z.size() == M.rows(), "CheckSolution: size mismatch");
  const Eigen::Index n = M.rows();
  LcpCheck check;
  if (n == 0) {
    check.is_solution = true;
    return check;
  }
  if (!z.allFinite()) {
    check.worst_violation = std::numeric_limits<double>::infinity();
    return check;
  }
  const double max_m = max_abs_M;
  const double max_q = max_abs_q;
  const double max_z = z.cwiseAbs().maxCoeff();
  const double s_z = max_z > 0.0 ? max_z : 1.0;
  const double s_w_raw = max_m * max_z + max_q;
  const double s_w = s_w_raw > 0.0 ? s_w_raw : 1.0;

  // w_i = q_i + M_i0 z_0 + M_i1 z_1 + ... by explicit sums in that order, so the check shares no
  // code path with the solver. The rows are taken kRows at a time, each block's sums column by
  // column (M is column-major): every w_i is the same sequence of operations as a row's loop.
  constexpr Eigen::Index kRows = 16;
  const double* m = M.data();
  const Eigen::Index ld = M.outerStride();
  double w[kRows];
  double worst = 0.0;
  for (Eigen::Index i0 = 0; i0 < n; i0 += kRows) {
    const Eigen::Index rows = std::min(kRows, n - i0);
    for (Eigen::Index r = 0; r < rows; ++r) w[r] = q(i0 + r);
    for (Eigen::Index j = 0; j < n; ++j) {
      const double* col = m + j * ld + i0;
      const double z_j = z(j);
      for (Eigen::Index r = 0; r < rows; ++r) w[r] += col[r] * z_j;
    }
    for (Eigen::Index r = 0; r < rows; ++r) {
      const double z_i = z(i0 + r);
      worst = std::max(worst, -z_i / s_z);
      worst = std::max(worst, -w[r] / s_w);
      worst = std::max(worst, std::abs(z_i * w[r]) / (s_z * s_w));
    }
  }
  check.worst_violation = worst;
  check.is_solution = worst <= tolerance;
  return check;
}

}  // namespace skewbridge::lcp
