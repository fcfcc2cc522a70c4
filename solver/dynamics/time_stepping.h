#pragma once
/// @file
/// The Moreau-Jean time-stepping scheme [Acary and Brogliato 2008, ch. 10 (§10.1); Moreau 1988;
/// Jean 1999], the independent check of the event-driven integrator [docs/theory.md §3, independent
/// check]. On a fixed grid t_k = k h (the last step shortened to reach the end time):
///
///     W = M + h theta C + h^2 theta^2 K                      (factorised once per step size)
///     u_free = u_k + W^-1 h ( -C u_k - K (q_k + h theta u_k) - M r abar_g )
///     u_k+1  = u_free + W^-1 ( W_N P_N + W_T P_T )
///     q_k+1  = q_k + h ( theta u_k+1 + (1 - theta) u_k )
///
/// with abar_g the exact mean of the ground acceleration over the step (so a kink inside a step
/// costs no order), W_N, W_T at q_k, and the impulses P from the velocity-level LCP of
/// [docs/theory.md §3, impact problem] over the active index set with W in place of M:
///
///     z = (P_N, P_R, gamma_TL),  w = (gamma_N,k+1 + eps gamma_N,k, gamma_TR, P_L)
///     b = (gamma_N,free + eps gamma_N,k, gamma_T,free, 0),  gamma_free = w^T u_free
///
/// (Newton's law at velocity level, Coulomb's law in the split form of docs/theory.md §3). A
/// contact is active when its predicted gap g_k + (h / 2) gamma_N,k <= 0 [Acary and Brogliato 2008,
/// §10.1.2, the index set I_1 with gamma = 1/2]. Every threshold of the scheme is a member of
/// TimeSteppingPolicy (solver/dynamics/time_stepping_policy.h), its defaults these values. Solved
/// with the same Lemke solver (solver/lcp/lemke.h). With theta = 1/2 the contact-free scheme is the
/// trapezoidal rule: second order without contacts, first order with impacts.
///
/// The RunResult is filled as by the event-driven integrator, with these readings:
/// - maxima over the grid points (q is piecewise linear in t, so they are its true maxima);
/// - the decks' corner travels (max_travel_m) over the grid points, as the maxima;
/// - impacts: steps in which a contact has a positive P_N while it had none in the previous
///   step (one event entry per such contact); detachments: the reverse; stick / slip
///   transitions: changes of a loaded contact between |gamma_T,k+1| <= v_tol and above, v_tol =
///   TimeSteppingPolicy::velocity_tolerance max(a_peak / omega_1, |u(0)|_inf) with a_peak and
///   omega_1 as the event-driven integrator takes them (ExcitationPeak, model::LowestFrequency);
/// - free_steps counts steps without an active contact, rk_steps steps with an LCP solve;
///   plastic_closures is 0 (the scheme needs no accumulation threshold);
/// - min_impact_separation_s: the smallest time between two impact steps (a multiple of h);
/// - energy ledger with the theta-point velocity u_theta: damping h u_theta^T C u_theta, input
///   -h u_theta^T M r abar_g, impact -u_theta^T W_N P_N, friction -u_theta^T W_T P_T; exact
///   (balance error at rounding level) for theta = 1/2;
/// - histories linear in t between grid points; the contact forces are P / h of the step.
///
/// Linear algebra (RunControl::linear_algebra, docs/multispan.md): the dense path inverts W once
/// per step size and multiplies by W^-1 (O(n_dof^2) per step); the sparse path keeps K, C, W and
/// the active W_N, W_T sparse (a deck's columns have at most 6 non-zeros), factorises W with
/// CHOLMOD (simplicial LL^T, fill-reducing AMD ordering, symbolic analysis once per model) and
/// solves with the factor (O(nnz(L)) per right-hand side). "auto" takes the sparse path from
/// kSparseThresholdDof DOFs on. Both paths solve the same equations; they agree to rounding.
/// The sparse path allocates inside CHOLMOD's solves (the dense path allocates nothing per step).

#include <Eigen/Cholesky>
#include <Eigen/CholmodSupport>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <vector>

#include "solver/common/excitation.h"
#include "solver/contact/kinematics.h"
#include "solver/dynamics/run_result.h"
#include "solver/dynamics/simulate.h"
#include "solver/dynamics/time_stepping_policy.h"
#include "solver/lcp/lemke.h"
#include "solver/model/model.h"
#include "solver/model/run_control.h"

namespace skewbridge::dynamics {

/// The DOF count from which run.linear_algebra = "auto" takes the sparse path: the measured
/// crossover of docs/multispan.md (dense and sparse cost the same at 5 decks, 15 DOFs; the sparse
/// path is 1.3 times faster at 10 decks and 10 times faster at 50).
inline constexpr int kSparseThresholdDof = 15;

/// Whether a run of `model` under `control` takes the sparse path: control.linear_algebra is
/// "sparse", or "auto" with model.n_dof() >= kSparseThresholdDof.
/// @throws InputError when control.linear_algebra is not "auto", "dense" or "sparse".
bool UsesSparseLinearAlgebra(const model::Model& model, const model::RunControl& control);

/// Scratch memory of the time-stepping scheme for one model: build once, reuse for every run of
/// that model; results never depend on what ran before. Keeps a reference to the model.
class TimeSteppingWorkspace {
 public:
  /// Sizes everything for `model`; theta in (0, 1] of the theta-method (1/2: trapezoidal).
  /// @throws InputError when theta is outside (0, 1].
  explicit TimeSteppingWorkspace(const model::Model& model, double theta = 0.5);

  const model::Model& model() const { return model_; }
  double theta() const { return theta_; }

 private:
  friend RunResult SimulateTimeStepping(const model::Model&, const Excitation&,
                                        const model::RunControl&, TimeSteppingWorkspace&,
                                        const InitialState&, const TimeSteppingPolicy&);

  /// Factorises W for step h (no-op when h is the factorised step).
  void Factorise(double h_s);
  /// Factorises the sparse W for step h with CHOLMOD (no-op when h is the factorised step).
  void FactoriseSparse(double h_s);
  /// The sparse n_dof x k matrices of the first k gathered columns of W_N, W_T (WN_, WT_), from
  /// the rows of each active contact's bodies.
  void GatherSparseJacobians(int k);

  const model::Model& model_;
  double theta_;
  double factorised_h_s_ = -1.0;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd W_inverse_;  // n_dof x n_dof
  // The sparse path: K, C once per model, W and its CHOLMOD factor per step size.
  double factorised_sparse_h_s_ = -1.0;
  bool pattern_analysed_ = false;
  Eigen::SparseMatrix<double> K_sparse_, C_sparse_, M_sparse_, W_sparse_;
  Eigen::CholmodSimplicialLLT<Eigen::SparseMatrix<double>> cholmod_;
  Eigen::SparseMatrix<double> WN_sparse_, WT_sparse_;
  std::vector<Eigen::Triplet<double>> triplets_;
  contact::ContactKinematics kin_;
  lcp::LemkeSolver lemke_;
  std::vector<lcp::LcpSolution> solutions_;  // one per LCP size: no allocation per step
  std::vector<int> active_;
  Eigen::MatrixXd WN_, WT_, WinvWN_, WinvWT_, A_;
  Eigen::VectorXd b_, mu_, eps_;
  Eigen::VectorXd P_N_, P_T_, P_N_previous_;  // per model contact
  std::vector<int> state_, state_previous_;   // ContactState per contact
  Eigen::VectorXd rhs_, u_free_, u1_, q1_, u_theta_, work_;
};

/// One Moreau-Jean run of `model` under `excitation` with step control.time_step_s up to
/// control.EndTime(excitation.Duration()) from `initial`, with the thresholds of `policy`.
/// @pre workspace built for `model`.
/// @throws InputError when time_step_s <= 0, the initial state has the wrong size or a member of
/// `policy` is outside its range.
/// @return status kLcpFailure (with the LCP status and time in the message) when Lemke fails,
/// kStepLimit when more than control.max_steps steps would be needed (run stops there).
RunResult SimulateTimeStepping(const model::Model& model, const Excitation& excitation,
                               const model::RunControl& control, TimeSteppingWorkspace& workspace,
                               const InitialState& initial = {},
                               const TimeSteppingPolicy& policy = {});

/// The mean ground acceleration (m/s^2) over [t0_s, t1_s], exact for the excitation's pieces.
/// @pre t1_s > t0_s >= 0.
Eigen::Vector2d MeanAcceleration(const Excitation& excitation, double t0_s, double t1_s);

}  // namespace skewbridge::dynamics
