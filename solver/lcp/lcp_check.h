#pragma once
/// @file
/// An independent check of a candidate LCP solution, written without any pivoting so that it
/// can judge the solver (the idea of Drake's LinearComplementarityConstraint / IsSolution).

#include <Eigen/Core>

namespace skewbridge::lcp {

/// How far a candidate z is from solving w = M z + q, w >= 0, z >= 0, w^T z = 0.
struct LcpCheck {
  double worst_violation = 0.0;  ///< largest scaled violation (see CheckSolution); +inf if NaN
  bool is_solution = false;      ///< worst_violation <= the tolerance given
};

/// Worst scaled violation of the LCP conditions by z, with w = M z + q evaluated here:
///
///     max_i max( -z_i / s_z,  -w_i / s_w,  |z_i w_i| / (s_z s_w) )
///     s_z = max|z|,  s_w = max|M| max|z| + max|q|   (each replaced by 1 when zero)
///
/// so the measure is invariant under scaling M, q and z, and the complementarity term is
/// |z_i w_i| relative to the size of the terms that make up w. Allocates nothing.
/// @pre M is square, q and z have its size (checked by SB_DEMAND).
LcpCheck CheckSolution(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::VectorXd>& q,
                       const Eigen::Ref<const Eigen::VectorXd>& z, double tolerance);

/// CheckSolution of a problem known to be finite, given its max|M| and max|q| (as
/// M.cwiseAbs().maxCoeff() and q.cwiseAbs().maxCoeff() give them): the same result without
/// reading M and q for their finiteness and sizes again. For a solver that has checked and
/// measured its input (LemkeSolver::Solve).
/// @pre as CheckSolution (SB_DEMAND); M and q finite, max_abs_M and max_abs_q their largest
/// magnitudes.
LcpCheck CheckSolutionOfFinite(const Eigen::Ref<const Eigen::MatrixXd>& M,
                               const Eigen::Ref<const Eigen::VectorXd>& q,
                               const Eigen::Ref<const Eigen::VectorXd>& z, double max_abs_M,
                               double max_abs_q, double tolerance);

}  // namespace skewbridge::lcp
