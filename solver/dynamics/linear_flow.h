#pragma once
/// @file
/// The exact contact-free state transition of the linear system
///
///     M du/dt = -C u - K q - M r a_g(t),   s = (q, u)
///
/// over one smooth piece of the excitation ([docs/theory.md §3, smooth phases]). The piece's ground
/// acceleration a_g = a + p is produced by a forcing generator appended to the state: the linear
/// part (a, slope) with da/dt = slope, and the harmonic part as a rotating pair (p, k) with
/// dp/dt = omega k, dk/dt = -omega p. The augmented state z = (q, u, a, slope, p, k) of size
/// 2 n + 8 obeys dz/dt = A_hat z, so z(t + tau) = e^{A_hat tau} z(t) exactly: the matrix
/// exponential carries the forcing terms Gamma0, Gamma1 of the Nigam-Jennings scheme and their
/// harmonic counterparts in its last columns [Van Loan 1978]. The energy integrals of a step are
/// quadratic forms of z(t) whose matrices follow from a second Van Loan exponential [Van Loan 1978,
/// §4].
///
/// That is the general path, for any C. A classically damped model (every model the builders and
/// the model file make from xi) takes the modal path of solver/dynamics/modal_flow.h instead: the
/// same transition per mode in closed form, O(n) to build for a new step and O(n^2) to apply,
/// with the energy forms per mode. The general path stays the oracle of the modal one.

#include <Eigen/Core>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "solver/common/excitation.h"
#include "solver/dynamics/modal_flow.h"

namespace skewbridge::dynamics {

/// Size of the forcing generator appended to (q, u): (a, slope, p, k), two components each.
inline constexpr int kGeneratorSize = 8;

namespace detail {

// Apply's modal path from Y = ToModal(z) (n x 6, column-major) to (q, u) at the step's end, in
// one pass over plain arrays: the per-mode rows T (12 x n) and the back transform
// (q, u) = (Phi eta, Phi eta'). Every sum runs over the same terms in the same order from the same
// 0.0 as the mode loop and ModalProduct (row-wise or by columns), so the result is the same bits;
// with the mode count kN known at compile time (a deck's 3) the loops unroll and no Eigen
// expression is built per step. kN = 0: the count `n_runtime`.
//
// kHarmonic false: the harmonic columns of Y (gamma, delta) are zeros (a record's piece), and
// their terms are left out. That is the same bits: each term is then a signed zero, a sum that
// starts from +0.0 is never -0.0 (x + (-x) rounds to +0.0), and s + (+-0) = s for every s other
// than -0.0.
//
// The arrays do not overlap (__restrict: no run-time overlap tests, the same operations).
template <int kN, bool kHarmonic>
inline void ModalStep(const double* __restrict Phi, int n_runtime, const double* __restrict T,
                      const double* __restrict Y, double* __restrict eta, double* __restrict deta,
                      double* __restrict q_next, double* __restrict u_next) {
  const int n = kN > 0 ? kN : n_runtime;
  constexpr int kColumns = kHarmonic ? 6 : 4;
  for (int k = 0; k < n; ++k) {
    const double* Tk = T + 12 * k;
    double e = 0.0, de = 0.0;
    for (int j = 0; j < kColumns; ++j) {
      e += Tk[j] * Y[j * n + k];
      de += Tk[6 + j] * Y[j * n + k];
    }
    eta[k] = e;
    deta[k] = de;
  }
  for (int i = 0; i < n; ++i) {
    double s = 0.0;
    for (int j = 0; j < n; ++j) s += Phi[i + j * n] * eta[j];
    q_next[i] = s;
  }
  for (int i = 0; i < n; ++i) {
    double s = 0.0;
    for (int j = 0; j < n; ++j) s += Phi[i + j * n] * deta[j];
    u_next[i] = s;
  }
}

// Two doubles side by side: each operation on it is the IEEE operation on each lane.
using Lanes2 = double __attribute__((vector_size(16)));

// A deck's modal transforms (three modes) with each entry in both lanes (LinearFlow's deck
// step): Phi^T M and Phi (entry i + 3 j, column-major) and -L (entry k + 3 c, column c).
struct DeckLanes {
  Lanes2 PhiTM[9], Phi[9], negL[6];
};

// DeckRecordLanes' modal transform (below) alone: qu and ab from zq, gx and gy.
inline void DeckModalLanes(const DeckLanes& d, const Lanes2 zq[3], Lanes2 gx, Lanes2 gy,
                           Lanes2 qu[3], Lanes2 ab[3]) {
  for (int i = 0; i < 3; ++i) {
    Lanes2 s = {0.0, 0.0};
    for (int j = 0; j < 3; ++j) s += d.PhiTM[i + 3 * j] * zq[j];
    qu[i] = s;
    ab[i] = d.negL[i] * gx + d.negL[3 + i] * gy;
  }
}

// ApplyMotion of a deck's three modes on a piece without harmonic part with two lanes per
// operation, in registers: ToModalFixed<3, false> of the state zq (the pairs (q_i, u_i)) and the
// generator's (a, slope) gx of x and gy of y into qu[k] = (eta_k, eta_k') and ab[k] = (a_k,
// slope_k) (Y's columns 0 to 3 of mode k); ModalStep<3, false> with (eta_k, eta_k') side by side
// (the rows of T_k in `pairs`, per mode and column j < 4 the pair (T_k[j], T_k[6 + j])) into
// the step's end (q_i, u_i) in next[i]. Every lane runs the scalar path's operations in its order
// from the same +0.0, so the same bits.
inline void DeckRecordLanes(const DeckLanes& d, const double* __restrict pairs, const Lanes2 zq[3],
                            Lanes2 gx, Lanes2 gy, Lanes2 qu[3], Lanes2 ab[3], Lanes2 next[3]) {
  Lanes2 ed[3];
  // Eigen's storage is aligned to 16 bytes: a pair loads as one operand.
  const auto* T = static_cast<const double*>(__builtin_assume_aligned(pairs, 16));
  DeckModalLanes(d, zq, gx, gy, qu, ab);
  for (int k = 0; k < 3; ++k) {
    const Lanes2 y[4] = {
        {qu[k][0], qu[k][0]}, {qu[k][1], qu[k][1]}, {ab[k][0], ab[k][0]}, {ab[k][1], ab[k][1]}};
    Lanes2 e = {0.0, 0.0};
    for (int j = 0; j < 4; ++j) {
      Lanes2 t;
      __builtin_memcpy(&t, T + 8 * k + 2 * j, sizeof t);
      e += t * y[j];
    }
    ed[k] = e;
  }
  for (int i = 0; i < 3; ++i) {
    Lanes2 s = {0.0, 0.0};
    for (int j = 0; j < 3; ++j) s += d.Phi[i + 3 * j] * ed[j];
    next[i] = s;
  }
}

// DeckRecordLanes for a caller that reads qu only through magnitudes and the mode sums: qu
// and each mode's sums (eta_k, eta_k') at the step's end start from their first product instead
// of +0. A sum begun at +0 and one begun at its first product differ only when their value is
// zero (+0 against -0): a term is zero of either sign in both or in neither, so every partial sum
// has the same value in both. The step's end sums each mode's products from +0, where no partial
// sum is -0, so a zero term adds the same bits whatever its sign: `next` and ab are
// DeckRecordLanes' bits, qu its values (a zero's sign aside).
// The y generator gy's share of each mode's input (a, slope), the products DeckRecordLanes adds
// to the x generator's: ab_y[i] = negL[3 + i] * gy.
inline void DeckYForcing(const DeckLanes& d, Lanes2 gy, Lanes2 ab_y[3]) {
  for (int i = 0; i < 3; ++i) ab_y[i] = d.negL[3 + i] * gy;
}

// DeckStepLanes takes the y generator as its products ab_y (DeckYForcing): a caller whose y
// generator does not change over its steps takes them once.
[[gnu::always_inline]] inline void DeckStepLanes(const DeckLanes& d, const double* __restrict pairs,
                                                 const Lanes2 zq[3], Lanes2 gx,
                                                 const Lanes2 ab_y[3], Lanes2 qu[3], Lanes2 ab[3],
                                                 Lanes2 next[3]) {
  Lanes2 ed[3];
  const auto* T = static_cast<const double*>(__builtin_assume_aligned(pairs, 16));
  for (int i = 0; i < 3; ++i) {
    qu[i] = d.PhiTM[i] * zq[0] + d.PhiTM[i + 3] * zq[1] + d.PhiTM[i + 6] * zq[2];
    ab[i] = d.negL[i] * gx + ab_y[i];
  }
  for (int k = 0; k < 3; ++k) {
    const Lanes2 y[4] = {
        {qu[k][0], qu[k][0]}, {qu[k][1], qu[k][1]}, {ab[k][0], ab[k][0]}, {ab[k][1], ab[k][1]}};
    Lanes2 t[4];
    __builtin_memcpy(t, T + 8 * k, sizeof t);
    ed[k] = t[0] * y[0] + t[1] * y[1] + t[2] * y[2] + t[3] * y[3];
  }
  for (int i = 0; i < 3; ++i) {
    Lanes2 s = {0.0, 0.0};
    for (int j = 0; j < 3; ++j) s += d.Phi[i + 3 * j] * ed[j];
    next[i] = s;
  }
}

// DeckRecordLanes' results stored: the modal coordinates Y (n x 6, the harmonic columns +0)
// from qu and ab, and the step's end (q, u) into z_next's head from next.
[[gnu::always_inline]] inline void DeckRecordStore(const Lanes2 qu[3], const Lanes2 ab[3],
                                                   const Lanes2 next[3], double* __restrict Y,
                                                   double* __restrict z_next) {
  for (int i = 0; i < 3; ++i) {
    z_next[i] = next[i][0];
    z_next[3 + i] = next[i][1];
  }
  for (int i = 0; i < 3; ++i) {
    Y[i] = qu[i][0];
    Y[3 + i] = qu[i][1];
    Y[6 + i] = ab[i][0];
    Y[9 + i] = ab[i][1];
  }
  for (int k = 12; k < 18; ++k) Y[k] = 0.0;
}

// DeckRecordLanes from the augmented state z (q, u, then the generator's a and slope) into
// z_next's (q, u) and the modal coordinates Y (n x 6, the harmonic columns +0).
inline void DeckRecordStep(const DeckLanes& d, const double* __restrict pairs,
                           const double* __restrict z, double* __restrict Y,
                           double* __restrict z_next) {
  Lanes2 qu[3], ab[3], next[3];
  const Lanes2 zq[3] = {{z[0], z[3]}, {z[1], z[4]}, {z[2], z[5]}};
  const Lanes2 gx = {z[6], z[8]}, gy = {z[7], z[9]};  // (a, slope) of x, of y
  DeckRecordLanes(d, pairs, zq, gx, gy, qu, ab, next);
  DeckRecordStore(qu, ab, next, Y, z_next);
}

// ApplyMotion of a deck's three modes on a piece with a harmonic part, with two lanes per
// operation: ToModalFixed<3, true> of z (the pairs (q_i, u_i), the generator's (a, slope) and
// (p, k) of x and of y) into Y (3 x 6, column-major), and ModalStep<3, true> with (eta_k,
// eta_k') side by side (per mode k and column j < 6 the pair (T_k[j], T_k[6 + j]) at
// pairs[12 k + 2 j]) into z_next's (q, u). Every lane runs the scalar path's operations in its
// order from the same +0.0, so the same bits.
inline void DeckHarmonicStep(const DeckLanes& d, const double* __restrict pairs,
                             const double* __restrict z, double* __restrict Y,
                             double* __restrict z_next) {
  const Lanes2 zq[3] = {{z[0], z[3]}, {z[1], z[4]}, {z[2], z[5]}};
  const Lanes2 gx = {z[6], z[8]}, gy = {z[7], z[9]};      // (a, slope) of x, of y
  const Lanes2 hx = {z[10], z[12]}, hy = {z[11], z[13]};  // (p, k) of x, of y
  Lanes2 qu[3], ab[3], pk[3], ed[3];
  for (int i = 0; i < 3; ++i) {
    Lanes2 s = {0.0, 0.0};
    for (int j = 0; j < 3; ++j) s += d.PhiTM[i + 3 * j] * zq[j];
    qu[i] = s;
    ab[i] = d.negL[i] * gx + d.negL[3 + i] * gy;
    pk[i] = d.negL[i] * hx + d.negL[3 + i] * hy;
  }
  const auto* T = static_cast<const double*>(__builtin_assume_aligned(pairs, 16));
  for (int k = 0; k < 3; ++k) {
    const Lanes2 y[6] = {{qu[k][0], qu[k][0]}, {qu[k][1], qu[k][1]}, {ab[k][0], ab[k][0]},
                         {ab[k][1], ab[k][1]}, {pk[k][0], pk[k][0]}, {pk[k][1], pk[k][1]}};
    Lanes2 e = {0.0, 0.0};
    for (int j = 0; j < 6; ++j) {
      Lanes2 t;
      __builtin_memcpy(&t, T + 12 * k + 2 * j, sizeof t);
      e += t * y[j];
    }
    ed[k] = e;
  }
  for (int i = 0; i < 3; ++i) {
    Lanes2 s = {0.0, 0.0};
    for (int j = 0; j < 3; ++j) s += d.Phi[i + 3 * j] * ed[j];
    z_next[i] = s[0];
    z_next[3 + i] = s[1];
  }
  for (int i = 0; i < 3; ++i) {
    Y[i] = qu[i][0];
    Y[3 + i] = qu[i][1];
    Y[6 + i] = ab[i][0];
    Y[9 + i] = ab[i][1];
    Y[12 + i] = pk[i][0];
    Y[15 + i] = pk[i][1];
  }
}

}  // namespace detail

/// c = std::cos(x_rad) and s = std::sin(x_rad), the same bits: at x = +0 or -0 the library's
/// values are exactly 1 and x itself (IEEE 754 and C Annex F), taken here without its call (a
/// step on a piece without harmonic part has omega tau = 0); elsewhere the library's.
inline void LibraryCosSin(double x_rad, double& c, double& s) {
  if (x_rad == 0.0) {
    c = 1.0;
    s = x_rad;
    return;
  }
  c = std::cos(x_rad);
  s = std::sin(x_rad);
}

/// cos and sin (the library's bits) of angles already taken, keyed by the angle's bits: a pulse's
/// steps take the harmonic generator at the angles omega t of one grid, which the cells of a
/// sweep share while their models leave the step alone. Direct-mapped, 2^kBits slots (96 KiB):
/// enough for the grids of a row of cells, which the next row takes again (the default spec's
/// 81 frequency ratios, about 3 000 angles); a slot starts as the angle +0 (cos 1, sin +0: the
/// library's values there).
class AngleMemo {
 public:
  /// c = cos(x_rad), s = sin(x_rad), from the memo or computed and kept.
  void CosSin(double x_rad, double& c, double& s) {
    const auto key = std::bit_cast<std::uint64_t>(x_rad);
    Slot& slot = slots_[(key * 0x9E3779B97F4A7C15ULL) >> (64 - kBits)];
    if (slot.key != key) {
      slot.key = key;
      slot.c = std::cos(x_rad);
      slot.s = std::sin(x_rad);
    }
    c = slot.c;
    s = slot.s;
  }

 private:
  static constexpr int kBits = 12;
  struct Slot {
    std::uint64_t key = 0;  // the bits of +0.0
    double c = 1.0, s = 0.0;
  };
  std::array<Slot, std::size_t{1} << kBits> slots_{};
};

/// Which transition a LinearFlow uses.
enum class FlowPath {
  kAuto,       ///< modal when C is classical, else augmented
  kAugmented,  ///< always the augmented matrix exponential (the general path and test oracle)
};

/// The exact transition over one step of length tau_s with harmonic rate omega_radps. Apply it
/// with LinearFlow::Apply and LinearFlow::StepEnergy, which know the path.
struct FreePropagator {
  double tau_s = 0.0;        ///< step length (s)
  double omega_radps = 0.0;  ///< harmonic rate of the excitation piece (rad/s)
  bool has_energy = false;   ///< the energy forms below were computed
  // Augmented path.
  Eigen::MatrixXd phi;           ///< e^{A_hat tau}, (2n+8) x (2n+8)
  Eigen::MatrixXd input_gram;    ///< z0^T G z0 = -int_0^tau u^T M r a_g dt (J), symmetric
  Eigen::MatrixXd damping_gram;  ///< z0^T G z0 = int_0^tau u^T C u dt (J), symmetric
  // Modal path (ModalFlow::Transitions).
  Eigen::MatrixXd modal_rows;     ///< 12 x n: per mode the 2 x 6 transition T_k(tau)
  Eigen::MatrixXd modal_input;    ///< 36 x n: per mode the input-energy form Q_k (J)
  Eigen::MatrixXd modal_damping;  ///< 36 x n: per mode the damping-energy form Q_k (J)
  /// Modal path of three modes: per mode k and column j < 4 the pair (T_k[0][j], T_k[1][j])
  /// (the eta and eta' rows side by side, 24 entries, 16-byte aligned), for
  /// LinearFlow::ApplyRecordMotion.
  Eigen::VectorXd record_pairs;
  /// Modal path of three modes: per mode k and column j < 6 the pair (T_k[0][j], T_k[1][j])
  /// (36 entries, 16-byte aligned), for the harmonic step detail::DeckHarmonicStep.
  Eigen::VectorXd deck_pairs;
  double cos_wt = 1.0;  ///< cos(omega tau), the generator's rotation
  double sin_wt = 0.0;  ///< sin(omega tau)
};

/// The contact-free linear flow of a model: matrices, generator bookkeeping and a cache of
/// propagators keyed by the exact (tau, omega), least recently used out. A record with a fixed
/// sample interval needs one propagator; a pulse two. The cache is a pure function of (model, tau,
/// omega): reusing it across runs never changes a result. One flow serves one thread (the cache and
/// the augmented matrices, built on first use, change inside const calls too).
class LinearFlow {
 public:
  /// @param M, K, C n x n mass (kg, kg m^2), stiffness and damping matrices;
  /// @param r n x 2 ground-influence matrix mapping (a_gx, a_gy) to the DOFs.
  /// @param path kAuto: the modal path when Phi^T C Phi is diagonal (ModalFlow::Classical).
  /// @param modes model::ComputeModes(M, K) if already solved (Model::modes()), else null.
  /// @pre M symmetric positive definite; sizes consistent (checked by SB_DEMAND).
  LinearFlow(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::MatrixXd>& K,
             const Eigen::Ref<const Eigen::MatrixXd>& C, const Eigen::Ref<const Eigen::MatrixXd>& r,
             FlowPath path = FlowPath::kAuto, const model::Modes* modes = nullptr);

  /// Makes this flow what LinearFlow(M, K, C, r, path, modes) would be, with the path it was
  /// built with: at the same size its matrices and its propagators' storage are kept (no heap
  /// block per new model of a sweep), and the cache starts empty. The same bits as a new flow.
  void Refit(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::MatrixXd>& K,
             const Eigen::Ref<const Eigen::MatrixXd>& C, const Eigen::Ref<const Eigen::MatrixXd>& r,
             const model::Modes* modes = nullptr);

  /// True when the flow propagates in modal coordinates.
  bool modal() const { return modal_.has_value(); }
  /// The modal flow. @pre modal().
  const ModalFlow& modal_flow() const { return *modal_; }

  int n_dof() const { return n_; }
  /// 2 n + 8.
  int augmented_size() const { return 2 * n_ + kGeneratorSize; }

  /// A_hat for the harmonic rate omega (rad/s): dz/dt = A_hat z.
  Eigen::MatrixXd AugmentedMatrix(double omega_radps) const;

  /// Writes the generator part of z (entries 2n .. 2n+7) for time t_s inside piece.
  void SetGenerator(const ExcitationPiece& piece, double t_s, Eigen::Ref<Eigen::VectorXd> z) const;

  /// The propagator of a step tau_s (> 0) at rate omega_radps, from the cache or computed once;
  /// with `energy`, also its energy forms (only then: they cost more than the transition). The
  /// transition is the same bits with and without them. The reference stays valid until the next
  /// call.
  const FreePropagator& Propagator(double tau_s, double omega_radps, bool energy = true);

  /// z_next = e^{A_hat tau} z over the propagator's step (no allocation); with input_J and
  /// damping_J, also the step's energy as StepEnergy gives it, from the same modal transform.
  /// @pre z and z_next of the augmented size and distinct; p.has_energy if energy is asked.
  void Apply(const FreePropagator& p, const Eigen::Ref<const Eigen::VectorXd>& z,
             Eigen::Ref<Eigen::VectorXd> z_next, double* input_J = nullptr,
             double* damping_J = nullptr);

  /// Apply's (q, u) at the step's end (the heads of z_next, the same bits) and energy, for a
  /// caller that sets the generator itself at the next step: on the modal path the generator
  /// part of z_next is left as it was. @pre as Apply's.
  void ApplyMotion(const FreePropagator& p, const Eigen::Ref<const Eigen::VectorXd>& z,
                   Eigen::Ref<Eigen::VectorXd> z_next, double* input_J = nullptr,
                   double* damping_J = nullptr);

  /// ApplyMotion without energy of a step on a piece without harmonic part (a record's: z's
  /// (p, k) zeros), inline over plain arrays for a deck's three modes: the same operations, so
  /// the same bits, as ApplyMotion's. @pre modal(); z and z_next of the augmented size, distinct;
  /// z's harmonic generator entries zeros.
  void ApplyRecordMotion(const FreePropagator& p, Eigen::VectorXd& z, Eigen::VectorXd& z_next) {
    if (n_ != 3) {
      ApplyMotion(p, z, z_next);
      return;
    }
    detail::DeckRecordStep(deck_, p.record_pairs.data(), z.data(), Y_.data(), z_next.data());
  }

  /// ApplyMotion without energy: for a deck's three modes inline over plain arrays (the
  /// harmonic step in two lanes, detail::DeckHarmonicStep, or a record's, ApplyRecordMotion's),
  /// the same operations, so the same bits; any other flow through ApplyMotion.
  /// @pre as ApplyMotion's.
  void ApplyStepMotion(const FreePropagator& p, const Eigen::VectorXd& z, Eigen::VectorXd& z_next) {
    if (n_ != 3 || !modal_) {
      ApplyMotion(p, z, z_next);
      return;
    }
    const double* h = z.data() + 10;  // the harmonic generator (p, k)
    if (h[0] != 0.0 || h[1] != 0.0 || h[2] != 0.0 || h[3] != 0.0) {
      detail::DeckHarmonicStep(deck_, p.deck_pairs.data(), z.data(), Y_.data(), z_next.data());
    } else {
      detail::DeckRecordStep(deck_, p.record_pairs.data(), z.data(), Y_.data(), z_next.data());
    }
  }

  /// A deck's transforms in both lanes (detail::DeckRecordLanes), for a caller that steps a
  /// deck's record in registers. @pre modal() and three degrees of freedom.
  const detail::DeckLanes& deck_lanes() const { return deck_; }

  /// What ApplyRecordMotion leaves of a deck's step that a caller took in registers with
  /// detail::DeckRecordLanes from zq, gx and gy to `next`: the modal coordinates (the modal
  /// transform taken again, not the step) and z_next's (q, u), the same bits. @pre modal() and
  /// three degrees of freedom; z_next of the augmented size.
  void StoreDeckRecord(const detail::Lanes2 zq[3], detail::Lanes2 gx, detail::Lanes2 gy,
                       const detail::Lanes2 next[3], Eigen::VectorXd& z_next) {
    detail::Lanes2 qu[3], ab[3];
    detail::DeckModalLanes(deck_, zq, gx, gy, qu, ab);
    detail::DeckRecordStore(qu, ab, next, Y_.data(), z_next.data());
  }

  /// The modal coordinates (n x 6, rows y_k as ModalFlow::ToModal) of the state the last Apply
  /// started from. @pre modal(), and Apply was called.
  const Eigen::MatrixXd& modal_coordinates() const { return Y_; }

  /// The step's work of the ground -int u^T M r a_g dt and of damping int u^T C u dt (J) from the
  /// step's initial state z. @pre p.has_energy.
  void StepEnergy(const FreePropagator& p, const Eigen::Ref<const Eigen::VectorXd>& z,
                  double& input_J, double& damping_J);

  /// dz/dt = A_hat z (no allocation).
  void Derivative(double omega_radps, const Eigen::Ref<const Eigen::VectorXd>& z,
                  Eigen::Ref<Eigen::VectorXd> dz) const;

  /// Kinetic 1/2 u^T M u plus strain 1/2 q^T K q (J) of the (q, u) part of z.
  double MechanicalEnergy(const Eigen::Ref<const Eigen::VectorXd>& z) const;

  /// Power of the ground -u^T M r a_g (W) and of damping u^T C u (W) at the augmented state z.
  void Powers(const Eigen::Ref<const Eigen::VectorXd>& z, double& input_W, double& damping_W) const;

  const Eigen::MatrixXd& M() const { return M_; }
  const Eigen::MatrixXd& K() const { return K_; }
  const Eigen::MatrixXd& C() const { return C_; }
  const Eigen::MatrixXd& r() const { return r_; }

 private:
  void Compute(double tau_s, double omega_radps, bool energy, FreePropagator& out) const;
  // The constructor's work past the matrices' copies: the checks, M r, the modal flow (into
  // modal_'s storage when it has one), the lanes and the zeroed state.
  void Setup(const model::Modes* modes);
  void ModalEnergy(const FreePropagator& p, double& input_J, double& damping_J) const;

  int n_;
  FlowPath path_ = FlowPath::kAuto;
  std::optional<ModalFlow> modal_;
  Eigen::MatrixXd Y_;           // n x 6 modal coordinates of the state being propagated
  Eigen::VectorXd eta_, deta_;  // modal state at the step end
  detail::DeckLanes deck_{};    // a deck's transforms in both lanes (three modes)
  Eigen::MatrixXd M_, K_, C_, r_;
  Eigen::MatrixXd Mr_;  // M r, n x 2
  // The augmented path's matrices, built on first use: a modal flow (every sweep cell's) needs
  // them only for a dense output longer than the modal series' radius, which the integrator's
  // steps never are, so a new model does not pay for them.
  void EnsureAugmented() const;
  mutable bool augmented_ready_ = false;
  mutable Eigen::MatrixXd A_base_;     // A_hat without the omega entries
  mutable Eigen::MatrixXd A_u_;        // its n rows of du/dt
  mutable Eigen::MatrixXd Q_input_;    // quadratic form of the ground's power on z
  mutable Eigen::MatrixXd Q_damping_;  // quadratic form of the damping power on z
  // The cache: its first cache_size_ entries are live; those past them are storage kept from
  // before a Refit, filled again before any other grows the vector.
  std::vector<FreePropagator> cache_;
  std::size_t cache_size_ = 0;
  // The modes' transitions of this flow and of those it was refitted from (Compute's): a
  // sweep's models share modes' frequencies and damping from cell to cell.
  mutable TransitionMemo memo_;
  // The harmonic generator's cos and sin (SetGenerator's), kept across refits likewise.
  mutable AngleMemo angles_;
  std::vector<unsigned long> last_use_;  // per cache entry, the clock of its last use (LRU)
  unsigned long clock_ = 0;
};

// In the header: a free step per record sample sets the generator, a few operations.
inline void LinearFlow::SetGenerator(const ExcitationPiece& piece, double t_s,
                                     Eigen::Ref<Eigen::VectorXd> z) const {
  const double tau = t_s - piece.t_begin;
  const int ia = 2 * n_;
  z.segment<2>(ia) = piece.a_begin + piece.slope * tau;
  z.segment<2>(ia + 2) = piece.slope;
  if (piece.omega != 0.0) {
    // Matches ExcitationPiece::At, which ignores the harmonic part when omega = 0.
    double c, s;
    angles_.CosSin(piece.omega * tau, c, s);
    z.segment<2>(ia + 4) = piece.cos_amplitude * c + piece.sin_amplitude * s;
    z.segment<2>(ia + 6) = -piece.cos_amplitude * s + piece.sin_amplitude * c;
  } else {
    z.segment<4>(ia + 4).setZero();
  }
}

/// The exact solution inside one step, used to locate events and to sample output inside a step.
/// On the modal path: per mode the Taylor series of the closed-form transition (modal_flow.h),
/// eta_k(tau) = sum_m e_km tau^m with as many terms as rho_k = tau_max (w_k + c_k + |Omega|)
/// needs, then q = Phi eta, u = Phi eta'; building costs O(n^2) (the modal transform of z0), a
/// component O(n) per mode series. On the augmented path: z(tau) = sum_k c_k tau^k,
/// c_k = A_hat^k z0 / k!, truncated where the terms fall below round-off for |tau| <= tau_max.
/// e^{A_hat tau} itself is never formed for these. The generator's entries are exact (cos/sin).
class FreeDenseOutput {
 public:
  /// Storage for a flow of augmented size n_aug, at most max_terms Taylor terms.
  explicit FreeDenseOutput(int n_aug = 0, int max_terms = 48);

  /// Builds the series from z0 for |tau| <= tau_max_s.
  /// @pre omega_radps * tau_max and the flow's rates times tau_max are O(1) (steps bounded by a
  /// fraction of the shortest period). A modal flow with some rho_k > kModalSeriesRadius takes
  /// the augmented series.
  void Build(const LinearFlow& flow, double omega_radps,
             const Eigen::Ref<const Eigen::VectorXd>& z0, double tau_max_s);

  /// z(tau) (s since the step start).
  void Evaluate(double tau_s, Eigen::Ref<Eigen::VectorXd> z);

  /// The first `count` components of z(tau) (the rest of z untouched). A deck's three modes
  /// share the modes' series summed at tau with EvaluateComponent: positions sum eta's series
  /// alone, and a read at an instant whose halves are summed already sums nothing.
  /// @pre count <= the augmented size, z.size() >= count.
  void EvaluateHead(double tau_s, int count, Eigen::Ref<Eigen::VectorXd> z);

  /// Component i of z(tau). @pre 0 <= i < the augmented size.
  /// Inline when the modes' series of its half (eta's or eta''s) at tau are already summed
  /// (the other components of an instant), out of line otherwise.
  double EvaluateComponent(double tau_s, int i) const {
    if (i < 2 * n_) {
      const int half = i < n_ ? 0 : 1;  // eta's series or eta''s
      // NaN on the augmented path: never equal.
      if (series_tau_s_[half] == tau_s) return ModalComponent(i - half * n_, half);
    }
    return EvaluateComponentAt(tau_s, i);
  }

  /// Components i[0..3] of z(tau) into out, each < 2 n (a corner's rate: positions and
  /// velocities at one instant): EvaluateComponent of each, the same bits, with the modes'
  /// series of both halves summed at most once, together.
  void EvaluateComponents(double tau_s, const int (&i)[4], double (&out)[4]) const {
    if (modal_ && n_ == 3) {
      if (!(series_tau_s_[0] == tau_s && series_tau_s_[1] == tau_s)) DeckSeriesAt(tau_s, true);
      for (int j = 0; j < 4; ++j) {
        const int half = i[j] < 3 ? 0 : 1;
        out[j] = ModalComponent(i[j] - 3 * half, half);
      }
      return;
    }
    for (int j = 0; j < 4; ++j) out[j] = EvaluateComponent(tau_s, i[j]);
  }

  /// dz/dtau at tau.
  void EvaluateDerivative(double tau_s, Eigen::Ref<Eigen::VectorXd> dz);

  /// Number of Taylor terms (on the modal path, of the mode that needs most).
  int terms() const { return terms_; }

 private:
  void ModalAt(double tau_s, bool velocities);
  // EvaluateComponent past its inline test: the modes' series at tau (both halves) or the
  // generator's entries or the augmented series.
  double EvaluateComponentAt(double tau_s, int i) const;
  // Row `row` of Phi against the modes' series of eta (half 0) or eta' (half 1) in series_,
  // summed in mode order from 0.0.
  double ModalComponent(int row, int half) const {
    const double* h = series_.data() + half * n_;
    const double* p = phi_ + row;
    double x = 0.0;
    if (n_ == 3) {
      x += p[0] * h[0];
      x += p[3] * h[1];
      x += p[6] * h[2];
      return x;
    }
    for (int k = 0; k < n_; ++k) x += p[k * n_] * h[k];
    return x;
  }
  void GeneratorAt(double tau_s, Eigen::Ref<Eigen::VectorXd> z) const;
  // Three modes (a deck): the modes' series at tau into series_ for the halves that are not
  // summed there already: eta's alone, or with `velocities` eta''s too (both at once in pairs
  // of lanes when both are missing). Each series is Horner's operations in Horner's order, so
  // the same bits however the halves are taken. @pre a half it is asked for is missing.
  void DeckSeriesAt(double tau_s, bool velocities) const;
  // Three modes: the first `count` (<= 6) components of z(tau) into out, from the series
  // summed at tau (DeckSeriesAt for the missing halves), each row of Phi as ModalComponent,
  // ModalProduct's sums (the same bits).
  void DeckHead(double tau_s, int count, double* out) const {
    const bool velocities = count > 3;
    if (!(series_tau_s_[0] == tau_s && (!velocities || series_tau_s_[1] == tau_s))) {
      DeckSeriesAt(tau_s, velocities);
    }
    const double* h = series_.data();
    const double* p = phi_;
    const auto row = [p](int i, const double* e) {
      double x = 0.0;
      x += p[i] * e[0];
      x += p[i + 3] * e[1];
      x += p[i + 6] * e[2];
      return x;
    };
    if (count == 3 || count == 6) {
      out[0] = row(0, h);
      out[1] = row(1, h);
      out[2] = row(2, h);
      if (count == 6) {
        out[3] = row(0, h + 3);
        out[4] = row(1, h + 3);
        out[5] = row(2, h + 3);
      }
      return;
    }
    for (int i = 0; i < count; ++i) out[i] = i < 3 ? row(i, h) : row(i - 3, h + 3);
  }

  const LinearFlow* flow_ = nullptr;
  bool modal_ = false;
  int n_ = 0;
  int n_aug_ = 0;      // 2 n + 8
  int max_terms_ = 0;  // Taylor terms of the augmented series at most
  double omega_radps_ = 0.0;
  Eigen::MatrixXd coefficients_;        // augmented, sized on first use: column k = c_k
  Eigen::MatrixXd modal_coefficients_;  // modal: column k (n + k) = eta_k (eta_k') coefficients
  Eigen::VectorXd largest_;             // per component, the largest term so far
  Eigen::VectorXd generator_;           // modal: the generator (a, slope, p, k) at tau = 0
  Eigen::MatrixXd Y_;                   // modal: n x 6 modal coordinates of z0
  Eigen::VectorXd eta_, deta_;          // modal: eta(tau), eta'(tau) of the last ModalAt
  Eigen::VectorXd z_scratch_;           // for EvaluateDerivative
  const double* phi_ = nullptr;         // modal: Phi's entries (n x n, column-major), from the flow
  // modal: the modes' series of eta (first n) and eta' (last n) at the instants series_tau_s_
  // (NaN: none since the last Build), for EvaluateComponent.
  mutable Eigen::VectorXd series_;
  mutable double series_tau_s_[2] = {std::numeric_limits<double>::quiet_NaN(),
                                     std::numeric_limits<double>::quiet_NaN()};
  std::vector<int> mode_terms_;   // modal: terms per mode
  std::vector<double> mode_rho_;  // modal: the rho per mode mode_terms_ counts for (NaN: none)
  int terms_ = 0;
};

}  // namespace skewbridge::dynamics
