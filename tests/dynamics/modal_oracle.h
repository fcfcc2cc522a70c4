#pragma once
// Independent oracle for contact-free runs: modal superposition with closed forms per mode for
// a forcing F0 + F1 t + Fc cos(W t) + Fs sin(W t) on each excitation piece (classical damping).

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include "solver/common/excitation.h"

namespace skewbridge::dynamics::testing {

// eta'' + 2 xi w eta' + w^2 eta = F0 + F1 t + Fc cos(W t) + Fs sin(W t), 0 < w, 0 <= xi < 1.
inline void ModalResponse(double w, double xi, double F0, double F1, double Fc, double Fs, double W,
                          double eta0, double deta0, double t, double& eta, double& deta) {
  const double B = F1 / (w * w), A = (F0 - 2.0 * xi * w * B) / (w * w);
  double P = 0.0, Q = 0.0;
  if (W != 0.0) {
    const double a = w * w - W * W, b = 2.0 * xi * w * W, det = a * a + b * b;
    P = (a * Fc - b * Fs) / det;
    Q = (b * Fc + a * Fs) / det;
  }
  const double wd = w * std::sqrt(1.0 - xi * xi);
  const double h0 = eta0 - (A + P), dh0 = deta0 - (B + W * Q);
  const double c1 = h0, c2 = (dh0 + xi * w * h0) / wd;
  const double decay = std::exp(-xi * w * t), cs = std::cos(wd * t), sn = std::sin(wd * t);
  eta = decay * (c1 * cs + c2 * sn) + A + B * t + P * std::cos(W * t) + Q * std::sin(W * t);
  deta = decay * ((-xi * w * c1 + wd * c2) * cs + (-xi * w * c2 - wd * c1) * sn) + B -
         W * P * std::sin(W * t) + W * Q * std::cos(W * t);
}

// The response of M q'' + C q' + K q = -M r a_g(t), C classical with ratio xi, from (q0, u0) at
// t = 0, through the pieces of an excitation.
class ModalOracle {
 public:
  ModalOracle(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, double xi,
              const Eigen::MatrixXd& r)
      : M_(M), r_(r), xi_(xi) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
    phi_ = eig.eigenvectors();
    omega_ = eig.eigenvalues().cwiseSqrt();
  }

  void At(const Excitation& ex, const Eigen::VectorXd& q0, const Eigen::VectorXd& u0, double t,
          Eigen::VectorXd& q, Eigen::VectorXd& u) const {
    const int n = static_cast<int>(q0.size());
    Eigen::VectorXd eta = phi_.transpose() * M_ * q0, deta = phi_.transpose() * M_ * u0;
    const Eigen::MatrixXd L = -phi_.transpose() * M_ * r_;
    double s = 0.0;
    while (s < t) {
      const ExcitationPiece p = ex.PieceAt(s);
      const double end = std::min(p.t_end, t);
      const double tau0 = s - p.t_begin, tau = end - s;
      // Re-express the piece's forcing in the local time from s.
      const Eigen::Vector2d a0 = p.a_begin + p.slope * tau0;
      Eigen::Vector2d c = Eigen::Vector2d::Zero(), sn = Eigen::Vector2d::Zero();
      if (p.omega != 0.0) {
        c = p.cos_amplitude * std::cos(p.omega * tau0) + p.sin_amplitude * std::sin(p.omega * tau0);
        sn = -p.cos_amplitude * std::sin(p.omega * tau0) +
             p.sin_amplitude * std::cos(p.omega * tau0);
      }
      for (int k = 0; k < n; ++k) {
        double e, de;
        ModalResponse(omega_[k], xi_, L.row(k).dot(a0), L.row(k).dot(p.slope), L.row(k).dot(c),
                      L.row(k).dot(sn), p.omega, eta[k], deta[k], tau, e, de);
        eta[k] = e;
        deta[k] = de;
      }
      s = end;
    }
    q = phi_ * eta;
    u = phi_ * deta;
  }

 private:
  Eigen::MatrixXd M_, r_, phi_;
  Eigen::VectorXd omega_;
  double xi_;
};

}  // namespace skewbridge::dynamics::testing
