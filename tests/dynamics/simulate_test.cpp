#include "solver/dynamics/simulate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/common/error.h"
#include "solver/dynamics/run.h"
#include "solver/dynamics/time_stepping.h"
#include "solver/model/builders.h"
#include "tests/dynamics/modal_oracle.h"

namespace skewbridge::dynamics::simulate_test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// A constant ground acceleration on [0, duration), at rest after.
class ConstantExcitation final : public Excitation {
 public:
  ConstantExcitation(Eigen::Vector2d a_mps2, double duration_s)
      : a_(std::move(a_mps2)), duration_(duration_s) {}
  ExcitationPiece PieceAt(double t) const override {
    ExcitationPiece piece;
    if (t < duration_) {
      piece.t_begin = 0.0;
      piece.t_end = duration_;
      piece.a_begin = a_;
    } else {
      piece.t_begin = duration_;
    }
    return piece;
  }
  double Duration() const override { return duration_; }

 private:
  Eigen::Vector2d a_;
  double duration_;
};

struct DeckParams {
  double skew_deg = 30.0;
  double length_m = 30.0;
  double width_m = 10.0;
  double w0 = 2.0 * kPi;  // rad/s, x and y
  double W0 = 2.0 * kPi;  // rad/s, torsion
  double xi = 0.05;
  double gap_m = 0.01;
  double eps = 0.5;
  double mu = 0.0;
  model::AbutmentSet set = model::AbutmentSet::kPlusX;
};

model::Model MakeDeck(const DeckParams& p) {
  model::DeckSpec spec;
  spec.mass_kg = 1.0e5;
  spec.geometry = {p.length_m, p.width_m, p.skew_deg * kDeg};
  spec.stiffness = model::DeckSpec::StiffnessKind::kUncoupled;
  spec.w0x_radps = spec.w0y_radps = p.w0;
  spec.W0_radps = p.W0;
  spec.xi = p.xi;
  spec.abutments = p.set;
  spec.gap_plus_m = spec.gap_minus_m = p.gap_m;
  spec.restitution = p.eps;
  spec.friction = p.mu;
  return model::BuildDeckModel(spec);
}

double Rho(const model::Model& m) { return std::sqrt(m.body(0).inertia_kgm2 / m.body(0).mass_kg); }

InitialState Moving(const Eigen::Vector3d& q, const Eigen::Vector3d& u) {
  InitialState s;
  s.q = q;
  s.u = u;
  return s;
}

model::RunControl EndAt(double t_end) {
  model::RunControl control;
  control.end_time_s = t_end;
  return control;
}

// docs/theory.md §4 fact 1: a translating deck striking the +x abutment full-edge leaves without
// rotating iff eta0 <= 1; for eta0 > 1 only the obtuse corner P2 takes an impulse.
TEST(LowestFrequency, IsTheModelsFirstModeWithOrWithoutItsModes) {
  // The one lowest frequency of every scale and end time: from the modes a builder solved, or
  // from an eigenvalue solve of its own, the bits of ComputeModes either way; 0 for a free body.
  model::DeckSpec deck;
  deck.mass_kg = 2e5;
  deck.geometry = {40.0, 15.0, 0.4};
  deck.w0x_radps = 3.0;
  deck.w0y_radps = 4.0;
  deck.W0_radps = 6.0;
  deck.xi = 0.05;
  const model::Model classical = model::BuildDeckModel(deck);
  ASSERT_NE(classical.modes(), nullptr);
  const model::Model without_modes(classical.bodies(), classical.K(), classical.C(), classical.r(),
                                   classical.contacts());
  ASSERT_EQ(without_modes.modes(), nullptr);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, 3);
  C(0, 0) = 1e4;
  C(1, 1) = 2e3;
  C(0, 1) = C(1, 0) = 3e3;
  const model::Model general(classical.bodies(), classical.K(), C, classical.r(),
                             classical.contacts());
  for (const model::Model* m : {&classical, &without_modes, &general}) {
    const model::Modes modes = model::ComputeModes(m->M(), m->K());
    EXPECT_EQ(model::LowestFrequency(*m), modes.omega_radps.minCoeff());
    EXPECT_EQ(model::NaturalFrequencyRange(*m).highest_radps, modes.omega_radps.maxCoeff());
    // K = diag(m w0x^2, m w0y^2, I W0^2) about the centre of mass: the frequencies are 3, 4, 6.
    EXPECT_NEAR(model::LowestFrequency(*m), 3.0, 1e-12);
    EXPECT_NEAR(model::NaturalFrequencyRange(*m).highest_radps, 6.0, 1e-12);
    // The workspace reads its own from its flow's modes or its own eigenvalue solve: the same
    // bits.
    const SimulationWorkspace workspace(*m);
    EXPECT_EQ(workspace.omega_min_radps(), model::LowestFrequency(*m));
  }
  const model::Model free_body(classical.bodies(), Eigen::MatrixXd::Zero(3, 3),
                               Eigen::MatrixXd::Zero(3, 3), classical.r(), classical.contacts());
  EXPECT_EQ(model::LowestFrequency(free_body), 0.0);
  EXPECT_TRUE(LinearFlow(classical.M(), classical.K(), classical.C(), classical.r()).modal());
  EXPECT_FALSE(LinearFlow(general.M(), general.K(), general.C(), general.r()).modal());
}

TEST(Simulate, FullEdgeImpactRotatesOnlyAboveSkewRatioOne) {
  for (double skew : {15.0, 30.0, 45.0, 60.0}) {
    for (double eta0 : {0.6, 0.95, 1.1, 1.6}) {
      DeckParams p;
      p.skew_deg = skew;
      p.width_m = model::WidthFromEta0(eta0, skew * kDeg, p.length_m);
      p.w0 = p.W0 = 0.2;
      p.xi = 0.0;
      const model::Model m = MakeDeck(p);
      SimulationWorkspace ws(m);
      const ConstantExcitation rest({0.0, 0.0}, 0.0);
      const RunResult r = Simulate(m, rest, EndAt(0.5), ws, Moving({0, 0, 0}, {0.1, 0, 0}));
      ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
      ASSERT_EQ(r.impacts, 1) << "skew " << skew << " eta0 " << eta0;
      const double rotation = r.max_abs_q[2] * Rho(m);
      int impulses = 0, at_p2 = 0;
      for (const EventRecord& e : r.events) {
        if (e.kind == EventKind::kImpact) {
          ++impulses;
          at_p2 += m.contact(e.contact).name == "P2" ? 1 : 0;
        }
      }
      if (eta0 <= 1.0) {
        EXPECT_LE(rotation, 1e-12 * r.max_abs_q[0]) << "skew " << skew << " eta0 " << eta0;
        EXPECT_EQ(impulses, 2);
      } else {
        EXPECT_GT(rotation, 1e-3 * r.max_abs_q[0]) << "skew " << skew << " eta0 " << eta0;
        EXPECT_EQ(impulses, 1);
        EXPECT_EQ(at_p2, 1);
      }
    }
  }
}

// docs/theory.md §4 fact 2: slipping along -t through the impact (friction along +t), a = 30 deg,
// eta0 = 0.87: mu = 0.08 gives eta1 = 0.99 (no rotation), mu = 0.10 gives eta1 = 1.02.
TEST(Simulate, FrictionalImpactFollowsFrictionalSkewRatio) {
  for (double mu : {0.08, 0.10}) {
    DeckParams p;
    p.skew_deg = 30.0;
    p.width_m = model::WidthFromEta0(0.87, 30.0 * kDeg, p.length_m);
    p.w0 = p.W0 = 0.2;
    p.xi = 0.0;
    p.mu = mu;
    const model::Model m = MakeDeck(p);
    const double eta1 = model::Eta1(m.body(0).geometry, mu);
    SimulationWorkspace ws(m);
    const ConstantExcitation rest({0.0, 0.0}, 0.0);
    // gamma_T = v (sin a - 3 cos a) < 0: slip along -t, large enough to last through the impact.
    const RunResult r = Simulate(m, rest, EndAt(0.3), ws, Moving({0, 0, 0}, {0.1, -0.3, 0}));
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    ASSERT_EQ(r.impacts, 1);
    const double rotation = r.max_abs_q[2] * Rho(m);
    if (eta1 <= 1.0) {
      EXPECT_LE(rotation, 1e-12 * r.max_abs_q[0]) << "mu " << mu << " eta1 " << eta1;
    } else {
      EXPECT_GT(rotation, 1e-4 * r.max_abs_q[0]) << "mu " << mu << " eta1 " << eta1;
    }
  }
}

// docs/theory.md §4 fact 3: with a = 0 the deck is the pounding oscillator; y and theta stay zero.
TEST(Simulate, ZeroSkewKeepsTransverseAndRotationExactlyZero) {
  DeckParams p;
  p.skew_deg = 0.0;
  p.mu = 0.2;
  p.set = model::AbutmentSet::kBoth;
  p.gap_m = 0.02;
  const model::Model m = MakeDeck(p);
  SimulationWorkspace ws(m);
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 4.0, 2.0 * kPi);
  const RunResult r = Simulate(m, pulse, EndAt(3.0), ws);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_GT(r.impacts, 0);
  // Zero up to the round-off of the two-corner impulses (16 digits of x), which the modal
  // transforms of each free step (q = Phi eta) round a few times more.
  EXPECT_LE(r.max_abs_q[1], 1e-14 * r.max_abs_q[0]);
  EXPECT_LE(r.max_abs_q[2] * Rho(m), 1e-14 * r.max_abs_q[0]);
}

// Run dispatches on RunControl::method: each method gives the bits of its integrator's own entry,
// and the two methods differ (a pounding skew deck, 1e-4 s Moreau-Jean steps).
TEST(Run, TakesTheIntegratorOfItsMethod) {
  DeckParams p;
  p.mu = 0.2;
  const model::Model m = MakeDeck(p);
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 4.0, 2.0 * kPi);
  model::RunControl control = EndAt(2.0);
  control.time_step_s = 1e-4;
  SimulationWorkspace ws(m);
  const RunResult event_driven = Simulate(m, pulse, control, ws);
  TimeSteppingWorkspace ts(m);
  const RunResult time_stepping = SimulateTimeStepping(m, pulse, control, ts);
  ASSERT_GT(event_driven.impacts, 0);
  ASSERT_GT(time_stepping.impacts, 0);
  control.method = model::Method::kEventDriven;
  const RunResult a = dynamics::Run(m, pulse, control);
  control.method = model::Method::kTimeStepping;
  const RunResult b = dynamics::Run(m, pulse, control);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.max_abs_q[i], event_driven.max_abs_q[i]);
    EXPECT_EQ(b.max_abs_q[i], time_stepping.max_abs_q[i]);
  }
  EXPECT_EQ(a.events.size(), event_driven.events.size());
  EXPECT_EQ(b.events.size(), time_stepping.events.size());
  EXPECT_EQ(b.rk_steps, time_stepping.rk_steps);
  EXPECT_NE(a.max_abs_q[0], b.max_abs_q[0]);
  // The same displacement peak to the scheme's first order (about h over the response's time).
  EXPECT_NEAR(a.max_abs_q[0], b.max_abs_q[0], 0.01 * a.max_abs_q[0]);
}

// Gaps too large to close: the run is the linear response, checked against modal superposition.
TEST(Simulate, WideGapsReproduceModalSuperposition) {
  DeckParams p;
  p.gap_m = 100.0;
  p.set = model::AbutmentSet::kBoth;
  p.W0 = 9.0;
  const model::Model m = MakeDeck(p);
  SimulationWorkspace ws(m);
  const Eigen::Vector2d dir(std::cos(0.4), std::sin(0.4));
  const records::PulseExcitation pulse(records::PulseShape::kSine, 3.0, 5.0, dir);
  model::RunControl control = EndAt(4.0);
  control.output_interval_s = 0.05;
  const Eigen::Vector3d q0(0.01, -0.02, 0.001), u0(0.1, 0.05, -0.01);
  const RunResult r = Simulate(m, pulse, control, ws, Moving(q0, u0));
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_EQ(r.impacts, 0);
  const testing::ModalOracle oracle(m.M(), m.K(), p.xi, m.r());
  Eigen::VectorXd q, u;
  double scale = 0.0, worst = 0.0;
  for (std::size_t s = 0; s < r.histories.t_s.size(); ++s) {
    oracle.At(pulse, q0, u0, r.histories.t_s[s], q, u);
    for (int i = 0; i < 3; ++i) {
      scale = std::max(scale, std::abs(q[i]));
      worst = std::max(worst, std::abs(q[i] - r.histories.q[s * 3 + i]));
    }
  }
  EXPECT_EQ(r.histories.t_s.size(), 81u);
  EXPECT_LT(worst, 1e-9 * scale);
  oracle.At(pulse, q0, u0, 4.0, q, u);
  EXPECT_LT((r.q_end - q).cwiseAbs().maxCoeff(), 1e-9 * q.cwiseAbs().maxCoeff());
  // Maxima: the oracle on a fine grid, refined by golden-section search per DOF.
  for (int i = 0; i < 3; ++i) {
    const auto value = [&](double t) {
      oracle.At(pulse, q0, u0, t, q, u);
      return std::abs(q[i]);
    };
    double best_t = 0.0, best = 0.0;
    for (int k = 0; k <= 4000; ++k) {
      const double v = value(k * 1e-3);
      if (v > best) {
        best = v;
        best_t = k * 1e-3;
      }
    }
    double a = std::max(0.0, best_t - 1e-3), b = std::min(4.0, best_t + 1e-3);
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int it = 0; it < 80; ++it) {
      const double x1 = b - g * (b - a), x2 = a + g * (b - a);
      (value(x1) > value(x2) ? b : a) = value(x1) > value(x2) ? x2 : x1;
    }
    EXPECT_NEAR(r.max_abs_q[i], value(0.5 * (a + b)), 1e-9 * value(0.5 * (a + b))) << "dof " << i;
  }
}

// Undamped pounding oscillator (a = 0, uncoupled): impact k has approach speed eps^(k-1) v1 and
// the time between impacts is (2 pi - 2 phi_k) / w with phi_k = atan2(eps v_k / w, delta).
TEST(Simulate, UndampedImpactSequenceMatchesClosedForm) {
  DeckParams p;
  p.skew_deg = 0.0;
  p.xi = 0.0;
  p.w0 = 3.0;
  p.gap_m = 0.02;
  p.eps = 0.6;
  const model::Model m = MakeDeck(p);
  SimulationWorkspace ws(m);
  const ConstantExcitation rest({0.0, 0.0}, 0.0);
  const double v0 = 0.1, w = p.w0, delta = p.gap_m;
  const RunResult r = Simulate(m, rest, EndAt(12.0), ws, Moving({0, 0, 0}, {v0, 0, 0}));
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  double t = std::asin(delta * w / v0) / w;
  double v = std::sqrt(v0 * v0 - w * w * delta * delta);
  std::vector<const EventRecord*> impacts;
  for (const EventRecord& e : r.events) {
    if (e.kind == EventKind::kImpact && m.contact(e.contact).name == "P1") {
      impacts.push_back(&e);
    }
  }
  ASSERT_GE(impacts.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_NEAR(impacts[k]->t_s, t, 1e-9 * t) << "impact " << k;
    EXPECT_NEAR(-impacts[k]->gamma_N_before_mps, v, 1e-9 * v) << "impact " << k;
    EXPECT_NEAR(impacts[k]->gamma_N_after_mps, p.eps * v, 1e-9 * v) << "impact " << k;
    const double phi = std::atan2(p.eps * v / w, delta);
    t += (2.0 * kPi - 2.0 * phi) / w;
    v *= p.eps;
  }
}

struct Dimensionless {
  Eigen::Vector3d maxima;
};

Eigen::Vector3d DimensionlessMaxima(double a_g, double pi_delta, bool* ok) {
  const double w_g = 2.0 * kPi;
  DeckParams p;
  p.skew_deg = 30.0;
  p.width_m = model::WidthFromEta0(1.5, 30.0 * kDeg, p.length_m);
  p.w0 = 0.8 * w_g;
  p.W0 = 1.2 * w_g;
  p.gap_m = pi_delta * a_g / (w_g * w_g);
  const model::Model m = MakeDeck(p);
  SimulationWorkspace ws(m);
  const records::PulseExcitation pulse(records::PulseShape::kCosine, a_g, w_g);
  // abs_tol is in state units: it scales with the persistency a_g / w_g^2 like every length.
  model::RunControl control = EndAt(3.0);
  control.absolute_tolerance = 1e-12 * a_g;
  const RunResult r = Simulate(m, pulse, control, ws);
  *ok = r.status == RunStatus::kOk && r.impacts > 0;
  const double scale = w_g * w_g / a_g;
  return {r.max_abs_q[0] * scale, r.max_abs_q[1] * scale, r.max_abs_q[2] * Rho(m) * scale};
}

// docs/theory.md §4 fact 4: at fixed Pi_delta the dimensionless maxima do not depend on a_g (exact
// in the small-rotation limit; the deviation with full kinematics is printed).
TEST(Simulate, DimensionlessMaximaAreSelfSimilarInIntensity) {
  bool ok = false;
  const Eigen::Vector3d base = DimensionlessMaxima(1e-4, 0.5, &ok);
  ASSERT_TRUE(ok);
  // a_g from 1e-10 to 1e-1 m/s^2 (the base 1e-4 scaled by 1e-6 .. 1e3): every threshold of the
  // event logic (gap, velocity and accumulation tolerances) scales with the excitation, so two
  // residuals are left. The kinematic nonlinearity, linear in a_g: 1.08e-6 at a_g = 1e-3 m/s^2
  // (rotation ~1e-6 rad), 1.08e-5 at 1e-2. The rounding of gaps computed from world
  // coordinates (ulps of the 15 m lever arms against a gap of 0.5 a_g / w_g^2), in 1 / a_g:
  // 5.7e-6 at a_g = 1e-8 m/s^2. Before the gap tolerance had that rounding as its floor, the
  // full-edge impact split into two single-corner impacts below a_g = 1e-6 and the maxima
  // moved by 18 % (x) to 110 % (theta).
  for (double factor : {1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.1, 10.0, 100.0, 1e3}) {
    const double a_g = 1e-4 * factor;
    const Eigen::Vector3d other = DimensionlessMaxima(a_g, 0.5, &ok);
    ASSERT_TRUE(ok) << "a_g " << a_g;
    const double deviation = ((other - base).cwiseQuotient(base)).cwiseAbs().maxCoeff();
    EXPECT_LT(deviation, 2e-6 + 1.2e-3 * a_g + 2e-13 / a_g) << "a_g " << a_g;
  }
  const Eigen::Vector3d realistic = DimensionlessMaxima(1.0, 0.5, &ok);
  ASSERT_TRUE(ok);
  for (double factor : {0.1, 10.0}) {
    const Eigen::Vector3d other = DimensionlessMaxima(factor, 0.5, &ok);
    ASSERT_TRUE(ok);
    const double deviation = ((other - realistic).cwiseQuotient(realistic)).cwiseAbs().maxCoeff();
    std::printf(
        "self-similarity with full kinematics, a_g = %g vs 1 m/s^2: max relative "
        "deviation %.3e\n",
        factor, deviation);
    EXPECT_LT(deviation, 0.2);
  }
}

}  // namespace
RunResult Canonical(double rel_tol, double abs_tol, double mu) {
  static DeckParams p = [] {
    DeckParams d;
    d.skew_deg = 30.0;
    d.width_m = model::WidthFromEta0(2.0, 30.0 * kDeg, d.length_m);
    d.w0 = 0.5 * 2.0 * kPi;
    d.W0 = 0.5 * 2.0 * kPi;
    d.gap_m = 0.5 * 5.0 / (4.0 * kPi * kPi);
    return d;
  }();
  p.mu = mu;
  const model::Model m = MakeDeck(p);
  SimulationWorkspace ws(m);
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 5.0, 2.0 * kPi);
  model::RunControl control = EndAt(3.0);
  control.relative_tolerance = rel_tol;
  control.absolute_tolerance = abs_tol;
  return Simulate(m, pulse, control, ws);
}

namespace {
// Tightening every tolerance 100x moves the maxima of the canonical subsystem by < 1e-6.
TEST(Simulate, MaximaConvergeUnderTolerance) {
  for (double mu : {0.0, 0.2}) {
    const RunResult loose = Canonical(1e-8, 1e-10, mu);
    const RunResult tight = Canonical(1e-10, 1e-12, mu);
    ASSERT_EQ(loose.status, RunStatus::kOk) << loose.message;
    ASSERT_EQ(tight.status, RunStatus::kOk) << tight.message;
    EXPECT_GT(tight.impacts, 0);
    const double change =
        ((loose.max_abs_q - tight.max_abs_q).cwiseQuotient(tight.max_abs_q)).cwiseAbs().maxCoeff();
    EXPECT_LT(change, 1e-6) << "mu " << mu;
  }
}

// docs/theory.md §4 fact 6: no impact creates energy; the ledger balances to 1e-6 of the input.
TEST(Simulate, ImpactsNeverCreateEnergyAndLedgerBalances) {
  for (double mu : {0.0, 0.2}) {
    const RunResult r = Canonical(1e-10, 1e-12, mu);
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    ASSERT_GT(r.impacts, 0);
    for (const EventRecord& e : r.events) {
      if (e.kind == EventKind::kImpact) {
        EXPECT_GE(e.kinetic_loss_J, -1e-12 * r.energy.input_J) << "t = " << e.t_s;
      }
    }
    EXPECT_GE(r.energy.impact_J, 0.0);
    EXPECT_GE(r.energy.friction_J, 0.0);
    EXPECT_GT(r.energy.damping_J, 0.0);
    EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-6 * std::abs(r.energy.input_J)) << "mu " << mu;
  }
}

// A deck pressed onto the abutment by a sustained ground acceleration ends, after finitely many
// steps, in persistent contact carrying the static force m A - k delta.
TEST(Simulate, AccumulationEndsInPersistentContactWithStaticForce) {
  DeckParams p;
  p.skew_deg = 0.0;
  p.w0 = p.W0 = 1.0;
  p.gap_m = 0.05;
  p.eps = 0.5;
  const model::Model m = MakeDeck(p);
  SimulationWorkspace ws(m);
  const double A = 2.0;
  const ConstantExcitation push({-A, 0.0}, 30.0);
  model::RunControl control = EndAt(20.0);
  control.output_interval_s = 0.5;
  const RunResult r = Simulate(m, push, control, ws);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_GT(r.impacts, 3);
  EXPECT_LT(r.free_steps + r.rk_steps, 20000);
  const Histories& h = r.histories;
  const std::size_t last = h.t_s.size() - 1;
  const double mass = m.body(0).mass_kg, k = mass * p.w0 * p.w0;
  const double total = h.lambda_N[last * 2] + h.lambda_N[last * 2 + 1];
  EXPECT_NEAR(total, mass * A - k * p.gap_m, 1e-6 * mass * A);
  EXPECT_NEAR(r.q_end[0], p.gap_m, 1e-9);
  EXPECT_NE(h.state[last * 2], static_cast<int>(ContactState::kOpen));
}

// Held against the abutment (a = 0) and pushed along y: Coulomb says stick when m B <= mu N and
// slide otherwise with y(t) = (B - mu N / m) (1 - cos w t) / w^2 until the slip stops.
TEST(Simulate, StickAndSlipFollowCoulomb) {
  DeckParams p;
  p.skew_deg = 0.0;
  p.length_m = p.width_m = 10.0;
  p.w0 = p.W0 = 2.0;
  p.gap_m = 0.01;
  p.mu = 0.3;
  p.xi = 0.0;
  const model::Model m = MakeDeck(p);
  const double mass = m.body(0).mass_kg, A = 5.0;
  const double N = mass * A - mass * p.w0 * p.w0 * p.gap_m;
  for (double B : {0.5 * p.mu * N / mass, 1.5 * p.mu * N / mass}) {
    SimulationWorkspace ws(m);
    const ConstantExcitation push({-A, -B}, 10.0);
    const double quarter = 0.25 * 2.0 * kPi / p.w0;
    const RunResult r = Simulate(m, push, EndAt(quarter), ws, Moving({p.gap_m, 0, 0}, {0, 0, 0}));
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    EXPECT_EQ(r.impacts, 0);
    if (mass * B <= p.mu * N) {
      EXPECT_LT(std::abs(r.q_end[1]), 1e-12);
    } else {
      const double expected = (B - p.mu * N / mass) / (p.w0 * p.w0);  // 1 - cos(pi/2) = 1
      EXPECT_NEAR(r.q_end[1], expected, 1e-8 * expected);
      EXPECT_NEAR(r.q_end[0], p.gap_m, 1e-10);
    }
  }
}

// A policy the integrator cannot run with is refused before the run with one line naming the
// member, what is allowed and the value given: a finite-check interval that is no power of two
// would silently check at the wrong steps (the check masks the step count), and no decision
// pass, no position pass or less than one step a period leaves nothing to run. Powers of two,
// including 1, are accepted.
TEST(Simulate, RefusesAnEventPolicyItCannotRunWith) {
  struct Row {
    std::function<void(EventPolicy&)> set;
    std::string message;
  };
  const std::vector<Row> rows = {
      {[](EventPolicy& p) { p.finite_check_steps = 10; },
       "event policy: finite_check_steps: must be a power of two (1, 2, 4, ...) (got 10)"},
      {[](EventPolicy& p) { p.finite_check_steps = 0; },
       "event policy: finite_check_steps: must be a power of two (1, 2, 4, ...) (got 0)"},
      {[](EventPolicy& p) { p.decision_passes = 0; },
       "event policy: decision_passes: must be at least 1 (got 0)"},
      {[](EventPolicy& p) { p.position_passes = -1; },
       "event policy: position_passes: must be at least 1 (got -1)"},
      {[](EventPolicy& p) { p.steps_per_period = 0.5; },
       "event policy: steps_per_period: must be at least 1 (got 0.5)"},
      {[](EventPolicy& p) { p.steps_per_period = std::numeric_limits<double>::quiet_NaN(); },
       "event policy: steps_per_period: must be at least 1 (got nan)"},
      {[](EventPolicy& p) { p.touch_probes = -1; },
       "event policy: touch_probes: must be at least 0 (got -1)"},
      {[](EventPolicy& p) { p.max_events_at_one_instant = -2; },
       "event policy: max_events_at_one_instant: must be at least 0 (got -2)"},
  };
  const model::Model m = MakeDeck(DeckParams{});
  const ConstantExcitation rest({0.0, 0.0}, 0.0);
  for (const Row& row : rows) {
    EventPolicy policy;
    row.set(policy);
    SimulationWorkspace ws(m);
    try {
      Simulate(m, rest, EndAt(0.1), ws, {}, policy);
      ADD_FAILURE() << "accepted: " << row.message;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), row.message);
    }
  }
  for (const long steps : {1L, 2L, 32L}) {
    EventPolicy policy;
    policy.finite_check_steps = steps;
    SimulationWorkspace ws(m);
    EXPECT_EQ(Simulate(m, rest, EndAt(0.1), ws, {}, policy).status, RunStatus::kOk) << steps;
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::simulate_test
