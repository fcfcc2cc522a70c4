#pragma once
/// @file
/// The acceleration-level contact problem of [docs/theory.md §3, contact problem; Pfeiffer and
/// Glocker 1996, §6] over the closed contacts (gamma_N = 0), split into sliding ones G (slip
/// sign s_G, lambda_T = -mu s_G lambda_N) and possibly sticking ones H
/// (lambda_R = mu lambda_N + lambda_T, lambda_L = mu lambda_N - lambda_T,
/// d gamma_T/dt = a_R - a_L):
///
///     z = (lambda_N, lambda_R, a_L),  w = (d gamma_N/dt, a_R, lambda_L)
///     W_Q = W_N - W_G mu_G s_G - W_H mu_H
///     A = [ W_N^T M^-1 W_Q   W_N^T M^-1 W_H   0
///           W_H^T M^-1 W_Q   W_H^T M^-1 W_H   E
///           2 mu_H           -E               0 ]
///     b = (W_N^T M^-1 h + what_N, W_H^T M^-1 h + what_H, 0)
///
/// A secondary ray of Lemke's algorithm is a Painleve situation (no or several solutions):
/// reported as a status, never answered silently.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "solver/contact/contact_policy.h"
#include "solver/contact/delassus.h"
#include "solver/contact/kinematics.h"
#include "solver/lcp/lemke.h"
#include "solver/model/model.h"

namespace skewbridge::contact {

/// A closed contact and its friction mode going into the contact problem.
struct ClosedContact {
  int contact = 0;    ///< contact index in the model
  int slip_sign = 0;  ///< 0: possibly sticking (set H); +1 / -1: sliding with sign(gamma_T) (G)
};

/// What a closed contact does next, read from the solution.
enum class ContactOutcome {
  kStaysClosed,         ///< lambda_N > 0 (or both zero), keeps its friction mode
  kDetaches,            ///< d gamma_N/dt > 0 with lambda_N = 0
  kSticks,              ///< in H, d gamma_T/dt = 0 with |lambda_T| < mu lambda_N or lambda_N = 0
  kStartsSlipPositive,  ///< in H, a_R > 0: slip starts along +t (lambda_T = -mu lambda_N)
  kStartsSlipNegative,  ///< in H, a_L > 0: slip starts along -t (lambda_T = +mu lambda_N)
  kSlides,              ///< in G, keeps sliding with lambda_T = -mu s lambda_N
};

/// How the contact problem ended.
enum class ContactStatus {
  kSolved,      ///< forces and accelerations consistent
  kPainleve,    ///< Lemke ended on a secondary ray: no consistent contact forces found
  kLcpFailure,  ///< pivot limit or invalid input (a bug or an ill-posed model)
};

/// Human-readable name of a status ("solved", "painleve", "lcp-failure").
const char* ToString(ContactStatus status);

/// Outcome of the contact problem; vectors indexed like `closed` (entry j = closed[j]), sized
/// for all contacts, only the first k entries meaningful.
struct ContactResult {
  ContactStatus status = ContactStatus::kLcpFailure;
  lcp::LcpStatus lcp_status = lcp::LcpStatus::kInvalidInput;
  int k = 0;
  Eigen::VectorXd du_dt;                ///< M^-1 (h + W_N lambda_N + W_T lambda_T) (n_dof)
  Eigen::VectorXd lambda_N;             ///< normal forces (N) >= 0
  Eigen::VectorXd lambda_T;             ///< tangential forces (N)
  Eigen::VectorXd gammadot_N;           ///< d gamma_N / dt (m/s^2)
  Eigen::VectorXd gammadot_T;           ///< d gamma_T / dt (m/s^2)
  std::vector<ContactOutcome> outcome;  ///< per entry of `closed`
  /// Per entry of `closed`: the friction outcome alone (kSlides, kSticks, kStartsSlip...), also
  /// for a contact whose `outcome` is kDetaches, so that a caller that keeps such a contact
  /// closed (a separating acceleration within its tolerance) knows its friction mode.
  std::vector<ContactOutcome> friction_outcome;
  int pivots = 0;
};

/// The contact problem with its workspace (sized once per model: no allocation per solve).
class ContactProblem {
 public:
  /// Sizes the workspace for up to model.n_contacts() closed contacts. Keeps a reference.
  /// `assembly` chooses how W^T M^-1 W is formed (solver/contact/delassus.h).
  explicit ContactProblem(const model::Model& model, lcp::LemkeOptions options = {},
                          Assembly assembly = Assembly::kAuto);

  /// Solves for the contact forces and accelerations with the closed contacts `closed`, the
  /// Jacobians and velocity terms of `kinematics` and the applied forces h = -C u - K q - M r a_g.
  /// With no closed contact du/dt = M^-1 h.
  /// @pre distinct valid contact indices, slip_sign in {-1, 0, 1}, h of size n_dof (SB_ASSERT).
  ContactStatus Solve(const ContactKinematics& kinematics, std::span<const ClosedContact> closed,
                      const Eigen::Ref<const Eigen::VectorXd>& h, ContactResult& result);

  /// A result sized for this model.
  ContactResult MakeResult() const;

  /// The thresholds of the following solves (tie_tolerance, contact_compliance,
  /// enumeration_unknowns; ContactPolicy{} until set).
  /// @pre tolerances finite and >= 0, 0 <= enumeration_unknowns <= lcp::kMaxEnumerationSize
  /// (SB_DEMAND).
  void SetPolicy(const ContactPolicy& policy);

  /// The LCP matrix and vector of the last Solve, for inspection and tests.
  Eigen::Ref<const Eigen::MatrixXd> last_A() const;
  Eigen::Ref<const Eigen::VectorXd> last_b() const;

 private:
  const model::Model& model_;
  ContactPolicy policy_;
  lcp::LemkeSolver solver_;
  // One solution per LCP size: LcpSolution resizes when n changes, so each size keeps its own
  // and a change of the index set does not allocate.
  std::vector<lcp::LcpSolution> solutions_;
  int n_lcp_ = 0;
  Eigen::MatrixXd WN_, WQ_, WH_;     // columns of the closed set; W_H of its H part
  Eigen::MatrixXd MinvWQ_, MinvWH_;  // M^-1 W_Q, M^-1 W_H
  Eigen::VectorXd Minvh_;            // M^-1 h
  Eigen::VectorXd mu_H_;
  bool sparse_ = false;                 // UsesSparseAssembly
  std::vector<int> closed_, sticking_;  // contact of each column of W_N (W_Q) and of W_H
  Eigen::MatrixXd A_;
  Eigen::VectorXd b_;
};

}  // namespace skewbridge::contact
