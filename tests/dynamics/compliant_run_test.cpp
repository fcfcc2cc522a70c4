// The deck's dynamics with compliant abutments (solver/dynamics/compliant_run.h), against things
// the integrator does not compute: the energy ledger (a conservation law), the rigid Newton
// impact of the event-driven integrator as the limit of stiffening spring-dashpots tuned to its
// restitution, and a static equilibrium solved in closed form.
#include "solver/dynamics/compliant_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"
#include "tests/dynamics/benchmark_cases.h"

namespace skewbridge::dynamics::compliant_run_test {
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

// The full edge of the +x end of deck `rigid` (P1 to P2) as n linear spring-dashpots sharing the
// stiffness k_N_per_m, each with the damping ratio zeta against an n-th of the deck's mass.
std::vector<CompliantSpring> FullEdgeSpringDashpots(const model::Model& rigid, double k_N_per_m,
                                                    double zeta, int n) {
  const joint::HyperbolicGap unused{1.0, 1.0, 1.0, 1.0, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 0, 1, unused, n, "+x");
  const double m = rigid.body(0).mass_kg / n;
  for (CompliantSpring& s : springs) {
    s.law = SpringLaw::kSpringDashpot;
    s.k_N_per_m = k_N_per_m / n;
    s.c_Ns_per_m = 2.0 * zeta * std::sqrt(s.k_N_per_m * m);
  }
  return springs;
}

// A skew deck (a = 30 deg, L = 30 m, 1e6 kg) of skew ratio eta0 on an uncoupled substructure
// (w0 = W0 = 2 pi rad/s, dampers at the critical), with the rigid frictionless +x abutment of
// eps_N = 0 at 20 mm.
model::Model PressedDeck(double eta0) {
  model::DeckSpec spec;
  spec.mass_kg = 1.0e6;
  const double a = 30.0 * kPi / 180.0;
  spec.geometry = {30.0, model::WidthFromEta0(eta0, a, 30.0), a};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = 2.0 * kPi;
  const double k = spec.mass_kg * 4.0 * kPi * kPi;
  const double inertia = model::UniformDeckInertia(spec.mass_kg, spec.geometry);
  spec.C = Eigen::Vector3d(2.0 * std::sqrt(k * spec.mass_kg), 2.0 * std::sqrt(k * spec.mass_kg),
                           2.0 * std::sqrt(4.0 * kPi * kPi * inertia * inertia))
               .asDiagonal();
  spec.abutments = model::AbutmentSet::kPlusX;
  spec.gap_plus_m = 0.02;
  spec.restitution = 0.0;
  spec.friction = 0.0;
  return model::BuildDeckModel(spec);
}

TEST(CompliantRun, PressedWithItsWholeEdgeTheDeckTurnsOnlyForEta0AboveOne) {
  // docs/theory.md §4, fact 1, as the moment balance of a persistent frictionless full-edge
  // contact: a deck pressed into the face along the face's normal (the ground accelerating along
  // n, ramped over 1 s to 3 m/s^2 and held; equal translational stiffnesses, so it translates
  // without turning until its whole edge meets the face) can be held without turning only if the
  // corners' lever arms r_1 > 0 and r_2 have opposite signs, eta0 <= 1. The rigid law at rest:
  // eta0 = 0.8 rests on both corners at theta = 0; eta0 = 1.25 rests on P2 alone, turned. Stiff
  // spring-dashpots on the full edge (5, the total k = 1e10 and 1.6e11 N/m): below one the turn is
  // the springs' unequal shortening across the edge, falling as 1/k; above one it converges to the
  // rigid law's turn, its error falling as 1/k.
  const double a = 30.0 * kPi / 180.0, A = 3.0;
  const Eigen::Vector2d n(-std::cos(a), std::sin(a));
  std::vector<double> ax(21, A * n.x()), ay(21, A * n.y());
  ax[0] = ay[0] = 0.0;
  records::SampledExcitation push(1.0, ax, ay);
  model::RunControl control;
  control.end_time_s = 20.0;
  for (const double eta0 : {0.8, 1.25}) {
    const model::Model rigid = PressedDeck(eta0);
    SimulationWorkspace ws(rigid);
    const RunResult r_rigid = Simulate(rigid, push, control, ws);
    ASSERT_EQ(r_rigid.status, RunStatus::kOk) << r_rigid.message;
    ASSERT_GE(r_rigid.impacts, 1);
    std::vector<double> theta;
    for (const double k : {1e10, 16e10}) {
      const CompliantRunResult out = SimulateCompliant(
          WithoutContacts(rigid), FullEdgeSpringDashpots(rigid, k, 0.5, 5), push, control);
      ASSERT_EQ(out.run.status, RunStatus::kOk) << out.run.message;
      EXPECT_LT(std::abs(out.run.energy.balance_error_J), 1e-6 * out.run.energy.input_J);
      EXPECT_LT(out.run.u_end.norm(), 1e-6);  // at rest
      theta.push_back(out.run.q_end[2]);
    }
    std::printf("eta0 %.2f: rigid theta %.4e rad; compliant %.4e, %.4e rad\n", eta0,
                r_rigid.q_end[2], theta[0], theta[1]);
    if (eta0 < 1.0) {
      EXPECT_LT(std::abs(r_rigid.q_end[2]), 1e-12);
      EXPECT_NEAR(theta[0] / theta[1], 16.0, 1.6);
      EXPECT_LT(std::abs(theta[1]), 1e-5);
    } else {
      EXPECT_GT(r_rigid.q_end[2], 1e-4);
      const double e0 = theta[0] - r_rigid.q_end[2], e1 = theta[1] - r_rigid.q_end[2];
      EXPECT_NEAR(e0 / e1, 16.0, 1.6);
      EXPECT_LT(std::abs(e1), 1e-2 * r_rigid.q_end[2]);
    }
  }
}

TEST(CompliantRun, AFullEdgeStrikeOfStiffSpringsTurnsTheDeckBelowEta0OfOneToo) {
  // The impact form of fact 1 is the rigid law's own: Newton's law at both corners at once leaves
  // a deck of eta0 <= 1 unturned. Springs on the full edge share the load by their shortening,
  // which starts equal along the edge: their resultant at the edge's mid-point has the lever arm
  // (r_1 + r_2) / 2 = (L / 2) sin a > 0 whatever eta0, and turns the deck during the contact. The
  // contact's outcome does not depend on the stiffness (time scales as sqrt(m / k), all else is
  // fixed), so stiffening does not bring the rigid answer back: a free deck (eta0 = 0.8) at
  // 0.5 m/s into 5 undamped springs on the full edge leaves spinning, with the same spin at
  // k = 1e10 and 1.6e11 N/m, where the rigid law (eps_N = 1) leaves it unturned.
  model::DeckSpec spec;
  spec.mass_kg = 1.0e6;
  const double a = 30.0 * kPi / 180.0, v0 = 0.5;
  spec.geometry = {30.0, model::WidthFromEta0(0.8, a, 30.0), a};
  spec.C = Eigen::Matrix3d::Zero();
  spec.abutments = model::AbutmentSet::kPlusX;
  spec.gap_plus_m = 0.02;
  spec.restitution = 1.0;
  spec.friction = 0.0;
  const model::Model rigid = model::BuildDeckModel(spec);
  InitialState initial;
  initial.q = Eigen::Vector3d::Zero();
  initial.u = v0 * Eigen::Vector3d(std::cos(a), -std::sin(a), 0.0);  // along -n
  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = 0.1;  // the contact ends by 0.07 s; no second strike yet
  SimulationWorkspace ws(rigid);
  const RunResult r_rigid = Simulate(rigid, still, control, ws, initial);
  ASSERT_EQ(r_rigid.status, RunStatus::kOk);
  ASSERT_EQ(r_rigid.impacts, 1);
  EXPECT_LT(std::abs(r_rigid.u_end[2]), 1e-12);
  std::vector<double> spin;
  for (const double k : {1e10, 16e10}) {
    const CompliantRunResult out = SimulateCompliant(
        WithoutContacts(rigid), FullEdgeSpringDashpots(rigid, k, 0.0, 5), still, control, initial);
    ASSERT_EQ(out.run.status, RunStatus::kOk) << out.run.message;
    EXPECT_LT(std::abs(out.run.energy.balance_error_J), 1e-6 * out.run.energy.initial_J);
    spin.push_back(out.run.u_end[2] * spec.geometry.length_m / v0);
  }
  std::printf("full-edge strike, eta0 0.8: omega L / v0 = %.4f (k), %.4f (16 k); rigid %.1e\n",
              spin[0], spin[1], r_rigid.u_end[2] * spec.geometry.length_m / v0);
  EXPECT_GT(std::abs(spin[0]), 0.1);
  EXPECT_NEAR(spin[1], spin[0], 1e-3 * std::abs(spin[0]));
}

TEST(CompliantRun, StrikeSeparationIsTheClosedFormBetweenTwoWalls) {
  // A free deck with square ends (a = 0, no substructure, no damping) between two walls of
  // linear spring-dashpots at the gap g, set off at v0 along x: it strikes +x at t1 = g / v0,
  // leaves with e v0 after the closed-form contact time t_c (docs/compliant.md §3), parting at the
  // deformation d_p = c e v0 / k beyond the face, flies 2 g + d_p to the -x wall and strikes it at
  // t2 = t1 + t_c + (2 g + d_p) / (e v0); the third strike comes after t_c + (2 g + e d_p) /
  // (e^2 v0), later still. min_impact_separation of a compliant run is the smallest time between
  // the starts of successive strikes: t2 - t1. With one strike it is inf, as a rigid run's.
  const double m = 1.0e6, k = 4.0e8, zeta = 0.2, g = 0.05, v0 = 0.5;
  model::DeckSpec spec;
  spec.mass_kg = m;
  spec.geometry = {30.0, 10.0, 0.0};
  spec.C = Eigen::Matrix3d::Zero();
  spec.abutments = model::AbutmentSet::kBoth;
  spec.gap_plus_m = spec.gap_minus_m = g;
  spec.friction = 0.0;
  const model::Model rigid = model::BuildDeckModel(spec);
  ASSERT_EQ(rigid.contact(0).name, "P1");
  ASSERT_EQ(rigid.contact(2).name, "P3");
  const double c = 2.0 * zeta * std::sqrt(k * m), w0 = std::sqrt(k / m);
  std::vector<CompliantSpring> springs = SpringDashpots(rigid, 0, 1, k, c, 5, "+x");
  const std::vector<CompliantSpring> minus = SpringDashpots(rigid, 2, 3, k, c, 5, "-x");
  springs.insert(springs.end(), minus.begin(), minus.end());
  const double e = SpringDashpotRestitution(zeta), root = std::sqrt(1.0 - zeta * zeta);
  const double t_c = (kPi - std::atan2(2.0 * zeta * root, 1.0 - 2.0 * zeta * zeta)) / (w0 * root);
  const double d_p = c * e * v0 / k;
  const double t1 = g / v0, t2 = t1 + t_c + (2.0 * g + d_p) / (e * v0);
  const double t3 = t2 + t_c + (2.0 * g + e * d_p) / (e * e * v0);
  InitialState initial;
  initial.q = Eigen::Vector3d::Zero();
  initial.u = Eigen::Vector3d(v0, 0.0, 0.0);
  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = t3 + t_c + 0.05;  // the third strike over, the fourth far off
  const CompliantRunResult out =
      SimulateCompliant(WithoutContacts(rigid), springs, still, control, initial);
  ASSERT_EQ(out.run.status, RunStatus::kOk) << out.run.message;
  ASSERT_EQ(out.run.impacts, 3);
  EXPECT_NEAR(out.run.min_impact_separation_s, t2 - t1, 1e-9 * (t2 - t1))
      << "closed form " << t2 - t1 << "; t3 - t2 = " << t3 - t2;
  // The velocity after the three strikes: e^3 v0 towards -x.
  EXPECT_NEAR(out.run.u_end[0], -e * e * e * v0, 1e-8 * v0);
  // One strike (the run ends before the second): no separation, as a rigid run's.
  control.end_time_s = 0.5 * (t1 + t2);
  const CompliantRunResult one =
      SimulateCompliant(WithoutContacts(rigid), springs, still, control, initial);
  ASSERT_EQ(one.run.impacts, 1);
  EXPECT_EQ(one.run.min_impact_separation_s, std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace skewbridge::dynamics::compliant_run_test
