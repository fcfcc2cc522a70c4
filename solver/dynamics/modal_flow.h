#pragma once
/// @file
/// The exact contact-free transition of a classically damped linear system in modal coordinates.
///
/// With Phi the M-orthonormal modes (Phi^T M Phi = I, Phi^T K Phi = diag(w_k^2)) and classical
/// damping (Phi^T C Phi = diag(c_k), c_k = 2 xi_k w_k for the builders' C), q = Phi eta splits
///
///     M du/dt = -C u - K q - M r a_g(t)
///
/// into n uncoupled oscillators
///
///     eta_k'' + c_k eta_k' + w_k^2 eta_k = f_k(s),   f_k = -L_k . a_g,   L = Phi^T M r,
///
/// and over a smooth piece of the excitation (solver/common/excitation.h) the forcing of a step
/// that starts at s = 0 is f_k(s) = alpha + beta s + gamma cos(Omega s) + delta sin(Omega s). The
/// state of mode k and its forcing form the 6-vector y_k = (eta, eta', alpha, beta, gamma, delta);
/// its exact transition over tau is a 2 x 6 matrix T_k(tau) whose columns are the free response
/// and the Nigam-Jennings responses to the constant, the ramp, the cosine and the sine [Nigam and
/// Jennings 1969]. T_k is evaluated as the everywhere-convergent power series of these closed
/// forms (the phi-functions of the 2 x 2 mode matrix), which is their stable evaluation for
/// rho_k = tau (w_k + c_k + |Omega|) <= kModalSeriesRadius: the closed forms themselves lose
/// digits by cancellation for small w tau (1 - e^{-xi w tau} cos ...), at a zero-frequency mode
/// and at resonance (Omega equal to a natural or damped frequency), where the series has none of
/// these singular cases. A longer step is halved until it fits and the 6 x 6 transition (with
/// the forcing generator) squared back. Building T for a new step costs O(n), applying it
/// O(n^2) (the two modal transforms), and no matrix exponential is formed.
///
/// The energy integrals of a step are quadratic forms of y_k per mode:
///     int u^T C u ds = sum_k c_k int eta_k'^2 ds,  -int u^T M r a_g ds = sum_k int eta_k' f_k ds.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// Largest rho_k = tau (w_k + c_k + |Omega|) evaluated by the series directly.
inline constexpr double kModalSeriesRadius = 4.0;
/// Most Taylor terms a mode uses (rho = kModalSeriesRadius needs 34).
inline constexpr int kModalMaxTerms = 48;

/// Number of Taylor terms (coefficients 0 .. N - 1) that bring rho^N / N! below 1e-18: the
/// product of the rounded rho / j up to the first j >= 4 at most 1e-18 (or j = kModalMaxTerms -
/// 1), the count j + 1; for rho >= 0 from a table of the rho where the count grows, built at
/// compile time from that product (the same count for every rho).
int ModalTermCount(double rho);

/// y1 = A.topRows(rows) x1 and y2 = A.topRows(rows) x2 in one pass over the column-major A, as
/// plain loops: for the few DOFs of a deck, Eigen's general matrix-vector kernel costs more in
/// its set-up than in its arithmetic. y2 (and x2) may be null.
void ModalProduct(const Eigen::MatrixXd& A, int rows, const double* x1, const double* x2,
                  double* y1, double* y2);

namespace detail {

// ToModal for kN modes known at compile time, Y column-major with stride kN: y_k's (eta, eta')
// as ModalProduct's row-wise sums, and the generator columns -L (gx, gy): all four, or with
// kHarmonic false the linear pair alone and +0 in the harmonic pair. Y overlaps none of the
// inputs (__restrict: no run-time overlap tests, the same operations).
template <int kN, bool kHarmonic = true>
inline void ToModalFixed(const double* __restrict PhiTM, const double* __restrict negL,
                         const double* __restrict z, double* __restrict Y) {
  for (int i = 0; i < kN; ++i) {
    double s = 0.0;
    for (int j = 0; j < kN; ++j) s += PhiTM[i + j * kN] * z[j];
    Y[i] = s;
  }
  for (int i = 0; i < kN; ++i) {
    double s = 0.0;
    for (int j = 0; j < kN; ++j) s += PhiTM[i + j * kN] * z[kN + j];
    Y[kN + i] = s;
  }
  constexpr int kColumns = kHarmonic ? 4 : 2;
  for (int j = 0; j < kColumns; ++j) {
    const double gx = z[2 * kN + 2 * j], gy = z[2 * kN + 2 * j + 1];
    double* y = Y + (2 + j) * kN;
    for (int k = 0; k < kN; ++k) y[k] = negL[k] * gx + negL[kN + k] * gy;
  }
  for (int k = (2 + kColumns) * kN; k < 6 * kN; ++k) Y[k] = 0.0;
}

}  // namespace detail

/// Per-mode transitions already computed, keyed by the bits of (w_k^2, c_k, tau, omega): T_k is
/// a function of these alone (ModalFlow::Transitions), so a sweep's next model whose mode has
/// the same frequency and damping (or another mode of the same model) takes its T_k from here,
/// the same bits. Set-associative: a key's set (kSets of them) holds its kWays latest keys, a new
/// key taking the oldest one's slot, so the models of one sweep axis (a few keys each, a few
/// hundred models apart) find theirs again. Its storage (kSets kWays slots) is allocated on first
/// use and not cleared: a slot holds a row only once its bit in `used_` is set, so a new memo
/// costs an allocation and 384 bytes of zeros.
class TransitionMemo {
 public:
  TransitionMemo() = default;
  /// A copy holds the same rows.
  TransitionMemo(const TransitionMemo& other);
  TransitionMemo& operator=(const TransitionMemo& other);
  /// A move leaves `other` empty.
  TransitionMemo(TransitionMemo&& other) noexcept { *this = std::move(other); }
  TransitionMemo& operator=(TransitionMemo&& other) noexcept {
    if (this != &other) {
      slots_ = std::move(other.slots_);
      for (std::size_t w = 0; w < kSlots / 64; ++w) {
        used_[w] = other.used_[w];
        other.used_[w] = 0;
      }
      for (std::size_t w = 0; w < kSets / 32; ++w) {
        next_[w] = other.next_[w];
        other.next_[w] = 0;
      }
    }
    return *this;
  }
  ~TransitionMemo() = default;

  /// Copies the 12 entries of T_k held for `key` into `row`; false when none is held.
  bool Find(const double (&key)[4], double* row) const;
  /// Holds `row` (12 entries) for `key`.
  /// @pre Find(key) is false (a key is held in one slot at most).
  void Store(const double (&key)[4], const double* row);

 private:
  static constexpr std::size_t kSets = 512;
  static constexpr std::size_t kWays = 4;
  static constexpr std::size_t kSlots = kSets * kWays;
  static_assert(kWays == 4 && kSets % 32 == 0, "next_ holds a 2-bit way per set");
  struct Slot {
    std::uint64_t key[4];
    double row[12];
  };
  static std::size_t SetOf(const double (&key)[4]);
  bool Used(std::size_t s) const { return ((used_[s / 64] >> (s % 64)) & 1U) != 0; }
  std::unique_ptr<Slot[]> slots_;         // kSlots slots, set j in j kWays ..; unset until Store
  std::uint64_t used_[kSlots / 64] = {};  // bit s: slot s holds a row
  std::uint64_t next_[kSets / 32] = {};   // 2 bits per set: the way its next Store takes
};

/// The modes of a classically damped model and the per-mode transitions.
class ModalFlow {
 public:
  /// The modal flow of (M, K, C, r), or nothing when C is not classical: max_{i != j}
  /// |(Phi^T C Phi)_ij| > 1e-12 max_k |(Phi^T C Phi)_kk| (an undamped model is classical).
  /// @pre M symmetric positive definite, K symmetric positive semi-definite.
  static std::optional<ModalFlow> Classical(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                            const Eigen::Ref<const Eigen::MatrixXd>& K,
                                            const Eigen::Ref<const Eigen::MatrixXd>& C,
                                            const Eigen::Ref<const Eigen::MatrixXd>& r);

  /// The same from the modes of (K, M) already solved (model::ComputeModes(M, K), which a
  /// builder's model carries): a sweep cell is a new model, and the solve cost as much as a dozen
  /// free steps of a deck.
  static std::optional<ModalFlow> Classical(const model::Modes& modes,
                                            const Eigen::Ref<const Eigen::MatrixXd>& M,
                                            const Eigen::Ref<const Eigen::MatrixXd>& C,
                                            const Eigen::Ref<const Eigen::MatrixXd>& r);

  /// An empty flow (no modes), storage for Assign.
  ModalFlow() = default;

  /// Classical's flow of (modes, M, C, r) in this object's storage (no allocation at the same
  /// size): the same bits as Classical's; false (the flow then unusable) when C is not classical.
  bool Assign(const model::Modes& modes, const Eigen::Ref<const Eigen::MatrixXd>& M,
              const Eigen::Ref<const Eigen::MatrixXd>& C,
              const Eigen::Ref<const Eigen::MatrixXd>& r);

  int n_modes() const { return static_cast<int>(w2_.size()); }
  /// w_k^2 (rad^2/s^2), ascending; rounding below zero of a free body's rigid modes is set to 0.
  const Eigen::VectorXd& w2() const { return w2_; }
  /// c_k = (Phi^T C Phi)_kk (1/s).
  const Eigen::VectorXd& c() const { return c_; }
  /// Phi, n x n, column k = mode k (Phi^T M Phi = I).
  const Eigen::MatrixXd& Phi() const { return Phi_; }
  /// Phi^T M, n x n (ToModal's transform of q and u).
  const Eigen::MatrixXd& PhiTM() const { return PhiTM_; }
  /// -L = -Phi^T M r, n x 2 (ToModal's transform of a ground acceleration (x, y), m/s^2).
  const Eigen::MatrixXd& negL() const { return negL_; }

  /// Modal coordinates of the augmented state z = (q, u, a, slope, p, k) (linear_flow.h): Y is
  /// n x 6, row k = y_k = (Phi^T M q, Phi^T M u, -L a, -L slope, -L p, -L k)_k. No allocation.
  /// harmonic false: z's (p, k) are zeros (a record's piece), and Y's last two columns are set to
  /// +0 without their products (which are zeros of either sign).
  void ToModal(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::MatrixXd> Y,
               bool harmonic = true) const;
  /// ToModal of a deck's three modes (n_modes() == 3) into Y's 18 entries (column-major, 3 x 6),
  /// inline and over plain arrays: the same operations. @pre z has 2 n + 8 entries.
  void ToModal3(const double* z, double* Y, bool harmonic) const {
    if (harmonic) {
      detail::ToModalFixed<3, true>(PhiTM_.data(), negL_.data(), z, Y);
    } else {
      detail::ToModalFixed<3, false>(PhiTM_.data(), negL_.data(), z, Y);
    }
  }

  /// The transitions over tau_s (> 0) at the harmonic rate omega_radps: column k of `rows`
  /// (12 x n) holds T_k row-major (eta row, then eta' row). With `input` and `damping` (36 x n,
  /// column k a 6 x 6 column-major symmetric form Q_k), also the step's energy integrals:
  /// y_k^T Q_k y_k summed over k is -int u^T M r a_g ds (input) or int u^T C u ds (damping), J.
  /// Without the energy forms, `memo` (if given) supplies the modes' T_k it holds and keeps
  /// those computed.
  void Transitions(double tau_s, double omega_radps, Eigen::Ref<Eigen::MatrixXd> rows,
                   Eigen::MatrixXd* input, Eigen::MatrixXd* damping,
                   TransitionMemo* memo = nullptr) const;

  /// Taylor coefficients of eta_k and eta_k' (s since the step start) from y_k, `terms` of each
  /// into eta[0 .. terms) and deta[0 .. terms). @pre terms <= kModalMaxTerms.
  void ModeCoefficients(int k, double omega_radps, const double* y, int terms, double* eta,
                        double* deta) const;

  /// ModeCoefficients of every mode (the same bits), two modes per loop so that their
  /// independent recursions overlap: mode k from row k of Y (n x 6), terms[k] coefficients into
  /// eta + k stride and deta + k stride. @pre every terms[k] <= kModalMaxTerms.
  void AllModeCoefficients(double omega_radps, const Eigen::Ref<const Eigen::MatrixXd>& Y,
                           const int* terms, double* eta, double* deta, Eigen::Index stride) const;

 private:
  Eigen::VectorXd w2_, c_;
  Eigen::MatrixXd Phi_;        // n x n
  Eigen::MatrixXd PhiTM_;      // Phi^T M, n x n
  Eigen::MatrixXd negL_;       // -Phi^T M r, n x 2
  Eigen::MatrixXd PhiTC_, D_;  // Assign's Phi^T C and Phi^T C Phi, n x n
};

}  // namespace skewbridge::dynamics
