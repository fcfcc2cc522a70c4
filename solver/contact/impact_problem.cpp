#include "solver/contact/impact_problem.h"

#include <algorithm>

#include "solver/common/error.h"
#include "solver/lcp/enumeration.h"

namespace skewbridge::contact {

namespace {

// Relative compliance of the normal rows in the retry of a degenerate impact (see Solve).
constexpr double kImpactCompliance = 1e-9;

}  // namespace

ImpactProblem::ImpactProblem(const model::Model& model, lcp::LemkeOptions options,
                             Assembly assembly)
    : model_(model), solver_(options), sparse_(UsesSparseAssembly(model, assembly)) {
  const int n = model.n_dof();
  const int nc = model.n_contacts();
  WN_.setZero(n, nc);
  WT_.setZero(n, nc);
  MinvWN_.setZero(n, nc);
  MinvWT_.setZero(n, nc);
  mu_.setZero(nc);
  eps_.setZero(nc);
  A_.setZero(3 * nc, 3 * nc);
  b_.setZero(3 * nc);
  solver_.Prepare(3 * nc, solutions_);
}

ImpactResult ImpactProblem::MakeResult() const {
  const int n = model_.n_dof();
  const int nc = model_.n_contacts();
  ImpactResult r;
  r.u_E.setZero(n);
  r.Lambda_N.setZero(nc);
  r.Lambda_T.setZero(nc);
  r.gamma_N_A.setZero(nc);
  r.gamma_N_E.setZero(nc);
  r.gamma_T_E.setZero(nc);
  return r;
}

Eigen::Ref<const Eigen::MatrixXd> ImpactProblem::last_A() const {
  return A_.topLeftCorner(3 * k_, 3 * k_);
}

Eigen::Ref<const Eigen::VectorXd> ImpactProblem::last_b() const { return b_.head(3 * k_); }

lcp::LcpStatus ImpactProblem::Solve(const ContactKinematics& kinematics,
                                    std::span<const int> index_set,
                                    const Eigen::Ref<const Eigen::VectorXd>& u_A,
                                    ImpactResult& result, std::span<const int> persistent,
                                    bool frictionless) {
  const int k = static_cast<int>(index_set.size());
  SB_ASSERT(k <= model_.n_contacts(), "index set larger than the model's contacts");
  SB_ASSERT(u_A.size() == model_.n_dof(), "u_A has the wrong size");
  SB_ASSERT(result.u_E.size() == model_.n_dof(), "ImpactResult not sized (MakeResult)");
  k_ = k;
  result.k = k;
  result.pivots = 0;
  result.u_E = u_A;
  result.Lambda_N.head(k).setZero();
  result.Lambda_T.head(k).setZero();

  const Eigen::VectorXd& Minv = model_.inverse_mass_diagonal();
  for (int j = 0; j < k; ++j) {
    const int c = index_set[static_cast<std::size_t>(j)];
    SB_ASSERT(c >= 0 && c < model_.n_contacts(), "contact index out of range");
    WN_.col(j) = kinematics.W_N.col(c);
    WT_.col(j) = kinematics.W_T.col(c);
    mu_(j) = frictionless ? 0.0 : model_.contact(c).friction;
    // A persistent contact takes part with its own (tiny) gamma_N,A and no restitution, so that
    // after the impact it neither approaches (gamma_N,E >= 0 for the real velocities, not for a
    // pretended gamma_N,A = 0) nor bounces off by restitution of a closure speed it never had.
    const bool is_persistent =
        std::find(persistent.begin(), persistent.end(), c) != persistent.end();
    eps_(j) = is_persistent ? 0.0 : model_.contact(c).restitution;
    result.gamma_N_A(j) = WN_.col(j).dot(u_A);
  }
  if (k == 0) {
    result.status = lcp::LcpStatus::kSolved;
    return result.status;
  }
  auto WN = WN_.leftCols(k);
  auto WT = WT_.leftCols(k);
  MinvWN_.leftCols(k).noalias() = Minv.asDiagonal() * WN;
  MinvWT_.leftCols(k).noalias() = Minv.asDiagonal() * WT;
  auto MinvWN = MinvWN_.leftCols(k);
  auto MinvWT = MinvWT_.leftCols(k);
  auto mu = mu_.head(k);
  auto eps = eps_.head(k);

  // [docs/theory.md §3, impact problem]: rows (Lambda_N, Lambda_R, gamma_TL) blocks.
  auto A = A_.topLeftCorner(3 * k, 3 * k);
  A.setZero();
  if (sparse_) {
    SparseDelassus(model_, WN, index_set, WT, index_set, A.block(0, k, k, k));
    SparseDelassus(model_, WN, index_set, WN, index_set, A.block(0, 0, k, k));
    SparseDelassus(model_, WT, index_set, WT, index_set, A.block(k, k, k, k));
    SparseDelassus(model_, WT, index_set, WN, index_set, A.block(k, 0, k, k));
  } else {
    A.block(0, k, k, k).noalias() = WN.transpose() * MinvWT;
    A.block(0, 0, k, k).noalias() = WN.transpose() * MinvWN;
    A.block(k, k, k, k).noalias() = WT.transpose() * MinvWT;
    A.block(k, 0, k, k).noalias() = WT.transpose() * MinvWN;
  }
  A.block(0, 0, k, k).noalias() -= A.block(0, k, k, k) * mu.asDiagonal();
  A.block(k, 0, k, k).noalias() -= A.block(k, k, k, k) * mu.asDiagonal();
  for (int j = 0; j < k; ++j) {
    A(k + j, 2 * k + j) = 1.0;
    A(2 * k + j, j) = 2.0 * mu(j);
    A(2 * k + j, k + j) = -1.0;
  }
  auto b = b_.head(3 * k);
  b.head(k) = (1.0 + eps.array()) * result.gamma_N_A.head(k).array();
  b.segment(k, k).noalias() = WT.transpose() * u_A;
  b.tail(k).setZero();

  result.status = solver_.Solve(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
  if (result.status != lcp::LcpStatus::kSolved && 3 * k <= lcp::kMaxEnumerationSize) {
    // Lemke's ray on a degenerate impact (identical tangent rows of two corners on one face)
    // proves nothing: the enumeration of the complementary bases decides.
    result.status = lcp::SolveByEnumeration(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
  }
  if (result.status != lcp::LcpStatus::kSolved) {
    // A deck clamped between two closed faces: the normal rows are dependent (a squeeze of
    // both faces changes no velocity), the complementary bases are singular, and neither method
    // finds the solutions that exist. A compliance of kImpactCompliance of the largest normal
    // entry per unit impulse (gamma_N,E + eps gamma_N,A = -c Lambda_N at a closed contact) makes
    // the normal block regular and picks the solution without squeeze: both faces cannot yield
    // at once. It changes the impulses by that relative amount and only where the rigid problem
    // found no solution.
    double top = 0.0;
    for (int j = 0; j < k; ++j) {
      top = std::max(top, std::abs(A(j, j)));
    }
    for (int j = 0; j < k; ++j) {
      A(j, j) += kImpactCompliance * top;
    }
    result.status = solver_.Solve(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
    if (result.status != lcp::LcpStatus::kSolved && 3 * k <= lcp::kMaxEnumerationSize) {
      result.status = lcp::SolveByEnumeration(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
    }
  }
  const lcp::LcpSolution& solution = solutions_[static_cast<std::size_t>(A.rows())];
  result.pivots = solution.pivots;
  if (result.status != lcp::LcpStatus::kSolved) {
    return result.status;
  }
  // Lambda_T = Lambda_R - mu Lambda_N; u_E = u_A + M^-1 (W_N Lambda_N + W_T Lambda_T).
  result.Lambda_N.head(k) = solution.z.head(k);
  result.Lambda_T.head(k) =
      solution.z.segment(k, k).array() - mu.array() * solution.z.head(k).array();
  result.u_E.noalias() += MinvWN * result.Lambda_N.head(k);
  result.u_E.noalias() += MinvWT * result.Lambda_T.head(k);
  result.gamma_N_E.head(k).noalias() = WN.transpose() * result.u_E;
  result.gamma_T_E.head(k).noalias() = WT.transpose() * result.u_E;
  return result.status;
}

}  // namespace skewbridge::contact
