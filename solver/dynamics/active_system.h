#pragma once
/// @file
/// The dense linear system of a constrained phase's active set [docs/theory.md §3.10, §3.13]:
/// A x = b with one row per closed contact's normal and per sticking contact's tangent, solved
/// by written-out Gaussian elimination for a few rows, LU or LDL^T beyond, and Eigen's complete
/// orthogonal decomposition (the minimum-norm least-squares solution) when A is singular, with
/// the kernel of a singular A for the split of statically indeterminate forces.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "solver/common/error.h"

namespace skewbridge::dynamics {

/// The dense system A x = b of the active set (one row per closed contact's normal and per
/// sticking contact's tangent), at most 2 n_c rows. Up to kSmallCapacity rows (12 contacts, a
/// bridge of up to 5 spans) it lives in fixed-capacity storage, so the time loop of such models
/// never touches the heap; a larger model sizes heap storage once for its own 2 n_c rows, and
/// only the decomposition's workspace follows the active-set size.
class ActiveSystem {
 public:
  /// Rows held in fixed-capacity storage (12 contacts: a bridge of up to 5 spans).
  static constexpr int kSmallCapacity = 24;

  /// `rank_threshold`: pivots below it times the largest make A singular
  /// (EventPolicy::rank_threshold).
  ActiveSystem(int capacity, double rank_threshold);
  /// Out of line, with the decompositions' code (active_system.cpp).
  ~ActiveSystem();

  /// The raw pointers below point into this object's own storage.
  ActiveSystem(const ActiveSystem&) = delete;
  ActiveSystem& operator=(const ActiveSystem&) = delete;

  /// From now on pivots below `rank_threshold` times the largest make A singular (a workspace
  /// reused by runs of different policies).
  void SetRankThreshold(double rank_threshold);

  /// The largest number of rows (2 n_c of the model).
  int capacity() const { return capacity_; }
  /// Sizes A as m x m (its entries are undefined until written); b keeps its entries.
  void Start(int m) {
    SB_DEMAND(m <= capacity_, "ActiveSystem: more rows than the model has constraints");
    m_ = m;
    if (small_) {
      a_small_.resize(m, m);
      a_stride_ = m;
    }
  }
  /// Column-major raw storage: no branch on the storage kind in the assembly loops.
  double& A(int i, int j) { return a_[i + j * a_stride_]; }
  /// Entry i of the right-hand side.
  double& b(int i) { return b_[i]; }
  /// Entry j of the last solution.
  double x(int j) const { return x_[j]; }
  /// Least-squares minimum-norm solution (a redundant constraint, such as a deck's four corners
  /// on one straight face of two aligned decks, makes A singular).
  void Solve();
  /// For a symmetric A (a Gram matrix W^T M^-1 W: the projection, or an active set without a
  /// sliding contact): LDL^T when every pivot is above the rank threshold relative to the largest,
  /// otherwise (redundant constraints) the orthogonal decomposition of Solve. A fraction of the
  /// decomposition's cost on the small path.
  void SolveSymmetric();
  /// Gaussian elimination with partial pivoting, written out for the few rows of the usual
  /// active set (two to four): the blocked LU of a dynamic-size matrix spends most of its time in
  /// set-up at that size (17 % of a sliding cell's instructions). The same pivots, and the same
  /// regularity test on U's diagonal; false (x untouched) when A is not clearly regular.
  bool SolveDirect();
  /// True when the last Solve or SolveSymmetric met a singular A (small path only).
  bool rank_deficient() const { return rank_deficient_; }
  /// An orthonormal basis of the kernel of the last A (columns of `kernel`, at most `max_dim`);
  /// returns its dimension. The minimum-norm solution plus any combination of these columns
  /// solves A x = b as well (b is in the range of A for a consistent contact problem).
  int Kernel(Eigen::Ref<Eigen::MatrixXd> kernel, int max_dim);
  /// Writable solution (the caller moves it along the kernel).
  double& x_mutable(int j) { return small_ ? x_small_[j] : x_large_[j]; }

 private:
  double rank_threshold_;                // EventPolicy::rank_threshold
  static constexpr int kDirectRows = 6;  // SolveDirect up to this many rows
  using SmallMatrix =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kSmallCapacity, kSmallCapacity>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kSmallCapacity, 1>;

  int capacity_;
  bool small_;
  int m_ = 0;
  int a_stride_ = 0;
  double* a_ = nullptr;
  double* b_ = nullptr;
  const double* x_ = nullptr;
  SmallMatrix a_small_;
  SmallVector b_small_, x_small_;
  Eigen::CompleteOrthogonalDecomposition<SmallMatrix> cod_small_;
  Eigen::LDLT<SmallMatrix> ldlt_small_;
  Eigen::PartialPivLU<SmallMatrix> lu_small_;
  Eigen::SelfAdjointEigenSolver<SmallMatrix> eig_small_;
  Eigen::JacobiSVD<SmallMatrix> svd_small_;
  bool rank_deficient_ = false;
  bool symmetric_ = false;  // the last solve was SolveSymmetric's (Kernel: eigenvectors)
  Eigen::MatrixXd a_large_;
  Eigen::VectorXd b_large_, x_large_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod_large_;
};

}  // namespace skewbridge::dynamics
