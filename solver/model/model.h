#pragma once
/// @file
/// The immutable deck model: bodies, mass, stiffness, damping, ground influence and the
/// potential contacts in the general form of [docs/theory.md §2, contacts (general form)].
/// Validated at construction: a Model that exists is consistent. State (q, u) and scratch
/// memory live outside it (solver/contact workspaces, the integrator's workspace).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "solver/model/deck.h"

namespace skewbridge::model {

/// Index of the ground in Face::body.
inline constexpr int kGround = -1;

/// A face of a potential contact: a point A on it, its unit normal n into the free side and
/// unit tangent t, all in the frame of `body` (the ground frame when body == kGround). For a
/// body-fixed face they rotate with the body (deck-to-deck joints).
struct Face {
  int body = kGround;                                  ///< kGround or a body index
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();   ///< A (m)
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();   ///< n, unit, into the free side
  Eigen::Vector2d tangent = Eigen::Vector2d::UnitY();  ///< t, unit, n . t = 0
};

/// A potential contact: the body-fixed point p of `body` against `face`, with the gap
/// g = n . ((x, y) + R(theta) p - A) for a ground face [docs/theory.md §2].
struct Contact {
  std::string name;                                   ///< "P1".."P4" for deck corners
  int body = 0;                                       ///< body carrying the point p
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();  ///< p in the body frame (m)
  Face face;                                          ///< the face it may strike
  double restitution = 0.5;                           ///< eps_N in [0, 1]
  double friction = 0.0;                              ///< mu >= 0
};

/// The normal, tangent and point A of the +x abutment face for a deck of skew a and gap delta
/// (m, along x): n = (-cos a, sin a), t = (sin a, cos a), A = (L/2 + delta, 0) [docs/theory.md §2].
Face PlusXAbutmentFace(const DeckGeometry& deck, double gap_m);

/// The -x abutment face: n = (cos a, -sin a), t = (-sin a, -cos a), A = (-L/2 - delta, 0)
/// [docs/theory.md §2].
Face MinusXAbutmentFace(const DeckGeometry& deck, double gap_m);

/// The deck model, immutable after construction. DOFs: q = (x_0, y_0, theta_0, x_1, ...)
/// (m, m, rad) relative to the ground; n_dof = 3 n_bodies. Equation of motion between events
/// Natural frequencies w_k (rad/s, ascending) and mass-normalised modes Phi (columns,
/// Phi^T M Phi = E) of K Phi = M Phi diag(w^2), as ComputeModes (builders.h) solves them.
struct Modes {
  Eigen::VectorXd omega_radps;
  Eigen::MatrixXd phi;
  /// w_k^2 as solved (rad^2/s^2): a free body's rigid modes may lie a rounding below zero,
  /// where omega_radps holds 0.
  Eigen::VectorXd eigenvalues;
};

/// [docs/theory.md §2]: M du/dt = h + W_N lambda_N + W_T lambda_T, h = -C u - K q - M r a_g(t).
class Model {
 public:
  /// Builds and validates a model. `source` names the input in error messages (a file name or
  /// "model"); field names in messages follow the model file's keys (deck.m, deck.W, ...).
  /// @param K, C n_dof x n_dof stiffness (N/m, N m/rad, ...) and damping matrices;
  /// @param r n_dof x 2 ground-influence matrix.
  /// @throws InputError when a body has m <= 0, I_m <= 0, L <= 0, W <= 0, a outside [0, 90) deg;
  /// K or C not symmetric (relative 1e-9) or not positive semi-definite; a size mismatch; a
  /// contact with eps_N outside [0, 1], mu < 0, a non-unit or non-orthogonal n, t, a bad body
  /// index, a negative gap at q = 0; or a NaN / Inf anywhere.
  /// @param modes ComputeModes(M, K) when the caller has solved it (a builder, for the damping):
  /// kept for the integrator's modal flow, which then need not solve it again. Trusted: only
  /// its sizes are checked (SB_DEMAND).
  Model(std::vector<Body> bodies, Eigen::MatrixXd K, Eigen::MatrixXd C, Eigen::MatrixXd r,
        std::vector<Contact> contacts, std::string source = "model",
        std::optional<Modes> modes = std::nullopt);

  int n_bodies() const { return static_cast<int>(bodies_.size()); }
  int n_dof() const { return 3 * n_bodies(); }
  int n_contacts() const { return static_cast<int>(contacts_.size()); }

  const std::vector<Body>& bodies() const { return bodies_; }
  const Body& body(int i) const { return bodies_[static_cast<std::size_t>(i)]; }
  const std::vector<Contact>& contacts() const { return contacts_; }
  const Contact& contact(int c) const { return contacts_[static_cast<std::size_t>(c)]; }
  /// Index of the contact named `name`, or -1.
  int FindContact(const std::string& name) const;

  /// M = blockdiag(m, m, I_m) per body, n_dof x n_dof.
  const Eigen::MatrixXd& M() const { return M_; }
  /// The diagonal of M (M is diagonal for planar rigid decks).
  const Eigen::VectorXd& mass_diagonal() const { return mass_diagonal_; }
  /// The diagonal of M^-1.
  const Eigen::VectorXd& inverse_mass_diagonal() const { return inverse_mass_diagonal_; }
  const Eigen::MatrixXd& K() const { return K_; }
  const Eigen::MatrixXd& C() const { return C_; }
  /// r: n_dof x 2, column j maps a_g,j (j = x, y) to the DOFs.
  const Eigen::MatrixXd& r() const { return r_; }
  const std::string& source() const { return source_; }
  /// The modes of (K, M) given at construction, or null.
  const Modes* modes() const { return modes_ ? &*modes_ : nullptr; }

  /// h = -C u - K q - M r a_g (N, N m) into h, without allocating.
  void AppliedForces(const Eigen::Ref<const Eigen::VectorXd>& q,
                     const Eigen::Ref<const Eigen::VectorXd>& u, const Eigen::Vector2d& a_g_mps2,
                     Eigen::Ref<Eigen::VectorXd> h) const;

  /// Kinetic 1/2 u^T M u plus strain 1/2 q^T K q (J).
  double MechanicalEnergy(const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& u) const;

 private:
  std::vector<Body> bodies_;
  Eigen::MatrixXd M_;
  Eigen::VectorXd mass_diagonal_;
  Eigen::VectorXd inverse_mass_diagonal_;
  Eigen::MatrixXd K_;
  Eigen::MatrixXd C_;
  Eigen::MatrixXd r_;
  Eigen::MatrixXd mass_r_;  // M r (n_dof x 2): the ground acceleration's force per unit a_g
  std::vector<Contact> contacts_;
  std::string source_;
  std::optional<Modes> modes_;
};

}  // namespace skewbridge::model
