#pragma once
/// @file
/// A conservative bound of |q_i| over a free step of a classically damped model, from the step's
/// two ends and the modal state at its start [docs/theory.md §3.20]: the cubic Hermite
/// interpolant H of the ends' positions and velocities, bounded by its Bernstein control points
/// after two halvings, plus the interpolation error M4 h^4 / 384, M4 a bound of |q_i''''| over
/// the step from each mode's energy (§3.18). A velocity root whose peak this bound keeps below
/// the running maximum needs no root search: the search could not raise the maximum.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/dynamics/modal_flow.h"

namespace skewbridge::dynamics {

/// The largest |control point| of the cubic with Bernstein control points b[0..3] over the
/// pieces of `depth` halvings by de Casteljau's construction, `reached` (a value the curve
/// reaches, at least max(|b[0]|, |b[3]|)) raised to every piece's end it forms: at least
/// max |H(x)| over x in [0, 1] (each half's curve lies in the hull of its own control points),
/// to within a few ulps of max |b| for the rounding of the midpoints. A piece whose control
/// points all lie within `reached` is not halved: its curve does not exceed what the curve
/// reaches elsewhere, so the bound is that of the pieces around the curve's peak.
inline double BernsteinAbsBound(const double b[4], int depth, double& reached) {
  const double hull = std::max({std::abs(b[1]), std::abs(b[2]), std::abs(b[0]), std::abs(b[3])});
  if (depth == 0 || hull <= reached) {
    return hull;
  }
  const double m01 = 0.5 * (b[0] + b[1]), m12 = 0.5 * (b[1] + b[2]), m23 = 0.5 * (b[2] + b[3]);
  const double m012 = 0.5 * (m01 + m12), m123 = 0.5 * (m12 + m23);
  const double mid = 0.5 * (m012 + m123);
  reached = std::max(reached, std::abs(mid));
  const double left[4] = {b[0], m01, m012, mid};
  const double right[4] = {mid, m123, m23, b[3]};
  const double l = BernsteinAbsBound(left, depth - 1, reached);
  return std::max(l, BernsteinAbsBound(right, depth - 1, reached));
}

/// BernsteinAbsBound from the curve's ends alone: an upper bound of max |H(x)| over x in [0, 1].
inline double BernsteinAbsBound(const double b[4], int depth) {
  double reached = std::max(std::abs(b[0]), std::abs(b[3]));
  return BernsteinAbsBound(b, depth, reached);
}

/// An upper bound of max |H(s)| over s in [0, h] for the cubic Hermite interpolant with
/// H(0) = q0, H'(0) = u0, H(h) = q1, H'(h) = u1 (control points q0, q0 + h u0 / 3,
/// q1 - h u1 / 3, q1; `halvings` halvings, two unless told), rounded up by a relative 1e-12 of
/// its terms.
inline double HermiteAbsBound(double q0, double u0, double q1, double u1, double h_s,
                              int halvings = 2) {
  const double b[4] = {q0, q0 + h_s * u0 / 3.0, q1 - h_s * u1 / 3.0, q1};
  const double scale = std::abs(q0) + std::abs(q1) + h_s * (std::abs(u0) + std::abs(u1));
  return BernsteinAbsBound(b, halvings) + 1e-12 * scale;
}

/// Per mode the bounds over a step [0, tau_s] of the mode eta'' + c eta' + w^2 eta = f(s),
/// f = alpha + beta s + gamma cos(Omega s) + delta sin(Omega s), c >= 0, from y = (eta, eta',
/// alpha, beta, gamma, delta) at s = 0 [docs/theory.md §3.20]: a[m - 1] bounds the m-th
/// derivative |eta^(m)| for m = 1 .. 4, and `size` bounds |eta| + tau |eta'| over the step.
inline void ModeDerivativeBounds(double w, double c, double eta, double deta, double alpha,
                                 double beta, double gamma, double delta, double tau_s,
                                 double omega_radps, double a[4], double& size) {
  const double amplitude = std::abs(deta) + w * std::abs(eta);  // >= sqrt(E(0))
  const double a0 = std::abs(alpha), a1 = std::abs(alpha + beta * tau_s);
  const double harmonic = std::abs(gamma) + std::abs(delta);
  const double F = std::max(a0, a1) + harmonic;  // >= |f|
  const double Om = std::abs(omega_radps);
  const double F1 = std::abs(beta) + Om * harmonic;  // >= |f'|
  const double F2 = Om * Om * harmonic;              // >= |f''|
  const double S = amplitude + tau_s * F;            // >= sqrt(E(s)) >= |eta'|, w |eta|
  a[0] = S;
  a[1] = F + (c + w) * S;               // >= the second derivative
  a[2] = F1 + c * a[1] + w * w * S;     // >= the third
  a[3] = F2 + c * a[2] + w * w * a[1];  // >= the fourth
  // |eta(s)| <= |eta(0)| + D (§3.18), |eta'(s)| <= S.
  size = std::abs(eta) + tau_s * (amplitude + 0.5 * tau_s * F) + tau_s * S;
}

/// The per-step bounds of a classically damped model's coordinates over a free step
/// [docs/theory.md §3.20]: per mode bounds of |eta_k^(m)|, m = 1 .. 4, and of the mode's size,
/// combined per coordinate with |Phi_ik|. Sized once per run (one allocation); Step and the
/// queries allocate nothing.
class ModalPeakBound {
 public:
  ModalPeakBound() = default;
  /// The bound of `modal`'s modes; it applies only when every c_k >= 0 (applies()).
  explicit ModalPeakBound(const ModalFlow& modal) {
    const int n = modal.n_modes();
    if (n == 0 || (modal.c().array() < 0.0).any()) return;
    n_ = n;
    data_.resize(static_cast<Eigen::Index>(n) * (n + kPerMode));
    double* d = data_.data();
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < n; ++k) d[i * n + k] = std::abs(modal.Phi()(i, k));
    }
    for (int k = 0; k < n; ++k) {
      Mode(0)[k] = std::sqrt(std::max(0.0, modal.w2()[k]));
      Mode(1)[k] = modal.c()[k];
    }
  }

  /// True when the bound applies (a modal flow with non-negative modal damping).
  bool applies() const { return n_ > 0; }

  /// Prepares the step [0, tau_s] at harmonic rate omega_radps from the modal coordinates Y of
  /// its start (n x 6 column-major, rows (eta, eta', alpha, beta, gamma, delta) as
  /// ModalFlow::ToModal gives them).
  void Step(const double* Y, double tau_s, double omega_radps) {
    const int n = n_;
    const double* w = Mode(0);
    const double* c = Mode(1);
    double* size = Mode(6);
    for (int k = 0; k < n; ++k) {
      double a[4];
      ModeDerivativeBounds(w[k], c[k], Y[k], Y[n + k], Y[2 * n + k], Y[3 * n + k], Y[4 * n + k],
                           Y[5 * n + k], tau_s, omega_radps, a, size[k]);
      for (int m = 0; m < 4; ++m) Mode(2 + m)[k] = a[m];
    }
  }

  /// Bounds of coordinate i over the step prepared by Step: d[m - 1] >= |q_i^(m)|, m = 1 .. 4;
  /// returns a bound of the modal terms |Phi_ik| (|eta_k| + tau |eta_k'|) summed over k (the
  /// size that the rounding of q_i and tau u_i is relative to).
  double Derivatives(int i, double d[4]) const {
    const double* phi = data_.data() + static_cast<Eigen::Index>(i) * n_;  // |Phi_ik| over k
    d[0] = d[1] = d[2] = d[3] = 0.0;
    double size = 0.0;
    for (int k = 0; k < n_; ++k) {
      for (int m = 0; m < 4; ++m) d[m] += phi[k] * Mode(2 + m)[k];
      size += phi[k] * Mode(6)[k];
    }
    return size;
  }

  /// An upper bound of max |q_i(s)| over an interval of length h_s inside the step prepared by
  /// Step, from q_i and u_i at its two ends: HermiteAbsBound plus M4 h^4 / 384, and a relative
  /// 1e-12 of the coordinate's modal size for the rounding of the ends and of a dense output's
  /// evaluation.
  double PeakBound(int i, double q0, double u0, double q1, double u1, double h_s) const {
    return PeakBoundOfHull(i, HermiteAbsBound(q0, u0, q1, u1, h_s), h_s);
  }

  /// PeakBound from its HermiteAbsBound term `hull` (the ends' cubic's bound): hull plus
  /// M4 h^4 / 384, rounded up as PeakBound rounds it. Never below `hull` (the added terms are
  /// non-negative and each rounding is monotone).
  double PeakBoundOfHull(int i, double hull, double h_s) const {
    const double* phi = data_.data() + static_cast<Eigen::Index>(i) * n_;  // |Phi_ik| over k
    const double* a4 = Mode(5);
    const double* sz = Mode(6);
    double m4 = 0.0, size = 0.0;  // Derivatives' d[3] and size, the same sums
    for (int k = 0; k < n_; ++k) {
      m4 += phi[k] * a4[k];
      size += phi[k] * sz[k];
    }
    const double h2 = h_s * h_s;
    return (hull + m4 * (h2 * h2 / 384.0)) * (1.0 + 1e-12) + 1e-12 * size;
  }

 private:
  // Per mode: w_k, c_k, the step's bounds of |eta'| .. |eta''''|, and its size.
  static constexpr int kPerMode = 7;
  double* Mode(int j) { return data_.data() + static_cast<Eigen::Index>(n_) * (n_ + j); }
  const double* Mode(int j) const {
    return data_.data() + static_cast<Eigen::Index>(n_) * (n_ + j);
  }

  int n_ = 0;
  // |Phi| transposed (row i of |Phi| contiguous, n x n), then kPerMode rows of n.
  Eigen::VectorXd data_;
};

/// CornerPeakBound's halvings of the Hermite hull: four leave about 1/256 of the curve's bulge
/// (two, 1/16). The corners' bound is asked only where a search would follow, and
/// BernsteinAbsBound halves only the pieces around the peak, so the two more halvings cost
/// little beside the searches they spare.
inline constexpr int kCornerHalvings = 4;

/// CornerPeakBound from its HermiteAbsBound term `hull` (kCornerHalvings halvings of the ends'
/// cubic): hull plus M4 h^4 / 384, rounded up as CornerPeakBound rounds it. Never below `hull`
/// (the added terms are non-negative and each rounding is monotone).
inline double CornerPeakBoundOfHull(double nx, double ny, double radius_m, const double dx[4],
                                    const double dy[4], const double dth[4], double size_m,
                                    double hull, double h_s) {
  const double t1 = dth[0], t2 = dth[1], t3 = dth[2], t4 = dth[3];
  const double turn = t4 + 4.0 * t1 * t3 + 3.0 * t2 * t2 + 6.0 * t1 * t1 * t2 + t1 * t1 * t1 * t1;
  const double m4 = std::abs(nx) * dx[3] + std::abs(ny) * dy[3] + radius_m * turn;
  const double h2 = h_s * h_s;
  return (hull + m4 * (h2 * h2 / 384.0)) * (1.0 + 1e-12) + 1e-12 * size_m;
}

/// An upper bound of a deck corner's travel |f| over an interval of length h_s inside a free
/// step [docs/theory.md §3.20], f = n_e . (x, y) +- ((cos theta - 1) A + sin theta B) with
/// |P| = sqrt(A^2 + B^2) the corner's radius (m), from f and df/dt at the two ends, the bounds
/// dx, dy, dth of the first four derivatives of x, y, theta (ModalPeakBound::Derivatives) and
/// the terms' size `size_m`: HermiteAbsBound (kCornerHalvings halvings) plus M4 h^4 / 384 with M4 =
/// |n_x| X4 + |n_y| Y4 + |P| (T4 + 4 T1 T3 + 3 T2^2 + 6 T1^2 T2 + T1^4) (Faa di Bruno; every
/// derivative of (cos - 1) A + sin B is at most |P| in magnitude), and a relative 1e-12 of
/// `size_m`.
inline double CornerPeakBound(double nx, double ny, double radius_m, const double dx[4],
                              const double dy[4], const double dth[4], double size_m, double f0,
                              double r0, double f1, double r1, double h_s) {
  return CornerPeakBoundOfHull(nx, ny, radius_m, dx, dy, dth, size_m,
                               HermiteAbsBound(f0, r0, f1, r1, h_s, kCornerHalvings), h_s);
}

/// The peak bound of the free step being recorded (ModalPeakBound): armed by the free step after
/// its transition, asked at candidate roots only, its per-mode terms computed at the step's first
/// question. Unarmed (outside a full modal free step) it proves nothing.
class FreeStepPeaks {
 public:
  /// For a flow of `modal` (null: a flow that is not modal; the bound never applies).
  explicit FreeStepPeaks(const ModalFlow* modal)
      : bound_(modal != nullptr ? ModalPeakBound(*modal) : ModalPeakBound()) {}

  /// Arms the bound for a step [0, tau_s] at omega_radps from the modal coordinates Y of its
  /// start (ModalPeakBound::Step's layout; the storage must outlive the step), when `full` and
  /// the bound applies.
  /// max_travel_m (null: none) holds the decks' running maxima of the corners' travel (m) that
  /// the travel bound is compared with (the deck at DOF b is max_travel_m[b / 3]).
  void Arm(bool full, const double* Y, double tau_s, double omega_radps,
           const double* max_travel_m = nullptr) {
    if (full && bound_.applies()) {
      Y_ = Y;
      max_travel_m_ = max_travel_m;
      tau_s_ = tau_s;
      omega_radps_ = omega_radps;
      ready_ = false;
    }
  }
  /// Ends the step: no bound until the next Arm.
  void Disarm() {
    Y_ = nullptr;
    max_travel_m_ = nullptr;
  }

  /// Whether |q_i| provably stays below `best` over an interval of length h_s of the armed step
  /// with the ends (q0, u0), (q1, u1). The ends' cubic first: where its hull alone reaches
  /// `best` the whole bound does too (PeakBoundOfHull), and the step's per-mode terms are not
  /// computed for it. Out of line: asked at candidate roots only.
  [[gnu::noinline]] bool PeakBelow(int i, double q0, double u0, double q1, double u1, double h_s,
                                   double best) {
    const double hull = HermiteAbsBound(q0, u0, q1, u1, h_s);
    return hull < best && Prepare() && bound_.PeakBoundOfHull(i, hull, h_s) < best;
  }

  /// CornerTravelTracker::Scan's travel bound: CornerPeakBound of a corner of the deck at DOF b
  /// over an interval of length h_s of the armed step (+inf unarmed): end-line normal (nx, ny),
  /// corner radius (m), travel (m) and rate (m/s) at the ends. +inf also where the ends' hull
  /// alone reaches the deck's running maximum (Arm's max_travel_m): the whole bound would reach
  /// it too (CornerPeakBoundOfHull), and the step's per-mode terms are not computed for it.
  [[gnu::noinline]] double operator()(int b, double nx, double ny, double radius, double f0,
                                      double r0, double f1, double r1, double h_s) {
    if (Y_ == nullptr) return std::numeric_limits<double>::infinity();
    const double hull = HermiteAbsBound(f0, r0, f1, r1, h_s, kCornerHalvings);
    if (max_travel_m_ != nullptr && !(hull < max_travel_m_[b / 3])) {
      return std::numeric_limits<double>::infinity();
    }
    Prepare();
    double dx[4], dy[4], dth[4];
    const double size = std::abs(nx) * bound_.Derivatives(b, dx) +
                        std::abs(ny) * bound_.Derivatives(b + 1, dy) +
                        radius * bound_.Derivatives(b + 2, dth);
    return CornerPeakBoundOfHull(nx, ny, radius, dx, dy, dth, size, hull, h_s);
  }

 private:
  bool Prepare() {
    if (Y_ == nullptr) return false;
    if (!ready_) {
      bound_.Step(Y_, tau_s_, omega_radps_);
      ready_ = true;
    }
    return true;
  }

  ModalPeakBound bound_;
  const double* Y_ = nullptr;             // the armed step's modal coordinates at its start
  const double* max_travel_m_ = nullptr;  // the decks' running maxima of the travel (m)
  double tau_s_ = 0.0;                    // its length (s)
  double omega_radps_ = 0.0;              // its harmonic rate (rad/s)
  bool ready_ = false;                    // bound_.Step done for it
};

}  // namespace skewbridge::dynamics
