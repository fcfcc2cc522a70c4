#pragma once
/// @file
/// The velocity-level impact LCP of docs/theory.md §3 for a planar rigid deck, written here from
/// the formulas alone (independent of solver/contact) so the LCP tests can check the physical
/// facts of docs/theory.md §4.
///
/// Sign conventions (docs/theory.md §2): q = (x, y, theta), theta CCW. A contact pairs a body point
/// p with a face of unit normal n pointing into the free side and tangent t; the contact
/// velocities are gamma_N = w_N^T u (< 0: approaching) and gamma_T = w_T^T u (slip along +t
/// when > 0). Impulses act on the deck as W_N Lambda_N + W_T Lambda_T, so Lambda_N >= 0 pushes
/// along +n and Lambda_T > 0 pushes along +t. With Lambda_R = mu Lambda_N + Lambda_T,
/// Lambda_L = mu Lambda_N - Lambda_T and gamma_T,E = gamma_TR - gamma_TL:
///   sliding along -t after the impact (gamma_TL > 0) forces Lambda_L = 0, Lambda_T = +mu
///   Lambda_N (friction along +t, sigma = +1); sliding along +t (gamma_TR > 0) forces
///   Lambda_R = 0, Lambda_T = -mu Lambda_N (sigma = -1): friction opposes the slip.

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <vector>

namespace skewbridge::lcp::testing {

/// Uniform parallelogram deck (docs/theory.md §2): length L (m), width W (m), skew a (rad), mass m.
struct Deck {
  double L = 1.0;
  double W = 1.0;
  double a = 0.0;
  double m = 1.0;

  /// Radius of gyration from 12 rho^2 = L^2 + W^2 / cos^2 a (m).
  double Rho() const { return std::sqrt((L * L + W * W / (std::cos(a) * std::cos(a))) / 12.0); }
  /// I_m = m rho^2 (kg m^2).
  double Inertia() const { return m * Rho() * Rho(); }
  /// M = diag(m, m, I_m).
  Eigen::Matrix3d MassMatrix() const { return Eigen::Vector3d(m, m, Inertia()).asDiagonal(); }
  /// Corner i = 1..4 in the body frame (P1, P2 at the +x end; P1, P3 acute).
  Eigen::Vector2d Corner(int i) const {
    const double h = 0.5 * W * std::tan(a);
    switch (i) {
      case 1:
        return {0.5 * L + h, 0.5 * W};
      case 2:
        return {0.5 * L - h, -0.5 * W};
      case 3:
        return {-0.5 * L - h, -0.5 * W};
      default:
        return {-0.5 * L + h, 0.5 * W};
    }
  }
  /// The deck with eta0 = sin 2a / (2 W / L) for the given L, a: W = L sin 2a / (2 eta0).
  static Deck WithSkewRatio(double L, double a, double eta0, double m) {
    return Deck{L, L * std::sin(2.0 * a) / (2.0 * eta0), a, m};
  }
};

/// A corner against an abutment face: normal n (into the free side), tangent t, body point p.
struct Contact {
  Eigen::Vector2d n;
  Eigen::Vector2d t;
  Eigen::Vector2d p;
};

/// Corner i against the abutment at its end: +x for P1, P2 with n = (-cos a, sin a),
/// t = (sin a, cos a); -x for P3, P4 with n = (cos a, -sin a), t = (-sin a, -cos a).
inline Contact CornerContact(const Deck& deck, int i) {
  const double c = std::cos(deck.a);
  const double s = std::sin(deck.a);
  if (i <= 2) return {{-c, s}, {s, c}, deck.Corner(i)};
  return {{c, -s}, {-s, -c}, deck.Corner(i)};
}

/// Generalised direction (d, d . R'(theta) p) of a contact direction d: w_N for d = n,
/// w_T for d = t (docs/theory.md §2, "Contacts").
inline Eigen::Vector3d Jacobian(const Eigen::Vector2d& d, const Eigen::Vector2d& p, double theta) {
  const Eigen::Vector2d rp(-std::sin(theta) * p.x() - std::cos(theta) * p.y(),
                           std::cos(theta) * p.x() - std::sin(theta) * p.y());
  return {d.x(), d.y(), d.dot(rp)};
}

/// The impact LCP w = A z + b of docs/theory.md §3 over k closed contacts and its ingredients.
struct ImpactProblem {
  Eigen::Matrix3d M_inv;
  Eigen::MatrixXd W_N;  // 3 x k
  Eigen::MatrixXd W_T;  // 3 x k
  Eigen::VectorXd mu;   // k
  Eigen::MatrixXd A;    // 3k x 3k, z = (Lambda_N, Lambda_R, gamma_TL)
  Eigen::VectorXd b;    // 3k
  Eigen::Vector3d u_A;

  int Contacts() const { return static_cast<int>(mu.size()); }
  /// Lambda_N = z(0..k), Lambda_T = Lambda_R - mu Lambda_N.
  Eigen::VectorXd LambdaN(const Eigen::VectorXd& z) const { return z.head(Contacts()); }
  Eigen::VectorXd LambdaT(const Eigen::VectorXd& z) const {
    return z.segment(Contacts(), Contacts()) - mu.cwiseProduct(LambdaN(z));
  }
  /// u_E = u_A + M^-1 (W_N Lambda_N + W_T Lambda_T).
  Eigen::Vector3d PostImpactVelocity(const Eigen::VectorXd& z) const {
    return u_A + M_inv * (W_N * LambdaN(z) + W_T * LambdaT(z));
  }
};

/// Builds A and b exactly as docs/theory.md §3 writes them:
///   A = [ W_N^T M^-1 (W_N - W_T mu)   W_N^T M^-1 W_T   0
///         W_T^T M^-1 (W_N - W_T mu)   W_T^T M^-1 W_T   E
///         2 mu                        -E               0 ]
///   b = ( (E + eps) gamma_N,A,  gamma_T,A,  0 )
inline ImpactProblem BuildImpactProblem(const Deck& deck, const std::vector<int>& corners,
                                        double theta, const Eigen::Vector3d& u_A, double mu,
                                        double eps) {
  const int k = static_cast<int>(corners.size());
  ImpactProblem p;
  p.u_A = u_A;
  p.M_inv = deck.MassMatrix().inverse();
  p.W_N.resize(3, k);
  p.W_T.resize(3, k);
  for (int c = 0; c < k; ++c) {
    const Contact contact = CornerContact(deck, corners[c]);
    p.W_N.col(c) = Jacobian(contact.n, contact.p, theta);
    p.W_T.col(c) = Jacobian(contact.t, contact.p, theta);
  }
  p.mu = Eigen::VectorXd::Constant(k, mu);
  const Eigen::MatrixXd mu_d = p.mu.asDiagonal();
  const Eigen::MatrixXd eye = Eigen::MatrixXd::Identity(k, k);
  const Eigen::MatrixXd w_q = p.W_N - p.W_T * mu_d;
  p.A = Eigen::MatrixXd::Zero(3 * k, 3 * k);
  p.A.block(0, 0, k, k) = p.W_N.transpose() * p.M_inv * w_q;
  p.A.block(0, k, k, k) = p.W_N.transpose() * p.M_inv * p.W_T;
  p.A.block(k, 0, k, k) = p.W_T.transpose() * p.M_inv * w_q;
  p.A.block(k, k, k, k) = p.W_T.transpose() * p.M_inv * p.W_T;
  p.A.block(k, 2 * k, k, k) = eye;
  p.A.block(2 * k, 0, k, k) = 2.0 * mu_d;
  p.A.block(2 * k, k, k, k) = -eye;
  const Eigen::VectorXd gamma_n = p.W_N.transpose() * u_A;
  const Eigen::VectorXd gamma_t = p.W_T.transpose() * u_A;
  p.b = Eigen::VectorXd::Zero(3 * k);
  p.b.head(k) = (1.0 + eps) * gamma_n;
  p.b.segment(k, k) = gamma_t;
  return p;
}

/// Kinetic energy 1/2 u^T M u (J).
inline double KineticEnergy(const Deck& deck, const Eigen::Vector3d& u) {
  return 0.5 * u.dot(deck.MassMatrix() * u);
}

}  // namespace skewbridge::lcp::testing
