#pragma once
/// @file
/// The embedded Runge-Kutta pair of Dormand and Prince, 5(4), with its 4th-order continuous
/// extension (dense output) [Hairer, Norsett and Wanner 1993, §II.5 and §II.6, DOPRI5]. It
/// integrates the constrained smooth phases [docs/theory.md §3]; the integrator owns the step loop,
/// the error control and the event location, this class one step and its dense output.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace skewbridge::dynamics {

/// One Dormand-Prince 5(4) step with its error estimate and dense output; storage sized once.
class DormandPrince45 {
 public:
  /// Storage for systems of n equations.
  explicit DormandPrince45(int n = 0) { Resize(n); }

  /// Re-sizes the storage (allocates; call outside the time loop).
  void Resize(int n) {
    stages_.setZero(n, 7);
    y0_.setZero(n);
    y1_.setZero(n);
    work_.setZero(n);
    error_.setZero(n);
    dense_.setZero(n, 5);
  }

  int size() const { return static_cast<int>(y0_.size()); }

  /// Advances y' = f(t, y) from (t, y) with the derivative dy0 = f(t, y) by h (FSAL: the
  /// derivative at the end, dy_end(), serves the next step). f(t, y, dy) writes dy.
  template <class Rhs>
  void Step(Rhs&& f, double t, const Eigen::Ref<const Eigen::VectorXd>& y,
            const Eigen::Ref<const Eigen::VectorXd>& dy0, double h) {
    // clang-format off
    constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
    constexpr double a21 = 1.0 / 5;
    constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
    constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
    constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                     a54 = -212.0 / 729;
    constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247,
                     a64 = 49.0 / 176, a65 = -5103.0 / 18656;
    constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192,
                     a75 = -2187.0 / 6784, a76 = 11.0 / 84;
    constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920,
                     e5 = -17253.0 / 339200, e6 = 22.0 / 525, e7 = -1.0 / 40;
    constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                     d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                     d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
    // clang-format on
    t0_ = t;
    h_ = h;
    y0_ = y;
    auto k = [this](int i) { return stages_.col(i); };
    k(0) = dy0;
    work_ = y0_ + h * (a21 * k(0));
    f(t + c2 * h, work_, k(1));
    work_ = y0_ + h * (a31 * k(0) + a32 * k(1));
    f(t + c3 * h, work_, k(2));
    work_ = y0_ + h * (a41 * k(0) + a42 * k(1) + a43 * k(2));
    f(t + c4 * h, work_, k(3));
    work_ = y0_ + h * (a51 * k(0) + a52 * k(1) + a53 * k(2) + a54 * k(3));
    f(t + c5 * h, work_, k(4));
    work_ = y0_ + h * (a61 * k(0) + a62 * k(1) + a63 * k(2) + a64 * k(3) + a65 * k(4));
    f(t + h, work_, k(5));
    y1_ = y0_ + h * (a71 * k(0) + a73 * k(2) + a74 * k(3) + a75 * k(4) + a76 * k(5));
    f(t + h, y1_, k(6));
    error_ = h * (e1 * k(0) + e3 * k(2) + e4 * k(3) + e5 * k(4) + e6 * k(5) + e7 * k(6));
    dense_.col(0) = y0_;
    dense_.col(1) = y1_ - y0_;
    dense_.col(2) = h * k(0) - dense_.col(1);
    dense_.col(3) = dense_.col(1) - h * k(6) - dense_.col(2);
    dense_.col(4) = h * (d1 * k(0) + d3 * k(2) + d4 * k(3) + d5 * k(4) + d6 * k(5) + d7 * k(6));
  }

  /// The 5th-order solution at t + h of the last step.
  const Eigen::VectorXd& y_end() const { return y1_; }
  /// f(t + h, y_end()) (first stage of the next step).
  Eigen::Ref<const Eigen::VectorXd> dy_end() const { return stages_.col(6); }

  /// RMS of err_i / (atol_i + rtol max(|y0_i|, |y1_i|)): the step is accepted when <= 1.
  double ErrorNorm(const Eigen::Ref<const Eigen::VectorXd>& atol, double rtol) const {
    return ErrorNorm(atol, rtol, y0_.size());
  }
  /// As ErrorNorm, the mean taken over `count` entries: a state whose further entries ride along
  /// with an infinite absolute tolerance (their terms zero) then has the norm of its first
  /// `count` entries alone, bit for bit.
  double ErrorNorm(const Eigen::Ref<const Eigen::VectorXd>& atol, double rtol,
                   Eigen::Index count) const {
    double sum = 0.0;
    for (Eigen::Index i = 0; i < y0_.size(); ++i) {
      const double scale = atol[i] + rtol * std::max(std::abs(y0_[i]), std::abs(y1_[i]));
      const double e = error_[i] / scale;
      sum += e * e;
    }
    return std::sqrt(sum / static_cast<double>(std::max<Eigen::Index>(1, count)));
  }

  /// Dense output y(t0 + s h) for s in [0, 1] (4th order) [Hairer et al. 1993, §II.6].
  void Dense(double s, Eigen::Ref<Eigen::VectorXd> out) const {
    const double r = 1.0 - s;
    out = dense_.col(0) +
          s * (dense_.col(1) + r * (dense_.col(2) + s * (dense_.col(3) + r * dense_.col(4))));
  }

  /// Dense output at absolute time t in [t0, t0 + h].
  void DenseAt(double t, Eigen::Ref<Eigen::VectorXd> out) const { Dense((t - t0_) / h_, out); }

  /// The first `count` entries of DenseAt(t) (the same bits), into out.head(count): an event
  /// search on positions needs no velocities.
  void DenseHeadAt(double t, int count, Eigen::Ref<Eigen::VectorXd> out) const {
    const double s = (t - t0_) / h_, r = 1.0 - s;
    const auto d = dense_.topRows(count);
    out.head(count) = d.col(0) + s * (d.col(1) + r * (d.col(2) + s * (d.col(3) + r * d.col(4))));
  }

  /// Component i of the dense output at absolute time t.
  double DenseComponentAt(double t, int i) const {
    const double s = (t - t0_) / h_, r = 1.0 - s;
    return dense_(i, 0) +
           s * (dense_(i, 1) + r * (dense_(i, 2) + s * (dense_(i, 3) + r * dense_(i, 4))));
  }

  double t0() const { return t0_; }
  double h() const { return h_; }

  /// Step-size factor of the standard controller: 0.9 err^(-1/5), limited to [0.2, 5].
  static double StepFactor(double error_norm) {
    if (error_norm <= 0.0) {
      return 5.0;
    }
    return std::clamp(0.9 * std::pow(error_norm, -0.2), 0.2, 5.0);
  }

 private:
  Eigen::MatrixXd stages_;
  Eigen::VectorXd y0_, y1_, work_, error_;
  Eigen::MatrixXd dense_;
  double t0_ = 0.0;
  double h_ = 0.0;
};

}  // namespace skewbridge::dynamics
