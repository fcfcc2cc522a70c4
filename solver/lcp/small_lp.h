#pragma once
/// @file
/// A small dense linear program: maximise c^T y subject to G y <= h, y free, solved by the
/// revised simplex method on its dual, min h^T w subject to G^T w = c, w >= 0 [Chvatal 1983,
/// ch. 5 and 8], with Bland's rule (no cycling on degenerate vertices) and a phase 1 over
/// artificial variables. The optimal y are the simplex multipliers of the dual's equality rows.
/// Meant for a handful of variables and a few dozen constraints (the split of statically
/// indeterminate contact forces along the kernel of an active set); storage of fixed capacity,
/// so a solve never touches the heap.

#include <Eigen/Core>

namespace skewbridge::lcp {

/// How a small LP ended.
enum class LpStatus {
  kOptimal,         ///< y optimal (feasible to the tolerance, no improving direction)
  kInfeasible,      ///< no y satisfies G y <= h (the dual is unbounded)
  kUnbounded,       ///< c^T y grows without bound on the feasible set (the dual is infeasible)
  kIterationLimit,  ///< more pivots than the limit (should not happen with Bland's rule)
  kInvalidInput,    ///< sizes above the capacity, inconsistent sizes, non-finite entries
};

/// Human-readable name of a status ("optimal", "infeasible", ...).
const char* ToString(LpStatus status);

/// The solver with its fixed-capacity workspace.
class SmallLp {
 public:
  /// Largest number of variables (entries of y).
  static constexpr int kMaxVariables = 32;
  /// Largest number of constraints (rows of G).
  static constexpr int kMaxConstraints = 96;

  /// Maximises c^T y subject to G y <= h. G is r x p, h of size r, c and y of size p. The data
  /// should be scaled to order one: the tolerances are absolute (1e-11 on reduced costs and
  /// pivots, 1e-9 on the phase-1 residual).
  LpStatus Maximize(const Eigen::Ref<const Eigen::MatrixXd>& G,
                    const Eigen::Ref<const Eigen::VectorXd>& h,
                    const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> y);

  /// Pivots of the last solve (both phases).
  int pivots() const { return pivots_; }

 private:
  using Square =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxVariables, kMaxVariables>;
  using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxVariables, 1>;
  using Costs = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxConstraints + kMaxVariables, 1>;

  // One phase of the revised simplex over the columns 0..r-1 (constraints) and r..r+p-1
  // (artificials, entering only in phase 1). False when unbounded (kUnbounded in *status) or
  // out of pivots.
  bool Iterate(const Eigen::Ref<const Eigen::MatrixXd>& G, bool phase1, LpStatus* status);
  // Column j of the sign-scaled dual constraint matrix [S G^T | S].
  void ColumnOf(const Eigen::Ref<const Eigen::MatrixXd>& G, int j, Column& col) const;

  int p_ = 0, r_ = 0, pivots_ = 0;
  Column sign_, x_b_, pi_, col_, dir_, c_b_;
  Costs cost_;
  Square b_inv_, basis_matrix_;
  int basis_[kMaxVariables] = {};
};

}  // namespace skewbridge::lcp
