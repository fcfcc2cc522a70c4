#include "solver/dynamics/active_system.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

// The decompositions' code is instantiated here, once, rather than in every file that includes
// the header (there it took more than half of a test file's compile time).

namespace skewbridge::dynamics {

ActiveSystem::ActiveSystem(int capacity, double rank_threshold)
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

void ActiveSystem::SetRankThreshold(double rank_threshold) {
  rank_threshold_ = rank_threshold;
  cod_small_.setThreshold(rank_threshold_);
  cod_large_.setThreshold(rank_threshold_);
}

void ActiveSystem::Solve() {
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

void ActiveSystem::SolveSymmetric() {
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

bool ActiveSystem::SolveDirect() {
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

int ActiveSystem::Kernel(Eigen::Ref<Eigen::MatrixXd> kernel, int max_dim) {
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

ActiveSystem::~ActiveSystem() = default;

}  // namespace skewbridge::dynamics
