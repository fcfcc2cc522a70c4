#pragma once
/// @file
/// The constrained forces of a fixed active set [docs/theory.md §3, contact problem with the
/// active set fixed; §3.13]: with every closed contact's mode given (sticking, sliding with a
/// sign, frictionless), the normal forces lambda_N of the closed contacts and the tangential
/// forces lambda_T of the sticking ones solve
///     w_N^T M^-1 (h + sum_j col_j x_j) + what_N = 0   (every closed contact),
///     w_T^T M^-1 (h + sum_j col_j x_j) + what_T = 0   (every sticking contact),
/// with col = w_N - mu s w_T for a contact sliding with sign s, w_N otherwise, and col = w_T for
/// a sticking contact's tangential unknown. A singular (statically indeterminate) system moves
/// its solution along the kernel (SplitIndeterminateForces). Then du/dt = M^-1 (h + sum col x).

#include <Eigen/Core>
#include <vector>

#include "solver/contact/kinematics.h"
#include "solver/dynamics/active_system.h"
#include "solver/dynamics/contact_modes.h"
#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/indeterminate_split.h"
#include "solver/lcp/small_lp.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// Storage of one evaluation of the active set's forces, sized once for a model: the inputs it
/// evaluates (applied forces, kinematics), the dense system, the split's storage and the
/// results (lambda per contact, the friction power). Owns all of it.
struct ActiveForcesStorage {
  /// Sized for `model`; `rank_threshold` is EventPolicy::rank_threshold.
  ActiveForcesStorage(const model::Model& model, double rank_threshold);
  /// `split` refers to the members below.
  ActiveForcesStorage(const ActiveForcesStorage&) = delete;
  ActiveForcesStorage& operator=(const ActiveForcesStorage&) = delete;

  Eigen::VectorXd h;                  ///< applied forces h(t, q, u) (N, N m), n_dof
  contact::ContactKinematics kin;     ///< kinematics at (q, u)
  ActiveSystem sys;                   ///< the active set's rows, 2 n_c at most
  Eigen::VectorXd mh;                 ///< M^-1 h
  Eigen::MatrixXd cols;               ///< n_dof x 2 n_c: the force direction of each unknown
  Eigen::MatrixXd m_cols;             ///< M^-1 cols
  std::vector<const double*> row_of;  ///< the kinematics' column (constraint row) of each row
  Eigen::MatrixXd kernel, lp_G;       ///< the split's kernel basis and LP constraints
  Eigen::VectorXd x_bal, x_try, lp_h, lp_c, lp_y;  ///< the split's vectors
  std::vector<int> normal_of, tangent_of;          ///< the split's active-set layout
  lcp::SmallLp lp;                                 ///< the split's LP solver
  SplitWorkspace split;                            ///< the split's view of the members above
  Eigen::VectorXd lambda_N;                        ///< per contact (N); 0 when open
  Eigen::VectorXd lambda_T;                        ///< per contact (N); 0 when open
  double friction_power_W = 0.0;  ///< -sum lambda_T gamma_T over the closed contacts (W)
};

/// Forces a run adds to the model's applied forces h(t, q, u) = -C u - K q - M r a_g: a compliant
/// wall's springs beside the rigid contacts [docs/compliant.md §4]. Every place the event-driven
/// integrator forms h (EvaluateActiveForces, the mode decision's contact problem and bounce
/// prediction) calls AppliedForces below, which adds them.
class AddedForces {
 public:
  virtual ~AddedForces() = default;
  /// Adds the forces at (q, u) to h (N, N m; n_dof entries).
  virtual void AddTo(const Eigen::Ref<const Eigen::VectorXd>& q,
                     const Eigen::Ref<const Eigen::VectorXd>& u, Eigen::Ref<Eigen::VectorXd> h) = 0;
};

/// h = Model::AppliedForces(q, u, a_g), then `added`'s forces when not null; without them h is the
/// model's, bit for bit.
inline void AppliedForces(const model::Model& model, AddedForces* added,
                          const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& u,
                          const Eigen::Vector2d& a_g_mps2, Eigen::Ref<Eigen::VectorXd> h) {
  model.AppliedForces(q, u, a_g_mps2, h);
  if (added != nullptr) {
    added->AddTo(q, u, h);
  }
}

/// Which contacts' kinematics an evaluation computes.
enum class KinematicsOf {
  kAllContacts,     ///< every contact (kin complete afterwards)
  kClosedContacts,  ///< the closed contacts only (the open ones' entries left as they were)
};

/// Evaluates the forces of the active set `modes` at (q, u) under the ground acceleration
/// `a_g_mps2` into `s`: s.kin, s.h, s.lambda_N, s.lambda_T, s.friction_power_W, and
/// du = du/dt (m/s^2, rad/s^2). A rank-deficient system is split by SplitIndeterminateForces
/// with `policy` and the force scale `force_tol_N` [docs/theory.md §3.13]. The applied forces
/// include `added`'s (AppliedForces) when it is not null.
/// @pre s sized for `model`; q, u, du of size n_dof.
void EvaluateActiveForces(const model::Model& model, const ContactModes& modes,
                          const EventPolicy& policy, double force_tol_N,
                          const Eigen::Vector2d& a_g_mps2,
                          const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& u, KinematicsOf which,
                          Eigen::Ref<Eigen::VectorXd> du, ActiveForcesStorage& s,
                          AddedForces* added = nullptr);

}  // namespace skewbridge::dynamics
