#pragma once
/// @file
/// Lemke's complementary pivoting algorithm for the linear complementarity problem
///
///     w = M z + q,   w >= 0,   z >= 0,   w^T z = 0
///
/// [Cottle, Pang and Stone 1992, §4.4], with the lexicographic ratio test that keeps it from
/// cycling on degenerate problems [ibid., §4.9]. The solver knows nothing of decks or contacts.
///
/// The scheme augments the problem with the covering vector e = (1, ..., 1) and an artificial
/// variable z0, w = M z + q + e z0, and pivots from the almost-complementary basis {w} along the
/// path that keeps exactly one complementary pair out of the basis, until z0 leaves (a solution)
/// or the entering column has no positive entry (a secondary ray). The inverse basis is kept
/// explicitly (revised form), so one pivot costs about 2 n^2 flops and allocates nothing.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace skewbridge::lcp {

/// How a solve ended. Only kSolved carries a solution; the others are expected outcomes that
/// callers store as data (a Painleve situation of the contact problem ends on a secondary ray).
enum class LcpStatus {
  kSolved,        ///< z, w satisfy the LCP within the tolerances
  kSecondaryRay,  ///< Lemke ended on a secondary ray: no solution found (none may exist)
  kPivotLimit,    ///< the pivot budget ran out
  kInvalidInput,  ///< non-square M, size mismatch, NaN or Inf, empty problem
  kInaccurate,    ///< Lemke ended on a complementary basis, but rounding left z, w outside the
                  ///< acceptance tolerance (a near-singular basis); z, w are the best found
};

/// Human-readable name of a status ("solved", "secondary-ray", ...).
const char* ToString(LcpStatus status);

/// Tuning of the solver; the defaults suit the contact problems (n <= 24).
struct LemkeOptions {
  int max_pivots_per_unknown = 50;  ///< pivot budget = this * (n + 1)
  /// Pivot tolerance: |q'_i| <= 2 relative_tolerance counts as q'_i = 0, and an entry d_i of
  /// the entering column counts as positive when
  /// d_i > relative_tolerance g_i max|a_e|, where M and q are first scaled exactly by powers of
  /// two to max|M'|, max|q'| in (1/2, 1] and g_i is the growth bound of row i of the inverse
  /// basis (the largest magnitude combined into it, hence the size of its rounding error).
  double relative_tolerance = 1e-13;
  /// Tie tolerance of the ratio test, on the same scale: two ratios tie when they differ by less
  /// than tie_tolerance g_i (1 + |ratio_i| max|a_e|) / d_i summed over both rows. Tighter than
  /// the pivot tolerance so that near-ties are resolved by value, exact ties lexicographically.
  double tie_tolerance = 1e-14;
  /// A terminal basis is accepted as kSolved when CheckSolution's worst violation is at most
  /// this; otherwise the status is kInaccurate.
  double acceptance_tolerance = 1e-8;
};

/// The result of a solve. Vectors are resized only when n changes, so a reused solution does
/// not allocate in steady state.
struct LcpSolution {
  LcpStatus status = LcpStatus::kInvalidInput;
  Eigen::VectorXd z;             ///< complementary variable (meaningful when solved)
  Eigen::VectorXd w;             ///< w = M z + q, recomputed from the unscaled data
  int pivots = 0;                ///< pivots performed (the first one brings in z0)
  double complementarity = 0.0;  ///< max(|min(z, w)|) after the solve (0 for an exact solution)
  double worst_violation = 0.0;  ///< CheckSolution(M, q, z).worst_violation after the solve
  std::string message;  ///< empty when solved; otherwise why not (invalid input names the problem)
};

/// Lemke's algorithm with a reusable workspace: construct once, call Solve many times.
/// Not thread-safe (the workspace is per instance); one instance per integrator. The workspace
/// grows to the largest n seen and is never shrunk, so solves of any n up to that size do not
/// allocate.
class LemkeSolver {
 public:
  /// A solver whose workspace is sized lazily on the first solve of each size.
  explicit LemkeSolver(LemkeOptions options = {});

  /// Solves w = M z + q, w, z >= 0, w^T z = 0. Never throws; the status says how it ended.
  /// Entries of q within 2 relative_tolerance max|q| of zero are taken as zero, so that q with
  /// rounding residue of either sign is not sent down a false secondary ray; q >= 0 (after
  /// that) gives z = 0 with zero pivots. With a P-matrix M the solution is unique and always
  /// found; with a copositive-plus M a secondary ray proves that {z >= 0 : M z + q >= 0} is
  /// empty [Cottle, Pang and Stone 1992, §4.4].
  /// @return solution.status
  LcpStatus Solve(const Eigen::Ref<const Eigen::MatrixXd>& M,
                  const Eigen::Ref<const Eigen::VectorXd>& q, LcpSolution& solution);

  /// Sizes the workspace for problems up to size max_n and makes `solutions` one solution per
  /// size 0..max_n, so that solves of those sizes into solutions[n] never allocate. The contact
  /// and impact problems call it once per model, not in the time loop.
  void Prepare(Eigen::Index max_n, std::vector<LcpSolution>& solutions);

  /// The options the solver was built with.
  const LemkeOptions& options() const { return options_; }

 private:
  /// Grows the workspace to hold problems of size n (never shrinks it).
  void Reserve(Eigen::Index n);
  /// Pivots on row r with the entering column in column_: the inverse basis and basic values
  /// are updated by one Gauss-Jordan step.
  void Pivot(Eigen::Index n, Eigen::Index r);
  /// The lexicographic minimum-ratio row for the entering column in column_ (whose original
  /// column a_e has max|a_e| = column_size), or -1 when the column has no positive entry
  /// (secondary ray) [Cottle, Pang and Stone 1992, §4.9].
  Eigen::Index LexicographicRatioTest(Eigen::Index n, Eigen::Index z0_row, double column_size);

  LemkeOptions options_;
  Eigen::Index capacity_ = 0;      // workspace holds problems up to this size
  Eigen::MatrixXd inverse_basis_;  // capacity x capacity, top-left n x n used: B^-1
  Eigen::VectorXd basic_values_;   // B^-1 q (scaled problem)
  Eigen::VectorXd column_;         // entering column B^-1 a_e
  Eigen::VectorXd residual_;       // refinement residual q - B x_B
  Eigen::VectorXi basis_;          // basic variable of each row: w_i = i, z_i = n + i, z0 = 2n
  Eigen::VectorXi ties_;           // rows tied in the ratio test
  Eigen::VectorXd row_size_;       // growth bound of each row of [B^-1 | x_B]
  Eigen::VectorXd tie_size_;       // growth bounds of the rows tied in the ratio test
};

}  // namespace skewbridge::lcp
