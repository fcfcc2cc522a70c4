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
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

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

/// The gap g (m) of contact c against a face on a body, at q: Gap's general path.
double BodyFaceGap(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q);

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

/// Scratch of the gap-and-rate path (GapsAndRates, NormalRate): a sine and cosine per body and
/// two Jacobian columns; sized once per model. A single deck whose contacts all face the ground
/// (at most kMaxDeckCorners) keeps its corners' data here instead, in the order GroundFaceGap and
/// GroundFaceNormalRate read it, and allocates nothing.
struct GapRateScratch {
  static constexpr int kMaxDeckCorners = 8;  ///< the most corners of the deck path
  /// The corners of a single deck against ground faces, one array per coordinate indexed by
  /// contact (the corners side by side in a vector register): the body's rest position X (m),
  /// the point p in the body frame (m), the face's normal n and point A (m).
  struct DeckCorners {
    double X_x[kMaxDeckCorners], X_y[kMaxDeckCorners];
    double p_x[kMaxDeckCorners], p_y[kMaxDeckCorners];
    double n_x[kMaxDeckCorners], n_y[kMaxDeckCorners];
    double A_x[kMaxDeckCorners], A_y[kMaxDeckCorners];
  };

  std::vector<double> cos, sin;  ///< per body, of theta at the last GapsAndRates
  Eigen::VectorXd w_N, w_T;      ///< n_dof: Jacobian columns for a face on a body
  int deck_corners = 0;          ///< > 0: the model is a single deck with this many corners
  DeckCorners corners;           ///< the deck's corners (deck_corners of each array)

  /// cos(theta) and sin(theta) of the deck path, from the last theta taken when it is the same
  /// bits (std::cos and std::sin are functions of their argument's bits, so the same values): a
  /// search reads the gap and the rate at one instant, and every open corner's gap at another.
  void SinCos(double theta, double& cos_theta, double& sin_theta) const {
    const auto bits = std::bit_cast<std::uint64_t>(theta);
    if (bits != last_theta_bits_) {
      last_cos_ = std::cos(theta);
      last_sin_ = std::sin(theta);
      last_theta_bits_ = bits;
    }
    cos_theta = last_cos_;
    sin_theta = last_sin_;
  }

  /// Sizes for a model (bodies, n_dof), or copies its corners when it is a single deck against
  /// ground faces. Called again after the model changes.
  void Resize(const model::Model& model);

 private:
  // SinCos's last argument (its bits) and its cosine and sine: +0, cos(+0) = 1 and sin(+0) = +0
  // exactly until the first call.
  mutable std::uint64_t last_theta_bits_ = 0;
  mutable double last_cos_ = 1.0, last_sin_ = 0.0;
};

/// The arm R(theta) p (m) from cos(theta) and sin(theta), entry by entry as Rotation(theta) p
/// (the same bits).
inline Eigen::Vector2d RotatedArm(double cos_theta, double sin_theta, const Eigen::Vector2d& p) {
  return {cos_theta * p.x() - sin_theta * p.y(), sin_theta * p.x() + cos_theta * p.y()};
}

/// The gap of a point against a ground face, n . ((X + (x, y)) + arm - A) (m), its body at
/// q_body = (x, y, ...) with `arm` = R(theta) p: what Gap computes for a ground face.
inline double GroundFaceGap(const model::Model& model, const model::Contact& contact,
                            const Eigen::Ref<const Eigen::VectorXd>& q,
                            const Eigen::Vector2d& arm) {
  const int i = 3 * contact.body;
  const Eigen::Vector2d position = model.body(contact.body).rest_position_m + q.segment<2>(i) + arm;
  return contact.face.normal.dot(position - contact.face.point_m);
}

/// The normal rate against a ground face, n . (v + thetadot J arm) (m/s), summed as w_N . u of
/// Evaluate (the same bits).
inline double GroundFaceNormalRate(const model::Contact& contact,
                                   const Eigen::Ref<const Eigen::VectorXd>& u,
                                   const Eigen::Vector2d& arm) {
  const int i = 3 * contact.body;
  const Eigen::Vector2d& n = contact.face.normal;
  return n.dot(u.segment<2>(i)) + u[i + 2] * (n.y() * arm.x() - n.x() * arm.y());
}

// Gap, GapsAndRates and NormalRate are defined here, not in kinematics.cpp, so that the event
// searches of the integrator (every step, every root-finding iteration) compile them in place
// rather than call across libraries. A face on a body calls out to the general path, and so do
// the gaps and rates of every model but a single deck against ground faces.

/// The gap g (m) of contact c at q. No allocation.
inline double Gap(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q) {
  const model::Contact& contact = model.contact(c);
  if (contact.face.body != model::kGround) {
    return BodyFaceGap(model, c, q);
  }
  // The general path's operations for a ground face, without the rotation matrix:
  // arm = R(theta) p, P = (X + (x, y)) + arm, n . (P - A).
  const double theta = q(3 * contact.body + 2);
  return GroundFaceGap(model, contact, q,
                       RotatedArm(std::cos(theta), std::sin(theta), contact.point_m));
}

/// GapsAndRates of a single deck against ground faces (GapRateScratch::deck_corners > 0): q, u
/// its 3 positions and velocities, `gap` and `gamma_N` one entry per corner. GroundFaceGap's and
/// GroundFaceNormalRate's operations in their order on the corners' copied data, one sine and
/// cosine (the same bits).
inline void DeckGapsAndRates(const GapRateScratch& scratch, const double* q, const double* u,
                             double* __restrict gap, double* __restrict gamma_N) {
  double cos_theta, sin_theta;
  scratch.SinCos(q[2], cos_theta, sin_theta);
  const double x = q[0], y = q[1], ux = u[0], uy = u[1], w = u[2];
  const GapRateScratch::DeckCorners& k = scratch.corners;
  for (int c = 0; c < scratch.deck_corners; ++c) {
    const double arm_x = cos_theta * k.p_x[c] - sin_theta * k.p_y[c];
    const double arm_y = sin_theta * k.p_x[c] + cos_theta * k.p_y[c];
    gap[c] = k.n_x[c] * (((k.X_x[c] + x) + arm_x) - k.A_x[c]) +
             k.n_y[c] * (((k.X_y[c] + y) + arm_y) - k.A_y[c]);
    gamma_N[c] = (k.n_x[c] * ux + k.n_y[c] * uy) + w * (k.n_y[c] * arm_x - k.n_x[c] * arm_y);
  }
}

/// The gap g (m) of corner c of a single deck against ground faces (GapRateScratch::deck_corners
/// > c) at the deck's positions q = (x, y, theta): DeckGapsAndRates's gap alone, GroundFaceGap's
/// operations in their order on the corner's copied data (the same bits as Gap).
inline double DeckGap(const GapRateScratch& scratch, int c, const double* q) {
  double cos_theta, sin_theta;
  scratch.SinCos(q[2], cos_theta, sin_theta);
  const GapRateScratch::DeckCorners& k = scratch.corners;
  const double arm_x = cos_theta * k.p_x[c] - sin_theta * k.p_y[c];
  const double arm_y = sin_theta * k.p_x[c] + cos_theta * k.p_y[c];
  return k.n_x[c] * (((k.X_x[c] + q[0]) + arm_x) - k.A_x[c]) +
         k.n_y[c] * (((k.X_y[c] + q[1]) + arm_y) - k.A_y[c]);
}

/// The normal rate gamma_N (m/s) of corner c of a single deck against ground faces
/// (GapRateScratch::deck_corners > c) at the deck's positions q and velocities u (3 each):
/// DeckGapsAndRates's rate alone, GroundFaceNormalRate's operations in their order on the
/// corner's copied data (the same bits as NormalRate's ground-face path).
inline double DeckNormalRate(const GapRateScratch& scratch, int c, const double* q,
                             const double* u) {
  double cos_theta, sin_theta;
  scratch.SinCos(q[2], cos_theta, sin_theta);
  const GapRateScratch::DeckCorners& k = scratch.corners;
  const double arm_x = cos_theta * k.p_x[c] - sin_theta * k.p_y[c];
  const double arm_y = sin_theta * k.p_x[c] + cos_theta * k.p_y[c];
  return (k.n_x[c] * u[0] + k.n_y[c] * u[1]) + u[2] * (k.n_y[c] * arm_x - k.n_x[c] * arm_y);
}

/// The gap g (m) of contact c at q, the same bits as Gap: a single deck against ground faces by
/// DeckGap from the corners of `scratch` (sized for the model), any other model by Gap.
inline double Gap(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q,
                  const GapRateScratch& scratch) {
  if (scratch.deck_corners > 0) {
    return DeckGap(scratch, c, q.data());
  }
  return Gap(model, c, q);
}

/// GapsAndRates of any model: a sine and cosine per body, a ground face without its rotation
/// matrix, face frame or Jacobian columns, a face on a body by the general path.
void GeneralGapsAndRates(const model::Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                         const Eigen::Ref<const Eigen::VectorXd>& u, Eigen::VectorXd& gap,
                         Eigen::VectorXd& gamma_N, GapRateScratch& scratch);

/// The gap g (m) and normal rate gamma_N (m/s) of every contact at (q, u), the same bits as Gap
/// and NormalRate (and for a single deck as Evaluate's gamma_N), for the event searches of the
/// integrator: a single deck against ground faces by DeckGapsAndRates, any other model by
/// GeneralGapsAndRates. No allocation once `scratch` is sized.
inline void GapsAndRates(const model::Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                         const Eigen::Ref<const Eigen::VectorXd>& u, Eigen::VectorXd& gap,
                         Eigen::VectorXd& gamma_N, GapRateScratch& scratch) {
  if (scratch.deck_corners > 0) {
    DeckGapsAndRates(scratch, q.data(), u.data(), gap.data(), gamma_N.data());
    return;
  }
  GeneralGapsAndRates(model, q, u, gap, gamma_N, scratch);
}

/// The normal rate gamma_N (m/s) of contact c at (q, u): a single deck against a ground face
/// without the Jacobians, otherwise w_N . u over the whole column (the same bits).
inline double NormalRate(const model::Model& model, int c,
                         const Eigen::Ref<const Eigen::VectorXd>& q,
                         const Eigen::Ref<const Eigen::VectorXd>& u, GapRateScratch& scratch) {
  if (scratch.deck_corners > 0) {
    return DeckNormalRate(scratch, c, q.data(), u.data());
  }
  const model::Contact& contact = model.contact(c);
  if (model.n_dof() != 3 || contact.face.body != model::kGround) {
    Jacobians(model, c, q, scratch.w_N, scratch.w_T);
    return scratch.w_N.dot(u);
  }
  return GroundFaceNormalRate(contact, u,
                              RotatedArm(std::cos(q[2]), std::sin(q[2]), contact.point_m));
}

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
