#include "solver/dynamics/linear_flow.h"

#include "tests/dynamics/modal_oracle.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace skewbridge::dynamics::linear_flow_test {
namespace {

// A coupled 3-DOF deck-like system; modal superposition with closed forms per mode is the oracle.
struct TestSystem {
  Eigen::MatrixXd M, K, C, r, Phi;
  Eigen::VectorXd omega;
  double xi;

  explicit TestSystem(double damping_ratio) : xi(damping_ratio) {
    M = Eigen::Vector3d(1200.0, 1200.0, 1200.0 * 35.0).asDiagonal();
    K.resize(3, 3);
    // clang-format off
    K << 5.0e4, 8.0e3, -2.0e4,
         8.0e3, 6.5e4,  3.0e4,
        -2.0e4, 3.0e4,  2.9e6;
    // clang-format on
    r.resize(3, 2);
    r << 1.0, 0.0, 0.0, 1.0, 0.05, -0.02;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
    Phi = eig.eigenvectors();  // mass-normalised: Phi^T M Phi = I
    omega = eig.eigenvalues().cwiseSqrt();
    const Eigen::VectorXd c_modal = 2.0 * xi * omega;
    C = M * Phi * c_modal.asDiagonal() * Phi.transpose() * M;
  }
};

// Response of eta'' + 2 xi w eta' + w^2 eta = F0 + F1 t + Fc cos(W t) + Fs sin(W t).
struct ModalClosedForm {
  double w, xi, F0, F1, Fc, Fs, W, eta0, deta0;

  // The closed form lives in modal_oracle.h, shared with the integrator tests.
  void Evaluate(double t, double& eta, double& deta) const {
    testing::ModalResponse(w, xi, F0, F1, Fc, Fs, W, eta0, deta0, t, eta, deta);
  }
};

struct ModalSolution {
  const TestSystem& sys;
  std::vector<ModalClosedForm> modes;

  ModalSolution(const TestSystem& s, const ExcitationPiece& piece, const Eigen::Vector3d& q0,
                const Eigen::Vector3d& u0)
      : sys(s) {
    const Eigen::MatrixXd L = -sys.Phi.transpose() * sys.M * sys.r;  // modal participation
    const Eigen::VectorXd eta0 = sys.Phi.transpose() * sys.M * q0;
    const Eigen::VectorXd deta0 = sys.Phi.transpose() * sys.M * u0;
    for (int k = 0; k < 3; ++k) {
      modes.push_back({sys.omega[k], sys.xi, L.row(k).dot(piece.a_begin), L.row(k).dot(piece.slope),
                       L.row(k).dot(piece.cos_amplitude), L.row(k).dot(piece.sin_amplitude),
                       piece.omega, eta0[k], deta0[k]});
    }
  }

  void At(double tau, Eigen::Vector3d& q, Eigen::Vector3d& u) const {
    Eigen::Vector3d eta, deta;
    for (int k = 0; k < 3; ++k) {
      modes[k].Evaluate(tau, eta[k], deta[k]);
    }
    q = sys.Phi * eta;
    u = sys.Phi * deta;
  }
};

ExcitationPiece TestPiece(double omega) {
  ExcitationPiece piece;
  piece.t_begin = 0.2;
  piece.t_end = 10.0;
  piece.a_begin = {0.7, -0.3};
  piece.slope = {1.5, 0.4};
  piece.omega = omega;
  if (omega != 0.0) {
    piece.cos_amplitude = {0.9, 0.2};
    piece.sin_amplitude = {-0.4, 1.1};
  }
  return piece;
}

class LinearFlowAgainstModalSuperposition
    : public ::testing::TestWithParam<std::tuple<double, double, FlowPath>> {};

TEST_P(LinearFlowAgainstModalSuperposition, StepsDenseOutputAndEnergyIntegralsMatch) {
  const auto [xi, omega_g, path] = GetParam();
  const TestSystem sys(xi);
  LinearFlow flow(sys.M, sys.K, sys.C, sys.r, path);
  EXPECT_EQ(flow.modal(), path == FlowPath::kAuto);
  const ExcitationPiece piece = TestPiece(omega_g);
  const Eigen::Vector3d q0(0.012, -0.004, 0.0007), u0(-0.05, 0.09, -0.002);
  const ModalSolution exact(sys, piece, q0, u0);

  const int n_aug = flow.augmented_size();
  Eigen::VectorXd z(n_aug), z_next(n_aug);
  z.head(3) = q0;
  z.segment(3, 3) = u0;
  const double h = 0.05, t0 = piece.t_begin;
  flow.SetGenerator(piece, t0, z);
  double input_J = 0.0, damping_J = 0.0;
  const double energy0 = flow.MechanicalEnergy(z);
  FreeDenseOutput dense(n_aug);
  Eigen::VectorXd z_dense(n_aug);
  double worst_dense = 0.0, scale_q = 0.0, scale_u = 0.0, worst_q = 0.0, worst_u = 0.0;
  for (int step = 0; step < 40; ++step) {
    const FreePropagator& p = flow.Propagator(h, piece.omega);
    double input_step = 0.0, damping_step = 0.0;
    flow.StepEnergy(p, z, input_step, damping_step);
    input_J += input_step;
    damping_J += damping_step;
    dense.Build(flow, piece.omega, z, h);
    dense.Evaluate(0.37 * h, z_dense);
    Eigen::Vector3d q, u;
    exact.At(step * h + 0.37 * h, q, u);
    worst_dense = std::max(worst_dense, (z_dense.head(3) - q).cwiseAbs().maxCoeff());
    flow.Apply(p, z, z_next);
    z = z_next;
    exact.At((step + 1) * h, q, u);
    scale_q = std::max(scale_q, q.cwiseAbs().maxCoeff());
    scale_u = std::max(scale_u, u.cwiseAbs().maxCoeff());
    worst_q = std::max(worst_q, (z.head(3) - q).cwiseAbs().maxCoeff());
    worst_u = std::max(worst_u, (z.segment(3, 3) - u).cwiseAbs().maxCoeff());
    // The generator must reproduce the excitation at the step end.
    const Eigen::Vector2d ag = z.segment<2>(6) + z.segment<2>(10);
    ASSERT_LT((ag - piece.At(t0 + (step + 1) * h)).norm(), 1e-12);
  }
  EXPECT_LT(worst_q, 1e-9 * scale_q);
  EXPECT_LT(worst_u, 1e-9 * scale_u);
  EXPECT_LT(worst_dense, 1e-9 * scale_q);

  // Energy integrals against Gauss-Legendre quadrature of the modal solution.
  const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                        0.9061798459386640};
  const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                        0.4786286704993665, 0.2369268850561891};
  double input_ref = 0.0, damping_ref = 0.0;
  const int panels = 400;
  const double T = 40 * h, dt = T / panels;
  for (int i = 0; i < panels; ++i) {
    for (int j = 0; j < 5; ++j) {
      const double tau = (i + 0.5) * dt + 0.5 * dt * gx[j];
      Eigen::Vector3d q, u;
      exact.At(tau, q, u);
      const Eigen::Vector2d ag = piece.At(t0 + tau);
      input_ref += 0.5 * dt * gw[j] * (-u.dot(sys.M * sys.r * ag));
      damping_ref += 0.5 * dt * gw[j] * u.dot(sys.C * u);
    }
  }
  EXPECT_NEAR(input_J, input_ref, 1e-9 * std::abs(input_ref));
  if (xi > 0.0) {
    EXPECT_NEAR(damping_J, damping_ref, 1e-9 * std::abs(damping_ref));
  } else {
    EXPECT_LT(std::abs(damping_J), 1e-14 * std::abs(input_J));
  }
  // The ledger closes: E(T) - E(0) = input - damping.
  EXPECT_NEAR(flow.MechanicalEnergy(z) - energy0, input_J - damping_J, 1e-10 * std::abs(input_J));
}

INSTANTIATE_TEST_SUITE_P(
    RampAndHarmonic, LinearFlowAgainstModalSuperposition,
    ::testing::Combine(::testing::Values(0.05, 0.0, 0.3), ::testing::Values(0.0, 5.3, 11.0),
                       ::testing::Values(FlowPath::kAuto, FlowPath::kAugmented)));

TEST(LibraryCosSin, IsTheBitsOfStdCosAndSin) {
  // Both zeros (sin keeps the sign), the smallest subnormals, small, large, huge and NaN angles:
  // the shortcut at zero must be the library's own values there, and every other angle the
  // library's.
  std::vector<double> angles = {0.0,
                                -0.0,
                                std::numeric_limits<double>::denorm_min(),
                                -std::numeric_limits<double>::denorm_min(),
                                1e-300,
                                1e-8,
                                -0.5,
                                3.141592653589793,
                                1e22,
                                -std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::quiet_NaN()};
  for (int i = 0; i < 1000; ++i) angles.push_back(std::ldexp(std::sin(1.0 + i), (i % 80) - 60));
  for (const double x : angles) {
    double c = 7.0, s = 7.0;
    LibraryCosSin(x, c, s);
    const double lc = std::cos(x), ls = std::sin(x);
    std::uint64_t bc, bs, blc, bls;
    std::memcpy(&bc, &c, sizeof c);
    std::memcpy(&bs, &s, sizeof s);
    std::memcpy(&blc, &lc, sizeof lc);
    std::memcpy(&bls, &ls, sizeof ls);
    EXPECT_EQ(bc, blc) << x;
    EXPECT_EQ(bs, bls) << x;
  }
}

TEST(LinearFlow, CachesOnePropagatorPerStepSize) {
  const TestSystem sys(0.05);
  LinearFlow flow(sys.M, sys.K, sys.C, sys.r, FlowPath::kAugmented);
  const FreePropagator* first = &flow.Propagator(0.01, 0.0);
  const FreePropagator* again = &flow.Propagator(0.01, 0.0);
  EXPECT_EQ(first, again);
  const FreePropagator& other = flow.Propagator(0.02, 0.0);
  // e^{A 2h} = (e^{A h})^2: an independent check of the exponential.
  const FreePropagator& single = flow.Propagator(0.01, 0.0);
  const Eigen::MatrixXd squared = single.phi * single.phi;
  EXPECT_LT((other.phi - squared).cwiseAbs().maxCoeff(), 1e-12 * squared.cwiseAbs().maxCoeff());
}

// The bits of two matrices are the same (NaNs by their bits too).
bool SameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

// Expects `refitted` and `fresh` to be the same flow: the modal transforms, and the transition
// and end state of a step at each (tau, omega), from the same state.
void ExpectSameFlow(LinearFlow& refitted, LinearFlow& fresh) {
  ASSERT_EQ(refitted.modal(), fresh.modal());
  if (fresh.modal()) {
    const ModalFlow& a = refitted.modal_flow();
    const ModalFlow& b = fresh.modal_flow();
    EXPECT_TRUE(SameBits(a.w2(), b.w2()));
    EXPECT_TRUE(SameBits(a.c(), b.c()));
    EXPECT_TRUE(SameBits(a.Phi(), b.Phi()));
    EXPECT_TRUE(SameBits(a.PhiTM(), b.PhiTM()));
    EXPECT_TRUE(SameBits(a.negL(), b.negL()));
  }
  const ExcitationPiece piece = TestPiece(5.3);
  for (const double tau : {0.01, 0.013, 0.02}) {
    for (const double omega : {0.0, piece.omega}) {
      const FreePropagator& p = refitted.Propagator(tau, omega, true);
      const FreePropagator& q = fresh.Propagator(tau, omega, true);
      // The path's own members (a kept entry may hold the other path's from before).
      if (fresh.modal()) {
        EXPECT_TRUE(SameBits(p.modal_rows, q.modal_rows));
        EXPECT_TRUE(SameBits(p.record_pairs, q.record_pairs));
        EXPECT_TRUE(SameBits(p.modal_input, q.modal_input));
      } else {
        EXPECT_TRUE(SameBits(p.phi, q.phi));
        EXPECT_TRUE(SameBits(p.input_gram, q.input_gram));
      }
      Eigen::VectorXd z = Eigen::VectorXd::Zero(fresh.augmented_size());
      z.head(3) << 0.01, -0.02, 0.003;
      z.segment(3, 3) << 0.1, 0.05, -0.01;
      fresh.SetGenerator(piece, 0.3, z);
      Eigen::VectorXd za(z.size()), zb(z.size());
      double ia = 0.0, da = 0.0, ib = 0.0, db = 0.0;
      refitted.Apply(refitted.Propagator(tau, omega, true), z, za, &ia, &da);
      fresh.Apply(fresh.Propagator(tau, omega, true), z, zb, &ib, &db);
      EXPECT_TRUE(SameBits(za, zb)) << "tau " << tau << " omega " << omega;
      EXPECT_EQ(ia, ib);
      EXPECT_EQ(da, db);
    }
  }
}

TEST(LinearFlow, ARefittedFlowIsTheBitsOfANewOne) {
  // A flow used for one system (its cache full and cycling) and refitted to others in turn:
  // classical with other matrices, not classical (the augmented path), classical again. Each
  // time every transform and propagator is a new flow's, none of the last system's.
  const TestSystem first(0.05), second(0.3);
  LinearFlow flow(first.M, first.K, first.C, first.r);
  for (int i = 1; i <= 12; ++i) flow.Propagator(0.001 * i, 0.0);
  flow.Propagator(0.01, 5.3);
  flow.Refit(second.M, second.K, second.C, second.r);
  LinearFlow fresh_second(second.M, second.K, second.C, second.r);
  ExpectSameFlow(flow, fresh_second);

  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, 3);
  C(0, 0) = 50.0;
  C(0, 1) = C(1, 0) = 20.0;
  LinearFlow fresh_general(first.M, first.K, C, first.r);
  ASSERT_FALSE(fresh_general.modal());
  flow.Refit(first.M, first.K, C, first.r);
  ExpectSameFlow(flow, fresh_general);

  flow.Refit(first.M, first.K, first.C, first.r);
  LinearFlow fresh_first(first.M, first.K, first.C, first.r);
  ExpectSameFlow(flow, fresh_first);
}

TEST(LinearFlow, ModalStepOfTwoHIsTwoStepsOfH) {
  // The modal path's semigroup property, on a state with every forcing term.
  const TestSystem sys(0.05);
  LinearFlow flow(sys.M, sys.K, sys.C, sys.r);
  ASSERT_TRUE(flow.modal());
  const ExcitationPiece piece = TestPiece(5.3);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(flow.augmented_size());
  z.head(3) << 0.01, -0.02, 0.003;
  z.segment(3, 3) << 0.1, 0.05, -0.01;
  flow.SetGenerator(piece, 0.3, z);
  Eigen::VectorXd once(z.size()), twice(z.size()), half(z.size());
  flow.Apply(flow.Propagator(0.02, piece.omega), z, once);
  flow.Apply(flow.Propagator(0.01, piece.omega), z, half);
  flow.Apply(flow.Propagator(0.01, piece.omega), half, twice);
  EXPECT_LT((once - twice).head(6).cwiseAbs().maxCoeff(),
            1e-13 * once.head(6).cwiseAbs().maxCoeff());
}

// A deck's dense output read in any order (positions, states, single components, a corner
// rate's four, whole states, at instants met before or not) gives at every read the bits of the
// definition: per mode Horner's rule on ModalFlow::ModeCoefficients' series, then q = Phi eta and u
// = Phi eta' summed in mode order from 0.0.
TEST(FreeDenseOutput, ADecksReadsInAnyOrderAreHornerThenPhi) {
  const TestSystem sys(0.05);
  for (const double omega : {0.0, 9.0}) {
    LinearFlow flow(sys.M, sys.K, sys.C, sys.r);
    ASSERT_TRUE(flow.modal());
    const ModalFlow& modal = flow.modal_flow();
    const int N = flow.augmented_size();
    Eigen::VectorXd z0(N);
    z0.head(6) << 0.012, -0.007, 0.0031, 0.21, 0.05, -0.017;
    flow.SetGenerator(TestPiece(omega), 0.45, z0);
    const double tau_max = 0.02;
    FreeDenseOutput dense(N);
    dense.Build(flow, omega, z0, tau_max);
    // The definition, from the modes' own series.
    Eigen::MatrixXd Y(3, 6);
    modal.ToModal(z0, Y);
    std::vector<std::vector<double>> eta(3), deta(3);
    for (int k = 0; k < 3; ++k) {
      const double rho =
          tau_max * (std::sqrt(modal.w2()[k]) + std::abs(modal.c()[k]) + std::abs(omega));
      const int terms = ModalTermCount(rho);
      eta[k].resize(terms);
      deta[k].resize(terms);
      const Eigen::Matrix<double, 6, 1> y = Y.row(k).transpose();
      modal.ModeCoefficients(k, omega, y.data(), terms, eta[k].data(), deta[k].data());
    }
    const auto horner = [](const std::vector<double>& c, double tau) {
      double x = c.back();
      for (int m = static_cast<int>(c.size()) - 2; m >= 0; --m) x = x * tau + c[m];
      return x;
    };
    const auto expected = [&](double tau, int i) {
      const bool velocity = i >= 3;
      double x = 0.0;
      for (int k = 0; k < 3; ++k) {
        x += modal.Phi()(i % 3, k) * horner(velocity ? deta[k] : eta[k], tau);
      }
      return x;
    };
    Eigen::VectorXd z(N);
    const auto expect_head = [&](double tau, int count, const char* what) {
      z.setConstant(7.0);
      dense.EvaluateHead(tau, count, z);
      for (int i = 0; i < count; ++i) EXPECT_EQ(z[i], expected(tau, i)) << what << " " << i;
      EXPECT_EQ(z[count], 7.0) << what << ": written past its count";
    };
    const double t1 = 0.3 * tau_max, t2 = 0.71 * tau_max, t3 = tau_max;
    expect_head(t1, 3, "positions, a new instant");
    expect_head(t1, 6, "the state where the positions were summed");
    expect_head(t1, 3, "positions again");
    EXPECT_EQ(dense.EvaluateComponent(t1, 4), expected(t1, 4)) << "a velocity there";
    EXPECT_EQ(dense.EvaluateComponent(t2, 5), expected(t2, 5)) << "a velocity, a new instant";
    expect_head(t2, 3, "positions where a component read summed both");
    expect_head(t3, 6, "a state, a new instant");
    expect_head(t1, 5, "part of the velocities, an instant met before");
    expect_head(t2, 3, "positions");
    EXPECT_EQ(dense.EvaluateComponent(t2, 3), expected(t2, 3)) << "a velocity after positions";
    EXPECT_EQ(dense.EvaluateComponent(t2, 0), expected(t2, 0)) << "a position there";
    // A corner's rate: a position and three velocities at once, at a new instant, where the
    // positions alone or the velocities alone are summed, and where both are.
    const int at[4] = {2, 3, 4, 5};
    const auto expect_four = [&](double tau, const char* what) {
      double out[4];
      dense.EvaluateComponents(tau, at, out);
      for (int j = 0; j < 4; ++j) EXPECT_EQ(out[j], expected(tau, at[j])) << what << " " << j;
    };
    const double t4 = 0.13 * tau_max, t5 = 0.52 * tau_max, t6 = 0.9 * tau_max;
    expect_four(t4, "four, a new instant");
    expect_four(t4, "four again");
    expect_head(t5, 3, "positions");
    expect_four(t5, "four where the positions were summed");
    EXPECT_EQ(dense.EvaluateComponent(t6, 4), expected(t6, 4)) << "a velocity, a new instant";
    expect_four(t6, "four where the velocities were summed");
    EXPECT_EQ(dense.EvaluateComponent(t6, 1), expected(t6, 1)) << "a position there";
    dense.Evaluate(t3, z);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(z[i], expected(t3, i)) << "the whole state " << i;
    // A new build forgets the instants summed before.
    Eigen::VectorXd z1 = z0;
    z1.head(6) *= -0.5;
    dense.Build(flow, omega, z1, tau_max);
    Eigen::VectorXd fresh(N);
    FreeDenseOutput other(N);
    other.Build(flow, omega, z1, tau_max);
    other.Evaluate(t3, fresh);
    dense.EvaluateHead(t3, 6, z);
    EXPECT_TRUE(z.head(6) == fresh.head(6)) << "after a new build";
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::linear_flow_test
