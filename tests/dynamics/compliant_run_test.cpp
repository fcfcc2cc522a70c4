// The deck's dynamics with compliant abutments (solver/dynamics/compliant_run.h), against things
// the integrator does not compute: the energy ledger (a conservation law), the rigid Newton
// impact of the event-driven integrator as the limit of stiffening spring-dashpots tuned to its
// restitution, and a static equilibrium solved in closed form.
#include "solver/dynamics/compliant_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"
#include "tests/dynamics/benchmark_cases.h"

namespace skewbridge::dynamics {
namespace {

constexpr double kPi = std::numbers::pi;

// The pilot bridge at both gaps `gap_m` with compliant abutments: Wilson and Elgamal's per-metre
// backfill (K_max = K_ur = 20 300 kN/m/m, R_f = 0.7, F_ult = 326 kN/m) over the skewed backwall's
// length W / cos a, 5 springs from P1 to P2 and from P3 to P4.
struct CompliantBridge {
  model::Model model;
  std::vector<CompliantSpring> springs;
};
CompliantBridge CompliantPilot(double gap_m) {
  const model::Model rigid = bench::PilotBridge(true, gap_m);
  const model::DeckGeometry& g = rigid.body(0).geometry;
  const double wall_m = g.width_m / std::cos(g.skew_rad);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 0, 1, wall, 5, "+x");
  const std::vector<CompliantSpring> minus = WallSprings(rigid, 2, 3, wall, 5, "-x");
  springs.insert(springs.end(), minus.begin(), minus.end());
  return {WithoutContacts(rigid), springs};
}

TEST(CompliantRun, EnergyLedgerClosesWithTheHysteresis) {
  // The pilot deck pounding both backfills under the record-like signal: the springs' work split
  // into stored and dissipated energy closes the ledger to 1e-6 of the input.
  const CompliantBridge bridge = CompliantPilot(bench::kPilotStudyGap_m);
  ASSERT_EQ(bridge.springs.size(), 10u);
  ASSERT_EQ(bridge.model.n_contacts(), 0);
  records::SampledExcitation ex(0.01, bench::RecordLikeSignal());
  model::RunControl control;
  control.end_time_s = 40.0;
  const CompliantRunResult out = SimulateCompliant(bridge.model, bridge.springs, ex, control);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_GT(r.impacts, 5);
  EXPECT_GT(r.rk_steps, 100);
  EXPECT_GT(r.free_steps, 100);
  const EnergyLedger& e = r.energy;
  EXPECT_GT(out.joint_dissipated_J, 1e-3 * e.input_J);
  EXPECT_GE(out.joint_stored_J, 0.0);
  EXPECT_LT(std::abs(e.balance_error_J), 1e-6 * e.input_J)
      << "input " << e.input_J << " dissipated " << out.joint_dissipated_J;
  EXPECT_GT(out.max_spring_force_N.maxCoeff(), 0.0);
  EXPECT_EQ(out.max_spring_force_N.size(), 10);
  // The ledger is bookkeeping: without it the same responses, bit for bit.
  model::RunControl off = control;
  off.energy_ledger = false;
  const CompliantRunResult out_off = SimulateCompliant(bridge.model, bridge.springs, ex, off);
  EXPECT_TRUE(out_off.run.max_abs_q == r.max_abs_q);
  EXPECT_TRUE(out_off.run.max_travel_m == r.max_travel_m);
  EXPECT_TRUE(out_off.run.q_end == r.q_end);
  EXPECT_TRUE(std::isnan(out_off.run.energy.balance_error_J));
}

// The restitution of a linear spring-dashpot that pulls on nothing, against a point mass
// [Schwager and Poeschel 2007; docs/compliant.md §3], for zeta < 1/sqrt(2).
double SpringDashpotRestitution(double zeta) {
  const double root = std::sqrt(1.0 - zeta * zeta);
  const double wt = kPi - std::atan2(2.0 * zeta * root, 1.0 - 2.0 * zeta * zeta);
  return std::exp(-zeta * wt / root) * std::abs(std::cos(wt) - zeta / root * std::sin(wt));
}

// The damping ratio whose restitution is e (bisection: the restitution falls with zeta).
double ZetaFor(double e) {
  double lo = 0.0, hi = 0.7;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (SpringDashpotRestitution(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(CompliantRun, StiffeningSpringDashpotsTendToTheRigidNewtonImpact) {
  // A free skew deck (eta0 = 2, a = 30 deg) turned by 0.02 rad drifts into the +x wall; only its
  // corner P1 can touch. The rigid run: the contact P1 with eps_N = e, frictionless. The compliant
  // runs: one spring-dashpot at P1 whose dashpot gives e against the corner's effective mass
  // 1 / (w^T M^-1 w), stiffened by 4 each time. After the strike both decks fly free: their
  // velocities converge, the error falling as the contact time sqrt(m / k) (order 1/2 in k).
  const double e = 0.6, gap = 0.2, v0 = 0.5;
  model::DeckSpec spec;
  spec.mass_kg = 1.0e5;
  spec.geometry = {30.0, model::WidthFromEta0(2.0, 30.0 * kPi / 180.0, 30.0), 30.0 * kPi / 180.0};
  spec.abutments = model::AbutmentSet::kPlusX;
  spec.gap_plus_m = gap;
  spec.restitution = e;
  spec.friction = 0.0;
  const model::Model base = model::BuildDeckModel(spec);
  const model::Contact p1 = base.contact(0);
  ASSERT_EQ(p1.name, "P1");
  const model::Model rigid(base.bodies(), base.K(), base.C(), base.r(), {p1}, "rigid");
  InitialState initial;
  initial.q = Eigen::Vector3d(0.0, 0.0, 0.02);
  initial.u = Eigen::Vector3d(v0, 0.0, 0.0);
  // The corner's gap and gradient at the turned rest.
  const double th = 0.02, c = std::cos(th), s = std::sin(th);
  const Eigen::Vector2d rp(c * p1.point_m.x() - s * p1.point_m.y(),
                           s * p1.point_m.x() + c * p1.point_m.y());
  const Eigen::Vector2d n = p1.face.normal;
  const double g0 = n.dot(rp - p1.face.point_m);
  ASSERT_GT(g0, 0.05);
  const Eigen::Vector3d w(n.x(), n.y(), -n.x() * rp.y() + n.y() * rp.x());
  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = g0 / (-w[0] * v0) + 0.5;
  SimulationWorkspace ws_rigid(rigid);
  const RunResult r_rigid = Simulate(rigid, still, control, ws_rigid, initial);
  ASSERT_EQ(r_rigid.status, RunStatus::kOk);
  ASSERT_EQ(r_rigid.impacts, 1);
  // The corner's effective mass at the turned rest.
  const double m_eff = 1.0 / (w.cwiseProduct(rigid.inverse_mass_diagonal()).dot(w));
  const double zeta = ZetaFor(e);
  const double scale = v0 * 0.5 * spec.geometry.length_m;
  std::vector<double> errors;
  for (const double k : {1e8, 4e8, 16e8, 64e8}) {
    CompliantSpring spring;
    spring.name = "+x.1";
    spring.body = 0;
    spring.point_m = p1.point_m;
    spring.face = p1.face;
    spring.law = SpringLaw::kSpringDashpot;
    spring.k_N_per_m = k;
    spring.c_Ns_per_m = 2.0 * zeta * std::sqrt(k * m_eff);
    const CompliantRunResult out =
        SimulateCompliant(WithoutContacts(rigid), {spring}, still, control, initial);
    const RunResult& r = out.run;
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    ASSERT_EQ(r.impacts, 1);
    EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-6 * 0.5 * spec.mass_kg * v0 * v0);
    const Eigen::Vector3d du = r.u_end - r_rigid.u_end;
    errors.push_back(std::hypot(du[0], du[1], du[2] * scale) / v0);
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log(errors[i - 1] / errors[i]) / std::log(4.0);
    std::printf("k x %d: velocity error %.3e, order in k %.3f\n", 1 << (2 * i), errors[i], order);
    EXPECT_GT(order, 0.35) << "step " << i;
    EXPECT_LT(order, 0.65) << "step " << i;
  }
  EXPECT_LT(errors.back(), 0.02);
}

TEST(CompliantRun, StaticForceOfTheBackfillMeetsTheClosedForm) {
  // A square deck with the +x backfill, uncoupled substructure w0 = 2 pi rad/s and dampers well
  // above critical, under a ground acceleration ramped over 1 s to -A and held: the deck creeps
  // into the wall along the envelope and rests where k x + F(x - gap) = m A, with
  // F(d) = d / (a + b d): k b d^2 + (k a + 1 - P b) d - P a = 0, P = m A - k gap.
  model::DeckSpec spec;
  spec.mass_kg = 1.0e6;
  spec.geometry = {40.0, 12.0, 0.0};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = 2.0 * kPi;
  spec.abutments = model::AbutmentSet::kPlusX;
  spec.gap_plus_m = 0.02;
  const joint::HyperbolicGap wall{4e8, 4e8, 0.7, 5e6, 0.0};
  const double k = spec.mass_kg * 4.0 * kPi * kPi;
  const double inertia = model::UniformDeckInertia(spec.mass_kg, spec.geometry);
  const double k_wall = wall.k_max_N_per_m;
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  C(0, 0) = 2.0 * 2.0 * std::sqrt((k + k_wall) * spec.mass_kg);
  C(1, 1) = 2.0 * 2.0 * std::sqrt(k * spec.mass_kg);
  C(2, 2) = 2.0 * 2.0 * std::sqrt((4.0 * kPi * kPi * inertia + k_wall * 36.0) * inertia);
  spec.C = C;
  const model::Model rigid = model::BuildDeckModel(spec);
  const std::vector<CompliantSpring> springs = WallSprings(rigid, 0, 1, wall, 5, "+x");
  const double A = 3.0;
  std::vector<double> samples(21, -A);
  samples[0] = 0.0;
  records::SampledExcitation ex(1.0, samples);
  model::RunControl control;
  control.end_time_s = 20.0;
  const CompliantRunResult out = SimulateCompliant(WithoutContacts(rigid), springs, ex, control);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  const double a = 1.0 / wall.k_max_N_per_m, b = wall.r_f / wall.f_ult_N;
  const double P = spec.mass_kg * A - k * spec.gap_plus_m;
  const double B = k * a + 1.0 - P * b;
  const double d = (-B + std::sqrt(B * B + 4.0 * k * b * P * a)) / (2.0 * k * b);
  EXPECT_NEAR(r.q_end[0], spec.gap_plus_m + d, 1e-7 * d);
  EXPECT_NEAR(r.q_end[2], 0.0, 1e-9);
  // The wall's force k x - m A balances, and is the envelope's at d.
  const double wall_force = P - k * d;
  EXPECT_NEAR(wall_force, d / (a + b * d), 1e-9 * wall_force);
  EXPECT_NEAR(spec.mass_kg * A - k * r.q_end[0], wall_force, 1e-6 * wall_force);
  EXPECT_NEAR(out.max_spring_force_N.sum(), wall_force, 1e-6 * wall_force);
  EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-6 * std::abs(r.energy.input_J));
}

}  // namespace
}  // namespace skewbridge::dynamics
