#pragma once
/// @file
/// A conservative bound on how far the gaps of a classically damped model's open contacts can
/// close over one free step, from the modal state at the step's start and the step's input alone
/// [docs/theory.md §3.18]. A step whose gaps all stay above the bound cannot strike: the free
/// step then skips the gaps at its end and the impact search, and carries a lower bound of each
/// gap to the next step instead.
///
/// Per mode, E_k = eta'^2 + w_k^2 eta^2 obeys dE/ds = 2 eta' f - 2 c_k eta'^2 <= 2 sqrt(E) |f| for
/// c_k >= 0, so sqrt(E_k(s)) <= sqrt(E_k(0)) + s F_k with F_k >= |f_k| over the step, and
///
///     |eta_k(s) - eta_k(0)| <= D_k = tau sqrt(E_k(0)) + tau^2 F_k / 2   for 0 <= s <= tau.
///
/// A corner p on body b against a ground face of normal n moves the gap by
/// n . dx_b + n . (R(theta) - R(theta_0)) p, at most sum_k W_ck D_k with
/// W_ck = |n_x Phi_xk + n_y Phi_yk| + |p| |Phi_theta,k| (|R(a) - R(b)| <= |a - b|).

#include <Eigen/Core>
#include <bit>
#include <cmath>
#include <cstddef>
#include <vector>

#include "solver/dynamics/modal_flow.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// What the bound needs of a model: the weights and the modes' natural frequencies.
struct ModalGapBound {
  /// W row-major (n_contacts x n_modes, m per unit of modal coordinate): the largest change of
  /// contact c's gap per unit change of eta_k. Empty when the bound does not apply: a contact
  /// against a face on a body (a joint between decks), or a negative modal damping.
  std::vector<double> weights;
  std::vector<double> w_radps;  ///< sqrt(w_k^2) per mode (rad/s)
  int n_modes = 0;
  int n_contacts = 0;

  /// The bound of `model` with its modal flow.
  ModalGapBound(const model::Model& model, const ModalFlow& modal);
  ModalGapBound() = default;
  /// Makes this the bound of `model` with its modal flow, ModalGapBound(model, modal)'s values,
  /// in the storage it holds: a model of the last one's sizes allocates nothing.
  void Assign(const model::Model& model, const ModalFlow& modal);
  /// Makes this the empty bound (applies() false), keeping its storage.
  void Clear();
  /// True when the bound applies to the model.
  bool applies() const { return !weights.empty(); }
  /// Takes the weights W of `count` gaps (row-major, count x n_modes) and the modes' frequencies
  /// of `modal`: the bound then applies.
  void Set(const ModalFlow& modal, std::vector<double> W, int count);
};

/// The weights of one gap, into W[0 .. n_modes): a corner at point_m (m, body frame) of the body
/// whose x, y and theta rows of Phi start at `row`, against a ground face of outward normal
/// `normal`, W_k = |n_x Phi_xk + n_y Phi_yk| + |n| |p| |Phi_theta,k|.
void CornerGapWeights(const Eigen::MatrixXd& Phi, int row, const Eigen::Vector2d& normal,
                      const Eigen::Vector2d& point_m, double* W);

/// D_k (per mode, into `drift`) of the step [0, tau_s] from the modal coordinates Y (n x 6,
/// column-major, rows y_k = (eta, eta', alpha, beta, gamma, delta) as ModalFlow::ToModal gives
/// them): the forcing f_k(s) = alpha + beta s + gamma cos(Omega s) + delta sin(Omega s) is bounded
/// by max(|alpha|, |alpha + beta tau|) + |gamma| + |delta|, and sqrt(E_k) by |eta'| + w_k |eta|.
inline void ModalDrift(const ModalGapBound& bound, const double* Y, double tau_s, double* drift) {
  const int n = bound.n_modes;
  const double* w = bound.w_radps.data();
  for (int k = 0; k < n; ++k) {
    const double amplitude = std::abs(Y[n + k]) + w[k] * std::abs(Y[k]);
    const double a0 = std::abs(Y[2 * n + k]), a1 = std::abs(Y[2 * n + k] + Y[3 * n + k] * tau_s);
    const double force = (a0 > a1 ? a0 : a1) + std::abs(Y[4 * n + k]) + std::abs(Y[5 * n + k]);
    drift[k] = tau_s * (amplitude + 0.5 * tau_s * force);
  }
}

/// ModalDrift of a deck's three modes (bound.n_modes == 3), unrolled: the same operations.
/// kHarmonic false: Y's harmonic columns (gamma, delta) are zeros (a record's piece) and their
/// magnitudes are left out, the same bits (+0 added to a sum of magnitudes changes nothing).
template <bool kHarmonic = true>
inline void ModalDrift3(const ModalGapBound& bound, const double* Y, double tau_s,
                        double drift[3]) {
  const double* w = bound.w_radps.data();
  const double half_tau = 0.5 * tau_s;
  for (int k = 0; k < 3; ++k) {
    const double amplitude = std::abs(Y[3 + k]) + w[k] * std::abs(Y[k]);
    const double a0 = std::abs(Y[6 + k]), a1 = std::abs(Y[6 + k] + Y[9 + k] * tau_s);
    const double ramp = a0 > a1 ? a0 : a1;
    const double force = kHarmonic ? ramp + std::abs(Y[12 + k]) + std::abs(Y[15 + k]) : ramp;
    drift[k] = tau_s * (amplitude + half_tau * force);
  }
}

/// Two doubles side by side: each operation on it is the IEEE operation on each lane.
using DriftLanes = double __attribute__((vector_size(16)));

/// ModalDrift3<false> from a deck's modal coordinates in registers: modes 0 and 1 side by side
/// (eta = (Y[0], Y[1]), deta = (Y[3], Y[4]), a = (Y[6], Y[7]), slope = (Y[9], Y[10])) and mode 2
/// alone (eta2 = Y[2], deta2 = Y[5], a2 = Y[8], slope2 = Y[11]). Each lane runs the scalar
/// operations in their order (a magnitude by clearing the sign bit, as std::abs does; the larger
/// ramp end by the same comparison), so the same bits.
inline void ModalDrift3Lanes(const ModalGapBound& bound, DriftLanes eta, DriftLanes deta,
                             DriftLanes a, DriftLanes slope, double eta2, double deta2, double a2,
                             double slope2, double tau_s, double drift[3]) {
  using Bits2 = long long __attribute__((vector_size(16)));
  const double* w = bound.w_radps.data();
  const double half_tau = 0.5 * tau_s;
  const auto magnitude = [](DriftLanes x) {
    return std::bit_cast<DriftLanes>(std::bit_cast<Bits2>(x) &
                                     Bits2{0x7fffffffffffffffLL, 0x7fffffffffffffffLL});
  };
  DriftLanes wk;
  __builtin_memcpy(&wk, w, sizeof wk);
  const DriftLanes tau = {tau_s, tau_s}, half = {half_tau, half_tau};
  const DriftLanes amplitude = magnitude(deta) + wk * magnitude(eta);
  const DriftLanes a0 = magnitude(a), a1 = magnitude(a + slope * tau);
  const DriftLanes ramp = a0 > a1 ? a0 : a1;
  const DriftLanes d = tau * (amplitude + half * ramp);
  drift[0] = d[0];
  drift[1] = d[1];
  const double amplitude2 = std::abs(deta2) + w[2] * std::abs(eta2);
  const double b0 = std::abs(a2), b1 = std::abs(a2 + slope2 * tau_s);
  drift[2] = tau_s * (amplitude2 + half_tau * (b0 > b1 ? b0 : b1));
}

/// ModalDrift3<false> with modes 0 and 1 side by side in two lanes and mode 2 alone (the
/// registers' form above, read from Y), so the same bits.
inline void ModalDrift3Lanes(const ModalGapBound& bound, const double* Y, double tau_s,
                             double drift[3]) {
  DriftLanes eta, deta, a, slope;
  __builtin_memcpy(&eta, Y, sizeof eta);
  __builtin_memcpy(&deta, Y + 3, sizeof deta);
  __builtin_memcpy(&a, Y + 6, sizeof a);
  __builtin_memcpy(&slope, Y + 9, sizeof slope);
  ModalDrift3Lanes(bound, eta, deta, a, slope, Y[2], Y[5], Y[8], Y[11], tau_s, drift);
}

/// The largest closure of contact c's gap over the step (m): sum_k W_ck D_k, rounded up by a
/// relative 1e-12 so that the rounding of the sum never makes it smaller than the exact bound.
inline double GapClosureBound(const ModalGapBound& bound, int c, const double* drift) {
  const int n = bound.n_modes;
  const double* W = bound.weights.data() + static_cast<std::ptrdiff_t>(c) * n;
  double s = 0.0;
  for (int k = 0; k < n; ++k) s += W[k] * drift[k];
  return s * (1.0 + 1e-12);
}

}  // namespace skewbridge::dynamics
