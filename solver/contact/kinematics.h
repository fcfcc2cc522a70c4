#pragma once
/// @file
/// Contact kinematics in the general form of [docs/theory.md §2, contacts (general form)]: for a
/// body-fixed point p (on body i) against a face (A, n, t), ground-fixed or on body j,
///
///     g      = n . (X_i + (x_i, y_i) + R(theta_i) p - A_world)
///     w_N    = d gamma_N / d u,  gamma_N = n . (v_P - v_Q),  gamma_T = t . (v_P - v_Q)
///     what_N = d gamma_N / dt - w_N^T du/dt   (the velocity-dependent part)
///
/// with X_i the body's rest position (Body::rest_position_m), A_world = X_j + (x_j, y_j) +
/// R(theta_j) A for a face on body j, P the point's world position and Q the face's material
/// point at P. For a ground face
/// w_N = (n, n . R'(theta) p), w_T = (t, t . R'(theta) p), what_N = -thetadot^2 n . R(theta) p,
/// what_T = -thetadot^2 t . R(theta) p, and for the +x abutment these equal the closed forms
/// of [Dimitrakopoulos 2011, eqs. 5-8]. For a body face the Jacobians have entries for both
/// bodies, and w_N is the gradient of g.

#include <Eigen/Core>
#include <span>

#include "solver/model/model.h"

namespace skewbridge::contact {

/// Kinematic quantities of all contacts of a model at one state; sized once per model
/// (Resize), refilled without allocating (Evaluate).
struct ContactKinematics {
  Eigen::VectorXd gap_m;    ///< g per contact (m)
  Eigen::MatrixXd W_N;      ///< n_dof x n_contacts, column c = w_N of contact c
  Eigen::MatrixXd W_T;      ///< n_dof x n_contacts, column c = w_T of contact c
  Eigen::VectorXd gamma_N;  ///< w_N^T u (m/s), > 0 when separating
  Eigen::VectorXd gamma_T;  ///< w_T^T u (m/s), slip velocity along t
  Eigen::VectorXd what_N;   ///< velocity-dependent part of d gamma_N / dt (m/s^2)
  Eigen::VectorXd what_T;   ///< velocity-dependent part of d gamma_T / dt (m/s^2)

  /// Allocates for a model (n_dof, n_contacts).
  void Resize(const model::Model& model);
};

/// The rotation R(theta) = [[cos, -sin], [sin, cos]].
Eigen::Matrix2d Rotation(double theta_rad);

/// The gap g (m) of contact c at q. No allocation.
double Gap(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q);

/// World position (m) of contact c's point P at q.
Eigen::Vector2d PointPosition(const model::Model& model, int c,
                              const Eigen::Ref<const Eigen::VectorXd>& q);

/// Unit normal and tangent (world frame) of contact c's face at q.
void FaceDirections(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q,
                    Eigen::Vector2d& n, Eigen::Vector2d& t);

/// The Jacobians w_N, w_T (n_dof each) of contact c at q. No allocation.
void Jacobians(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q,
               Eigen::Ref<Eigen::VectorXd> w_N, Eigen::Ref<Eigen::VectorXd> w_T);

/// The velocity-dependent terms what_N, what_T (m/s^2) of contact c at (q, u).
void VelocityTerms(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q,
                   const Eigen::Ref<const Eigen::VectorXd>& u, double& what_N, double& what_T);

/// w^T u for a column w of contact c's Jacobian (n_dof): the sum over the rows of the contact's
/// bodies only, which are its only non-zeros; for a single deck the same sum as w.dot(u).
double ColumnDot(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& w,
                 const Eigen::Ref<const Eigen::VectorXd>& u);

/// Fills every field of `out` for the state (q, u). No allocation once `out` is sized. Writes
/// only the rows of each contact's bodies (at most 6 per column): the others keep the zeros of
/// Resize, so the cost grows with the contacts, not with n_dof times the contacts.
/// @pre out.Resize(model) was called (SB_ASSERT) and W_N, W_T were not written elsewhere.
void Evaluate(const model::Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
              const Eigen::Ref<const Eigen::VectorXd>& u, ContactKinematics& out);

/// Evaluate for the listed contacts only: their entries of `out` are refilled, every other
/// entry keeps its last value. The Runge-Kutta stages of a constrained phase need the closed
/// contacts' Jacobians and velocity terms alone.
/// @pre out.Resize(model) was called (SB_ASSERT); valid contact indices.
void EvaluateContacts(const model::Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                      const Eigen::Ref<const Eigen::VectorXd>& u, std::span<const int> contacts,
                      ContactKinematics& out);

}  // namespace skewbridge::contact
