#pragma once
/// @file
/// Lemke's complementary pivoting algorithm for the linear complementarity problem
///
///     w = M z + q,   w >= 0,   z >= 0,   w^T z = 0
///
/// [Cottle, Pang and Stone 1992, §4.4], with the lexicographic ratio test that keeps it from
/// cycling on degenerate problems [ibid., §4.9]. The solver knows nothing of decks or contacts.

#include <Eigen/Core>
#include <string>

namespace skewbridge::lcp {

/// How a solve ended. Only kSolved carries a solution; the others are expected outcomes that
/// callers store as data (a Painleve situation of the contact problem ends on a secondary ray).
enum class LcpStatus {
  kSolved,        ///< z, w satisfy the LCP within the tolerances
  kSecondaryRay,  ///< Lemke ended on a secondary ray: no solution found (none may exist)
  kPivotLimit,    ///< the pivot budget ran out
  kInvalidInput,  ///< non-square M, size mismatch, NaN or Inf
};

/// Human-readable name of a status ("solved", "secondary-ray", ...).
const char* ToString(LcpStatus status);

/// Tuning of the solver; the defaults suit the contact problems (n <= 24).
struct LemkeOptions {
  int max_pivots_per_unknown = 50;  ///< pivot budget = this * (n + 1)
  double relative_tolerance =
      1e-12;  ///< pivot and feasibility tolerance, relative to max|M|, max|q|
};

/// The result of a solve. Vectors are resized only when n changes, so a reused solution does
/// not allocate in steady state.
struct LcpSolution {
  LcpStatus status = LcpStatus::kInvalidInput;
  Eigen::VectorXd z;             ///< complementary variable (meaningful when solved)
  Eigen::VectorXd w;             ///< w = M z + q
  int pivots = 0;                ///< complementary pivots performed
  double complementarity = 0.0;  ///< max(|min(z, w)|) after the solve (0 for an exact solution)
  std::string message;  ///< empty when solved; otherwise why not (invalid input names the problem)
};

/// Lemke's algorithm with a reusable workspace: construct once, call Solve many times.
/// Not thread-safe (the workspace is per instance); one instance per integrator.
class LemkeSolver {
 public:
  /// A solver whose workspace is sized lazily on the first solve of each size.
  explicit LemkeSolver(LemkeOptions options = {});

  /// Solves w = M z + q, w, z >= 0, w^T z = 0. Never throws; the status says how it ended.
  /// @return solution.status
  LcpStatus Solve(const Eigen::Ref<const Eigen::MatrixXd>& M,
                  const Eigen::Ref<const Eigen::VectorXd>& q, LcpSolution& solution);

 private:
  LemkeOptions options_;
  Eigen::MatrixXd tableau_;  // n x (2n + 2) working tableau
  Eigen::VectorXi basis_;    // basic variable of each row
};

}  // namespace skewbridge::lcp
