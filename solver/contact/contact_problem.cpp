#include "solver/contact/contact_problem.h"

#include <algorithm>
#include <cmath>

#include "solver/common/error.h"
#include "solver/lcp/enumeration.h"

namespace skewbridge::contact {

const char* ToString(ContactStatus status) {
  switch (status) {
    case ContactStatus::kSolved:
      return "solved";
    case ContactStatus::kPainleve:
      return "painleve";
    case ContactStatus::kLcpFailure:
    default:
      return "lcp-failure";
  }
}

ContactProblem::ContactProblem(const model::Model& model, lcp::LemkeOptions options,
                               Assembly assembly)
    : model_(model), solver_(options), sparse_(UsesSparseAssembly(model, assembly)) {
  const int n = model.n_dof();
  const int nc = model.n_contacts();
  closed_.reserve(static_cast<std::size_t>(nc));
  sticking_.reserve(static_cast<std::size_t>(nc));
  WN_.setZero(n, nc);
  WQ_.setZero(n, nc);
  WH_.setZero(n, nc);
  MinvWQ_.setZero(n, nc);
  MinvWH_.setZero(n, nc);
  Minvh_.setZero(n);
  mu_H_.setZero(nc);
  A_.setZero(3 * nc, 3 * nc);
  b_.setZero(3 * nc);
  solver_.Prepare(3 * nc, solutions_);
}

void ContactProblem::SetPolicy(const ContactPolicy& policy) {
  // The policy held was checked when it was set (the default is within its ranges), so the same
  // bytes again, as every run of a sweep brings, need no second check.
  if (SameBytes(policy, policy_)) {
    return;
  }
  CheckContactPolicy(policy);
  policy_ = policy;
}

ContactResult ContactProblem::MakeResult() const {
  const int nc = model_.n_contacts();
  ContactResult r;
  r.du_dt.setZero(model_.n_dof());
  r.lambda_N.setZero(nc);
  r.lambda_T.setZero(nc);
  r.gammadot_N.setZero(nc);
  r.gammadot_T.setZero(nc);
  r.outcome.assign(static_cast<std::size_t>(nc), ContactOutcome::kStaysClosed);
  r.friction_outcome.assign(static_cast<std::size_t>(nc), ContactOutcome::kStaysClosed);
  return r;
}

Eigen::Ref<const Eigen::MatrixXd> ContactProblem::last_A() const {
  return A_.topLeftCorner(n_lcp_, n_lcp_);
}

Eigen::Ref<const Eigen::VectorXd> ContactProblem::last_b() const { return b_.head(n_lcp_); }

ContactStatus ContactProblem::Solve(const ContactKinematics& kinematics,
                                    std::span<const ClosedContact> closed,
                                    const Eigen::Ref<const Eigen::VectorXd>& h,
                                    ContactResult& result) {
  const int k = static_cast<int>(closed.size());
  SB_ASSERT(k <= model_.n_contacts(), "closed set larger than the model's contacts");
  SB_ASSERT(h.size() == model_.n_dof(), "h has the wrong size");
  SB_ASSERT(result.du_dt.size() == model_.n_dof(), "ContactResult not sized (MakeResult)");
  const Eigen::VectorXd& Minv = model_.inverse_mass_diagonal();
  result.k = k;
  result.pivots = 0;
  Minvh_ = Minv.cwiseProduct(h);

  // Columns of the closed set N, of W_Q (per closed contact: w_N - mu s w_T on G,
  // w_N - mu w_T on H) and of the possibly sticking set H.
  int nh = 0;
  closed_.clear();
  sticking_.clear();
  for (int j = 0; j < k; ++j) {
    const ClosedContact& cc = closed[static_cast<std::size_t>(j)];
    SB_ASSERT(cc.contact >= 0 && cc.contact < model_.n_contacts(), "contact index out of range");
    SB_ASSERT(cc.slip_sign >= -1 && cc.slip_sign <= 1, "slip sign must be -1, 0 or 1");
    const double mu = model_.contact(cc.contact).friction;
    WN_.col(j) = kinematics.W_N.col(cc.contact);
    const double s = cc.slip_sign == 0 ? 1.0 : static_cast<double>(cc.slip_sign);
    WQ_.col(j) = kinematics.W_N.col(cc.contact) - mu * s * kinematics.W_T.col(cc.contact);
    closed_.push_back(cc.contact);
    if (cc.slip_sign == 0) {
      sticking_.push_back(cc.contact);
      WH_.col(nh) = kinematics.W_T.col(cc.contact);
      mu_H_(nh) = mu;
      ++nh;
    }
  }
  const int n = k + 2 * nh;
  n_lcp_ = n;
  if (k == 0) {
    result.du_dt = Minvh_;
    result.status = ContactStatus::kSolved;
    result.lcp_status = lcp::LcpStatus::kSolved;
    return result.status;
  }
  auto WN = WN_.leftCols(k);
  auto WH = WH_.leftCols(nh);
  MinvWQ_.leftCols(k).noalias() = Minv.asDiagonal() * WQ_.leftCols(k);
  MinvWH_.leftCols(nh).noalias() = Minv.asDiagonal() * WH;
  auto MinvWQ = MinvWQ_.leftCols(k);
  auto MinvWH = MinvWH_.leftCols(nh);

  // [docs/theory.md §3, contact problem]: unknowns (lambda_N, lambda_R, a_L).
  auto A = A_.topLeftCorner(n, n);
  A.setZero();
  if (sparse_) {
    const auto WQ = WQ_.leftCols(k);
    SparseDelassus(model_, WN, closed_, WQ, closed_, A.block(0, 0, k, k));
    SparseDelassus(model_, WN, closed_, WH, sticking_, A.block(0, k, k, nh));
    SparseDelassus(model_, WH, sticking_, WQ, closed_, A.block(k, 0, nh, k));
    SparseDelassus(model_, WH, sticking_, WH, sticking_, A.block(k, k, nh, nh));
  } else {
    A.block(0, 0, k, k).noalias() = WN.transpose() * MinvWQ;
    A.block(0, k, k, nh).noalias() = WN.transpose() * MinvWH;
    A.block(k, 0, nh, k).noalias() = WH.transpose() * MinvWQ;
    A.block(k, k, nh, nh).noalias() = WH.transpose() * MinvWH;
  }
  auto b = b_.head(n);
  b.head(k).noalias() = WN.transpose() * Minvh_;
  b.segment(k, nh).noalias() = WH.transpose() * Minvh_;
  b.tail(nh).setZero();
  int jh = 0;
  for (int j = 0; j < k; ++j) {
    const ClosedContact& cc = closed[static_cast<std::size_t>(j)];
    b(j) += kinematics.what_N(cc.contact);
    if (cc.slip_sign == 0) {
      A(k + jh, k + nh + jh) = 1.0;
      A(k + nh + jh, j) = 2.0 * mu_H_(jh);
      A(k + nh + jh, k + jh) = -1.0;
      b(k + jh) += kinematics.what_T(cc.contact);
      ++jh;
    }
  }

  result.lcp_status = solver_.Solve(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
  if (result.lcp_status != lcp::LcpStatus::kSolved && n <= policy_.enumeration_unknowns) {
    // A ray of Lemke's algorithm proves nothing for a degenerate problem (two corners of one
    // face have identical tangent rows); the enumeration of the complementary bases decides
    // whether a solution exists, so a Painleve status means that none does.
    result.lcp_status =
        lcp::SolveByEnumeration(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
  }
  if (result.lcp_status != lcp::LcpStatus::kSolved) {
    // A deck clamped between two closed faces: the normal rows are dependent (a squeeze of both
    // faces changes no acceleration), the complementary bases are singular, and neither method
    // finds the solutions that exist. A compliance of policy_.contact_compliance of the largest
    // normal entry (d gamma_N/dt = -c lambda_N at a closed contact) makes the normal block regular
    // and picks the solution without squeeze; it is used only where the rigid problem found none,
    // so a genuine Painleve situation (no solution for any small compliance) still ends as one.
    double top = 0.0;
    for (int j = 0; j < k; ++j) {
      top = std::max(top, std::abs(A(j, j)));
    }
    for (int j = 0; j < k; ++j) {
      A(j, j) += policy_.contact_compliance * top;
    }
    result.lcp_status = solver_.Solve(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
    if (result.lcp_status != lcp::LcpStatus::kSolved && n <= policy_.enumeration_unknowns) {
      result.lcp_status =
          lcp::SolveByEnumeration(A, b, solutions_[static_cast<std::size_t>(A.rows())]);
    }
  }
  const lcp::LcpSolution& solution = solutions_[static_cast<std::size_t>(A.rows())];
  result.pivots = solution.pivots;
  if (result.lcp_status != lcp::LcpStatus::kSolved) {
    result.status = result.lcp_status == lcp::LcpStatus::kSecondaryRay ? ContactStatus::kPainleve
                                                                       : ContactStatus::kLcpFailure;
    result.du_dt = Minvh_;
    result.lambda_N.head(k).setZero();
    result.lambda_T.head(k).setZero();
    return result.status;
  }

  // Forces: lambda_T = -mu s lambda_N on G, lambda_R - mu lambda_N on H.
  const Eigen::VectorXd& z = solution.z;
  const Eigen::VectorXd& w = solution.w;
  result.du_dt = Minvh_;
  // Complementary pairs with both members at round-off are ties: keep the contact's mode. The
  // round-off is that of the terms summed into each b entry, not of b itself: a closed joint
  // between two identical decks has b = 0 up to rounding, and a scale taken from that b would
  // call its rounding a separating acceleration (a detachment at lambda_N = 0).
  double scale_b = 0.0;
  for (int j = 0; j < k; ++j) {
    const int c = closed[static_cast<std::size_t>(j)].contact;
    scale_b = std::max(
        scale_b, WN.col(j).cwiseAbs().dot(Minvh_.cwiseAbs()) + std::abs(kinematics.what_N(c)));
  }
  for (int j = 0; j < nh; ++j) {
    scale_b =
        std::max(scale_b, WH.col(j).cwiseAbs().dot(Minvh_.cwiseAbs()) +
                              std::abs(kinematics.what_T(sticking_[static_cast<std::size_t>(j)])));
  }
  const double tol_w = policy_.tie_tolerance * (scale_b > 0.0 ? scale_b : 1.0);
  jh = 0;
  for (int j = 0; j < k; ++j) {
    const ClosedContact& cc = closed[static_cast<std::size_t>(j)];
    const double mu = model_.contact(cc.contact).friction;
    const double lambda_N = z(j);
    double lambda_T = 0.0;
    ContactOutcome outcome = ContactOutcome::kStaysClosed;
    if (cc.slip_sign != 0) {
      lambda_T = -mu * cc.slip_sign * lambda_N;
      outcome = ContactOutcome::kSlides;
    } else {
      lambda_T = z(k + jh) - mu * lambda_N;
      const double a_R = w(k + jh);
      const double a_L = z(k + nh + jh);
      if (a_R > tol_w) {
        outcome = ContactOutcome::kStartsSlipPositive;
      } else if (a_L > tol_w) {
        outcome = ContactOutcome::kStartsSlipNegative;
      } else {
        outcome = ContactOutcome::kSticks;
      }
      ++jh;
    }
    result.friction_outcome[static_cast<std::size_t>(j)] = outcome;
    if (w(j) > tol_w && w(j) > lambda_N) {
      outcome = ContactOutcome::kDetaches;
    }
    result.lambda_N(j) = lambda_N;
    result.lambda_T(j) = lambda_T;
    result.outcome[static_cast<std::size_t>(j)] = outcome;
    result.du_dt.noalias() += Minv.cwiseProduct(kinematics.W_N.col(cc.contact)) * lambda_N;
    result.du_dt.noalias() += Minv.cwiseProduct(kinematics.W_T.col(cc.contact)) * lambda_T;
  }
  for (int j = 0; j < k; ++j) {
    const int c = closed[static_cast<std::size_t>(j)].contact;
    result.gammadot_N(j) = kinematics.W_N.col(c).dot(result.du_dt) + kinematics.what_N(c);
    result.gammadot_T(j) = kinematics.W_T.col(c).dot(result.du_dt) + kinematics.what_T(c);
  }
  result.status = ContactStatus::kSolved;
  return result.status;
}

}  // namespace skewbridge::contact
