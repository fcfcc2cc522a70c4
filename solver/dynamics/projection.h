#pragma once
/// @file
/// The projection of a constrained phase's state onto its closed contacts' constraints
/// [docs/theory.md §3.10]: positions onto g = 0 by Gauss-Newton in the M^-1 metric, then
/// velocities onto gamma_N = 0 (gamma_T = 0 when sticking) with the open contacts at their face
/// as inequality rows gamma_N >= 0 of an active set.

#include <Eigen/Core>
#include <vector>

#include "solver/contact/kinematics.h"
#include "solver/dynamics/active_system.h"
#include "solver/dynamics/contact_modes.h"
#include "solver/dynamics/event_policy.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// The run's tolerances the projection reads besides the policy.
struct ProjectionTolerances {
  double length_scale_m = 0.0;  ///< L_d: the one-pass test compares gaps with one_pass_gap L_d
  double gap_tol_m = 0.0;       ///< an open contact with g <= gap_tol_m is at its face
  double v_tol_mps = 0.0;       ///< an open contact at its face approaching faster joins
};

/// Storage the projection works in, sized once for a model and owned whole. `kin` and `sys` are
/// left holding the last evaluation and solve: the mode decision, whose storage this is, reads
/// `kin` after the projection (solver/dynamics/mode_decision.h).
struct ProjectionWorkspace {
  /// Sized for `model`; `rank_threshold` is EventPolicy::rank_threshold.
  ProjectionWorkspace(const model::Model& model, double rank_threshold);

  contact::ContactKinematics kin;    ///< kinematics of every contact
  ActiveSystem sys;                  ///< the dense active set, 2 n_c rows at most
  Eigen::MatrixXd rows;              ///< n_dof x 2 n_c constraint rows
  std::vector<int> projection_rows;  ///< per contact: 1 when an open contact joins
  Eigen::VectorXd u_in;              ///< velocities before the velocity projection (m/s, rad/s)
  Eigen::VectorXd u_out;             ///< projected velocities
};

/// Projects (q, u) in place onto the constraints of the contacts closed in `modes`
/// [docs/theory.md §3.10]: at most policy.position_passes Gauss-Newton passes on the positions
/// (one once every closed gap is below one_pass_gap L_d), then the velocity projection with its
/// active set of open contacts at the face (at most n_c + 1 rounds). The change is the
/// least-squares one in the mass metric: dq = M^-1 W_N x, du = M^-1 W y.
void ProjectOntoContacts(const model::Model& model, const ContactModes& modes,
                         const EventPolicy& policy, const ProjectionTolerances& tol,
                         Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> u,
                         ProjectionWorkspace& ws);

}  // namespace skewbridge::dynamics
