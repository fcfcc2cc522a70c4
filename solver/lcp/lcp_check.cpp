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
  if (!M.allFinite() || !q.allFinite() || !z.allFinite()) {
    check.worst_violation = std::numeric_limits<double>::infinity();
    return check;
  }
  const double max_m = M.cwiseAbs().maxCoeff();
  const double max_q = q.cwiseAbs().maxCoeff();
  const double max_z = z.cwiseAbs().maxCoeff();
  const double s_z = max_z > 0.0 ? max_z : 1.0;
  const double s_w_raw = max_m * max_z + max_q;
  const double s_w = s_w_raw > 0.0 ? s_w_raw : 1.0;

  double worst = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    // w_i by an explicit sum, so the check shares no code path with the solver.
    double w_i = q(i);
    for (Eigen::Index j = 0; j < n; ++j) w_i += M(i, j) * z(j);
    worst = std::max(worst, -z(i) / s_z);
    worst = std::max(worst, -w_i / s_w);
    worst = std::max(worst, std::abs(z(i) * w_i) / (s_z * s_w));
  }
  check.worst_violation = worst;
  check.is_solution = worst <= tolerance;
  return check;
}

}  // namespace skewbridge::lcp
