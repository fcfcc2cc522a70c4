#include "solver/dynamics/modal_flow.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "solver/common/error.h"
#include "solver/model/builders.h"

namespace skewbridge::dynamics {
namespace {

// Off-diagonal of Phi^T C Phi, relative to its largest diagonal entry, still taken as rounding.
constexpr double kClassicalTolerance = 1e-12;

using Mat6 = Eigen::Matrix<double, 6, 6>;

// Two doubles side by side: each operation on it is the IEEE operation on each lane.
using Lanes2 = double __attribute__((vector_size(16)));

// Up to this many columns ModalProduct sums row by row in registers.
constexpr Eigen::Index kRowWiseColumns = 8;

// y = A.topRows(rows) x for few columns (kCols of them, or `cols` when kCols is 0): per row, the
// sum in a register, in the same order (j = 0, 1, ...) and from the same 0.0 as ModalProduct's
// column sweep, so the same bits without zeroing y and reading it back once per column.
template <int kCols>
inline void RowWise(const double* a, Eigen::Index stride, int rows, int cols, const double* x,
                    double* y) {
  const int n = kCols > 0 ? kCols : cols;
  for (int i = 0; i < rows; ++i) {
    double s = 0.0;
    for (int j = 0; j < n; ++j) s += a[i + j * stride] * x[j];
    y[i] = s;
  }
}

// 1 / (m + 1) for m < kModalMaxTerms, the same bits as the division (both correctly rounded):
// the coefficient recursions take a product per term instead of a division.
struct Reciprocals {
  double value[kModalMaxTerms];
  constexpr Reciprocals() : value() {
    for (int m = 0; m < kModalMaxTerms; ++m) value[m] = 1.0 / (m + 1);
  }
};
constexpr Reciprocals kInverseOf{};

// ModalTermCount by its definition: the terms rho^m / m! (the product of the rounded rho / j) up
// to the first m >= 4 at or below 1e-18, at most kModalMaxTerms. At least up to tau^3: the
// ramp's response of an undamped rigid mode is a cubic.
constexpr int TermCountLoop(double rho) {
  double term = 1.0;
  int m = 0;
  do {
    ++m;
    term *= rho / m;
  } while ((term > 1e-18 || m < 4) && m < kModalMaxTerms - 1);
  return m + 1;
}

// TermCountLoop on rho >= 0 is monotone in rho: each rounded rho / j and each rounded product of
// non-negative factors is monotone in them, so every term is, and so is the first m whose term
// is small enough. Its value on [0, kTableRho] is therefore 5 plus the number of thresholds at or
// below rho, the threshold of count N (6 <= N <= kModalMaxTerms) being the smallest double rho
// with TermCountLoop(rho) >= N: found here by bisection on the bit patterns of the non-negative
// doubles (ordered as their values) at compile time, where the arithmetic is the same IEEE
// double arithmetic as at run time, over [0, kTableRho] (no term overflows there). Entries past
// the last count are NaN (no rho is at or above them).
constexpr double kTableRho = 64.0;
static_assert(TermCountLoop(kTableRho) == kModalMaxTerms);
struct TermThresholds {
  double value[64];
  constexpr TermThresholds() : value() {
    for (double& v : value) v = std::numeric_limits<double>::quiet_NaN();
    for (int N = 6; N <= kModalMaxTerms; ++N) {
      std::uint64_t lo = 0;                                        // the bits of +0.0: count 5 < N
      std::uint64_t hi = std::bit_cast<std::uint64_t>(kTableRho);  // count kModalMaxTerms
      while (hi - lo > 1) {
        const std::uint64_t mid = lo + (hi - lo) / 2;
        if (TermCountLoop(std::bit_cast<double>(mid)) >= N) {
          hi = mid;
        } else {
          lo = mid;
        }
      }
      value[N - 6] = std::bit_cast<double>(hi);
    }
  }
};
constexpr TermThresholds kTermThresholds{};

}  // namespace

int ModalTermCount(double rho) {
  // Negative, NaN or past the table: the loop itself.
  if (!(rho >= 0.0 && rho <= kTableRho)) return TermCountLoop(rho);
  // The count is 5 plus the number of thresholds at or below rho: a branch-free binary search
  // over the table padded to 64 entries.
  const double* t = kTermThresholds.value;
  int i = 0;
  for (int half = 32; half > 0; half /= 2) {
    i += t[i + half - 1] <= rho ? half : 0;
  }
  return 5 + i;
}

void ModalProduct(const Eigen::MatrixXd& A, int rows, const double* x1, const double* x2,
                  double* y1, double* y2) {
  const Eigen::Index cols = A.cols(), stride = A.rows();
  const double* a = A.data();
  if (cols == 3) {
    // A single deck (the subsystem, the pilot bridge): the loop unrolled.
    RowWise<3>(a, stride, rows, 3, x1, y1);
    if (y2 != nullptr) RowWise<3>(a, stride, rows, 3, x2, y2);
    return;
  }
  if (cols <= kRowWiseColumns) {
    RowWise<0>(a, stride, rows, static_cast<int>(cols), x1, y1);
    if (y2 != nullptr) RowWise<0>(a, stride, rows, static_cast<int>(cols), x2, y2);
    return;
  }
  for (int i = 0; i < rows; ++i) y1[i] = 0.0;
  if (y2 != nullptr) {
    for (int i = 0; i < rows; ++i) y2[i] = 0.0;
  }
  for (Eigen::Index j = 0; j < cols; ++j, a += stride) {
    const double b1 = x1[j];
    for (int i = 0; i < rows; ++i) y1[i] += a[i] * b1;
    if (y2 != nullptr) {
      const double b2 = x2[j];
      for (int i = 0; i < rows; ++i) y2[i] += a[i] * b2;
    }
  }
}

std::optional<ModalFlow> ModalFlow::Classical(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                              const Eigen::Ref<const Eigen::MatrixXd>& K,
                                              const Eigen::Ref<const Eigen::MatrixXd>& C,
                                              const Eigen::Ref<const Eigen::MatrixXd>& r) {
  return Classical(model::ComputeModes(M, K), M, C, r);
}

std::optional<ModalFlow> ModalFlow::Classical(const model::Modes& modes,
                                              const Eigen::Ref<const Eigen::MatrixXd>& M,
                                              const Eigen::Ref<const Eigen::MatrixXd>& C,
                                              const Eigen::Ref<const Eigen::MatrixXd>& r) {
  ModalFlow flow;
  if (!flow.Assign(modes, M, C, r)) {
    return std::nullopt;
  }
  return flow;
}

bool ModalFlow::Assign(const model::Modes& modes, const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::MatrixXd>& C,
                       const Eigen::Ref<const Eigen::MatrixXd>& r) {
  SB_DEMAND(modes.phi.rows() == M.rows() && modes.phi.cols() == M.rows() &&
                modes.eigenvalues.size() == M.rows(),
            "ModalFlow: the modes do not match M");
  Phi_ = modes.phi;
  // Phi^T C Phi as the product of two products, each into storage of its own (the nested
  // product's temporary, kept).
  PhiTC_.noalias() = Phi_.transpose() * C;
  D_.noalias() = PhiTC_ * Phi_;
  const Eigen::MatrixXd& D = D_;
  const int n = static_cast<int>(M.rows());
  double diagonal = 0.0, off = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      (i == j ? diagonal : off) = std::max(i == j ? diagonal : off, std::abs(D(i, j)));
    }
  }
  if (off > kClassicalTolerance * diagonal) {
    return false;
  }
  // Entries at rounding level are zero: a DOF that no mode couples (the transverse DOFs of an
  // unskewed deck under a longitudinal pulse) then stays exactly at rest.
  for (int k = 0; k < n; ++k) {
    const double floor =
        64.0 * std::numeric_limits<double>::epsilon() * Phi_.col(k).cwiseAbs().maxCoeff();
    for (int i = 0; i < n; ++i) {
      if (std::abs(Phi_(i, k)) < floor) {
        Phi_(i, k) = 0.0;
      }
    }
  }
  w2_ = modes.eigenvalues.cwiseMax(0.0);
  c_ = D.diagonal();
  PhiTM_.noalias() = Phi_.transpose() * M;
  negL_.noalias() = -PhiTM_ * r;
  return true;
}

void ModalFlow::ToModal(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::MatrixXd> Y,
                        bool harmonic) const {
  const int n = n_modes();
  SB_ASSERT(Y.rows() == n && Y.cols() == 6, "ModalFlow: Y must be n x 6");
  if (n == 3 && Y.outerStride() == 3) {
    // A deck's three modes, once per free step: ModalProduct's and the loop's sums below, in the
    // same order from the same 0.0 (the same bits), unrolled over plain arrays.
    if (harmonic) {
      detail::ToModalFixed<3, true>(PhiTM_.data(), negL_.data(), z.data(), Y.data());
    } else {
      detail::ToModalFixed<3, false>(PhiTM_.data(), negL_.data(), z.data(), Y.data());
    }
    return;
  }
  ModalProduct(PhiTM_, n, z.data(), z.data() + n, Y.col(0).data(), Y.col(1).data());
  if (!harmonic) Y.rightCols(2).setZero();
  for (int j = 0; j < (harmonic ? 4 : 2); ++j) {
    const double gx = z[2 * n + 2 * j], gy = z[2 * n + 2 * j + 1];
    double* y = Y.col(2 + j).data();
    for (int k = 0; k < n; ++k) {
      y[k] = negL_(k, 0) * gx + negL_(k, 1) * gy;
    }
  }
}

void ModalFlow::ModeCoefficients(int k, double omega_radps, const double* y, int terms, double* eta,
                                 double* deta) const {
  SB_ASSERT(terms <= kModalMaxTerms, "ModalFlow: too many terms");
  const double w2 = w2_[k], c = c_[k];
  // Taylor coefficients of the harmonic forcing: g = gamma cos + delta sin, gt = delta cos -
  // gamma sin, g' = Omega gt, gt' = -Omega g.
  double g = y[4], gt = y[5];
  eta[0] = y[0];
  deta[0] = y[1];
  for (int m = 0; m + 1 < terms; ++m) {
    const double f = g + (m == 0 ? y[2] : 0.0) + (m == 1 ? y[3] : 0.0);
    const double inv = kInverseOf.value[m];
    eta[m + 1] = deta[m] * inv;
    deta[m + 1] = (f - w2 * eta[m] - c * deta[m]) * inv;
    const double g_next = omega_radps * gt * inv;
    gt = -omega_radps * g * inv;
    g = g_next;
  }
}

namespace {

// ModeCoefficients' recursion for one mode, a term at a time, so that two or three modes can
// share a loop with each mode's operations unchanged; the last coefficients in registers.
// Step<kPhase> is term m = kPhase (0, 1) or any m >= 2 (kPhase 2), whose forcing
// g + (m == 0 ? y2 : 0) + (m == 1 ? y3 : 0) is (g + y2) + 0, (g + 0) + y3 or (g + 0) + 0 = g + 0
// (x + 0 is never -0, so a second + 0 changes nothing).
//
// kHarmonic false: the harmonic inputs y[4], y[5] are zeros and omega is finite, so g and gt
// stay zeros (of either sign: omega times a zero) and are not carried; the forcing is then the
// same bits as y2 + 0, 0 + y3 and +0 (any zero plus y2 then plus +0 is y2, or +0 when y2 is a
// zero; a zero plus +0 is +0).
template <bool kHarmonic>
struct ModeRecursion {
  double w2, c, omega, y2, y3, g, gt, e, d;
  double* eta;
  double* deta;
  void Start(double w2_k, double c_k, double omega_radps, const double y[6], double* eta_k,
             double* deta_k) {
    w2 = w2_k;
    c = c_k;
    omega = omega_radps;
    y2 = y[2];
    y3 = y[3];
    g = y[4];
    gt = y[5];
    eta = eta_k;
    deta = deta_k;
    e = y[0];
    d = y[1];
    eta[0] = e;
    deta[0] = d;
  }
  template <int kPhase>
  double Forcing() const {
    if constexpr (kHarmonic) {
      if constexpr (kPhase == 0) return g + y2 + 0.0;
      if constexpr (kPhase == 1) return g + 0.0 + y3;
      return g + 0.0;
    } else {
      if constexpr (kPhase == 0) return y2 + 0.0;
      if constexpr (kPhase == 1) return 0.0 + y3;
      return 0.0;
    }
  }
  template <int kPhase>
  void Step(int m) {
    const double f = Forcing<kPhase>();
    const double inv = kInverseOf.value[m];
    const double e_next = d * inv;
    const double d_next = (f - w2 * e - c * d) * inv;
    eta[m + 1] = e_next;
    deta[m + 1] = d_next;
    e = e_next;
    d = d_next;
    if constexpr (kHarmonic) {
      const double g_next = omega * gt * inv;
      gt = -omega * g * inv;
      g = g_next;
    }
  }
  void StepAny(int m) {
    if (m == 0) {
      Step<0>(m);
    } else if (m == 1) {
      Step<1>(m);
    } else {
      Step<2>(m);
    }
  }
};

// Two modes' ModeRecursion in the two lanes of each operand: each lane runs ModeRecursion's
// operations in its order, so the same bits; Back hands the lanes' state to the two recursions,
// which go on alone past the shorter series.
template <bool kHarmonic>
struct PairRecursion {
  Lanes2 w2, c, omega, y2, y3, g, gt, e, d;
  double* eta[2];
  double* deta[2];
  void Start(const ModeRecursion<kHarmonic>& a, const ModeRecursion<kHarmonic>& b) {
    w2 = Lanes2{a.w2, b.w2};
    c = Lanes2{a.c, b.c};
    omega = Lanes2{a.omega, b.omega};
    y2 = Lanes2{a.y2, b.y2};
    y3 = Lanes2{a.y3, b.y3};
    g = Lanes2{a.g, b.g};
    gt = Lanes2{a.gt, b.gt};
    e = Lanes2{a.e, b.e};
    d = Lanes2{a.d, b.d};
    eta[0] = a.eta;
    eta[1] = b.eta;
    deta[0] = a.deta;
    deta[1] = b.deta;
  }
  template <int kPhase>
  Lanes2 Forcing() const {
    const Lanes2 zero = {0.0, 0.0};
    if constexpr (kHarmonic) {
      if constexpr (kPhase == 0) return g + y2 + zero;
      if constexpr (kPhase == 1) return g + zero + y3;
      return g + zero;
    } else {
      if constexpr (kPhase == 0) return y2 + zero;
      if constexpr (kPhase == 1) return zero + y3;
      return zero;
    }
  }
  template <int kPhase>
  void Step(int m) {
    const Lanes2 f = Forcing<kPhase>();
    const double s = kInverseOf.value[m];
    const Lanes2 inv = {s, s};
    const Lanes2 e_next = d * inv;
    const Lanes2 d_next = (f - w2 * e - c * d) * inv;
    eta[0][m + 1] = e_next[0];
    eta[1][m + 1] = e_next[1];
    deta[0][m + 1] = d_next[0];
    deta[1][m + 1] = d_next[1];
    e = e_next;
    d = d_next;
    if constexpr (kHarmonic) {
      const Lanes2 g_next = omega * gt * inv;
      gt = -omega * g * inv;
      g = g_next;
    }
  }
  void StepAny(int m) {
    if (m == 0) {
      Step<0>(m);
    } else if (m == 1) {
      Step<1>(m);
    } else {
      Step<2>(m);
    }
  }
  void Back(ModeRecursion<kHarmonic>& a, ModeRecursion<kHarmonic>& b) const {
    a.e = e[0];
    b.e = e[1];
    a.d = d[0];
    b.d = d[1];
    a.g = g[0];
    b.g = g[1];
    a.gt = gt[0];
    b.gt = gt[1];
  }
};

// kCount modes' recursions (terms t[j] each) in one loop up to the shortest, then each alone.
// kCount (2 or 3) modes' recursions (terms t[j] each): the last two share the lanes of
// PairRecursion up to the shorter of their series (the higher modes, ascending in frequency,
// need the most terms), the first of three runs beside them up to its own end; each goes on
// alone past that.
template <int kCount, bool kHarmonic>
void RunRecursions(ModeRecursion<kHarmonic> (&r)[kCount], const int (&t)[kCount]) {
  static_assert(kCount == 2 || kCount == 3);
  ModeRecursion<kHarmonic>& a = r[kCount - 2];
  ModeRecursion<kHarmonic>& b = r[kCount - 1];
  const int pair_end = std::min(t[kCount - 2], t[kCount - 1]);
  const int common = kCount == 3 ? std::min(pair_end, t[0]) : pair_end;
  PairRecursion<kHarmonic> pair;
  pair.Start(a, b);
  int m = 0;
  if (m + 1 < common) {
    pair.template Step<0>(m);
    if constexpr (kCount == 3) r[0].template Step<0>(m);
    ++m;
  }
  if (m == 1 && m + 1 < common) {
    pair.template Step<1>(m);
    if constexpr (kCount == 3) r[0].template Step<1>(m);
    ++m;
  }
  if (m == 2) {
    for (; m + 1 < common; ++m) {
      pair.template Step<2>(m);
      if constexpr (kCount == 3) r[0].template Step<2>(m);
    }
  }
  if constexpr (kCount == 3) {
    for (int mj = m; mj + 1 < t[0]; ++mj) r[0].StepAny(mj);
  }
  for (; m + 1 < pair_end; ++m) pair.StepAny(m);
  pair.Back(a, b);
  for (int mj = m; mj + 1 < t[kCount - 2]; ++mj) a.StepAny(mj);
  for (int mj = m; mj + 1 < t[kCount - 1]; ++mj) b.StepAny(mj);
}

// AllModeCoefficients' modes k0 .. k0 + kCount - 1.
template <int kCount, bool kHarmonic>
void ModeGroup(const Eigen::VectorXd& w2, const Eigen::VectorXd& c, double omega_radps,
               const Eigen::Ref<const Eigen::MatrixXd>& Y, const int* terms, int k0, double* eta,
               double* deta, Eigen::Index stride) {
  ModeRecursion<kHarmonic> r[kCount];
  int t[kCount];
  for (int j = 0; j < kCount; ++j) {
    const int k = k0 + j;
    SB_ASSERT(terms[k] <= kModalMaxTerms, "ModalFlow: too many terms");
    const double y[6] = {Y(k, 0), Y(k, 1), Y(k, 2), Y(k, 3), Y(k, 4), Y(k, 5)};
    r[j].Start(w2[k], c[k], omega_radps, y, eta + k * stride, deta + k * stride);
    t[j] = terms[k];
  }
  RunRecursions(r, t);
}

template <int kCount>
void ModeGroup(bool harmonic, const Eigen::VectorXd& w2, const Eigen::VectorXd& c,
               double omega_radps, const Eigen::Ref<const Eigen::MatrixXd>& Y, const int* terms,
               int k0, double* eta, double* deta, Eigen::Index stride) {
  if (harmonic) {
    ModeGroup<kCount, true>(w2, c, omega_radps, Y, terms, k0, eta, deta, stride);
  } else {
    ModeGroup<kCount, false>(w2, c, omega_radps, Y, terms, k0, eta, deta, stride);
  }
}

// Transitions' series of one mode without the energy forms, `terms` coefficients summed at tau
// into row (T_k row-major): the recursion of the six unit inputs with the columns in pairs
// (0, 1), (2, 3), (4, 5), two lanes per operation, each lane the scalar recursion's operations
// in its order, so the same bits. The forcing of the columns 0 to 3 is a constant: their
// harmonic g starts at 0 and stays a zero of either sign (omega finite: omega times a zero),
// and a zero plus 1.0 is 1.0, a zero plus +0.0 is +0.0, so g + (unit alpha at m = 0) + (unit
// beta at m = 1) is 1.0 at those terms and +0.0 at every other. kPairs 2: the pairs (0, 1) and
// (2, 3) alone (SeriesRow's case omega = 0). @pre omega_radps finite.
template <int kPairs>
void SeriesRowLanes(double w2, double c, double omega_radps, double tau, int terms,
                    double row[12]) {
  static_assert(kPairs == 2 || kPairs == 3);
  Lanes2 e[kModalMaxTerms][kPairs], v[kModalMaxTerms][kPairs];
  const Lanes2 w2_l = {w2, w2}, c_l = {c, c};
  const Lanes2 omega = {omega_radps, omega_radps}, minus_omega = {-omega_radps, -omega_radps};
  const Lanes2 zero = {0.0, 0.0};
  e[0][0] = Lanes2{1.0, 0.0};
  v[0][0] = Lanes2{0.0, 1.0};
  for (int p = 1; p < kPairs; ++p) e[0][p] = v[0][p] = zero;
  Lanes2 g = {1.0, 0.0}, gt = {0.0, 1.0};  // the columns 4 and 5 (gamma, delta)
  for (int m = 0; m + 1 < terms; ++m) {
    const double s = kInverseOf.value[m];
    const Lanes2 inv = {s, s};
    const Lanes2 f[3] = {zero, Lanes2{m == 0 ? 1.0 : 0.0, m == 1 ? 1.0 : 0.0}, g + zero + zero};
    for (int p = 0; p < kPairs; ++p) {
      e[m + 1][p] = v[m][p] * inv;
      v[m + 1][p] = (f[p] - w2_l * e[m][p] - c_l * v[m][p]) * inv;
    }
    if constexpr (kPairs == 3) {
      const Lanes2 g_next = omega * gt * inv;
      gt = minus_omega * g * inv;
      g = g_next;
    }
  }
  // Sum the series at tau (Horner).
  const Lanes2 t = {tau, tau};
  for (int p = 0; p < kPairs; ++p) {
    Lanes2 a = e[terms - 1][p], b = v[terms - 1][p];
    for (int m = terms - 2; m >= 0; --m) {
      a = a * t + e[m][p];
      b = b * t + v[m][p];
    }
    row[2 * p] = a[0];
    row[2 * p + 1] = a[1];
    row[6 + 2 * p] = b[0];
    row[6 + 2 * p + 1] = b[1];
  }
}

// SeriesRowLanes<3>'s row. At omega = +-0 (a piece without harmonic part) its pair (4, 5) needs
// no recursion: column 4's forcing g + 0 + 0 is 1.0 at m = 0 and +0.0 after (g a zero of either
// sign there: omega times a finite number), column 2's exactly, from the same zero start, so
// column 4 is column 2's bits; column 5's forcing is +0.0 at every term, and from +0.0 every
// coefficient is +0.0 (+0 - w2 (+0) - c (+0) is +0 for finite w2 and c, whatever their signs),
// and so is its sum at a finite tau. @pre omega_radps finite.
void SeriesRow(double w2, double c, double omega_radps, double tau, int terms, double row[12]) {
  if (omega_radps == 0.0 && std::isfinite(w2) && std::isfinite(c) && std::isfinite(tau)) {
    SeriesRowLanes<2>(w2, c, omega_radps, tau, terms, row);
    row[4] = row[2];
    row[10] = row[8];
    row[5] = row[11] = 0.0;
    return;
  }
  SeriesRowLanes<3>(w2, c, omega_radps, tau, terms, row);
}
}  // namespace

void ModalFlow::AllModeCoefficients(double omega_radps, const Eigen::Ref<const Eigen::MatrixXd>& Y,
                                    const int* terms, double* eta, double* deta,
                                    Eigen::Index stride) const {
  const int n = n_modes();
  SB_ASSERT(Y.rows() == n && Y.cols() == 6, "ModalFlow: Y must be n x 6");
  // Harmonic inputs all zeros (a record's piece, or a pulse's end): the recursions without them.
  bool harmonic = !std::isfinite(omega_radps);
  for (int k = 0; k < n && !harmonic; ++k) harmonic = Y(k, 4) != 0.0 || Y(k, 5) != 0.0;
  int k = 0;
  if (n % 2 == 1 && n >= 3) {
    // An odd count (a deck's 3 modes): the first three in one loop, the rest in pairs.
    ModeGroup<3>(harmonic, w2_, c_, omega_radps, Y, terms, 0, eta, deta, stride);
    k = 3;
  }
  for (; k + 1 < n; k += 2) {
    ModeGroup<2>(harmonic, w2_, c_, omega_radps, Y, terms, k, eta, deta, stride);
  }
  if (k < n) {
    const double y[6] = {Y(k, 0), Y(k, 1), Y(k, 2), Y(k, 3), Y(k, 4), Y(k, 5)};
    ModeCoefficients(k, omega_radps, y, terms[k], eta + k * stride, deta + k * stride);
  }
}

std::size_t TransitionMemo::SetOf(const double (&key)[4]) {
  std::uint64_t h = 0;
  for (const double x : key) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    h = (h ^ b) * 0x9E3779B97F4A7C15ULL;
    h ^= h >> 29;
  }
  return static_cast<std::size_t>(h % kSets);
}

TransitionMemo::TransitionMemo(const TransitionMemo& other) { *this = other; }

TransitionMemo& TransitionMemo::operator=(const TransitionMemo& other) {
  if (this == &other) {
    return *this;
  }
  std::memcpy(used_, other.used_, sizeof used_);
  std::memcpy(next_, other.next_, sizeof next_);
  if (other.slots_ == nullptr) {
    slots_.reset();
    return *this;
  }
  if (slots_ == nullptr) {
    slots_ = std::make_unique_for_overwrite<Slot[]>(kSlots);
  }
  for (std::size_t s = 0; s < kSlots; ++s) {
    if (other.Used(s)) {
      slots_[s] = other.slots_[s];
    }
  }
  return *this;
}

bool TransitionMemo::Find(const double (&key)[4], double* row) const {
  const std::size_t first = SetOf(key) * kWays;
  for (std::size_t s = first; s < first + kWays; ++s) {
    if (!Used(s)) {
      continue;
    }
    const Slot& slot = slots_[s];
    if (std::memcmp(slot.key, key, sizeof slot.key) == 0) {
      std::memcpy(row, slot.row, sizeof slot.row);
      return true;
    }
  }
  return false;
}

void TransitionMemo::Store(const double (&key)[4], const double* row) {
  if (slots_ == nullptr) {
    slots_ = std::make_unique_for_overwrite<Slot[]>(kSlots);
  }
  // The set's ways in turn: the slot taken is the one stored longest ago.
  const std::size_t set = SetOf(key);
  const std::size_t shift = 2 * (set % 32);
  const std::uint64_t way = (next_[set / 32] >> shift) & 3U;
  next_[set / 32] = (next_[set / 32] & ~(std::uint64_t{3} << shift)) | (((way + 1) & 3U) << shift);
  const std::size_t s = set * kWays + way;
  Slot& slot = slots_[s];
  std::memcpy(slot.key, key, sizeof slot.key);
  std::memcpy(slot.row, row, sizeof slot.row);
  used_[s / 64] |= std::uint64_t{1} << (s % 64);
}

void ModalFlow::Transitions(double tau_s, double omega_radps, Eigen::Ref<Eigen::MatrixXd> rows,
                            Eigen::MatrixXd* input, Eigen::MatrixXd* damping,
                            TransitionMemo* memo) const {
  const int n = n_modes();
  const bool energy = input != nullptr && damping != nullptr;
  SB_DEMAND(rows.rows() == 12 && rows.cols() == n, "ModalFlow: rows must be 12 x n");
  if (energy) {
    input->resize(36, n);
    damping->resize(36, n);
  }
  const double W = std::abs(omega_radps);
  // Columns: the responses to unit (eta, eta', alpha, beta, gamma, delta). Indices: [m][j].
  double e[kModalMaxTerms][6], v[kModalMaxTerms][6], f[kModalMaxTerms][6];
  double weight[2 * kModalMaxTerms];
  if (energy) {
    memo = nullptr;  // it holds the transitions alone
  }
  for (int k = 0; k < n; ++k) {
    // T_k is a function of these bits alone.
    const double key[4] = {w2_[k], c_[k], tau_s, omega_radps};
    double row[12];
    if (memo != nullptr && memo->Find(key, row)) {
      for (int i = 0; i < 12; ++i) {
        rows(i, k) = row[i];
      }
      continue;
    }
    const double rho = tau_s * (std::sqrt(w2_[k]) + std::abs(c_[k]) + W);
    int halvings = 0;
    double tau = tau_s;
    while (rho * std::ldexp(1.0, -halvings) > kModalSeriesRadius) {
      ++halvings;
    }
    tau = std::ldexp(tau_s, -halvings);
    const int terms = ModalTermCount(rho * std::ldexp(1.0, -halvings));
    if (!energy && std::isfinite(omega_radps)) {
      // The series alone, two columns per operation: the same bits.
      SeriesRow(w2_[k], c_[k], omega_radps, tau, terms, row);
    } else {
      // The coefficient recursion of ModeCoefficients for the six unit inputs at once, every
      // coefficient and forcing kept for the energy forms.
      double g[6] = {0, 0, 0, 0, 1, 0}, gt[6] = {0, 0, 0, 0, 0, 1};
      for (int j = 0; j < 6; ++j) {
        e[0][j] = j == 0 ? 1.0 : 0.0;
        v[0][j] = j == 1 ? 1.0 : 0.0;
      }
      for (int m = 0; m < terms; ++m) {
        const double inv = kInverseOf.value[m];
        for (int j = 0; j < 6; ++j) {
          f[m][j] = g[j] + (m == 0 && j == 2 ? 1.0 : 0.0) + (m == 1 && j == 3 ? 1.0 : 0.0);
          if (m + 1 < terms) {
            e[m + 1][j] = v[m][j] * inv;
            v[m + 1][j] = (f[m][j] - w2_[k] * e[m][j] - c_[k] * v[m][j]) * inv;
          }
          const double g_next = omega_radps * gt[j] * inv;
          gt[j] = -omega_radps * g[j] * inv;
          g[j] = g_next;
        }
      }
      // Sum the series at tau (Horner).
      for (int j = 0; j < 6; ++j) {
        double a = e[terms - 1][j], b = v[terms - 1][j];
        for (int m = terms - 2; m >= 0; --m) {
          a = a * tau + e[m][j];
          b = b * tau + v[m][j];
        }
        row[j] = a;
        row[6 + j] = b;
      }
    }
    Mat6 Qin, Qd;
    if (energy) {
      // int_0^tau s^j ds = tau^{j+1} / (j + 1); the products of two series of `terms` terms.
      double p = tau;
      for (int j = 0; j < 2 * terms; ++j) {
        weight[j] = p / (j + 1);
        p *= tau;
      }
      Qin.setZero();
      Qd.setZero();
      for (int m = 0; m < terms; ++m) {
        double gf[6] = {0, 0, 0, 0, 0, 0}, gv[6] = {0, 0, 0, 0, 0, 0};
        for (int l = 0; l < terms; ++l) {
          const double w = weight[m + l];
          for (int j = 0; j < 6; ++j) {
            gf[j] += w * f[l][j];
            gv[j] += w * v[l][j];
          }
        }
        for (int b = 0; b < 6; ++b) {
          for (int a = 0; a < 6; ++a) {
            Qin(a, b) += v[m][a] * gf[b];
            Qd(a, b) += v[m][a] * gv[b];
          }
        }
      }
      Qin = (0.5 * (Qin + Qin.transpose())).eval();
      Qd = (0.5 * c_[k] * (Qd + Qd.transpose())).eval();
    }
    if (halvings > 0) {
      // Square back: the 6 x 6 transition of (y_k) with the generator's own rows, and
      // int_0^{2 tau} = int_0^tau + int_tau^{2 tau}: Q <- Q + P^T Q P.
      Mat6 P = Mat6::Zero();
      for (int j = 0; j < 6; ++j) {
        P(0, j) = row[j];
        P(1, j) = row[6 + j];
      }
      P(2, 2) = 1.0;
      P(2, 3) = tau;
      P(3, 3) = 1.0;
      const double co = std::cos(omega_radps * tau), si = std::sin(omega_radps * tau);
      P(4, 4) = co;
      P(4, 5) = si;
      P(5, 4) = -si;
      P(5, 5) = co;
      for (int s = 0; s < halvings; ++s) {
        if (energy) {
          Qin = (Qin + P.transpose() * Qin * P).eval();
          Qd = (Qd + P.transpose() * Qd * P).eval();
        }
        P = (P * P).eval();
      }
      for (int j = 0; j < 6; ++j) {
        row[j] = P(0, j);
        row[6 + j] = P(1, j);
      }
    }
    for (int i = 0; i < 12; ++i) {
      rows(i, k) = row[i];
    }
    if (memo != nullptr) {
      memo->Store(key, row);
    }
    if (energy) {
      input->col(k) = Eigen::Map<const Eigen::Matrix<double, 36, 1>>(Qin.data());
      damping->col(k) = Eigen::Map<const Eigen::Matrix<double, 36, 1>>(Qd.data());
    }
  }
}

}  // namespace skewbridge::dynamics
