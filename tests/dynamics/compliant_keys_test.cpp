// Shear keys in the deck's dynamics (solver/dynamics/compliant_run.h, SpringLaw::kShearKey),
// against things the integrator does not compute: static equilibria on the backbone written by
// hand, the breaking time of a deck driven at a constant velocity, the piecewise closed-form motion
// of a mass through the backbone, the energy (the backbone's area, the ledger).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/compliant_run.h"
#include "solver/model/builders.h"
#include "tests/dynamics/benchmark_cases.h"

namespace skewbridge::dynamics::compliant_keys_test {
namespace {

constexpr double kPi = std::numbers::pi;

// The key of these tests: V_n = 2 MN at D3 = 20 mm (K_0 = 1e8 N/m), softening to V_res = 0.5 MN
// at D_res = 60 mm and to zero at DD = 100 mm. Its backbone's area (the energy it takes to break
// it): V_n D3 / 2 + (V_n + V_res) (D_res - D3) / 2 + V_res (DD - D_res) / 2 = 20 + 50 + 10 kJ.
joint::ShearKey TestKey() { return {0.0, 2.0e6, 0.02, 0.5e6, 0.06, 0.1}; }
constexpr double kKeyArea_J = 80.0e3;

// A free square deck (no substructure, no damping) of mass m, L = 30 m, W = 12 m, no abutment.
model::Model FreeDeck(double mass_kg, double w0_radps = 0.0,
                      const Eigen::Matrix3d& C = Eigen::Matrix3d::Zero()) {
  model::DeckSpec spec;
  spec.mass_kg = mass_kg;
  spec.geometry = {30.0, 12.0, 0.0};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = w0_radps;
  spec.C = C;
  spec.abutments = model::AbutmentSet::kPlusX;
  spec.gap_plus_m = 1.0;
  return model::BuildDeckModel(spec);
}

// One key against the side y = W/2 of body 0 at the side's mid-point (0, W/2): its force passes
// through the centre of mass, so the deck only translates. `gap_m` beyond the side.
CompliantSpring MidSideKey(double gap_m) {
  CompliantSpring s;
  s.name = "key";
  s.body = 0;
  s.point_m = Eigen::Vector2d(0.0, 6.0);
  s.face.body = model::kGround;
  s.face.normal = Eigen::Vector2d(0.0, -1.0);
  s.face.tangent = Eigen::Vector2d(1.0, 0.0);
  s.face.point_m = Eigen::Vector2d(0.0, 6.0 + gap_m);
  s.law = SpringLaw::kShearKey;
  s.key = TestKey();
  return s;
}

TEST(CompliantKeys, AbutmentKeysFaceEachOtherBesideTheDecksSides) {
  // A skew deck: the +x abutment's keys act on P1 (y = W/2) and P2 (y = -W/2), against faces
  // parallel to the deck's axis at the gap beyond each side, normals towards the deck.
  model::DeckSpec spec;
  spec.mass_kg = 1.0e6;
  spec.geometry = {30.0, 12.0, 30.0 * kPi / 180.0};
  spec.abutments = model::AbutmentSet::kBoth;
  spec.gap_plus_m = spec.gap_minus_m = 0.05;
  const model::Model rigid = model::BuildDeckModel(spec);
  joint::ShearKey key = TestKey();
  key.gap_m = 0.03;
  for (const auto& [first, last, prefix] :
       {std::tuple{0, 1, "+x"}, std::tuple{1, 0, "+x"}, std::tuple{2, 3, "-x"}}) {
    const std::vector<CompliantSpring> keys = AbutmentShearKeys(rigid, first, last, key, prefix);
    ASSERT_EQ(keys.size(), 2u);
    EXPECT_EQ(keys[0].name, std::string(prefix) + ".key+y");
    EXPECT_EQ(keys[1].name, std::string(prefix) + ".key-y");
    for (int i = 0; i < 2; ++i) {
      const double side = i == 0 ? 1.0 : -1.0;
      const CompliantSpring& s = keys[static_cast<std::size_t>(i)];
      EXPECT_EQ(s.law, SpringLaw::kShearKey);
      EXPECT_EQ(s.point_m.y(), side * 6.0);
      EXPECT_EQ(s.face.normal, Eigen::Vector2d(0.0, -side));
      // At rest the corner is the gap away from its key's face.
      EXPECT_NEAR(s.face.normal.dot(s.point_m - s.face.point_m), 0.03, 1e-15);
      EXPECT_EQ(s.key.gap_m, 0.0);
      EXPECT_EQ(s.key.v_n_N, key.v_n_N);
    }
  }
}

TEST(CompliantKeys, AQuasiStaticPushFollowsTheBackboneWrittenByHand) {
  // The deck on a substructure of k = m (2.4 pi)^2, dampers above critical at every stiffness the
  // key gives it, pushed transversely by a ground acceleration held at plateaus: at each it rests
  // where k y + F = m A. The plateaus are chosen at deformations d beyond the 10 mm gap with the
  // key's force written by hand: d = 10 mm on the rise (F = V_n d / D3 = 1 MN), 40 mm on the
  // softening (F = 2 - 1.5 x 20/40 = 1.25 MN), back to 35 mm on the unloading line from
  // d_max = 40 mm (F = 1.25 MN - K_0 x 5 mm = 0.75 MN), 80 mm on the residual reached by reloading
  // (F = 0.5 x 20/40 = 0.25 MN), past DD (F = 0), and back to the first plateau's acceleration:
  // the broken key carries nothing, the deck rests at y = m A / k (the intact key would hold it at
  // 20 mm).
  const double m = 1.0e6, gap = 0.01, w0 = 2.4 * kPi;
  const double k = m * w0 * w0;
  const double k0 = 1.0e8;
  const double c = 2.2 * std::sqrt((k + k0) * m);
  const model::Model deck = FreeDeck(m, w0, Eigen::Vector3d(c, c, c * 100.0).asDiagonal());
  const CompliantSpring key = MidSideKey(gap);
  struct Plateau {
    double d_m, force_N;
  };
  const std::vector<Plateau> plateaus = {
      {0.010, 1.0e6}, {0.040, 1.25e6}, {0.035, 0.75e6}, {0.080, 0.25e6}, {0.140, 0.0}};
  std::vector<double> accel_y{0.0};
  std::vector<double> rest_y;
  const int hold = 40, ramp = 2;
  std::vector<int> ends;
  auto push = [&](double A, double y) {
    const double from = accel_y.back();
    for (int i = 1; i <= ramp; ++i) accel_y.push_back(from + (A - from) * i / ramp);
    for (int i = 0; i < hold; ++i) accel_y.push_back(A);
    ends.push_back(static_cast<int>(accel_y.size()) - 1);
    rest_y.push_back(y);
  };
  for (const Plateau& p : plateaus) {
    // k y + F = m A, with the ground accelerating towards -y.
    const double y = gap + p.d_m;
    push(-(k * y + p.force_N) / m, y);
  }
  const double A1 = accel_y[static_cast<std::size_t>(ends[0])];
  push(A1, -m * A1 / k);
  records::SampledExcitation ex(1.0, std::vector<double>(accel_y.size(), 0.0), accel_y);
  model::RunControl control;
  control.end_time_s = static_cast<double>(accel_y.size() - 1);
  control.output_interval_s = 1.0;
  const CompliantRunResult out = SimulateCompliant(WithoutContacts(deck), {key}, ex, control);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  ASSERT_GE(r.histories.t_s.size(), accel_y.size());
  for (std::size_t i = 0; i < ends.size(); ++i) {
    const std::size_t at = static_cast<std::size_t>(ends[i]);
    ASSERT_EQ(r.histories.t_s[at], static_cast<double>(ends[i]));
    EXPECT_NEAR(r.histories.q[3 * at + 1], rest_y[i], 1e-8) << "plateau " << i;
    EXPECT_NEAR(r.histories.q[3 * at + 2], 0.0, 1e-12);
  }
  EXPECT_NEAR(r.q_end[1], 0.02 + 1.0e6 / k, 1e-8);  // m A1 / k = (k 20 mm + 1 MN) / k
  // The largest force is the capacity, reached on the way from the first plateau to the second.
  EXPECT_NEAR(out.max_spring_force_N[0], 2.0e6, 1e-6 * 2.0e6);
  EXPECT_NEAR(out.max_spring_deformation_m[0], 0.1, 1e-9);
  const double t_break = out.key_break_time_s[0];
  EXPECT_GT(t_break, ends[3]);
  EXPECT_LT(t_break, ends[3] + ramp + 1);
  EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-6 * std::abs(r.energy.input_J));
}

TEST(CompliantKeys, ADeckDrivenAtConstantVelocityBreaksTheKeyAtGapPlusDDOverV) {
  // A deck of 1e16 kg drifting at v = 0.5 m/s across the +x abutment towards +y: the keys cannot
  // slow it (their impulse changes v by 1e-11 m/s), so the +y key (on P1, gap 50 mm) breaks when
  // the corner has travelled gap + DD: t = (0.05 + 0.1) / 0.5 = 0.3 s, and reaches its capacity at
  // (gap + D3) / v = 0.14 s. The -y key, left behind, never carries anything.
  const double v = 0.5;
  model::DeckSpec spec;
  spec.mass_kg = 1.0e16;
  spec.geometry = {30.0, 12.0, 30.0 * kPi / 180.0};
  spec.C = Eigen::Matrix3d::Zero();
  spec.abutments = model::AbutmentSet::kPlusX;
  spec.gap_plus_m = 0.05;
  const model::Model rigid = model::BuildDeckModel(spec);
  joint::ShearKey key = TestKey();
  key.gap_m = 0.05;
  const std::vector<CompliantSpring> keys = AbutmentShearKeys(rigid, 0, 1, key, "+x");
  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = 0.5;
  InitialState initial;
  initial.q = Eigen::Vector3d::Zero();
  initial.u = Eigen::Vector3d(0.0, v, 0.0);
  const CompliantRunResult out =
      SimulateCompliant(WithoutContacts(rigid), keys, still, control, initial);
  ASSERT_EQ(out.run.status, RunStatus::kOk) << out.run.message;
  EXPECT_NEAR(out.key_break_time_s[0], (0.05 + 0.1) / v, 1e-9);
  EXPECT_TRUE(std::isnan(out.key_break_time_s[1]));
  EXPECT_NEAR(out.max_spring_force_N[0], key.v_n_N, 1e-9 * key.v_n_N);
  EXPECT_EQ(out.max_spring_force_N[1], 0.0);
  // The key took the backbone's area and gives nothing back.
  EXPECT_NEAR(out.joint_dissipated_J, kKeyArea_J, 1e-6 * kKeyArea_J);
  EXPECT_EQ(out.joint_stored_J, 0.0);
  EXPECT_EQ(out.run.impacts, 1);
}

TEST(CompliantKeys, AMassThroughTheBackboneMeetsThePiecewiseClosedForm) {
  // A free deck of m = 1e6 kg at v0 = 1 m/s towards the mid-side key (gap 50 mm): the motion is
  // harmonic on the rise (w = sqrt(K_0 / m) = 10 rad/s), hyperbolic on the two falling pieces
  // (lambda = sqrt(k_i / m) for their slopes k_i), so the times of D3, D_res and DD are closed
  // forms; after the break the deck flies on at sqrt(v0^2 - 2 area / m).
  const double m = 1.0e6, v0 = 1.0, gap = 0.05;
  const joint::ShearKey key = TestKey();
  const double w = std::sqrt(key.v_n_N / key.d3_m / m);
  const double t_contact = gap / v0;
  const double tau1 = std::asin(w * key.d3_m / v0) / w;
  const double v1 = std::sqrt(v0 * v0 - w * w * key.d3_m * key.d3_m);
  // Softening: s = d - D3 - V_n / k1 obeys s'' = lambda1^2 s; s = A cosh + B sinh reaches
  // s_T = D_res - D3 - V_n / k1 where (A + B) z^2 - 2 s_T z + (A - B) = 0, z = exp(lambda1 tau).
  const double k1 = (key.v_n_N - key.v_res_N) / (key.d_res_m - key.d3_m);
  const double l1 = std::sqrt(k1 / m);
  const double A = -key.v_n_N / k1, B = v1 / l1, sT = key.d_res_m - key.d3_m - key.v_n_N / k1;
  const double z = (sT + std::sqrt(sT * sT - (A + B) * (A - B))) / (A + B);
  const double tau2 = std::log(z) / l1;
  const double v2 = l1 * (A * std::sinh(l1 * tau2) + B * std::cosh(l1 * tau2));
  // Residual: s = d - DD, s'' = lambda2^2 s from s(0) = D_res - DD, s'(0) = v2, reaches 0 at
  // tanh(lambda2 tau) = (DD - D_res) lambda2 / v2.
  const double k2 = key.v_res_N / (key.dd_m - key.d_res_m);
  const double l2 = std::sqrt(k2 / m);
  const double tau3 = std::atanh((key.dd_m - key.d_res_m) * l2 / v2) / l2;
  const double t_break = t_contact + tau1 + tau2 + tau3;
  // The energy says the same speeds.
  ASSERT_NEAR(v1 * v1, v0 * v0 - 2.0 * 20.0e3 / m, 1e-12);
  ASSERT_NEAR(v2 * v2, v0 * v0 - 2.0 * 70.0e3 / m, 1e-9);

  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = 1.0;
  control.relative_tolerance = 1e-11;
  control.absolute_tolerance = 1e-13;
  InitialState initial;
  initial.q = Eigen::Vector3d::Zero();
  initial.u = Eigen::Vector3d(0.0, v0, 0.0);
  const CompliantRunResult out =
      SimulateCompliant(WithoutContacts(FreeDeck(m)), {MidSideKey(gap)}, still, control, initial);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_NEAR(out.key_break_time_s[0], t_break, 1e-9);
  const double v_end = std::sqrt(v0 * v0 - 2.0 * kKeyArea_J / m);
  EXPECT_NEAR(r.u_end[1], v_end, 1e-9);
  EXPECT_NEAR(r.q_end[1], gap + key.dd_m + v_end * (1.0 - t_break), 1e-9);
  EXPECT_NEAR(out.joint_dissipated_J, kKeyArea_J, 1e-6 * kKeyArea_J);
  EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-6 * r.energy.initial_J);
  EXPECT_NEAR(out.max_spring_force_N[0], key.v_n_N, 1e-6 * key.v_n_N);
  EXPECT_EQ(r.impacts, 1);
}

TEST(CompliantKeys, ABrokenKeyNeverPushesAgain) {
  // A deck on a substructure (w0 = 2 pi rad/s, no damping) released at 1.5 m/s towards the key
  // (gap 10 mm) breaks it on its first swing (kinetic 1.1 MJ against the 80 kJ of the backbone
  // plus the substructure's strain) and then oscillates through the key's place for 20 s: its
  // energy after the break is constant (nothing pushes), and its amplitude is the free
  // oscillator's sqrt(2 E / k).
  const double m = 1.0e6, w0 = 2.0 * kPi, v0 = 1.5, gap = 0.01;
  const model::Model deck = FreeDeck(m, w0);
  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = 20.0;
  InitialState initial;
  initial.q = Eigen::Vector3d::Zero();
  initial.u = Eigen::Vector3d(0.0, v0, 0.0);
  const CompliantRunResult out =
      SimulateCompliant(WithoutContacts(deck), {MidSideKey(gap)}, still, control, initial);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  ASSERT_TRUE(std::isfinite(out.key_break_time_s[0]));
  EXPECT_LT(out.key_break_time_s[0], 0.25);  // on the first quarter swing
  const double e_after = 0.5 * m * v0 * v0 - kKeyArea_J;
  const double k = m * w0 * w0;
  const double e_end = 0.5 * m * r.u_end.squaredNorm() + 0.5 * k * r.q_end.squaredNorm();
  EXPECT_NEAR(e_end, e_after, 1e-7 * e_after);
  EXPECT_NEAR(r.max_abs_q[1], std::sqrt(2.0 * e_after / k), 1e-7);
  EXPECT_EQ(r.impacts, 1);  // it closed once, the strike that broke it
  EXPECT_NEAR(out.joint_dissipated_J, kKeyArea_J, 1e-6 * kKeyArea_J);
}

TEST(CompliantKeys, EnergyLedgerClosesWithBackfillAndKeysOnThePilotBridge) {
  // The pilot bridge with Wilson and Elgamal's backfill and the exterior keys of both abutments
  // (gap 5 mm, V_n = 0.5 MN at D3 = 2 mm, V_res = 0.1 MN at 4 mm, DD = 8 mm), under the
  // record-like signal along x and another, scaled by 0.8, along y: the keys engage, unload and
  // break (all four, between 16 and 19 s); the ledger closes to 1e-6 of the input.
  const model::Model rigid = bench::PilotBridge(true, bench::kPilotStudyGap_m);
  const model::DeckGeometry& g = rigid.body(0).geometry;
  const double wall_m = g.width_m / std::cos(g.skew_rad);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 0, 1, wall, 5, "+x");
  for (const auto& more :
       {WallSprings(rigid, 2, 3, wall, 5, "-x"),
        AbutmentShearKeys(rigid, 0, 1, {0.005, 0.5e6, 0.002, 0.1e6, 0.004, 0.008}, "+x"),
        AbutmentShearKeys(rigid, 2, 3, {0.005, 0.5e6, 0.002, 0.1e6, 0.004, 0.008}, "-x")}) {
    springs.insert(springs.end(), more.begin(), more.end());
  }
  ASSERT_EQ(springs.size(), 14u);
  const std::vector<double> ax = bench::RecordLikeSignal();
  std::vector<double> ay = bench::RecordLikeSignal(777);
  for (double& a : ay) a *= 0.8;
  records::SampledExcitation ex(0.01, ax, ay);
  model::RunControl control;
  control.end_time_s = 20.0;
  const CompliantRunResult out = SimulateCompliant(WithoutContacts(rigid), springs, ex, control);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  int engaged = 0, broken = 0;
  for (int j = 10; j < 14; ++j) {
    engaged += out.max_spring_force_N[j] > 0.0;
    broken += std::isfinite(out.key_break_time_s[j]);
    EXPECT_LE(out.max_spring_force_N[j], 0.5e6 * (1.0 + 1e-6));
  }
  for (int j = 0; j < 10; ++j) EXPECT_TRUE(std::isnan(out.key_break_time_s[j]));
  EXPECT_GE(engaged, 2);
  EXPECT_GE(broken, 1);
  const EnergyLedger& e = r.energy;
  EXPECT_LT(std::abs(e.balance_error_J), 1e-6 * e.input_J)
      << "input " << e.input_J << " dissipated " << out.joint_dissipated_J;
}

}  // namespace
}  // namespace skewbridge::dynamics::compliant_keys_test
