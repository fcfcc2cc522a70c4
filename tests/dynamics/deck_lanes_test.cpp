// The modal flow's two-lane paths (a deck's harmonic step, the series of the transitions) and
// the harmonic generator's angle memo against what they stand for, bitwise: random classically
// damped models, states, rates and steps, zeros of either sign included.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "solver/dynamics/linear_flow.h"
#include "solver/dynamics/modal_flow.h"

namespace skewbridge::dynamics::deck_lanes_test {
namespace {

// A random model of n DOFs: diagonal M (kg), SPD K (or `rigid` zero-frequency modes),
// classical C = M Phi diag(2 xi w_k) Phi^T M, and r (n x 2).
struct RandomModel {
  Eigen::MatrixXd M, K, C, r;
};

RandomModel MakeModel(std::mt19937& rng, int n, int rigid, double xi) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), mass(1.0, 50.0);
  RandomModel m;
  m.M = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) m.M(i, i) = mass(rng) * 1e3;
  Eigen::MatrixXd B(n, n - rigid);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - rigid; ++j) B(i, j) = unit(rng);
  m.K = 4e5 * B * B.transpose() + (rigid == 0 ? 1e4 : 0.0) * Eigen::MatrixXd::Identity(n, n);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(m.K, m.M);
  const Eigen::MatrixXd Phi = eig.eigenvectors();
  const Eigen::VectorXd w = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::VectorXd c = 2.0 * xi * w;
  m.C = m.M * Phi * c.asDiagonal() * Phi.transpose() * m.M;
  m.C = 0.5 * (m.C + m.C.transpose()).eval();
  m.r = Eigen::MatrixXd::Zero(n, 2);
  for (int i = 0; i < n; ++i) {
    m.r(i, 0) = unit(rng);
    m.r(i, 1) = unit(rng);
  }
  return m;
}

// A piece of rate omega (rad/s) with random linear and harmonic parts (m/s^2, m/s^3).
ExcitationPiece RandomPiece(std::mt19937& rng, double omega) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  ExcitationPiece piece;
  piece.a_begin = {3.0 * unit(rng), 3.0 * unit(rng)};
  piece.slope = {20.0 * unit(rng), 20.0 * unit(rng)};
  piece.omega = omega;
  piece.cos_amplitude = {3.0 * unit(rng), 3.0 * unit(rng)};
  piece.sin_amplitude = {3.0 * unit(rng), 3.0 * unit(rng)};
  return piece;
}

TEST(LinearFlow, DeckHarmonicStepIsTheBitsOfTheGeneralModalStep) {
  // A deck's step on a harmonic piece in two lanes (ApplyMotion and ApplyStepMotion) must give
  // the bits, signs of zeros included, of the general loops: Y = ToModal(z) through
  // ModalProduct (a Y inside a taller matrix), eta_k = sum_j T_kj y_kj from 0.0 in column order
  // and (q, u) = ModalProduct(Phi, eta, eta'), over states, rates and steps of every scale; a
  // harmonic generator of zeros takes the record's step (its columns of Y +0).
  std::mt19937 rng(37u);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int n = 3;
  for (int model = 0; model < 4; ++model) {
    const RandomModel m = MakeModel(rng, n, model % 2, model < 2 ? 0.05 : 0.0);
    LinearFlow flow(m.M, m.K, m.C, m.r);
    ASSERT_TRUE(flow.modal());
    const ModalFlow& modal = flow.modal_flow();
    for (int trial = 0; trial < 60; ++trial) {
      const double rate = std::pow(10.0, 2.0 * unit(rng)) * (trial % 3 == 2 ? -1.0 : 1.0);
      ExcitationPiece piece = RandomPiece(rng, rate);
      if (trial % 7 == 3) {
        piece.cos_amplitude.setZero();  // a harmonic generator of zeros
        piece.sin_amplitude.setZero();
      }
      if (trial % 7 == 5) piece.cos_amplitude[1] = 0.0;
      Eigen::VectorXd z(flow.augmented_size());
      for (int i = 0; i < 2 * n; ++i) z[i] = (i < n ? 0.05 : 0.3) * unit(rng);
      flow.SetGenerator(piece, 0.03 * (unit(rng) + 1.0), z);
      z.head(2 * n) *= std::pow(10.0, 3.0 * unit(rng));
      if (trial % 5 == 1) z.head(2 * n).setZero();  // at rest: signed zeros in the sums
      if (trial % 5 == 2) z[1] = -0.0;
      if (trial % 5 == 3) z[2 * n] = -0.0;
      const double h = std::pow(10.0, -3.0 + 2.0 * (unit(rng) + 1.0) / 2.0);
      const FreePropagator& p = flow.Propagator(h, rate, false);
      Eigen::MatrixXd taller = Eigen::MatrixXd::Constant(n + 1, 6, 7.0);
      modal.ToModal(z, taller.topRows(n), trial % 7 != 3);
      const Eigen::MatrixXd Y = taller.topRows(n);
      double eta[n], deta[n];
      for (int k = 0; k < n; ++k) {
        double e = 0.0, de = 0.0;
        for (int j = 0; j < 6; ++j) {
          e += p.modal_rows(j, k) * Y(k, j);
          de += p.modal_rows(6 + j, k) * Y(k, j);
        }
        eta[k] = e;
        deta[k] = de;
      }
      Eigen::VectorXd want(2 * n);
      ModalProduct(modal.Phi(), n, eta, deta, want.data(), want.data() + n);
      for (int way = 0; way < 2; ++way) {
        Eigen::VectorXd got = Eigen::VectorXd::Constant(flow.augmented_size(), -3.5);
        flow.ApplyMotion(p, -z, got);  // other modal coordinates in between
        if (way == 0) {
          flow.ApplyMotion(p, z, got);
        } else {
          flow.ApplyStepMotion(p, z, got);
        }
        for (int i = 0; i < 2 * n; ++i) {
          EXPECT_EQ(got[i], want[i]) << "way " << way << ", entry " << i << ", trial " << trial;
          EXPECT_EQ(std::signbit(got[i]), std::signbit(want[i])) << "way " << way << ", " << i;
        }
        for (int j = 0; j < 6; ++j) {
          for (int k = 0; k < n; ++k) {
            EXPECT_EQ(flow.modal_coordinates()(k, j), Y(k, j)) << "Y(" << k << ", " << j << ")";
            EXPECT_EQ(std::signbit(flow.modal_coordinates()(k, j)), std::signbit(Y(k, j)))
                << "way " << way << ", Y(" << k << ", " << j << "), trial " << trial;
          }
        }
      }
    }
  }
}

TEST(ModalFlow, TransitionsWithoutEnergyAreTheBitsOfTheScalarRecursion) {
  // Without the energy forms the series run two columns per operation; with them one column at
  // a time (the forms need every coefficient and forcing): the rows must be the same bits, signs
  // of zeros included, for rigid, undamped and damped modes, rates of either sign and zeros of
  // either sign (whose harmonic pair the lanes take from the ramp's columns), and
  // steps from far inside the series' radius to beyond it (halved and squared back).
  std::mt19937 rng(41u);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int model = 0; model < 6; ++model) {
    const int n = 1 + model;
    const RandomModel m = MakeModel(rng, n, model % 3 == 1 ? 1 : 0, model % 3 == 2 ? 0.0 : 0.05);
    const std::optional<ModalFlow> flow = ModalFlow::Classical(m.M, m.K, m.C, m.r);
    ASSERT_TRUE(flow);
    for (int trial = 0; trial < 40; ++trial) {
      const double tau = std::pow(10.0, -4.0 + 4.0 * (unit(rng) + 1.0) / 2.0);
      const double rate = trial % 8 == 0 ? 0.0
                          : trial % 8 == 4
                              ? -0.0
                              : std::pow(10.0, 2.0 * unit(rng)) * (trial % 4 == 3 ? -1.0 : 1.0);
      Eigen::MatrixXd lanes(12, n), scalar(12, n), input, damping;
      flow->Transitions(tau, rate, lanes, nullptr, nullptr);
      flow->Transitions(tau, rate, scalar, &input, &damping);
      for (int k = 0; k < n; ++k) {
        for (int i = 0; i < 12; ++i) {
          EXPECT_EQ(lanes(i, k), scalar(i, k)) << "T(" << i << ", " << k << "), trial " << trial;
          EXPECT_EQ(std::signbit(lanes(i, k)), std::signbit(scalar(i, k)))
              << "T(" << i << ", " << k << "), trial " << trial;
        }
      }
    }
  }
}

TEST(AngleMemo, GivesTheLibrarysBitsOfEveryAngle) {
  // Angles of a few grids (a pulse's steps, taken again and again as by a sweep's cells), new
  // angles that take the grid's slots over, zeros of either sign and non-finite angles: every
  // answer must be the bits of std::cos and std::sin.
  std::mt19937 rng(43u);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  AngleMemo memo;
  const auto expect = [&](double x) {
    double c = 7.0, s = 7.0;
    memo.CosSin(x, c, s);
    const double c_ref = std::cos(x), s_ref = std::sin(x);
    EXPECT_EQ(std::memcmp(&c, &c_ref, sizeof c), 0) << "cos of " << x;
    EXPECT_EQ(std::memcmp(&s, &s_ref, sizeof s), 0) << "sin of " << x;
  };
  for (double x : {0.0, -0.0, 1e-300, -1e-300, 1e300, std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::quiet_NaN()}) {
    expect(x);
  }
  for (int pass = 0; pass < 3; ++pass) {
    for (const double omega : {3.7, 25.0, -8.5}) {
      const double h = 0.01 * (1.0 + 0.1 * pass);
      for (int k = 0; k < 400; ++k) expect(omega * ((k + 1.0) * h));
      for (int k = 0; k < 50; ++k) expect(1e3 * unit(rng));
    }
  }
  expect(0.0);
  expect(-0.0);
}

}  // namespace
}  // namespace skewbridge::dynamics::deck_lanes_test
