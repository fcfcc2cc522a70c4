#pragma once
/// @file
/// The velocity-level impact problem of [docs/theory.md §3, impact problem; Pfeiffer and Glocker
/// 1996, §7; Dimitrakopoulos 2011, eq. 11] over an index set of k contacts:
///
///     w = A z + b,  w >= 0, z >= 0, w^T z = 0
///     z = (Lambda_N, Lambda_R, gamma_TL),  w = (gamma_N,E + eps gamma_N,A, gamma_TR, Lambda_L)
///     A = [ W_N^T M^-1 (W_N - W_T mu)   W_N^T M^-1 W_T   0
///           W_T^T M^-1 (W_N - W_T mu)   W_T^T M^-1 W_T   E
///           2 mu                        -E               0 ]
///     b = ((E + eps) gamma_N,A, gamma_T,A, 0)
///     u_E = u_A + M^-1 (W_N Lambda_N + W_T Lambda_T),  Lambda_T = Lambda_R - mu Lambda_N
///
/// solved with Lemke's algorithm (solver/lcp/lemke.h); a single contact, where the solution is
/// unique (G_nn - mu |G_nt| > 0), in closed form (stick, or slip one way).
///
/// Energy: without friction, or with eps_N = 0, an impact never creates kinetic energy. With
/// both eps_N > 0 and friction, Newton's kinematic restitution can create energy when the
/// normal impulse drives the slip (Kane and Levinson 1985; Stronge 2000): the law above is
/// assembled exactly as written, so such gains are a property of the law, reported by the
/// energy ledger, not a fault of the solve (tests/contact/impact_test.cpp counts them).

#include <Eigen/Core>
#include <span>
#include <vector>

#include "solver/contact/contact_policy.h"
#include "solver/contact/delassus.h"
#include "solver/contact/kinematics.h"
#include "solver/lcp/lemke.h"
#include "solver/model/model.h"

namespace skewbridge::contact {

/// Outcome of an impact; vectors indexed like the index set (entry j = contact index_set[j]),
/// sized for all contacts of the model, only the first k entries meaningful.
struct ImpactResult {
  lcp::LcpStatus status = lcp::LcpStatus::kInvalidInput;
  int k = 0;                  ///< contacts in the index set
  Eigen::VectorXd u_E;        ///< post-impact velocities (n_dof)
  Eigen::VectorXd Lambda_N;   ///< normal impulses (N s) >= 0
  Eigen::VectorXd Lambda_T;   ///< tangential impulses (N s), |Lambda_T| <= mu Lambda_N
  Eigen::VectorXd gamma_N_A;  ///< normal relative velocity before (m/s), as used
  Eigen::VectorXd gamma_N_E;  ///< normal relative velocity after (m/s)
  Eigen::VectorXd gamma_T_E;  ///< slip velocity after (m/s)
  int pivots = 0;             ///< Lemke pivots
};

/// The impact problem with its workspace (sized once per model: no allocation per impact).
class ImpactProblem {
 public:
  /// Sizes the workspace for up to model.n_contacts() contacts. Keeps a reference to `model`.
  /// `assembly` chooses how W^T M^-1 W is formed (solver/contact/delassus.h); kAuto forms a
  /// single deck's two-contact problems by fixed-size sums, the bits of kDense's products.
  explicit ImpactProblem(const model::Model& model, lcp::LemkeOptions options = {},
                         Assembly assembly = Assembly::kAuto);

  /// Solves the impact of the contacts in `index_set` at the pre-impact velocity u_A, with the
  /// Jacobians of `kinematics` (evaluated at the impact configuration), gamma_N,A = w_N^T u_A.
  /// Contacts listed in `persistent` (closed, or closing slower than the accumulation threshold)
  /// take part with restitution 0: their gamma_N,A is zero up to drift, and an impact at one
  /// corner acts on them [docs/theory.md §3] without pushing them apart by restitution.
  /// @pre index_set entries distinct and valid; u_A of size n_dof (SB_ASSERT).
  /// @return result.status; when not kSolved, u_E = u_A and the impulses are zero.
  /// `frictionless` drops Coulomb's law (mu = 0) for this impact: a closure slower than the
  /// accumulation threshold only has its approach stopped, and its tangential impulse, bounded
  /// by mu times a vanishing normal one, is left to the contact problem that follows.
  lcp::LcpStatus Solve(const ContactKinematics& kinematics, std::span<const int> index_set,
                       const Eigen::Ref<const Eigen::VectorXd>& u_A, ImpactResult& result,
                       std::span<const int> persistent = {}, bool frictionless = false);

  /// A result sized for this model (so Solve does not allocate).
  ImpactResult MakeResult() const;

  /// The thresholds of the following solves (impact_compliance, enumeration_unknowns;
  /// ContactPolicy{} until set).
  /// @pre as ContactProblem::SetPolicy (SB_DEMAND).
  void SetPolicy(const ContactPolicy& policy);

  /// The LCP matrix and vector of the last Solve (3k x 3k and 3k), for inspection and tests.
  Eigen::Ref<const Eigen::MatrixXd> last_A() const;
  Eigen::Ref<const Eigen::VectorXd> last_b() const;

 private:
  // One contact in closed form (the index set's columns, mu_, eps_ and result.gamma_N_A set);
  // false where Lemke must decide.
  bool SolveOne(ImpactResult& result);
  // A_, b_ and M^-1 W of the k_ contacts by Eigen's products (dense or sparse), and the same
  // bits for two contacts of a single deck by fixed-size sums (the index set's columns, mu_,
  // eps_ and result.gamma_N_A set).
  void AssembleGeneral(const Eigen::Ref<const Eigen::VectorXd>& u_A, std::span<const int> index_set,
                       ImpactResult& result);
  void AssemblePair(const Eigen::Ref<const Eigen::VectorXd>& u_A, ImpactResult& result);
  // Lemke (then the enumeration, then the compliance) on the assembled problem, and the
  // impulses and post-impact velocities from its solution; `pair` as AssemblePair.
  lcp::LcpStatus SolveAssembled(bool pair, ImpactResult& result);

  const model::Model& model_;
  ContactPolicy policy_;
  lcp::LemkeSolver solver_;
  // One solution per LCP size: LcpSolution resizes when n changes, so each size keeps its own
  // and a change of the index set does not allocate.
  std::vector<lcp::LcpSolution> solutions_;
  int k_ = 0;
  bool sparse_ = false;              // UsesSparseAssembly
  bool pairs_ = false;               // kAuto on a single deck: two contacts by AssemblePair
  Eigen::MatrixXd WN_, WT_;          // n_dof x k columns of the index set
  Eigen::MatrixXd MinvWN_, MinvWT_;  // M^-1 W_N, M^-1 W_T
  Eigen::VectorXd mu_, eps_;         // per index-set entry
  Eigen::MatrixXd A_;                // 3 n_c x 3 n_c, top-left 3k x 3k used
  Eigen::VectorXd b_;
};

}  // namespace skewbridge::contact
