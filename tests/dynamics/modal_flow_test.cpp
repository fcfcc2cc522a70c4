// The modal path of the linear flow (solver/dynamics/modal_flow.h) against the augmented matrix
// exponential of the general path (its oracle): propagators, energy forms and the dense output on
// random classically damped models, steps and excitation pieces.
#include "solver/dynamics/modal_flow.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "solver/dynamics/gap_bound.h"
#include "solver/dynamics/linear_flow.h"
#include "solver/model/builders.h"
#include "solver/model/multispan.h"

namespace skewbridge::dynamics::modal_flow_test {
namespace {

constexpr double kRelative = 1e-12;

// A random model: diagonal M, SPD K (or singular: `rigid` zero-frequency modes), classical
// C = M Phi diag(2 xi_k w_k) Phi^T M with the damping ratios `xi` cycled over the modes (a rigid
// mode gets an undamped oscillator's c = 0 unless `rigid_damping` > 0).
struct RandomModel {
  Eigen::MatrixXd M, K, C, r;
  Eigen::VectorXd omega;
};

RandomModel MakeModel(std::mt19937& rng, int n, int rigid, const std::vector<double>& xi,
                      double rigid_damping = 0.0) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), mass(1.0, 50.0);
  RandomModel m;
  m.M = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) m.M(i, i) = mass(rng) * 1e3;
  Eigen::MatrixXd B(n, n - rigid);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - rigid; ++j) B(i, j) = unit(rng);
  // Frequencies from about 1 to 30 rad/s.
  m.K = 4e5 * B * B.transpose() + (rigid == 0 ? 1e4 : 0.0) * Eigen::MatrixXd::Identity(n, n);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(m.K, m.M);
  const Eigen::MatrixXd Phi = eig.eigenvectors();
  m.omega = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  Eigen::VectorXd c(n);
  for (int k = 0; k < n; ++k) {
    c[k] = k < rigid ? rigid_damping : 2.0 * xi[k % xi.size()] * m.omega[k];
  }
  m.C = m.M * Phi * c.asDiagonal() * Phi.transpose() * m.M;
  m.C = 0.5 * (m.C + m.C.transpose()).eval();
  m.r = Eigen::MatrixXd::Zero(n, 2);
  for (int i = 0; i < n; ++i) {
    m.r(i, 0) = unit(rng);
    m.r(i, 1) = unit(rng);
  }
  return m;
}

ExcitationPiece RandomPiece(std::mt19937& rng, double omega) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  ExcitationPiece piece;
  piece.t_begin = 0.0;
  piece.a_begin = {3.0 * unit(rng), 3.0 * unit(rng)};
  piece.slope = {20.0 * unit(rng), 20.0 * unit(rng)};
  piece.omega = omega;
  if (omega != 0.0) {
    piece.cos_amplitude = {3.0 * unit(rng), 3.0 * unit(rng)};
    piece.sin_amplitude = {3.0 * unit(rng), 3.0 * unit(rng)};
  }
  return piece;
}

// A random state of the size of a response to the piece (m, m/s).
Eigen::VectorXd RandomState(std::mt19937& rng, const LinearFlow& flow, const ExcitationPiece& p,
                            double t) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int n = flow.n_dof();
  Eigen::VectorXd z(flow.augmented_size());
  for (int i = 0; i < n; ++i) {
    z[i] = 0.05 * unit(rng);
    z[n + i] = 0.3 * unit(rng);
  }
  flow.SetGenerator(p, t, z);
  return z;
}

// |a - b| per block (q, u, generator) against the block's largest entry in the oracle b.
void ExpectStatesAgree(const Eigen::VectorXd& a, const Eigen::VectorXd& b, int n,
                       const std::string& what) {
  const int blocks[3][2] = {{0, n}, {n, n}, {2 * n, kGeneratorSize}};
  const char* names[3] = {"q", "u", "generator"};
  for (int i = 0; i < 3; ++i) {
    const auto x = a.segment(blocks[i][0], blocks[i][1]);
    const auto y = b.segment(blocks[i][0], blocks[i][1]);
    const double scale = std::max(y.cwiseAbs().maxCoeff(), 1e-300);
    EXPECT_LE((x - y).cwiseAbs().maxCoeff(), kRelative * scale) << what << ", block " << names[i];
  }
}

// -int u^T M r a_g and int u^T C u over [0, tau] by 8-point Gauss-Legendre on 32 panels, the
// states from the augmented transition.
void GaussEnergy(LinearFlow& oracle, const Eigen::VectorXd& z, double tau, double rate,
                 double& input_J, double& damping_J) {
  const double x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                       -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                       0.7966664774136267,  0.9602898564975363};
  const double w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                       0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                       0.2223810344533745, 0.1012285362903763};
  const int panels = 32;
  const double len = tau / panels;
  Eigen::VectorXd zs(z.size());
  input_J = damping_J = 0.0;
  for (int i = 0; i < panels; ++i) {
    for (int j = 0; j < 8; ++j) {
      const double s = (i + 0.5 + 0.5 * x[j]) * len;
      oracle.Apply(oracle.Propagator(s, rate, false), z, zs);
      double p_in, p_d;
      oracle.Powers(zs, p_in, p_d);
      input_J += 0.5 * len * w[j] * p_in;
      damping_J += 0.5 * len * w[j] * p_d;
    }
  }
}

struct Scenario {
  const char* name;
  int n;
  int rigid;
  std::vector<double> xi;
  double rigid_damping;
};

class ModalAgainstAugmented : public ::testing::TestWithParam<Scenario> {};

TEST_P(ModalAgainstAugmented, PropagatorsEnergyAndDenseOutputAgree) {
  const Scenario& s = GetParam();
  std::mt19937 rng(20261124u + static_cast<unsigned>(s.n * 7 + s.rigid));
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    const RandomModel m = MakeModel(rng, s.n, s.rigid, s.xi, s.rigid_damping);
    LinearFlow modal(m.M, m.K, m.C, m.r);
    LinearFlow oracle(m.M, m.K, m.C, m.r, FlowPath::kAugmented);
    ASSERT_TRUE(modal.modal()) << s.name;
    ASSERT_FALSE(oracle.modal());
    const int n = s.n, N = modal.augmented_size();
    const double w_max = m.omega.maxCoeff();
    // Excitation rates: none, random, and each resonance (natural and damped frequency).
    std::vector<double> rates = {0.0, 30.0 * uniform(rng)};
    const int k = static_cast<int>(uniform(rng) * n) % n;
    const double xi_k = k < s.rigid ? 0.0 : s.xi[k % s.xi.size()];
    rates.push_back(m.omega[k]);
    if (xi_k < 1.0) rates.push_back(m.omega[k] * std::sqrt(1.0 - xi_k * xi_k));
    for (double rate : rates) {
      const ExcitationPiece piece = RandomPiece(rng, rate);
      // Steps from far below to far above the integrator's (1/20 of the shortest period): the
      // longest ones take the modal path's halving and squaring.
      for (double fraction : {1e-4, 0.013, 0.05, 0.3, 1.0, 4.0}) {
        const double tau = fraction * (0.5 + uniform(rng)) * 2.0 * std::numbers::pi /
                           std::max({w_max, std::abs(rate), 1e-3});
        const std::string what = std::string(s.name) + " trial " + std::to_string(trial) +
                                 " rate " + std::to_string(rate) + " tau " + std::to_string(tau);
        const double t0 = 0.37 * tau;
        const Eigen::VectorXd z = RandomState(rng, modal, piece, t0);
        Eigen::VectorXd z_modal(N), z_oracle(N);
        modal.Apply(modal.Propagator(tau, rate), z, z_modal);
        oracle.Apply(oracle.Propagator(tau, rate), z, z_oracle);
        ExpectStatesAgree(z_modal, z_oracle, n, what + " propagator");
        double in_m, d_m, in_o = 0.0, d_o = 0.0;
        bool check_energy = true;
        modal.StepEnergy(modal.Propagator(tau, rate), z, in_m, d_m);
        if (fraction <= 0.05) {
          // The Van Loan Gram matrices, within the integrator's steps.
          oracle.StepEnergy(oracle.Propagator(tau, rate), z, in_o, d_o);
        } else if (trial == 0) {
          // Longer steps: the Van Loan block exponential grows like e^{c tau} and loses every
          // digit for a strongly damped mode, so the oracle is Gauss-Legendre quadrature of the
          // powers along the augmented transition.
          GaussEnergy(oracle, z, tau, rate, in_o, d_o);
        } else {
          check_energy = false;
        }
        // Against the energies moved in the step: the work terms and both mechanical energies.
        const double energy_scale =
            std::max({std::abs(in_o), std::abs(d_o), modal.MechanicalEnergy(z),
                      modal.MechanicalEnergy(z_oracle)});
        if (check_energy) {
          EXPECT_LE(std::abs(in_m - in_o), kRelative * energy_scale) << what << " input work";
          EXPECT_LE(std::abs(d_m - d_o), kRelative * energy_scale) << what << " damping work";
        }
        // The transition is the same bits with and without the energy forms.
        LinearFlow fresh(m.M, m.K, m.C, m.r);
        Eigen::VectorXd z_plain(N);
        fresh.Apply(fresh.Propagator(tau, rate, false), z, z_plain);
        EXPECT_TRUE(z_plain == z_modal) << what;

        // The dense output inside the step, where the integrator uses it (rho_k <= 4).
        if (fraction > 0.3) continue;
        FreeDenseOutput dense(N), dense_oracle(N);
        dense.Build(modal, rate, z, tau);
        Eigen::VectorXd z_dense(N), z_head(N), z_at(N);
        for (double part : {0.0, 1e-3, 0.21, 0.5, 0.77, 1.0}) {
          const double at = part * tau;
          if (at > 0.0) {
            oracle.Apply(oracle.Propagator(at, rate, false), z, z_at);
          } else {
            z_at = z;
          }
          dense.Evaluate(at, z_dense);
          ExpectStatesAgree(z_dense, z_at, n, what + " dense at " + std::to_string(part));
          z_head.setConstant(7.0);
          dense.EvaluateHead(at, 2 * n, z_head);
          EXPECT_TRUE(z_head.head(2 * n) == z_dense.head(2 * n));
          EXPECT_EQ(z_head[2 * n], 7.0) << "EvaluateHead wrote past its count";
          dense.EvaluateHead(at, n, z_head);
          EXPECT_TRUE(z_head.head(n) == z_dense.head(n));
          for (int i = 0; i < N; ++i) {
            if (i < 2 * n) {
              // One component alone (the maxima search) sums the same products in the same
              // order as the whole state: the same bits.
              EXPECT_EQ(dense.EvaluateComponent(at, i), z_dense[i]) << what << " component " << i;
            }
            const int block_begin = i < n ? 0 : i < 2 * n ? n : 2 * n;
            const int block_size = i < 2 * n ? n : kGeneratorSize;
            const double scale = z_at.segment(block_begin, block_size).cwiseAbs().maxCoeff();
            EXPECT_LE(std::abs(dense.EvaluateComponent(at, i) - z_at[i]), kRelative * scale)
                << what << " component " << i;
          }
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    RandomModels, ModalAgainstAugmented,
    ::testing::Values(Scenario{"one_dof_light", 1, 0, {0.05}, 0.0},
                      Scenario{"three_dof_undamped", 3, 0, {0.0}, 0.0},
                      Scenario{"three_dof_mixed", 3, 0, {0.0, 0.02, 0.7}, 0.0},
                      Scenario{"five_dof_critical_and_over", 5, 0, {1.0, 0.3, 1.5, 2.0}, 0.0},
                      Scenario{"four_dof_free_body", 4, 1, {0.05}, 0.0},
                      Scenario{"four_dof_damped_rigid_mode", 4, 2, {0.1}, 3.0},
                      Scenario{"eight_dof", 8, 0, {0.05, 0.1}, 0.0}),
    [](const ::testing::TestParamInfo<Scenario>& info) { return std::string(info.param.name); });

TEST(ModalFlow, DetectsClassicalDamping) {
  std::mt19937 rng(7);
  const RandomModel m = MakeModel(rng, 4, 0, {0.05});
  EXPECT_TRUE(ModalFlow::Classical(m.M, m.K, m.C, m.r).has_value());
  EXPECT_TRUE(ModalFlow::Classical(m.M, m.K, Eigen::MatrixXd::Zero(4, 4), m.r).has_value());
  // Rayleigh damping is classical; a damper on one DOF of a coupled system is not.
  EXPECT_TRUE(ModalFlow::Classical(m.M, m.K, 0.3 * m.M + 1e-3 * m.K, m.r).has_value());
  Eigen::MatrixXd local = Eigen::MatrixXd::Zero(4, 4);
  local(0, 0) = 1e3;
  EXPECT_FALSE(ModalFlow::Classical(m.M, m.K, local, m.r).has_value());
  // So is a classical C perturbed by 1e-9 of itself off its modes.
  Eigen::MatrixXd perturbed = m.C + 1e-9 * m.C.norm() * (local / 1e3);
  EXPECT_FALSE(ModalFlow::Classical(m.M, m.K, perturbed, m.r).has_value());
}

TEST(ModalFlow, EveryBuilderModelTakesTheModalPath) {
  model::DeckSpec deck;
  deck.mass_kg = 1e5;
  deck.geometry = {30.0, 12.0, 0.5};
  deck.w0x_radps = deck.w0y_radps = deck.W0_radps = 3.0;  // a triple natural frequency
  deck.xi = 0.05;
  const model::Model single = model::BuildDeckModel(deck);
  EXPECT_TRUE(LinearFlow(single.M(), single.K(), single.C(), single.r()).modal());
  model::MultiSpanSpec spec;
  spec.n_spans = 50;
  spec.span_lengths_m = {30.0};
  spec.width_m = 10.0;
  spec.skew_rad = 0.5;
  spec.mass_per_length_kgpm = 20e3;
  spec.w0x_radps = spec.w0y_radps = 8.0;
  spec.W0_radps = 10.0;
  spec.xi = 0.05;
  spec.abutment_gap_m = 0.02;
  spec.joint_gap_m = 0.01;
  const model::Model bridge = model::BuildMultiSpanBridge(spec, "test");
  EXPECT_TRUE(LinearFlow(bridge.M(), bridge.K(), bridge.C(), bridge.r()).modal());
}

TEST(ModalFlow, ClassicalFromASolvedBasisIsTheSameBits) {
  // A builder's model hands over the modes it solved for the damping: the flow must not differ.
  std::mt19937 rng(7u);
  for (int n : {1, 3, 8}) {
    const RandomModel m = MakeModel(rng, n, n > 1 ? 1 : 0, {0.05, 0.3});
    const auto direct = ModalFlow::Classical(m.M, m.K, m.C, m.r);
    const auto shared = ModalFlow::Classical(model::ComputeModes(m.M, m.K), m.M, m.C, m.r);
    ASSERT_TRUE(direct.has_value() && shared.has_value()) << n;
    EXPECT_TRUE(direct->Phi() == shared->Phi()) << n;
    EXPECT_TRUE(direct->w2() == shared->w2()) << n;
    EXPECT_TRUE(direct->c() == shared->c()) << n;
  }
}

TEST(ModalFlow, AllModeCoefficientsAreEachModesOwnBits) {
  // The dense output builds every mode's series with AllModeCoefficients (two or three modes per
  // loop, without the harmonic recursion when its inputs are zeros); each mode must get
  // ModeCoefficients' bits, zeros' signs included, whatever the modes' term counts and whichever
  // inputs are zeros of either sign.
  std::mt19937 rng(17u);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> term_count(1, kModalMaxTerms);
  const auto zero = [&] { return unit(rng) < 0.0 ? -0.0 : 0.0; };
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  int harmonic_free = 0;
  for (int n : {1, 2, 3, 5}) {
    const RandomModel m = MakeModel(rng, n, n > 2 ? 1 : 0, {0.05, 0.4});
    const auto flow = ModalFlow::Classical(m.M, m.K, m.C, m.r);
    ASSERT_TRUE(flow.has_value());
    for (int trial = 0; trial < 60; ++trial) {
      const double omega = trial % 4 == 0 ? 0.0 : 30.0 * unit(rng);
      Eigen::MatrixXd Y(n, 6);
      for (int k = 0; k < n; ++k)
        for (int j = 0; j < 6; ++j) Y(k, j) = unit(rng) * std::pow(10.0, 3.0 * unit(rng));
      // Zeros of either sign: the harmonic inputs (a record's piece, a pulse's end), or with
      // them the constant and ramp inputs (the forcing's zeros), or the whole state (at rest).
      const int zeros = trial % 5;
      if (zeros >= 1) {
        harmonic_free += 1;
        for (int k = 0; k < n; ++k) Y(k, 4) = zero(), Y(k, 5) = zero();
      }
      if (zeros == 2 || zeros == 4) {
        for (int k = 0; k < n; ++k) Y(k, 2) = zero(), Y(k, 3) = zero();
      }
      if (zeros == 3) {
        for (int k = 0; k < n; ++k) Y(k, 2) = zero();
      }
      if (zeros == 4) {
        for (int k = 0; k < n; ++k) Y(k, 0) = zero(), Y(k, 1) = zero();
      }
      std::vector<int> terms(static_cast<std::size_t>(n));
      for (int& t : terms) t = term_count(rng);
      const int stride = kModalMaxTerms + 1;  // one guard entry after each mode's series
      Eigen::MatrixXd eta = Eigen::MatrixXd::Constant(stride, n, 7.0), deta = eta;
      flow->AllModeCoefficients(omega, Y, terms.data(), eta.data(), deta.data(), stride);
      for (int k = 0; k < n; ++k) {
        const int t = terms[static_cast<std::size_t>(k)];
        double one_eta[kModalMaxTerms], one_deta[kModalMaxTerms];
        const double y[6] = {Y(k, 0), Y(k, 1), Y(k, 2), Y(k, 3), Y(k, 4), Y(k, 5)};
        flow->ModeCoefficients(k, omega, y, t, one_eta, one_deta);
        for (int i = 0; i < t; ++i) {
          EXPECT_EQ(bits(eta(i, k)), bits(one_eta[i]))
              << n << " modes, mode " << k << ", term " << i << ", zeros " << zeros;
          EXPECT_EQ(bits(deta(i, k)), bits(one_deta[i]))
              << n << " modes, mode " << k << ", term " << i << ", zeros " << zeros;
        }
        EXPECT_EQ(eta(t, k), 7.0) << "wrote past mode " << k << "'s terms";
        EXPECT_EQ(deta(t, k), 7.0) << "wrote past mode " << k << "'s terms";
      }
    }
  }
  EXPECT_EQ(harmonic_free, 4 * 48);
}

TEST(ModalFlow, TransitionsFromTheMemoAreTheBitsOfTheirComputation) {
  // Models of 3 and 5 modes share one memo over many steps and rates (440 keys): each transition,
  // computed with the memo or taken from it, is the bits of the transition computed without it. A
  // memo keyed on fewer of the mode's numbers would hand one model's T_k to another.
  std::mt19937 rng(11);
  const RandomModel a = MakeModel(rng, 3, 0, {0.05});
  const RandomModel b = MakeModel(rng, 5, 1, {0.02, 0.3});
  // c's modes are a's with their damping doubled: the same w_k^2, other c_k.
  const std::optional<ModalFlow> fa = ModalFlow::Classical(a.M, a.K, a.C, a.r);
  const std::optional<ModalFlow> fb = ModalFlow::Classical(b.M, b.K, b.C, b.r);
  const std::optional<ModalFlow> fc = ModalFlow::Classical(a.M, a.K, 2.0 * a.C, a.r);
  ASSERT_TRUE(fa && fb && fc);
  ASSERT_EQ(fa->w2()[0], fc->w2()[0]);
  ASSERT_NE(fa->c()[0], fc->c()[0]);
  TransitionMemo memo;
  int held = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 1; i <= 40; ++i) {
      const double tau = 0.0007 * i;
      const double omega = (i % 3) * 2.7;
      for (const ModalFlow* f : {&*fa, &*fb, &*fc}) {
        Eigen::MatrixXd plain(12, f->n_modes()), memoised(12, f->n_modes());
        f->Transitions(tau, omega, plain, nullptr, nullptr);
        for (int k = 0; k < f->n_modes(); ++k) {
          double row[12];
          const double key[4] = {f->w2()[k], f->c()[k], tau, omega};
          held += memo.Find(key, row) ? 1 : 0;
        }
        f->Transitions(tau, omega, memoised, nullptr, nullptr, &memo);
        ASSERT_EQ(0, std::memcmp(plain.data(), memoised.data(), sizeof(double) * plain.size()))
            << "tau " << tau << " omega " << omega << " modes " << f->n_modes();
      }
    }
  }
  EXPECT_GT(held, 100);  // the second pass found some in the memo
}

TEST(TransitionMemo, HoldsMostOfAThousandKeysAndOnlyTheirOwnRows) {
  // A sweep's models come back a few hundred models (a thousand keys) later: a memo that held
  // one key per slot of 512 would keep fewer than half of them. Every row found is the one
  // stored for its key (a row whose entries are the key's own numbers), and a key stored
  // once more after the others takes a slot without losing the key stored just before it.
  TransitionMemo memo;
  constexpr int kKeys = 1000;
  const auto key_of = [](int i, double(&key)[4]) {
    key[0] = 1.0 + 0.37 * i;
    key[1] = 0.01 * (i % 7);
    key[2] = 0.001 * (1 + i % 5);
    key[3] = (i % 3) * 6.25;
  };
  const auto row_of = [](const double(&key)[4], double* row) {
    for (int j = 0; j < 12; ++j) row[j] = key[j % 4] * (j + 1);
  };
  for (int i = 0; i < kKeys; ++i) {
    double key[4], row[12];
    key_of(i, key);
    ASSERT_FALSE(memo.Find(key, row)) << "key " << i << " before its Store";
    row_of(key, row);
    memo.Store(key, row);
    ASSERT_TRUE(memo.Find(key, row)) << "key " << i << " just stored";
  }
  int held = 0;
  for (int i = 0; i < kKeys; ++i) {
    double key[4], row[12], expected[12];
    key_of(i, key);
    if (!memo.Find(key, row)) continue;
    ++held;
    row_of(key, expected);
    ASSERT_EQ(0, std::memcmp(row, expected, sizeof row)) << "key " << i;
  }
  EXPECT_GT(held, 900);
  const double absent[4] = {0.5, 0.0, 0.001, 0.0};
  double row[12];
  EXPECT_FALSE(memo.Find(absent, row));
}

TEST(TransitionMemo, ACopyHoldsTheRowsAndAMovedFromMemoNone) {
  // Slots start empty by their bit, whatever bytes the allocation left in them: a new memo holds
  // nothing, a copy the same rows as its source, and a memo moved from nothing.
  TransitionMemo memo;
  double row[12];
  const double key[4] = {4.0, 0.1, 0.01, 0.0}, other[4] = {9.0, 0.2, 0.01, 0.0};
  EXPECT_FALSE(memo.Find(key, row));
  double stored[12];
  for (int j = 0; j < 12; ++j) stored[j] = 0.5 + j;
  memo.Store(key, stored);
  EXPECT_FALSE(memo.Find(other, row));
  TransitionMemo copy(memo);
  ASSERT_TRUE(copy.Find(key, row));
  EXPECT_EQ(0, std::memcmp(row, stored, sizeof row));
  EXPECT_FALSE(copy.Find(other, row));
  TransitionMemo moved(std::move(memo));
  EXPECT_TRUE(moved.Find(key, row));
  EXPECT_FALSE(memo.Find(key, row));  // NOLINT(bugprone-use-after-move): moved from is empty
  TransitionMemo assigned;
  assigned = copy;
  EXPECT_TRUE(assigned.Find(key, row));
}

TEST(ModalFlow, ProductsSumEachRowInColumnOrder) {
  // ModalProduct's row-wise kernels (up to 8 columns, 3 unrolled) and its column sweep must give
  // the bits of the plain sum y_i = ((0 + a_i0 x_0) + a_i1 x_1) + ... that the flow was validated
  // with, whatever the shape.
  std::mt19937 rng(11u);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int cols : {1, 3, 5, 8, 9, 20}) {
    Eigen::MatrixXd A(cols + 2, cols);
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < cols + 2; ++i) A(i, j) = unit(rng) * std::pow(10.0, 6.0 * unit(rng));
    Eigen::VectorXd x1(cols), x2(cols);
    for (int j = 0; j < cols; ++j) {
      x1[j] = unit(rng) * std::pow(10.0, 6.0 * unit(rng));
      x2[j] = unit(rng);
    }
    for (int rows : {cols, cols + 2, 1}) {
      Eigen::VectorXd y1 = Eigen::VectorXd::Constant(rows + 1, 7.0), y2 = y1, y1_only = y1;
      ModalProduct(A, rows, x1.data(), x2.data(), y1.data(), y2.data());
      ModalProduct(A, rows, x1.data(), nullptr, y1_only.data(), nullptr);
      for (int i = 0; i < rows; ++i) {
        double s1 = 0.0, s2 = 0.0;
        for (int j = 0; j < cols; ++j) {
          s1 += A(i, j) * x1[j];
          s2 += A(i, j) * x2[j];
        }
        EXPECT_EQ(y1[i], s1) << cols << " columns, row " << i;
        EXPECT_EQ(y2[i], s2) << cols << " columns, row " << i;
        EXPECT_EQ(y1_only[i], s1) << cols << " columns, row " << i;
      }
      EXPECT_EQ(y1[rows], 7.0) << "wrote past its rows";
      EXPECT_EQ(y2[rows], 7.0) << "wrote past its rows";
    }
  }
}

TEST(LinearFlow, ModalApplyIsTheBitsOfToModalRowsAndProducts) {
  // Apply's fused modal step (a deck's 3 modes unrolled, any other count at run time) must give
  // the bits of its parts: Y = ToModal(z) (its unrolled 3-mode path the bits of its general
  // one), eta_k = sum_j T_kj y_kj from 0.0 in column order, and
  // (q, u) = ModalProduct(Phi, eta, eta'); with and without the energy forms, whose sums must
  // equal StepEnergy's. 1, 3, 4 and 8 modes take ModalProduct's row-wise kernels, 9 and 12 its
  // column sweep.
  std::mt19937 rng(29u);
  for (int n : {1, 3, 4, 8, 9, 12}) {
    const RandomModel m = MakeModel(rng, n, n > 2 ? 1 : 0, {0.02, 0.3});
    LinearFlow flow(m.M, m.K, m.C, m.r);
    ASSERT_TRUE(flow.modal()) << n << " modes";
    const ModalFlow& modal = flow.modal_flow();
    for (double rate : {0.0, 7.5}) {
      const ExcitationPiece piece = RandomPiece(rng, rate);
      for (double h : {0.01, 0.37}) {
        const Eigen::VectorXd z = RandomState(rng, flow, piece, 0.02);
        const FreePropagator& p = flow.Propagator(h, rate, true);
        Eigen::MatrixXd Y(n, 6);
        modal.ToModal(z, Y);
        // A Y inside a taller matrix takes ToModal's general loops (ModalProduct): a deck's
        // unrolled path must give their bits.
        Eigen::MatrixXd taller = Eigen::MatrixXd::Constant(n + 2, 6, 7.0);
        modal.ToModal(z, taller.topRows(n));
        for (int j = 0; j < 6; ++j) {
          for (int k = 0; k < n; ++k) {
            EXPECT_EQ(Y(k, j), taller(k, j)) << n << " modes, Y(" << k << ", " << j << ")";
          }
          EXPECT_EQ(taller(n, j), 7.0) << "wrote past its rows";
        }
        Eigen::VectorXd eta(n), deta(n), want(2 * n);
        for (int k = 0; k < n; ++k) {
          double e = 0.0, de = 0.0;
          for (int j = 0; j < 6; ++j) {
            e += p.modal_rows(j, k) * Y(k, j);
            de += p.modal_rows(6 + j, k) * Y(k, j);
          }
          eta[k] = e;
          deta[k] = de;
        }
        ModalProduct(modal.Phi(), n, eta.data(), deta.data(), want.data(), want.data() + n);
        Eigen::VectorXd plain(flow.augmented_size()), with_energy(flow.augmented_size());
        double input = 0.0, damping = 0.0, input_ref = 0.0, damping_ref = 0.0;
        flow.Apply(p, z, plain);
        // The modal coordinates Apply leaves are ToModal's values (a piece without a harmonic
        // part: ToModal's harmonic columns are zeros of either sign, Apply's +0).
        for (int j = 0; j < 6; ++j) {
          for (int k = 0; k < n; ++k) {
            EXPECT_EQ(flow.modal_coordinates()(k, j), Y(k, j))
                << n << " modes, (" << k << ", " << j << ")";
            if (j >= 4 && rate == 0.0) {
              EXPECT_EQ(Y(k, j), 0.0);
            }
          }
        }
        flow.Apply(p, z, with_energy, &input, &damping);
        flow.StepEnergy(p, z, input_ref, damping_ref);
        for (int i = 0; i < 2 * n; ++i) {
          EXPECT_EQ(plain[i], want[i]) << n << " modes, entry " << i << ", h " << h;
          EXPECT_EQ(with_energy[i], want[i]) << n << " modes, entry " << i << ", h " << h;
        }
        EXPECT_EQ(plain.tail(kGeneratorSize), with_energy.tail(kGeneratorSize));
        // ApplyMotion: the same (q, u) bits and energy, the generator part left as it was.
        Eigen::VectorXd motion = Eigen::VectorXd::Constant(flow.augmented_size(), -3.5);
        double input_motion = 0.0, damping_motion = 0.0;
        flow.ApplyMotion(p, z, motion, &input_motion, &damping_motion);
        for (int i = 0; i < 2 * n; ++i) {
          EXPECT_EQ(motion[i], want[i]) << n << " modes, entry " << i << ", h " << h;
        }
        for (int i = 2 * n; i < flow.augmented_size(); ++i) {
          EXPECT_EQ(motion[i], -3.5) << n << " modes, generator entry " << i << " written";
        }
        EXPECT_EQ(input_motion, input_ref) << n << " modes";
        EXPECT_EQ(damping_motion, damping_ref) << n << " modes";
        EXPECT_EQ(input, input_ref) << n << " modes";
        EXPECT_EQ(damping, damping_ref) << n << " modes";
        EXPECT_NE(input, 0.0) << n << " modes";
      }
    }
  }
}

TEST(LinearFlow, RecordMotionIsTheBitsOfApplyMotion) {
  // ApplyRecordMotion (a deck's three modes with two lanes per operation; any other count
  // through ApplyMotion) must leave the bits of ApplyMotion's (q, u) and modal coordinates for a
  // piece without harmonic part, over states and steps of every scale, the generator included.
  std::mt19937 rng(31u);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int n : {3, 1, 6}) {
    const RandomModel m = MakeModel(rng, n, n > 2 ? 1 : 0, {0.02, 0.3});
    LinearFlow flow(m.M, m.K, m.C, m.r);
    ASSERT_TRUE(flow.modal()) << n << " modes";
    for (int trial = 0; trial < 40; ++trial) {
      const ExcitationPiece piece = RandomPiece(rng, 0.0);
      Eigen::VectorXd z = RandomState(rng, flow, piece, 0.005 * (unit(rng) + 1.0));
      z.head(2 * n) *= std::pow(10.0, 3.0 * unit(rng));
      if (trial % 4 == 1) z.head(2 * n).setZero();  // at rest: signed zeros in the sums
      if (trial % 4 == 2) z[2 * n] = -0.0;
      ASSERT_TRUE((z.segment<4>(2 * n + 4).array() == 0.0).all());
      const double h = std::pow(10.0, -3.0 + 2.0 * (unit(rng) + 1.0) / 2.0);
      const FreePropagator& p = flow.Propagator(h, 0.0, false);
      Eigen::VectorXd want = Eigen::VectorXd::Constant(flow.augmented_size(), -3.5);
      Eigen::VectorXd got = want;
      flow.ApplyMotion(p, z, want);
      const Eigen::MatrixXd Y_want = flow.modal_coordinates();
      flow.ApplyMotion(p, -z, got);  // other modal coordinates in between
      flow.ApplyRecordMotion(p, z, got);
      for (int i = 0; i < flow.augmented_size(); ++i) {
        EXPECT_EQ(std::signbit(got[i]), std::signbit(want[i])) << n << " modes, entry " << i;
        EXPECT_EQ(got[i], want[i]) << n << " modes, entry " << i << ", trial " << trial;
      }
      for (int j = 0; j < 6; ++j) {
        for (int k = 0; k < n; ++k) {
          EXPECT_EQ(flow.modal_coordinates()(k, j), Y_want(k, j))
              << n << " modes, Y(" << k << ", " << j << ")";
          EXPECT_EQ(std::signbit(flow.modal_coordinates()(k, j)), std::signbit(Y_want(k, j)));
        }
      }
      if (n == 3) {
        // A step taken in registers (detail::DeckRecordLanes) and stored by StoreDeckRecord,
        // which takes the modal transform again: ApplyMotion's bits too.
        using detail::Lanes2;
        const Lanes2 zq[3] = {{z[0], z[3]}, {z[1], z[4]}, {z[2], z[5]}};
        const Lanes2 gx = {z[6], z[8]}, gy = {z[7], z[9]};
        Lanes2 qu[3], ab[3], next[3];
        detail::DeckRecordLanes(flow.deck_lanes(), p.record_pairs.data(), zq, gx, gy, qu, ab, next);
        flow.ApplyMotion(p, -z, got);  // other modal coordinates in between
        got.setConstant(-3.5);
        flow.StoreDeckRecord(zq, gx, gy, next, got);
        for (int i = 0; i < 2 * n; ++i) {
          EXPECT_EQ(std::signbit(got[i]), std::signbit(want[i])) << "stored, entry " << i;
          EXPECT_EQ(got[i], want[i]) << "stored, entry " << i << ", trial " << trial;
        }
        for (int j = 0; j < 6; ++j) {
          for (int k = 0; k < n; ++k) {
            EXPECT_EQ(flow.modal_coordinates()(k, j), Y_want(k, j))
                << "stored, Y(" << k << ", " << j << ")";
            EXPECT_EQ(std::signbit(flow.modal_coordinates()(k, j)), std::signbit(Y_want(k, j)));
          }
        }
      }
    }
  }
}

TEST(LinearFlow, DeckStepLanesIsDeckRecordLanesUpToTheSignOfAModalZero) {
  // detail::DeckStepLanes against detail::DeckRecordLanes over drawn decks, states, generators
  // and steps: the step's end and the input's modal columns the same bits, the modal
  // coordinates the same values (a zero's sign aside), and a deck's drifts from them
  // (ModalDrift3Lanes) the same bits. Entries are drawn at every scale and as zeros of either
  // sign, so that sums of zero products occur.
  std::mt19937 rng(2026u);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto draw = [&]() {
    switch (rng() % 6) {
      case 0:
        return 0.0;
      case 1:
        return -0.0;
      default:
        return unit(rng) * std::pow(10.0, 6.0 * unit(rng));
    }
  };
  using detail::Lanes2;
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  int signed_zeros = 0;
  for (int deck = 0; deck < 20; ++deck) {
    const RandomModel m = MakeModel(rng, 3, 1, {0.02, 0.3});
    LinearFlow flow(m.M, m.K, m.C, m.r);
    ASSERT_TRUE(flow.modal());
    ModalGapBound bound;
    bound.n_modes = 3;
    bound.w_radps = {unit(rng) + 2.0, unit(rng) + 5.0, unit(rng) + 9.0};
    for (int trial = 0; trial < 500; ++trial) {
      const double h = std::pow(10.0, -3.0 + 2.0 * (unit(rng) + 1.0) / 2.0);
      const FreePropagator& p = flow.Propagator(h, 0.0, false);
      const Lanes2 zq[3] = {{draw(), draw()}, {draw(), draw()}, {draw(), draw()}};
      const Lanes2 gx = {draw(), draw()}, gy = {draw(), draw()};
      Lanes2 qu[3], ab[3], next[3], qu_ref[3], ab_ref[3], next_ref[3];
      Lanes2 ab_y[3];
      detail::DeckYForcing(flow.deck_lanes(), gy, ab_y);
      detail::DeckStepLanes(flow.deck_lanes(), p.record_pairs.data(), zq, gx, ab_y, qu, ab, next);
      detail::DeckRecordLanes(flow.deck_lanes(), p.record_pairs.data(), zq, gx, gy, qu_ref, ab_ref,
                              next_ref);
      for (int i = 0; i < 3; ++i) {
        for (int l = 0; l < 2; ++l) {
          ASSERT_EQ(bits(next[i][l]), bits(next_ref[i][l])) << deck << " " << trial;
          ASSERT_EQ(bits(ab[i][l]), bits(ab_ref[i][l])) << deck << " " << trial;
          ASSERT_EQ(qu[i][l], qu_ref[i][l]) << deck << " " << trial;
          signed_zeros += bits(qu[i][l]) != bits(qu_ref[i][l]);
        }
      }
      const double tau = h * (1.0 + 0.5 * unit(rng));
      double drift[3], drift_ref[3];
      const auto drifts = [&](const Lanes2* y, const Lanes2* a, double* out) {
        ModalDrift3Lanes(bound, Lanes2{y[0][0], y[1][0]}, Lanes2{y[0][1], y[1][1]},
                         Lanes2{a[0][0], a[1][0]}, Lanes2{a[0][1], a[1][1]}, y[2][0], y[2][1],
                         a[2][0], a[2][1], tau, out);
      };
      drifts(qu, ab, drift);
      drifts(qu_ref, ab_ref, drift_ref);
      for (int k = 0; k < 3; ++k) ASSERT_EQ(bits(drift[k]), bits(drift_ref[k]));
    }
  }
  EXPECT_GT(signed_zeros, 0) << "no modal zero of the other sign was drawn";
}

TEST(LinearFlow, AugmentedPartsOfAModalFlowAreBuiltOnDemandAndMatchTheGeneralPath) {
  // A modal flow builds A_hat only when asked (AugmentedMatrix, Derivative, or a dense output
  // longer than the modal series' radius): the same matrix and series as the general path's.
  std::mt19937 rng(13u);
  const RandomModel m = MakeModel(rng, 4, 0, {0.05, 0.2});
  LinearFlow modal(m.M, m.K, m.C, m.r);
  LinearFlow oracle(m.M, m.K, m.C, m.r, FlowPath::kAugmented);
  ASSERT_TRUE(modal.modal());
  const int N = modal.augmented_size();
  const ExcitationPiece piece = RandomPiece(rng, 2.5);
  const Eigen::VectorXd z = RandomState(rng, modal, piece, 0.1);
  // A dense output first (before any other use of the augmented parts), over a step whose
  // rho_k exceeds kModalSeriesRadius: it takes the augmented Taylor series.
  const double tau = 1.5 * kModalSeriesRadius / m.omega.maxCoeff();
  FreeDenseOutput dense(N), dense_oracle(N);
  dense.Build(modal, 2.5, z, tau);
  dense_oracle.Build(oracle, 2.5, z, tau);
  Eigen::VectorXd a(N), b(N);
  for (double part : {0.0, 0.3, 1.0}) {
    dense.Evaluate(part * tau, a);
    dense_oracle.Evaluate(part * tau, b);
    EXPECT_TRUE(a == b) << part;
  }
  EXPECT_TRUE(modal.AugmentedMatrix(2.5) == oracle.AugmentedMatrix(2.5));
  modal.Derivative(2.5, z, a);
  oracle.Derivative(2.5, z, b);
  EXPECT_TRUE(a == b);
  // Against the exact transition, so that the series itself is checked, not only the sameness.
  oracle.Apply(oracle.Propagator(tau, 2.5, false), z, b);
  dense.Evaluate(tau, a);
  ExpectStatesAgree(a, b, 4, "augmented series of a modal flow");
}

// ModalTermCount's definition, term by term.
int TermCountByTerms(double rho) {
  double term = 1.0;
  int m = 0;
  do {
    ++m;
    term *= rho / m;
  } while ((term > 1e-18 || m < 4) && m < kModalMaxTerms - 1);
  return m + 1;
}

TEST(ModalFlow, TermCountIsItsDefinitionTermByTerm) {
  // ModalTermCount reads a table of the rho where the count grows: at every such rho found here
  // by bisection of the definition, at the doubles on either side, and at random rho over 30
  // decades (and outside the table: negative, past it, inf and NaN), the same count.
  int checked = 0;
  for (int N = 6; N <= kModalMaxTerms; ++N) {
    double lo = 0.0, hi = 64.0;  // counts 5 and kModalMaxTerms
    ASSERT_EQ(TermCountByTerms(hi), kModalMaxTerms);
    while (std::nextafter(lo, hi) < hi) {
      const double mid = std::bit_cast<double>(
          std::bit_cast<std::uint64_t>(lo) / 2 + std::bit_cast<std::uint64_t>(hi) / 2 +
          (std::bit_cast<std::uint64_t>(lo) % 2 + std::bit_cast<std::uint64_t>(hi) % 2) / 2);
      (TermCountByTerms(mid) >= N ? hi : lo) = mid;
    }
    for (double rho : {lo, hi, std::nextafter(hi, 100.0)}) {
      EXPECT_EQ(ModalTermCount(rho), TermCountByTerms(rho)) << rho;
      ++checked;
    }
    EXPECT_LT(TermCountByTerms(lo), N);
    EXPECT_GE(TermCountByTerms(hi), N);
  }
  std::mt19937 rng(5u);
  std::uniform_real_distribution<double> decade(-24.0, 6.0);
  for (int i = 0; i < 200000; ++i) {
    const double rho = std::pow(10.0, decade(rng));
    ASSERT_EQ(ModalTermCount(rho), TermCountByTerms(rho)) << rho;
  }
  for (double rho : {0.0, -0.0, 4.0, 64.0, 64.5, 1e6, -1.0, std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_EQ(ModalTermCount(rho), TermCountByTerms(rho)) << rho;
  }
  EXPECT_EQ(checked, 3 * (kModalMaxTerms - 5));
}

TEST(ModalFlow, TermCountBoundsTheFirstOmittedTerm) {
  for (double rho : {0.0, 1e-6, 0.3, 1.0, 4.0}) {
    const int terms = ModalTermCount(rho);
    EXPECT_GE(terms, 5);
    EXPECT_LE(terms, kModalMaxTerms);
    // rho^terms / terms! below 1e-18.
    double term = 1.0;
    for (int m = 1; m <= terms - 1; ++m) term *= rho / m;
    EXPECT_LE(term, 1e-18) << rho;
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::modal_flow_test
