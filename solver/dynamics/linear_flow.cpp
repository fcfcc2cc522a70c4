#include "solver/dynamics/linear_flow.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <unsupported/Eigen/MatrixFunctions>

#include "solver/common/error.h"
#include "solver/model/builders.h"

namespace skewbridge::dynamics {
namespace {

constexpr std::size_t kCacheCapacity = 8;

// Whether M is diagonal with finite entries > 0: then it is symmetric positive definite (the
// Cholesky factorisation, whose verdict it is otherwise, succeeds on it) without factorising.
bool PositiveDiagonal(const Eigen::MatrixXd& M) {
  for (Eigen::Index j = 0; j < M.cols(); ++j) {
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      const double m = M(i, j);
      if (i == j ? !(std::isfinite(m) && m > 0.0) : m != 0.0) return false;
    }
  }
  return M.rows() == M.cols();
}

}  // namespace

LinearFlow::LinearFlow(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::MatrixXd>& K,
                       const Eigen::Ref<const Eigen::MatrixXd>& C,
                       const Eigen::Ref<const Eigen::MatrixXd>& r, FlowPath path,
                       const model::Modes* modes)
    : n_(static_cast<int>(M.rows())), path_(path), M_(M), K_(K), C_(C), r_(r) {
  Setup(modes);
}

void LinearFlow::Refit(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::MatrixXd>& K,
                       const Eigen::Ref<const Eigen::MatrixXd>& C,
                       const Eigen::Ref<const Eigen::MatrixXd>& r, const model::Modes* modes) {
  if (M.rows() != n_) {
    *this = LinearFlow(M, K, C, r, path_, modes);
    return;
  }
  M_ = M;
  K_ = K;
  C_ = C;
  r_ = r;
  augmented_ready_ = false;
  cache_size_ = 0;
  clock_ = 0;
  Setup(modes);
}

void LinearFlow::Setup(const model::Modes* modes) {
  SB_DEMAND(M_.cols() == n_ && K_.rows() == n_ && K_.cols() == n_ && C_.rows() == n_ &&
                C_.cols() == n_ && r_.rows() == n_ && r_.cols() == 2,
            "LinearFlow: inconsistent matrix sizes");
  SB_DEMAND(PositiveDiagonal(M_) || Eigen::LLT<Eigen::MatrixXd>(M_).info() == Eigen::Success,
            "LinearFlow: M must be symmetric positive definite");
  Mr_.noalias() = M_ * r_;
  bool modal = false;
  if (path_ == FlowPath::kAuto) {
    // Classical's flow, in the storage of the last one when there is one.
    std::optional<model::Modes> solved;
    if (modes == nullptr) {
      solved = model::ComputeModes(M_, K_);
      modes = &*solved;
    }
    if (!modal_) {
      modal_.emplace();
    }
    modal = modal_->Assign(*modes, M_, C_, r_);
  }
  if (!modal) {
    modal_.reset();
    EnsureAugmented();
  }
  Y_.setZero(n_, 6);
  if (modal_ && n_ == 3) {
    for (int e = 0; e < 9; ++e) {
      const double a = modal_->PhiTM().data()[e], b = modal_->Phi().data()[e];
      deck_.PhiTM[e] = detail::Lanes2{a, a};
      deck_.Phi[e] = detail::Lanes2{b, b};
    }
    for (int e = 0; e < 6; ++e) {
      const double a = modal_->negL().data()[e];
      deck_.negL[e] = detail::Lanes2{a, a};
    }
  }
  eta_.setZero(n_);
  deta_.setZero(n_);
}

void LinearFlow::EnsureAugmented() const {
  if (augmented_ready_) {
    return;
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(M_);
  const int N = augmented_size();
  const int ia = 2 * n_, is = 2 * n_ + 2, ip = 2 * n_ + 4;
  A_base_ = Eigen::MatrixXd::Zero(N, N);
  A_base_.block(0, n_, n_, n_).setIdentity();
  A_base_.block(n_, 0, n_, n_) = -llt.solve(K_);
  A_base_.block(n_, n_, n_, n_) = -llt.solve(C_);
  A_base_.block(n_, ia, n_, 2) = -r_;
  A_base_.block(n_, ip, n_, 2) = -r_;
  A_base_.block(ia, is, 2, 2).setIdentity();
  A_u_ = A_base_.middleRows(n_, n_);

  // Ground power -u^T M r (a + p) and damping power u^T C u as symmetric forms on z.
  Q_input_ = Eigen::MatrixXd::Zero(N, N);
  for (int col : {ia, ip}) {
    Q_input_.block(n_, col, n_, 2) = -0.5 * Mr_;
    Q_input_.block(col, n_, 2, n_) = -0.5 * Mr_.transpose();
  }
  Q_damping_ = Eigen::MatrixXd::Zero(N, N);
  Q_damping_.block(n_, n_, n_, n_) = 0.5 * (C_ + C_.transpose());
  augmented_ready_ = true;
}

Eigen::MatrixXd LinearFlow::AugmentedMatrix(double omega_radps) const {
  EnsureAugmented();
  Eigen::MatrixXd A = A_base_;
  const int ip = 2 * n_ + 4, ik = 2 * n_ + 6;
  for (int i = 0; i < 2; ++i) {
    A(ip + i, ik + i) = omega_radps;
    A(ik + i, ip + i) = -omega_radps;
  }
  return A;
}

void LinearFlow::Compute(double tau_s, double omega_radps, bool energy, FreePropagator& out) const {
  out.tau_s = tau_s;
  out.omega_radps = omega_radps;
  out.has_energy = energy;
  if (modal_) {
    out.modal_rows.resize(12, n_);
    modal_->Transitions(tau_s, omega_radps, out.modal_rows, energy ? &out.modal_input : nullptr,
                        energy ? &out.modal_damping : nullptr, &memo_);
    if (n_ == 3) {
      out.record_pairs.resize(24);
      out.deck_pairs.resize(36);
      for (int k = 0; k < 3; ++k) {
        for (int j = 0; j < 6; ++j) {
          if (j < 4) {
            out.record_pairs[8 * k + 2 * j] = out.modal_rows(j, k);
            out.record_pairs[8 * k + 2 * j + 1] = out.modal_rows(6 + j, k);
          }
          out.deck_pairs[12 * k + 2 * j] = out.modal_rows(j, k);
          out.deck_pairs[12 * k + 2 * j + 1] = out.modal_rows(6 + j, k);
        }
      }
    }
    LibraryCosSin(omega_radps * tau_s, out.cos_wt, out.sin_wt);
    return;
  }
  const int N = augmented_size();
  const Eigen::MatrixXd A = AugmentedMatrix(omega_radps);
  // The transition on its own, so that it is the same bits whether the energy forms are asked.
  out.phi = (A * tau_s).exp();
  if (!energy) {
    return;
  }
  // Van Loan: exp([[-A^T, Q], [0, A]] tau) = [[., G2], [0, e^{A tau}]] and
  // int_0^tau e^{A^T s} Q e^{A s} ds = e^{A tau}^T G2. Q is scaled to unit norm so that a heavy
  // deck does not inflate the norm that sets the scaling-and-squaring depth.
  const auto gram = [&](const Eigen::MatrixXd& Q, Eigen::MatrixXd& result) {
    const double scale = std::max(Q.cwiseAbs().maxCoeff(), 1e-300);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * N, 2 * N);
    H.topLeftCorner(N, N) = -A.transpose() * tau_s;
    H.topRightCorner(N, N) = Q * (tau_s / scale);
    H.bottomRightCorner(N, N) = A * tau_s;
    const Eigen::MatrixXd E = H.exp();
    const Eigen::MatrixXd F3 = E.bottomRightCorner(N, N);
    const Eigen::MatrixXd G = F3.transpose() * E.topRightCorner(N, N) * scale;
    result = 0.5 * (G + G.transpose());
  };
  gram(Q_input_, out.input_gram);
  gram(Q_damping_, out.damping_gram);
}

const FreePropagator& LinearFlow::Propagator(double tau_s, double omega_radps, bool energy) {
  SB_DEMAND(tau_s > 0.0 && std::isfinite(tau_s), "LinearFlow: step must be positive");
  ++clock_;
  for (std::size_t i = 0; i < cache_size_; ++i) {
    if (cache_[i].tau_s == tau_s && cache_[i].omega_radps == omega_radps) {
      last_use_[i] = clock_;
      if (energy && !cache_[i].has_energy) {
        Compute(tau_s, omega_radps, true, cache_[i]);
      }
      return cache_[i];
    }
  }
  if (cache_size_ < kCacheCapacity) {
    if (cache_size_ == cache_.size()) {
      cache_.emplace_back();
      last_use_.push_back(clock_);
    }
    // A kept entry's storage is written over: Compute sets every member a path reads.
    const std::size_t slot = cache_size_++;
    last_use_[slot] = clock_;
    Compute(tau_s, omega_radps, energy, cache_[slot]);
    return cache_[slot];
  }
  // Least recently used: a record's nominal step and a pulse's pieces stay while the odd step
  // sizes (a piece's last step) come and go.
  const std::size_t slot = static_cast<std::size_t>(
      std::min_element(last_use_.begin(), last_use_.end()) - last_use_.begin());
  last_use_[slot] = clock_;
  Compute(tau_s, omega_radps, energy, cache_[slot]);
  return cache_[slot];
}

void LinearFlow::Apply(const FreePropagator& p, const Eigen::Ref<const Eigen::VectorXd>& z,
                       Eigen::Ref<Eigen::VectorXd> z_next, double* input_J, double* damping_J) {
  ApplyMotion(p, z, z_next, input_J, damping_J);
  if (!modal_) {
    return;  // the whole of z_next: e^{A_hat tau} z
  }
  // The generator: a + slope tau, slope, and (p, k) turned by omega tau.
  const int ia = 2 * n_;
  z_next.segment<2>(ia) = z.segment<2>(ia) + p.tau_s * z.segment<2>(ia + 2);
  z_next.segment<2>(ia + 2) = z.segment<2>(ia + 2);
  z_next.segment<2>(ia + 4) = p.cos_wt * z.segment<2>(ia + 4) + p.sin_wt * z.segment<2>(ia + 6);
  z_next.segment<2>(ia + 6) = -p.sin_wt * z.segment<2>(ia + 4) + p.cos_wt * z.segment<2>(ia + 6);
}

void LinearFlow::ApplyMotion(const FreePropagator& p, const Eigen::Ref<const Eigen::VectorXd>& z,
                             Eigen::Ref<Eigen::VectorXd> z_next, double* input_J,
                             double* damping_J) {
  const bool energy = input_J != nullptr && damping_J != nullptr;
  if (!modal_) {
    z_next.noalias() = p.phi * z;
    if (energy) {
      StepEnergy(p, z, *input_J, *damping_J);
    }
    return;
  }
  // The harmonic generator (p, k) zero, as on every piece of a record: its columns of Y are
  // zeros, +0 from ToModal (their products would be zeros of either sign; a sum from 0.0 with
  // either gives the same bits, and the bounds read their magnitudes).
  const int ih = 2 * n_ + 4;
  const bool harmonic = z[ih] != 0.0 || z[ih + 1] != 0.0 || z[ih + 2] != 0.0 || z[ih + 3] != 0.0;
  // z and z_next are distinct (the precondition): the (q, u) written here is read by nothing after.
  if (n_ == 3) {
    // A deck's three modes, two lanes per operation: ToModal's and ModalStep's operations in
    // their order (the same bits), the harmonic columns left out when they are zeros.
    if (harmonic) {
      detail::DeckHarmonicStep(deck_, p.deck_pairs.data(), z.data(), Y_.data(), z_next.data());
    } else {
      detail::DeckRecordStep(deck_, p.record_pairs.data(), z.data(), Y_.data(), z_next.data());
    }
  } else {
    modal_->ToModal(z, Y_, harmonic);
    detail::ModalStep<0, true>(modal_->Phi().data(), n_, p.modal_rows.data(), Y_.data(),
                               eta_.data(), deta_.data(), z_next.data(), z_next.data() + n_);
  }
  if (energy) {
    SB_DEMAND(p.has_energy, "LinearFlow: the propagator was built without its energy forms");
    ModalEnergy(p, *input_J, *damping_J);
  }
}

void LinearFlow::StepEnergy(const FreePropagator& p, const Eigen::Ref<const Eigen::VectorXd>& z,
                            double& input_J, double& damping_J) {
  SB_DEMAND(p.has_energy, "LinearFlow: the propagator was built without its energy forms");
  if (!modal_) {
    // Coefficient-wise: no temporary for G z.
    input_J = 0.0;
    damping_J = 0.0;
    const Eigen::Index N = z.size();
    for (Eigen::Index j = 0; j < N; ++j) {
      input_J += z[j] * p.input_gram.col(j).dot(z);
      damping_J += z[j] * p.damping_gram.col(j).dot(z);
    }
    return;
  }
  modal_->ToModal(z, Y_);
  ModalEnergy(p, input_J, damping_J);
}

void LinearFlow::ModalEnergy(const FreePropagator& p, double& input_J, double& damping_J) const {
  // Sum over modes of y_k^T Q_k y_k, y_k the row k of Y_.
  input_J = 0.0;
  damping_J = 0.0;
  for (int k = 0; k < n_; ++k) {
    const double* Qi = p.modal_input.data() + 36 * k;
    const double* Qd = p.modal_damping.data() + 36 * k;
    for (int b = 0; b < 6; ++b) {
      double si = 0.0, sd = 0.0;
      for (int a = 0; a < 6; ++a) {
        si += Qi[6 * b + a] * Y_(k, a);
        sd += Qd[6 * b + a] * Y_(k, a);
      }
      input_J += Y_(k, b) * si;
      damping_J += Y_(k, b) * sd;
    }
  }
}

void LinearFlow::Derivative(double omega_radps, const Eigen::Ref<const Eigen::VectorXd>& z,
                            Eigen::Ref<Eigen::VectorXd> dz) const {
  // A_hat is sparse by blocks: dq = u, du from the n dense rows, and the generator's own rows
  // (da = slope, dslope = 0, dp = omega k, dk = -omega p).
  EnsureAugmented();
  const int ia = 2 * n_, is = ia + 2, ip = ia + 4, ik = ia + 6;
  dz.head(n_) = z.segment(n_, n_);
  dz.segment(n_, n_) = A_u_.lazyProduct(z);
  dz.segment<2>(ia) = z.segment<2>(is);
  dz.segment<2>(is).setZero();
  dz.segment<2>(ip) = omega_radps * z.segment<2>(ik);
  dz.segment<2>(ik) = -omega_radps * z.segment<2>(ip);
}

double LinearFlow::MechanicalEnergy(const Eigen::Ref<const Eigen::VectorXd>& z) const {
  const auto q = z.head(n_);
  const auto u = z.segment(n_, n_);
  return 0.5 * u.dot(M_ * u) + 0.5 * q.dot(K_ * q);
}

void LinearFlow::Powers(const Eigen::Ref<const Eigen::VectorXd>& z, double& input_W,
                        double& damping_W) const {
  const auto u = z.segment(n_, n_);
  const Eigen::Vector2d ag = z.segment<2>(2 * n_) + z.segment<2>(2 * n_ + 4);
  // Coefficient-wise products: no temporary in the quadrature of every partial step.
  input_W = -(ag(0) * u.dot(Mr_.col(0)) + ag(1) * u.dot(Mr_.col(1)));
  damping_W = u.dot(C_.lazyProduct(u));
}

FreeDenseOutput::FreeDenseOutput(int n_aug, int max_terms)
    : n_(std::max(0, (n_aug - kGeneratorSize) / 2)),
      n_aug_(n_aug),
      max_terms_(max_terms),
      // Only the first mode_terms_[k] coefficients of a mode are ever written or read.
      modal_coefficients_(kModalMaxTerms, 2 * n_),
      generator_(Eigen::VectorXd::Zero(kGeneratorSize)),
      Y_(Eigen::MatrixXd::Zero(n_, 6)),
      eta_(Eigen::VectorXd::Zero(n_)),
      deta_(Eigen::VectorXd::Zero(n_)),
      z_scratch_(Eigen::VectorXd::Zero(n_aug)),
      series_(Eigen::VectorXd::Zero(2 * n_)),
      mode_terms_(static_cast<std::size_t>(n_), 0),
      mode_rho_(static_cast<std::size_t>(n_), std::numeric_limits<double>::quiet_NaN()) {}

void FreeDenseOutput::Build(const LinearFlow& flow, double omega_radps,
                            const Eigen::Ref<const Eigen::VectorXd>& z0, double tau_max_s) {
  SB_DEMAND(n_aug_ == z0.size(), "FreeDenseOutput: wrong state size");
  flow_ = &flow;
  omega_radps_ = omega_radps;
  modal_ = false;
  series_tau_s_[0] = series_tau_s_[1] = std::numeric_limits<double>::quiet_NaN();
  int modal_terms = 0;
  if (flow.modal()) {
    // Each mode's rho once: the test of the modal path, and the mode's term count (that of its
    // last rho when it is the same: the steps of one length). A count kept for a rho past the
    // radius is ModalTermCount's, read only when the same rho comes again.
    const ModalFlow& modal = flow.modal_flow();
    double rho_max = 0.0;
    for (int k = 0; k < n_; ++k) {
      const double rho =
          tau_max_s * (std::sqrt(modal.w2()[k]) + std::abs(modal.c()[k]) + std::abs(omega_radps));
      rho_max = std::max(rho_max, rho);
      const auto ki = static_cast<std::size_t>(k);
      if (!(rho == mode_rho_[ki])) {
        mode_terms_[ki] = ModalTermCount(rho);
        mode_rho_[ki] = rho;
      }
      modal_terms = std::max(modal_terms, mode_terms_[ki]);
    }
    modal_ = rho_max <= kModalSeriesRadius;
  }
  if (modal_) {
    const ModalFlow& modal = flow.modal_flow();
    phi_ = modal.Phi().data();
    if (n_ == 3) {
      modal.ToModal3(z0.data(), Y_.data(), true);  // ToModal's deck path (Y_ is 3 x 6)
    } else {
      modal.ToModal(z0, Y_);
    }
    generator_ = z0.tail(kGeneratorSize);
    terms_ = modal_terms;
    modal.AllModeCoefficients(omega_radps, Y_, mode_terms_.data(), modal_coefficients_.data(),
                              modal_coefficients_.col(n_).data(), modal_coefficients_.rows());
    return;
  }
  if (coefficients_.cols() != max_terms_) {
    // The augmented series' storage, on first use: a modal flow never needs it for the
    // integrator's steps (they stay inside the modal series' radius).
    coefficients_.resize(n_aug_, max_terms_);
    largest_.resize(n_aug_);
  }
  const int max_terms = max_terms_;
  coefficients_.col(0) = z0;
  largest_ = z0.cwiseAbs();
  // Per component, stop once two successive terms are below round-off of the largest so far.
  int quiet = 0;
  terms_ = 1;
  double power = 1.0;
  for (int k = 1; k < max_terms; ++k) {
    flow.Derivative(omega_radps, coefficients_.col(k - 1), coefficients_.col(k));
    coefficients_.col(k) /= static_cast<double>(k);
    terms_ = k + 1;
    power *= tau_max_s;
    bool small = true;
    for (int i = 0; i < z0.size(); ++i) {
      const double term = std::abs(coefficients_(i, k)) * power;
      small = small && term <= 1e-17 * largest_[i] + 1e-300;
      largest_[i] = std::max(largest_[i], term);
    }
    quiet = small ? quiet + 1 : 0;
    if (quiet >= 2) {
      break;
    }
  }
}

namespace {

// Horner on `terms` contiguous coefficients.
inline double Horner(const double* c, int terms, double tau) {
  double x = c[terms - 1];
  for (int m = terms - 2; m >= 0; --m) {
    x = x * tau + c[m];
  }
  return x;
}

// Horner on two series at once (ta and tb terms), each with Horner's operations in Horner's
// order, so the same bits as two calls; the independent chains overlap in the processor.
inline void Horner2(const double* a, int ta, const double* b, int tb, double tau, double& x_a,
                    double& x_b) {
  double xa = a[ta - 1], xb = b[tb - 1];
  int ma = ta - 2, mb = tb - 2;
  for (; ma > mb; --ma) xa = xa * tau + a[ma];
  for (; mb > ma; --mb) xb = xb * tau + b[mb];
  for (; ma >= 0; --ma) {
    xa = xa * tau + a[ma];
    xb = xb * tau + b[ma];
  }
  x_a = xa;
  x_b = xb;
}

// Horner on three series at once, as Horner2.
inline void Horner3(const double* const c[3], const int t[3], double tau, double x[3]) {
  double x0 = c[0][t[0] - 1], x1 = c[1][t[1] - 1], x2 = c[2][t[2] - 1];
  const int common = std::min({t[0], t[1], t[2]});
  // The longer series first, down to the common length, then the three together.
  for (int m = t[0] - 2; m >= common - 1; --m) x0 = x0 * tau + c[0][m];
  for (int m = t[1] - 2; m >= common - 1; --m) x1 = x1 * tau + c[1][m];
  for (int m = t[2] - 2; m >= common - 1; --m) x2 = x2 * tau + c[2][m];
  for (int m = common - 2; m >= 0; --m) {
    x0 = x0 * tau + c[0][m];
    x1 = x1 * tau + c[1][m];
    x2 = x2 * tau + c[2][m];
  }
  x[0] = x0;
  x[1] = x1;
  x[2] = x2;
}

// Horner on kCount modes' series of eta and eta' at once, each mode's pair (eta_k, eta_k') in
// the two lanes of one operand: mode j's series at c_eta[j] and c_deta[j], t[j] terms each (the
// same for both). Each lane runs Horner's operations in Horner's order, so the same bits as
// Horner on each series; the longer series first, down to the common length, then all together.
template <int kCount>
inline void HornerPairs(const double* const (&c_eta)[kCount], const double* const (&c_deta)[kCount],
                        const int (&t)[kCount], double tau, double* eta, double* deta) {
  using detail::Lanes2;
  const Lanes2 tt = {tau, tau};
  Lanes2 x[kCount];
  int common = t[0];
  for (int j = 0; j < kCount; ++j) {
    x[j] = Lanes2{c_eta[j][t[j] - 1], c_deta[j][t[j] - 1]};
    common = std::min(common, t[j]);
  }
  for (int j = 0; j < kCount; ++j) {
    for (int m = t[j] - 2; m >= common - 1; --m) {
      x[j] = x[j] * tt + Lanes2{c_eta[j][m], c_deta[j][m]};
    }
  }
  for (int m = common - 2; m >= 0; --m) {
    for (int j = 0; j < kCount; ++j) x[j] = x[j] * tt + Lanes2{c_eta[j][m], c_deta[j][m]};
  }
  for (int j = 0; j < kCount; ++j) {
    eta[j] = x[j][0];
    deta[j] = x[j][1];
  }
}

}  // namespace

void FreeDenseOutput::ModalAt(double tau_s, bool velocities) {
  const Eigen::Index stride = modal_coefficients_.rows();
  const double* c = modal_coefficients_.data();
  if (velocities) {
    // eta_k and eta_k' have the same number of terms: one loop, two independent chains.
    for (int k = 0; k < n_; ++k) {
      const int terms = mode_terms_[static_cast<std::size_t>(k)];
      Horner2(c + k * stride, terms, c + (n_ + k) * stride, terms, tau_s, eta_[k], deta_[k]);
    }
    return;
  }
  int k = 0;
  if (n_ % 2 == 1 && n_ >= 3) {
    // An odd count (a deck's 3 modes): the first three in one loop, the rest in pairs.
    const double* const series[3] = {c, c + stride, c + 2 * stride};
    const int terms[3] = {mode_terms_[0], mode_terms_[1], mode_terms_[2]};
    Horner3(series, terms, tau_s, eta_.data());
    k = 3;
  }
  for (; k + 1 < n_; k += 2) {
    Horner2(c + k * stride, mode_terms_[static_cast<std::size_t>(k)], c + (k + 1) * stride,
            mode_terms_[static_cast<std::size_t>(k + 1)], tau_s, eta_[k], eta_[k + 1]);
  }
  if (k < n_) {
    eta_[k] = Horner(c + k * stride, mode_terms_[static_cast<std::size_t>(k)], tau_s);
  }
}

void FreeDenseOutput::DeckSeriesAt(double tau_s, bool velocities) const {
  const Eigen::Index stride = modal_coefficients_.rows();
  const double* c = modal_coefficients_.data();
  double* h = series_.data();
  const double* const ce[3] = {c, c + stride, c + 2 * stride};
  const double* const cd[3] = {c + 3 * stride, c + 4 * stride, c + 5 * stride};
  const int t[3] = {mode_terms_[0], mode_terms_[1], mode_terms_[2]};
  if (!velocities || series_tau_s_[1] == tau_s) {
    // eta's series alone are missing.
    Horner3(ce, t, tau_s, h);
    series_tau_s_[0] = tau_s;
  } else if (series_tau_s_[0] == tau_s) {
    // eta''s alone.
    Horner3(cd, t, tau_s, h + 3);
    series_tau_s_[1] = tau_s;
  } else {
    HornerPairs<3>(ce, cd, t, tau_s, h, h + 3);
    series_tau_s_[0] = series_tau_s_[1] = tau_s;
  }
}

void FreeDenseOutput::GeneratorAt(double tau_s, Eigen::Ref<Eigen::VectorXd> z) const {
  const int ia = 2 * n_;
  z.segment<2>(ia) = generator_.segment<2>(0) + tau_s * generator_.segment<2>(2);
  z.segment<2>(ia + 2) = generator_.segment<2>(2);
  double co, si;
  LibraryCosSin(omega_radps_ * tau_s, co, si);
  z.segment<2>(ia + 4) = co * generator_.segment<2>(4) + si * generator_.segment<2>(6);
  z.segment<2>(ia + 6) = -si * generator_.segment<2>(4) + co * generator_.segment<2>(6);
}

void FreeDenseOutput::Evaluate(double tau_s, Eigen::Ref<Eigen::VectorXd> z) {
  if (modal_) {
    if (n_ == 3) {
      DeckHead(tau_s, 6, z.data());
      GeneratorAt(tau_s, z);
      return;
    }
    ModalAt(tau_s, true);
    ModalProduct(flow_->modal_flow().Phi(), n_, eta_.data(), deta_.data(), z.data(), z.data() + n_);
    GeneratorAt(tau_s, z);
    return;
  }
  EvaluateHead(tau_s, n_aug_, z);
}

void FreeDenseOutput::EvaluateHead(double tau_s, int count, Eigen::Ref<Eigen::VectorXd> z) {
  SB_ASSERT(count <= n_aug_ && z.size() >= count, "FreeDenseOutput: bad count");
  if (modal_) {
    if (n_ == 3 && count <= 6) {
      DeckHead(tau_s, count, z.data());
      return;
    }
    const Eigen::MatrixXd& Phi = flow_->modal_flow().Phi();
    if (count > 2 * n_) {
      Evaluate(tau_s, z_scratch_);
      z.head(count) = z_scratch_.head(count);
    } else if (count == 2 * n_) {
      ModalAt(tau_s, true);
      ModalProduct(Phi, n_, eta_.data(), deta_.data(), z.data(), z.data() + n_);
    } else if (count > n_) {
      ModalAt(tau_s, true);
      ModalProduct(Phi, n_, eta_.data(), nullptr, z.data(), nullptr);
      ModalProduct(Phi, count - n_, deta_.data(), nullptr, z.data() + n_, nullptr);
    } else {
      ModalAt(tau_s, false);
      ModalProduct(Phi, count, eta_.data(), nullptr, z.data(), nullptr);
    }
    return;
  }
  // Horner on the raw columns: the hot path of event location and partial steps.
  const Eigen::Index n = count;
  const Eigen::Index stride = coefficients_.rows();
  const double* c = coefficients_.data();
  double* out = z.data();
  const double* last = c + (terms_ - 1) * stride;
  for (Eigen::Index i = 0; i < n; ++i) out[i] = last[i];
  for (int k = terms_ - 2; k >= 0; --k) {
    const double* ck = c + k * stride;
    for (Eigen::Index i = 0; i < n; ++i) out[i] = out[i] * tau_s + ck[i];
  }
}

double FreeDenseOutput::EvaluateComponentAt(double tau_s, int i) const {
  SB_ASSERT(i >= 0 && i < n_aug_, "FreeDenseOutput: bad component");
  if (modal_) {
    if (i < 2 * n_) {
      // The modes' series at tau, once per instant and half: the components at the same
      // instant take them inline. A deck sums this component's half alone (a velocity root's
      // search reads velocities only; EvaluateComponents sums both halves for a corner's rate),
      // more modes both halves at once.
      const Eigen::Index stride = modal_coefficients_.rows();
      const double* c = modal_coefficients_.data();
      double* h = series_.data();
      if (n_ == 3) {
        // A deck: the series of this component's half alone (a velocity root's search reads
        // velocities only; EvaluateComponents sums both halves for a corner's rate).
        const int half = i < n_ ? 0 : 1;
        const double* const cs[3] = {c + 3 * half * stride, c + (3 * half + 1) * stride,
                                     c + (3 * half + 2) * stride};
        const int t[3] = {mode_terms_[0], mode_terms_[1], mode_terms_[2]};
        Horner3(cs, t, tau_s, h + 3 * half);
        series_tau_s_[half] = tau_s;
        return ModalComponent(i - half * n_, half);
      }
      for (int k = 0; k < n_; ++k) {
        const double* const ce[1] = {c + k * stride};
        const double* const cd[1] = {c + (n_ + k) * stride};
        const int t[1] = {mode_terms_[static_cast<std::size_t>(k)]};
        HornerPairs<1>(ce, cd, t, tau_s, h + k, h + n_ + k);
      }
      series_tau_s_[0] = series_tau_s_[1] = tau_s;
      const int half = i < n_ ? 0 : 1;
      return ModalComponent(i - half * n_, half);
    }
    const int j = i - 2 * n_;
    double co, si;
    LibraryCosSin(omega_radps_ * tau_s, co, si);
    switch (j / 2) {
      case 0:
        return generator_[j] + tau_s * generator_[j + 2];
      case 1:
        return generator_[j];
      case 2:
        return co * generator_[j] + si * generator_[j + 2];
      default:
        return -si * generator_[j - 2] + co * generator_[j];
    }
  }
  double z = coefficients_(i, terms_ - 1);
  for (int k = terms_ - 2; k >= 0; --k) {
    z = z * tau_s + coefficients_(i, k);
  }
  return z;
}

void FreeDenseOutput::EvaluateDerivative(double tau_s, Eigen::Ref<Eigen::VectorXd> dz) {
  if (modal_) {
    Evaluate(tau_s, z_scratch_);
    flow_->Derivative(omega_radps_, z_scratch_, dz);
    return;
  }
  dz.setZero();
  for (int k = terms_ - 1; k >= 1; --k) {
    dz = dz * tau_s + coefficients_.col(k) * static_cast<double>(k);
  }
}

}  // namespace skewbridge::dynamics
