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
  ActiveSystem(int capacity, double rank_threshold)
      : rank_threshold_(rank_threshold),
        capacity_(std::max(capacity, 1)),
        small_(capacity_ <= kSmallCapacity) {
    if (small_) {
      a_small_.resize(kSmallCapacity, kSmallCapacity);
      b_small_.resize(kSmallCapacity);
      x_small_.resize(kSmallCapacity);
      cod_small_.setThreshold(rank_threshold_);
      a_ = a_small_.data();
      b_ = b_small_.data();
      x_ = x_small_.data();
    } else {
      a_large_.resize(capacity_, capacity_);
      b_large_.resize(capacity_);
      x_large_.resize(capacity_);
      cod_large_.setThreshold(rank_threshold_);
      a_ = a_large_.data();
      a_stride_ = capacity_;
      b_ = b_large_.data();
      x_ = x_large_.data();
    }
  }

  /// The raw pointers below point into this object's own storage.
  ActiveSystem(const ActiveSystem&) = delete;
  ActiveSystem& operator=(const ActiveSystem&) = delete;

  /// From now on pivots below `rank_threshold` times the largest make A singular (a workspace
  /// reused by runs of different policies).
  void SetRankThreshold(double rank_threshold) {
    rank_threshold_ = rank_threshold;
    cod_small_.setThreshold(rank_threshold_);
    cod_large_.setThreshold(rank_threshold_);
  }

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
  void Solve() {
    rank_deficient_ = false;
    symmetric_ = false;
    if (small_) {
      // LU with partial pivoting when A is clearly regular (the usual sliding active set), a
      // fraction of the orthogonal decomposition's cost; the decomposition for a singular A.
      if (m_ > 0 && m_ <= kDirectRows) {
        if (SolveDirect()) {
          return;
        }
      } else if (m_ > 0) {
        lu_small_.compute(a_small_);
        const auto diag = lu_small_.matrixLU().diagonal().cwiseAbs();
        if (diag.minCoeff() > rank_threshold_ * diag.maxCoeff()) {
          x_small_ = lu_small_.solve(b_small_.head(m_));
          return;
        }
      }
      cod_small_.compute(a_small_);
      x_small_ = cod_small_.solve(b_small_.head(m_));
      rank_deficient_ = m_ > 0 && cod_small_.rank() < m_;
    } else {
      cod_large_.compute(a_large_.topLeftCorner(m_, m_));
      x_large_.head(m_) = cod_large_.solve(b_large_.head(m_));
    }
  }
  /// For a symmetric A (a Gram matrix W^T M^-1 W: the projection, or an active set without a
  /// sliding contact): LDL^T when every pivot is above the rank threshold relative to the largest,
  /// otherwise (redundant constraints) the orthogonal decomposition of Solve. A fraction of the
  /// decomposition's cost on the small path.
  void SolveSymmetric() {
    rank_deficient_ = false;
    if (small_ && m_ > 0 && m_ <= kDirectRows) {
      // A symmetric A of a few rows: the written-out elimination (its pivots on the diagonal of
      // a Gram matrix are those of LDL^T up to rounding), the decomposition when singular.
      symmetric_ = true;
      if (SolveDirect()) {
        return;
      }
      Solve();
      rank_deficient_ = true;
      symmetric_ = true;
      return;
    }
    if (small_ && m_ > 0) {
      symmetric_ = true;
      ldlt_small_.compute(a_small_);
      const auto d = ldlt_small_.vectorD();
      if (ldlt_small_.info() == Eigen::Success && d.minCoeff() > rank_threshold_ * d.maxCoeff()) {
        x_small_ = ldlt_small_.solve(b_small_.head(m_));
        return;
      }
      Solve();
      rank_deficient_ = true;
      symmetric_ = true;
      return;
    }
    Solve();
  }
  /// Gaussian elimination with partial pivoting, written out for the few rows of the usual
  /// active set (two to four): the blocked LU of a dynamic-size matrix spends most of its time in
  /// set-up at that size (17 % of a sliding cell's instructions). The same pivots, and the same
  /// regularity test on U's diagonal; false (x untouched) when A is not clearly regular.
  bool SolveDirect() {
    const int m = m_;
    double lu[kDirectRows * kDirectRows];
    double rhs[kDirectRows];
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < m; ++i) {
        lu[i + j * m] = a_[i + j * a_stride_];
      }
      rhs[j] = b_[j];
    }
    double diag_min = std::numeric_limits<double>::infinity(), diag_max = 0.0;
    for (int k = 0; k < m; ++k) {
      int pivot = k;
      for (int i = k + 1; i < m; ++i) {
        if (std::abs(lu[i + k * m]) > std::abs(lu[pivot + k * m])) {
          pivot = i;
        }
      }
      if (pivot != k) {
        for (int j = 0; j < m; ++j) {
          std::swap(lu[k + j * m], lu[pivot + j * m]);
        }
        std::swap(rhs[k], rhs[pivot]);
      }
      const double d = lu[k + k * m];
      diag_min = std::min(diag_min, std::abs(d));
      diag_max = std::max(diag_max, std::abs(d));
      if (d == 0.0) {
        return false;
      }
      for (int i = k + 1; i < m; ++i) {
        const double f = lu[i + k * m] / d;
        lu[i + k * m] = f;
        for (int j = k + 1; j < m; ++j) {
          lu[i + j * m] -= f * lu[k + j * m];
        }
        rhs[i] -= f * rhs[k];
      }
    }
    if (!(diag_min > rank_threshold_ * diag_max)) {
      return false;
    }
    x_small_.resize(m);
    for (int i = m - 1; i >= 0; --i) {
      double v = rhs[i];
      for (int j = i + 1; j < m; ++j) {
        v -= lu[i + j * m] * x_small_[j];
      }
      x_small_[i] = v / lu[i + i * m];
    }
    return true;
  }
  /// True when the last Solve or SolveSymmetric met a singular A (small path only).
  bool rank_deficient() const { return rank_deficient_; }
  /// An orthonormal basis of the kernel of the last A (columns of `kernel`, at most `max_dim`);
  /// returns its dimension. The minimum-norm solution plus any combination of these columns
  /// solves A x = b as well (b is in the range of A for a consistent contact problem).
  int Kernel(Eigen::Ref<Eigen::MatrixXd> kernel, int max_dim) {
    if (!small_ || m_ == 0) {
      return 0;
    }
    if (!symmetric_) {
      svd_small_.compute(a_small_, Eigen::ComputeFullV);
      const auto& sv = svd_small_.singularValues();
      const double top = sv.maxCoeff();
      int d = 0;
      for (int i = 0; i < m_ && d < max_dim; ++i) {
        if (sv[i] <= rank_threshold_ * top) {
          kernel.col(d).head(m_) = svd_small_.matrixV().col(i);
          ++d;
        }
      }
      return d;
    }
    eig_small_.compute(a_small_);
    const auto& ev = eig_small_.eigenvalues();
    const double top = ev.cwiseAbs().maxCoeff();
    int d = 0;
    for (int i = 0; i < m_ && d < max_dim; ++i) {
      if (std::abs(ev[i]) <= rank_threshold_ * top) {
        kernel.col(d).head(m_) = eig_small_.eigenvectors().col(i);
        ++d;
      }
    }
    return d;
  }
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
