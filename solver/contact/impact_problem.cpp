#include "solver/contact/impact_problem.h"

#include <algorithm>
#include <cmath>

#include "solver/common/error.h"
#include "solver/lcp/enumeration.h"

namespace skewbridge::contact {

namespace {

// The impact of one contact in closed form: the LCP of the header with k = 1, given the
// Delassus entries G_nn = w_N^T M^-1 w_N, G_nt = w_N^T M^-1 w_T, G_tt = w_T^T M^-1 w_T (N^-1 s^-1
// per unit impulse, in m/s per N s). Along the impulses that meet the normal law
// (G_nn Lambda_N + G_nt Lambda_T = -(1 + eps) gamma_N,A), the post-impact slip grows strictly
// with Lambda_T (det > 0) while Coulomb's graph falls, so stick or slip in one direction is the
// unique solution when the friction interval -mu Lambda_N <= Lambda_T <= mu Lambda_N is proper on
// that line: G_nn - mu |G_nt| > 0. Returns false where that does not hold, or where the contact
// does not approach: Lemke (and the enumeration) decide those.
bool SolveSingleImpact(double G_nn, double G_nt, double G_tt, double mu, double eps,
                       double gamma_N_A, double gamma_T_A, double& Lambda_N, double& Lambda_T) {
  if (!(gamma_N_A < 0.0) || !(G_nn > 0.0)) {
    return false;
  }
  const double r = -(1.0 + eps) * gamma_N_A;  // G_nn Lambda_N + G_nt Lambda_T = r > 0
  if (mu == 0.0) {
    Lambda_N = r / G_nn;
    Lambda_T = 0.0;
    return true;
  }
  if (!(G_nn - mu * std::abs(G_nt) > 0.0)) {
    return false;
  }
  const double det = G_nn * G_tt - G_nt * G_nt;
  if (det > 0.0) {
    // Stick: gamma_T,E = 0 as well.
    const double n = (r * G_tt + G_nt * gamma_T_A) / det;
    const double t = -(G_nn * gamma_T_A + G_nt * r) / det;
    if (n > 0.0 && std::abs(t) <= mu * n) {
      Lambda_N = n;
      Lambda_T = t;
      return true;
    }
  }
  // Slip in direction s after the impact: Lambda_T = -s mu Lambda_N, s gamma_T,E >= 0.
  for (const double s : {1.0, -1.0}) {
    const double n = r / (G_nn - s * mu * G_nt);
    const double gamma_T_E = gamma_T_A + (G_nt - s * mu * G_tt) * n;
    if (s * gamma_T_E >= 0.0) {
      Lambda_N = n;
      Lambda_T = -s * mu * n;
      return true;
    }
  }
  return false;
}

}  // namespace

ImpactProblem::ImpactProblem(const model::Model& model, lcp::LemkeOptions options,
                             Assembly assembly)
    : model_(model),
      solver_(options),
      sparse_(UsesSparseAssembly(model, assembly)),
      pairs_(assembly == Assembly::kAuto && model.n_dof() == 3) {
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

void ImpactProblem::SetPolicy(const ContactPolicy& policy) {
  // The policy held was checked when it was set (the default is within its ranges), so the same
  // bytes again, as every run of a sweep brings, need no second check.
  if (SameBytes(policy, policy_)) {
    return;
  }
  CheckContactPolicy(policy);
  policy_ = policy;
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
  for (int j = 0; j < k; ++j) {
    result.Lambda_N(j) = 0.0;
    result.Lambda_T(j) = 0.0;
  }
  // A single deck (kAuto): its 3 rows copied and gamma_N,A = (w_0 u_0 + w_1 u_1) + w_2 u_2, the
  // sum of Eigen's dot product, without dynamic-size expressions.
  const bool deck = pairs_;
  if (deck) {
    const double* u = u_A.data();
    double* u_E = result.u_E.data();
    u_E[0] = u[0];
    u_E[1] = u[1];
    u_E[2] = u[2];
  } else {
    result.u_E = u_A;
  }
  for (int j = 0; j < k; ++j) {
    const int c = index_set[static_cast<std::size_t>(j)];
    SB_ASSERT(c >= 0 && c < model_.n_contacts(), "contact index out of range");
    if (deck) {
      const double* w_n = kinematics.W_N.col(c).data();
      const double* w_t = kinematics.W_T.col(c).data();
      double* to_n = WN_.col(j).data();
      double* to_t = WT_.col(j).data();
      for (int i = 0; i < 3; ++i) {
        to_n[i] = w_n[i];
        to_t[i] = w_t[i];
      }
      const double* u = u_A.data();
      result.gamma_N_A(j) = (w_n[0] * u[0] + w_n[1] * u[1]) + w_n[2] * u[2];
    } else {
      WN_.col(j) = kinematics.W_N.col(c);
      WT_.col(j) = kinematics.W_T.col(c);
      result.gamma_N_A(j) = WN_.col(j).dot(u_A);
    }
    mu_(j) = frictionless ? 0.0 : model_.contact(c).friction;
    // A persistent contact takes part with its own (tiny) gamma_N,A and no restitution, so that
    // after the impact it neither approaches (gamma_N,E >= 0 for the real velocities, not for a
    // pretended gamma_N,A = 0) nor bounces off by restitution of a closure speed it never had.
    const bool is_persistent =
        std::find(persistent.begin(), persistent.end(), c) != persistent.end();
    eps_(j) = is_persistent ? 0.0 : model_.contact(c).restitution;
  }
  if (k == 0) {
    result.status = lcp::LcpStatus::kSolved;
    return result.status;
  }
  if (k == 1 && SolveOne(result)) {
    return result.status;
  }
  // Two contacts of a single deck (a deck against one face at two corners, or one corner at each
  // abutment): the general path's operations in fixed size.
  const bool pair = k == 2 && pairs_;
  if (pair) {
    AssemblePair(u_A, result);
  } else {
    AssembleGeneral(u_A, index_set, result);
  }
  return SolveAssembled(pair, result);
}

void ImpactProblem::AssembleGeneral(const Eigen::Ref<const Eigen::VectorXd>& u_A,
                                    std::span<const int> index_set, ImpactResult& result) {
  const int k = k_;
  const Eigen::VectorXd& Minv = model_.inverse_mass_diagonal();
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
}

void ImpactProblem::AssemblePair(const Eigen::Ref<const Eigen::VectorXd>& u_A,
                                 ImpactResult& result) {
  // Entry by entry what AssembleGeneral's Eigen expressions compute at k = 2, n_dof = 3: a
  // Delassus entry is the dot product (w_0 m_0 + w_1 m_1) + w_2 m_2 (the lazy product's sum),
  // a product by a vector 0 + ((w_0 u_0 + w_1 u_1) + w_2 u_2) (the matrix-vector kernel's sum
  // from zero added to a zeroed result), and the friction columns are taken off as
  // G_nn - G_nt mu. tests/contact/impact_test.cpp holds both paths to the same bits.
  const double* inv_m = model_.inverse_mass_diagonal().data();
  const double* w_n = WN_.data();  // column j at w_n + 3 j
  const double* w_t = WT_.data();
  double* m_n = MinvWN_.data();
  double* m_t = MinvWT_.data();
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) {
      m_n[3 * j + i] = inv_m[i] * w_n[3 * j + i];
      m_t[3 * j + i] = inv_m[i] * w_t[3 * j + i];
    }
  }
  const auto dot = [](const double* x, const double* y) {
    return (x[0] * y[0] + x[1] * y[1]) + x[2] * y[2];
  };
  const double mu[2] = {mu_(0), mu_(1)};
  double* a = A_.data();
  const Eigen::Index ld = A_.outerStride();
  for (int s = 0; s < 6; ++s) {
    for (int r = 0; r < 6; ++r) a[s * ld + r] = 0.0;
  }
  for (int r = 0; r < 2; ++r) {
    for (int s = 0; s < 2; ++s) {
      const double G_nn = dot(w_n + 3 * r, m_n + 3 * s);
      const double G_nt = dot(w_n + 3 * r, m_t + 3 * s);
      const double G_tn = dot(w_t + 3 * r, m_n + 3 * s);
      const double G_tt = dot(w_t + 3 * r, m_t + 3 * s);
      a[s * ld + r] = G_nn - G_nt * mu[s];
      a[(2 + s) * ld + r] = G_nt;
      a[s * ld + 2 + r] = G_tn - G_tt * mu[s];
      a[(2 + s) * ld + 2 + r] = G_tt;
    }
  }
  for (int j = 0; j < 2; ++j) {
    a[(4 + j) * ld + 2 + j] = 1.0;
    a[j * ld + 4 + j] = 2.0 * mu[j];
    a[(2 + j) * ld + 4 + j] = -1.0;
  }
  const double* u = u_A.data();
  double* b = b_.data();
  for (int j = 0; j < 2; ++j) {
    b[j] = (1.0 + eps_(j)) * result.gamma_N_A(j);
    b[2 + j] = 0.0 + dot(w_t + 3 * j, u);
    b[4 + j] = 0.0;
  }
}

lcp::LcpStatus ImpactProblem::SolveAssembled(bool pair, ImpactResult& result) {
  const int k = k_;
  auto A = A_.topLeftCorner(3 * k, 3 * k);
  auto b = b_.head(3 * k);

  result.status = solver_.Solve(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
  if (result.status != lcp::LcpStatus::kSolved && 3 * k <= policy_.enumeration_unknowns) {
    // Lemke's ray on a degenerate impact (identical tangent rows of two corners on one face)
    // proves nothing: the enumeration of the complementary bases decides.
    result.status = lcp::SolveByEnumeration(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
  }
  if (result.status != lcp::LcpStatus::kSolved) {
    // A deck clamped between two closed faces: the normal rows are dependent (a squeeze of
    // both faces changes no velocity), the complementary bases are singular, and neither method
    // finds the solutions that exist. A compliance of policy_.impact_compliance of the largest
    // normal entry per unit impulse (gamma_N,E + eps gamma_N,A = -c Lambda_N at a closed contact)
    // makes the normal block regular and picks the solution without squeeze: both faces cannot
    // yield at once. It changes the impulses by that relative amount and only where the rigid
    // problem found no solution.
    double top = 0.0;
    for (int j = 0; j < k; ++j) {
      top = std::max(top, std::abs(A(j, j)));
    }
    for (int j = 0; j < k; ++j) {
      A(j, j) += policy_.impact_compliance * top;
    }
    result.status = solver_.Solve(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
    if (result.status != lcp::LcpStatus::kSolved && 3 * k <= policy_.enumeration_unknowns) {
      result.status = lcp::SolveByEnumeration(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
    }
  }
  const lcp::LcpSolution& solution = solutions_[static_cast<std::size_t>(A.rows())];
  result.pivots = solution.pivots;
  if (result.status != lcp::LcpStatus::kSolved) {
    return result.status;
  }
  // Lambda_T = Lambda_R - mu Lambda_N; u_E = u_A + M^-1 (W_N Lambda_N + W_T Lambda_T).
  auto mu = mu_.head(k);
  result.Lambda_N.head(k) = solution.z.head(k);
  result.Lambda_T.head(k) =
      solution.z.segment(k, k).array() - mu.array() * solution.z.head(k).array();
  if (pair) {
    // The matrix-vector kernel's sums as in AssemblePair: each row of M^-1 W Lambda from zero,
    // then added to u_E; gamma_E = 0 + w^T u_E.
    const double* m_n = MinvWN_.data();
    const double* m_t = MinvWT_.data();
    const double L_n[2] = {result.Lambda_N(0), result.Lambda_N(1)};
    const double L_t[2] = {result.Lambda_T(0), result.Lambda_T(1)};
    double* u = result.u_E.data();
    for (int i = 0; i < 3; ++i) {
      double c = 0.0;
      c += m_n[i] * L_n[0];
      c += m_n[3 + i] * L_n[1];
      u[i] += c;
    }
    for (int i = 0; i < 3; ++i) {
      double c = 0.0;
      c += m_t[i] * L_t[0];
      c += m_t[3 + i] * L_t[1];
      u[i] += c;
    }
    const double* w_n = WN_.data();
    const double* w_t = WT_.data();
    for (int j = 0; j < 2; ++j) {
      const double* wn = w_n + 3 * j;
      const double* wt = w_t + 3 * j;
      result.gamma_N_E(j) = 0.0 + ((wn[0] * u[0] + wn[1] * u[1]) + wn[2] * u[2]);
      result.gamma_T_E(j) = 0.0 + ((wt[0] * u[0] + wt[1] * u[1]) + wt[2] * u[2]);
    }
    return result.status;
  }
  auto WN = WN_.leftCols(k);
  auto WT = WT_.leftCols(k);
  result.u_E.noalias() += MinvWN_.leftCols(k) * result.Lambda_N.head(k);
  result.u_E.noalias() += MinvWT_.leftCols(k) * result.Lambda_T.head(k);
  result.gamma_N_E.head(k).noalias() = WN.transpose() * result.u_E;
  result.gamma_T_E.head(k).noalias() = WT.transpose() * result.u_E;
  return result.status;
}

bool ImpactProblem::SolveOne(ImpactResult& result) {
  // Raw loops: at one contact the set-up of dynamic-size Eigen products costs more than their
  // arithmetic. The sums run over every DOF in order; entries outside the contact's bodies are
  // zero, so this is the Delassus entry the sparse assembly forms, to rounding.
  const int n = model_.n_dof();
  const double* inv_m = model_.inverse_mass_diagonal().data();
  const double* w_n = WN_.col(0).data();
  const double* w_t = WT_.col(0).data();
  double* m_n = MinvWN_.col(0).data();
  double* m_t = MinvWT_.col(0).data();
  double G_nn = 0.0, G_nt = 0.0, G_tt = 0.0, gamma_T_A = 0.0;
  const double* u_A = result.u_E.data();  // u_E = u_A on entry
  for (int i = 0; i < n; ++i) {
    m_n[i] = inv_m[i] * w_n[i];
    m_t[i] = inv_m[i] * w_t[i];
    G_nn += w_n[i] * m_n[i];
    G_nt += w_n[i] * m_t[i];
    G_tt += w_t[i] * m_t[i];
    gamma_T_A += w_t[i] * u_A[i];
  }
  const double mu = mu_(0), eps = eps_(0), gamma_N_A = result.gamma_N_A(0);
  // The 3 x 3 LCP as the general path assembles it, for last_A() and last_b().
  A_.topLeftCorner(3, 3) << G_nn - mu * G_nt, G_nt, 0.0,  //
      G_nt - mu * G_tt, G_tt, 1.0,                        //
      2.0 * mu, -1.0, 0.0;
  b_.head(3) << (1.0 + eps) * gamma_N_A, gamma_T_A, 0.0;
  double Lambda_N = 0.0, Lambda_T = 0.0;
  if (!SolveSingleImpact(G_nn, G_nt, G_tt, mu, eps, gamma_N_A, gamma_T_A, Lambda_N, Lambda_T)) {
    return false;
  }
  result.status = lcp::LcpStatus::kSolved;
  result.Lambda_N(0) = Lambda_N;
  result.Lambda_T(0) = Lambda_T;
  double* u_E = result.u_E.data();
  double gamma_N_E = 0.0, gamma_T_E = 0.0;
  for (int i = 0; i < n; ++i) {
    u_E[i] += m_n[i] * Lambda_N + m_t[i] * Lambda_T;
    gamma_N_E += w_n[i] * u_E[i];
    gamma_T_E += w_t[i] * u_E[i];
  }
  result.gamma_N_E(0) = gamma_N_E;
  result.gamma_T_E(0) = gamma_T_E;
  return true;
}

}  // namespace skewbridge::contact
