#pragma once
/// @file
/// The split of statically indeterminate contact forces along the kernel of a singular active
/// set by three small LPs [docs/theory.md §3.13]: no pulling contact where a compressive split
/// exists, no squeeze, and the split deepest inside the sticking contacts' friction cones.

#include <Eigen/Core>
#include <vector>

#include "solver/dynamics/active_system.h"
#include "solver/dynamics/contact_modes.h"
#include "solver/dynamics/event_policy.h"
#include "solver/lcp/small_lp.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// Storage the split works in, sized once per model with capacity C = 2 n_c rows: kernel C x C,
/// normal_of and tangent_of n_c entries, x_bal and x_try C, lp_G (3 n_c + 2) x (C + 1), lp_h
/// 3 n_c + 2, lp_c and lp_y C + 1.
struct SplitWorkspace {
  Eigen::MatrixXd& kernel;       ///< kernel basis of the singular active set (columns)
  std::vector<int>& normal_of;   ///< unknown j < k: the contact of the j-th normal force
  std::vector<int>& tangent_of;  ///< the unknown of its tangential force, or -1 (not sticking)
  Eigen::VectorXd& x_bal;        ///< the forces scaled to order one
  Eigen::VectorXd& x_try;        ///< the split of LPs 1-2, kept should LP 3 fail
  lcp::SmallLp& lp;              ///< the LP solver
  Eigen::MatrixXd& lp_G;         ///< LP constraints G y <= h
  Eigen::VectorXd& lp_h;         ///< their right-hand sides
  Eigen::VectorXd& lp_c;         ///< LP objective
  Eigen::VectorXd& lp_y;         ///< LP solution (kernel coordinates, then the bound)
};

/// Moves the solution x of `sys` (just solved and rank deficient; unknowns j < k the normal
/// forces lambda_N (N) of the closed contacts in ascending order, k <= j < m the tangential
/// forces lambda_T of the sticking ones) along the kernel of A [docs/theory.md §3.13]: LP 1
/// maximises the smallest normal force capped at 0, LP 2 minimises the total normal force above
/// that floor, LP 3 maximises the smallest friction margin mu lambda_N - |lambda_T| with that
/// total. A x = b still holds afterwards. `force_tol_N` bounds the force scale from below.
void SplitIndeterminateForces(const model::Model& model, const ContactModes& modes,
                              const EventPolicy& policy, double force_tol_N, int k, int m,
                              ActiveSystem& sys, SplitWorkspace& ws);

}  // namespace skewbridge::dynamics
