#include "solver/dynamics/linear_flow.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <unsupported/Eigen/MatrixFunctions>

#include "solver/common/error.h"

namespace skewbridge::dynamics {
namespace {

constexpr std::size_t kCacheCapacity = 8;

}  // namespace

LinearFlow::LinearFlow(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::MatrixXd>& K,
                       const Eigen::Ref<const Eigen::MatrixXd>& C,
                       const Eigen::Ref<const Eigen::MatrixXd>& r)
    : n_(static_cast<int>(M.rows())), M_(M), K_(K), C_(C), r_(r) {
  SB_DEMAND(M.cols() == n_ && K.rows() == n_ && K.cols() == n_ && C.rows() == n_ &&
                C.cols() == n_ && r.rows() == n_ && r.cols() == 2,
            "LinearFlow: inconsistent matrix sizes");
  const Eigen::LLT<Eigen::MatrixXd> llt(M_);
  SB_DEMAND(llt.info() == Eigen::Success, "LinearFlow: M must be symmetric positive definite");
  Mr_ = M_ * r_;
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
}

Eigen::MatrixXd LinearFlow::AugmentedMatrix(double omega_radps) const {
  Eigen::MatrixXd A = A_base_;
  const int ip = 2 * n_ + 4, ik = 2 * n_ + 6;
  for (int i = 0; i < 2; ++i) {
    A(ip + i, ik + i) = omega_radps;
    A(ik + i, ip + i) = -omega_radps;
  }
  return A;
}

void LinearFlow::SetGenerator(const ExcitationPiece& piece, double t_s,
                              Eigen::Ref<Eigen::VectorXd> z) const {
  const double tau = t_s - piece.t_begin;
  const int ia = 2 * n_;
  z.segment<2>(ia) = piece.a_begin + piece.slope * tau;
  z.segment<2>(ia + 2) = piece.slope;
  if (piece.omega != 0.0) {
    // Matches ExcitationPiece::At, which ignores the harmonic part when omega = 0.
    const double c = std::cos(piece.omega * tau), s = std::sin(piece.omega * tau);
    z.segment<2>(ia + 4) = piece.cos_amplitude * c + piece.sin_amplitude * s;
    z.segment<2>(ia + 6) = -piece.cos_amplitude * s + piece.sin_amplitude * c;
  } else {
    z.segment<4>(ia + 4).setZero();
  }
}

void LinearFlow::Compute(double tau_s, double omega_radps, FreePropagator& out) const {
  const int N = augmented_size();
  const Eigen::MatrixXd A = AugmentedMatrix(omega_radps);
  out.tau_s = tau_s;
  out.omega_radps = omega_radps;
  // Van Loan: exp([[-A^T, Q], [0, A]] tau) = [[., G2], [0, e^{A tau}]] and
  // int_0^tau e^{A^T s} Q e^{A s} ds = e^{A tau}^T G2. Q is scaled to unit norm so that a heavy
  // deck does not inflate the norm that sets the scaling-and-squaring depth.
  const auto gram = [&](const Eigen::MatrixXd& Q, Eigen::MatrixXd& result, bool store_phi) {
    const double scale = std::max(Q.cwiseAbs().maxCoeff(), 1e-300);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * N, 2 * N);
    H.topLeftCorner(N, N) = -A.transpose() * tau_s;
    H.topRightCorner(N, N) = Q * (tau_s / scale);
    H.bottomRightCorner(N, N) = A * tau_s;
    const Eigen::MatrixXd E = H.exp();
    const Eigen::MatrixXd F3 = E.bottomRightCorner(N, N);
    const Eigen::MatrixXd G = F3.transpose() * E.topRightCorner(N, N) * scale;
    result = 0.5 * (G + G.transpose());
    if (store_phi) {
      out.phi = F3;
    }
  };
  gram(Q_input_, out.input_gram, true);
  gram(Q_damping_, out.damping_gram, false);
}

const FreePropagator& LinearFlow::Propagator(double tau_s, double omega_radps) {
  SB_DEMAND(tau_s > 0.0 && std::isfinite(tau_s), "LinearFlow: step must be positive");
  ++clock_;
  for (std::size_t i = 0; i < cache_.size(); ++i) {
    if (cache_[i].tau_s == tau_s && cache_[i].omega_radps == omega_radps) {
      last_use_[i] = clock_;
      return cache_[i];
    }
  }
  if (cache_.size() < kCacheCapacity) {
    cache_.emplace_back();
    last_use_.push_back(clock_);
    Compute(tau_s, omega_radps, cache_.back());
    return cache_.back();
  }
  // Least recently used: a record's nominal step and a pulse's pieces stay while the odd step
  // sizes (a piece's last step) come and go.
  const std::size_t slot = static_cast<std::size_t>(
      std::min_element(last_use_.begin(), last_use_.end()) - last_use_.begin());
  last_use_[slot] = clock_;
  Compute(tau_s, omega_radps, cache_[slot]);
  return cache_[slot];
}

void LinearFlow::Derivative(double omega_radps, const Eigen::Ref<const Eigen::VectorXd>& z,
                            Eigen::Ref<Eigen::VectorXd> dz) const {
  // A_hat is sparse by blocks: dq = u, du from the n dense rows, and the generator's own rows
  // (da = slope, dslope = 0, dp = omega k, dk = -omega p).
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
    : coefficients_(Eigen::MatrixXd::Zero(n_aug, max_terms)),
      largest_(Eigen::VectorXd::Zero(n_aug)) {}

void FreeDenseOutput::Build(const LinearFlow& flow, double omega_radps,
                            const Eigen::Ref<const Eigen::VectorXd>& z0, double tau_max_s) {
  SB_DEMAND(coefficients_.rows() == z0.size(), "FreeDenseOutput: wrong state size");
  const int max_terms = static_cast<int>(coefficients_.cols());
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

void FreeDenseOutput::Evaluate(double tau_s, Eigen::Ref<Eigen::VectorXd> z) const {
  EvaluateHead(tau_s, static_cast<int>(coefficients_.rows()), z);
}

void FreeDenseOutput::EvaluateHead(double tau_s, int count, Eigen::Ref<Eigen::VectorXd> z) const {
  SB_ASSERT(count <= coefficients_.rows() && z.size() >= count, "FreeDenseOutput: bad count");
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

double FreeDenseOutput::EvaluateComponent(double tau_s, int i) const {
  SB_ASSERT(i >= 0 && i < coefficients_.rows(), "FreeDenseOutput: bad component");
  double z = coefficients_(i, terms_ - 1);
  for (int k = terms_ - 2; k >= 0; --k) {
    z = z * tau_s + coefficients_(i, k);
  }
  return z;
}

void FreeDenseOutput::EvaluateDerivative(double tau_s, Eigen::Ref<Eigen::VectorXd> dz) const {
  dz.setZero();
  for (int k = terms_ - 1; k >= 1; --k) {
    dz = dz * tau_s + coefficients_.col(k) * static_cast<double>(k);
  }
}

}  // namespace skewbridge::dynamics
