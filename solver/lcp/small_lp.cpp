#include "solver/lcp/small_lp.h"

#include <cmath>

#include <Eigen/LU>

namespace skewbridge::lcp {

namespace {

constexpr double kReducedCostTol = 1e-11;
constexpr double kPivotTol = 1e-11;
constexpr double kPhase1Tol = 1e-9;
constexpr int kPivotsPerColumn = 50;

}  // namespace

const char* ToString(LpStatus status) {
  switch (status) {
    case LpStatus::kOptimal:
      return "optimal";
    case LpStatus::kInfeasible:
      return "infeasible";
    case LpStatus::kUnbounded:
      return "unbounded";
    case LpStatus::kIterationLimit:
      return "iteration-limit";
    case LpStatus::kInvalidInput:
      return "invalid-input";
  }
  return "unknown";
}

void SmallLp::ColumnOf(const Eigen::Ref<const Eigen::MatrixXd>& G, int j, Column& col) const {
  col.resize(p_);
  if (j < r_) {
    for (int i = 0; i < p_; ++i) {
      col[i] = sign_[i] * G(j, i);
    }
  } else {
    col.setZero();
    col[j - r_] = 1.0;
  }
}

bool SmallLp::Iterate(const Eigen::Ref<const Eigen::MatrixXd>& G, bool phase1, LpStatus* status) {
  const int n_cols = r_ + p_;
  const int limit = kPivotsPerColumn * n_cols;
  for (int it = 0; it < limit; ++it) {
    for (int i = 0; i < p_; ++i) {
      c_b_[i] = cost_[basis_[i]];
    }
    pi_.noalias() = b_inv_.transpose() * c_b_;
    // Bland: the lowest-index column with a negative reduced cost enters.
    int enter = -1;
    const int last = phase1 ? n_cols : r_;
    for (int j = 0; j < last && enter < 0; ++j) {
      bool basic = false;
      for (int i = 0; i < p_ && !basic; ++i) {
        basic = basis_[i] == j;
      }
      if (basic) {
        continue;
      }
      ColumnOf(G, j, col_);
      if (cost_[j] - pi_.dot(col_) < -kReducedCostTol) {
        enter = j;
      }
    }
    if (enter < 0) {
      return true;
    }
    ColumnOf(G, enter, col_);
    dir_.noalias() = b_inv_ * col_;
    // Ratio test; ties to the lowest basic index (Bland). In phase 2 an artificial still basic
    // (at zero) leaves as soon as the entering column touches its row.
    int leave = -1;
    double best = 0.0;
    for (int i = 0; i < p_; ++i) {
      double ratio = -1.0;
      if (!phase1 && basis_[i] >= r_ && std::abs(dir_[i]) > kPivotTol) {
        ratio = 0.0;
      } else if (dir_[i] > kPivotTol) {
        ratio = std::max(x_b_[i], 0.0) / dir_[i];
      }
      if (ratio < 0.0) {
        continue;
      }
      if (leave < 0 || ratio < best || (ratio == best && basis_[i] < basis_[leave])) {
        leave = i;
        best = ratio;
      }
    }
    if (leave < 0) {
      *status = LpStatus::kInfeasible;  // the dual is unbounded below
      return false;
    }
    const double pivot = dir_[leave];
    b_inv_.row(leave) /= pivot;
    x_b_[leave] /= pivot;
    for (int i = 0; i < p_; ++i) {
      if (i != leave && dir_[i] != 0.0) {
        b_inv_.row(i) -= dir_[i] * b_inv_.row(leave);
        x_b_[i] -= dir_[i] * x_b_[leave];
      }
    }
    basis_[leave] = enter;
    ++pivots_;
  }
  *status = LpStatus::kIterationLimit;
  return false;
}

LpStatus SmallLp::Maximize(const Eigen::Ref<const Eigen::MatrixXd>& G,
                           const Eigen::Ref<const Eigen::VectorXd>& h,
                           const Eigen::Ref<const Eigen::VectorXd>& c,
                           Eigen::Ref<Eigen::VectorXd> y) {
  pivots_ = 0;
  p_ = static_cast<int>(G.cols());
  r_ = static_cast<int>(G.rows());
  if (p_ < 1 || p_ > kMaxVariables || r_ > kMaxConstraints || h.size() != r_ || c.size() != p_ ||
      y.size() != p_ || !G.allFinite() || !h.allFinite() || !c.allFinite()) {
    return LpStatus::kInvalidInput;
  }
  // The dual's equality rows G^T w = c, each scaled by the sign of c_i so that the artificial
  // basis starts feasible (x_B = |c|).
  sign_.resize(p_);
  x_b_.resize(p_);
  c_b_.resize(p_);
  for (int i = 0; i < p_; ++i) {
    sign_[i] = c[i] < 0.0 ? -1.0 : 1.0;
    x_b_[i] = std::abs(c[i]);
    basis_[i] = r_ + i;
  }
  b_inv_.setIdentity(p_, p_);
  cost_.resize(r_ + p_);
  cost_.head(r_).setZero();
  cost_.tail(p_).setOnes();
  LpStatus status = LpStatus::kOptimal;
  if (!Iterate(G, true, &status)) {
    return status == LpStatus::kInfeasible ? LpStatus::kIterationLimit : status;
  }
  double residual = 0.0;
  for (int i = 0; i < p_; ++i) {
    if (basis_[i] >= r_) {
      residual += std::abs(x_b_[i]);
    }
  }
  if (residual > kPhase1Tol * (1.0 + c.cwiseAbs().sum())) {
    return LpStatus::kUnbounded;  // no w >= 0 with G^T w = c: the primal is unbounded (or empty)
  }
  cost_.head(r_) = h;
  cost_.tail(p_).setZero();
  if (!Iterate(G, false, &status)) {
    return status;
  }
  // The multipliers afresh from the final basis (the product-form inverse drifts).
  basis_matrix_.resize(p_, p_);
  for (int i = 0; i < p_; ++i) {
    ColumnOf(G, basis_[i], col_);
    basis_matrix_.col(i) = col_;
    c_b_[i] = cost_[basis_[i]];
  }
  Eigen::PartialPivLU<Square> lu(basis_matrix_.transpose());
  pi_ = lu.solve(c_b_);
  if (!pi_.allFinite()) {
    pi_.noalias() = b_inv_.transpose() * c_b_;
  }
  for (int i = 0; i < p_; ++i) {
    y[i] = sign_[i] * pi_[i];
  }
  return LpStatus::kOptimal;
}

}  // namespace skewbridge::lcp
