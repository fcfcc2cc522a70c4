// Coulomb friction on a compliant wall (CompliantSpring::mu, solver/dynamics/compliant_run.h),
// against things the integrator does not compute: the piecewise closed-form motion of a block
// pressed against the wall and pushed along it (stick on the stick spring, slip at mu N, stick
// again), the friction's dissipation as mu N times the slip, and the energy ledger of the pilot
// deck with a frictional backfill.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "records/excitations.h"
#include "solver/common/error.h"
#include "solver/dynamics/compliant_run.h"
#include "solver/model/builders.h"
#include "tests/dynamics/benchmark_cases.h"

namespace skewbridge::dynamics::compliant_friction_test {
namespace {

// The drive of the block test: the ground's acceleration along the wall D(t) (m/s^2, the block
// pushed by m D along +t) at the breakpoints (t, D), linear between them, constant after.
struct Drive {
  std::vector<double> t, a;
  double At(double time) const {
    if (time <= t.front()) return a.front();
    for (std::size_t i = 1; i < t.size(); ++i) {
      if (time <= t[i]) return a[i - 1] + (a[i] - a[i - 1]) * (time - t[i - 1]) / (t[i] - t[i - 1]);
    }
    return a.back();
  }
  // The exact integral of D over [t0, t1]: the trapezoid rule between breakpoints.
  double Integral(double t0, double t1) const {
    std::vector<double> cuts{t0};
    for (double b : t) {
      if (b > t0 && b < t1) cuts.push_back(b);
    }
    cuts.push_back(t1);
    double sum = 0.0;
    for (std::size_t i = 1; i < cuts.size(); ++i) {
      sum += 0.5 * (At(cuts[i - 1]) + At(cuts[i])) * (cuts[i] - cuts[i - 1]);
    }
    return sum;
  }
};

TEST(CompliantFriction, APressedBlockSlipsAtMuNDeceleratesAndSticksInClosedForm) {
  // A block (1e6 kg, no substructure stiffness) whose one backfill spring acts at its centre of
  // mass against a wall normal to x (no moment: it only translates). The ground presses it into
  // the wall (ramped over 1 s to 2 m/s^2 and held; a damper along x at the envelope's critical
  // settles it by t0 = 3 s), so N = m 2 m/s^2 = 2 MN. From t0 the ground pushes it along the wall
  // (y, the wall's tangent): D rises at c = 1.8 m/s^3 to 0.9 m/s^2 (1.5 mu N / m), holds, drops
  // to 0 at 4.05 s, rises to 0.3 m/s^2 (0.5 mu N / m) at 4.30 s and holds. mu = 0.3, k_t = K_max.
  //  - stick: m s'' + k_t s = m c tau: s = (c / w^2)(tau - sin(w tau) / w), w^2 = k_t / m; it slips
  //    when k_t s reaches mu N;
  //  - slip: m v' = m D(t) - mu N: the drive's exact integral; at 0 drive it decelerates at
  //    mu N / m;
  //  - stick again when v reaches 0 (the drive below mu N), then oscillates on the stick spring:
  //    v = -((mu N - m D) / k_t) w sin(w (t - t_k)), inside the cone (the run ends within its
  //    period);
  //  - the friction dissipates mu N times the slip, the velocity's integral over the slip.
  const double m = 1.0e6, A = 2.0, mu = 0.3, t0 = 3.0;
  model::DeckSpec spec;
  spec.mass_kg = m;
  spec.geometry = {30.0, 12.0, 0.0};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = 0.0;
  const joint::HyperbolicGap law{4e8, 4e8, 0.7, 5e6, 0.0};
  // The envelope's slope where it carries m A, for the damper.
  const double a_ = 1.0 / law.k_max_N_per_m, b_ = law.r_f / law.f_ult_N;
  const double d_rest = m * A * a_ / (1.0 - m * A * b_);
  const double slope = a_ / std::pow(a_ + b_ * d_rest, 2);
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  C(0, 0) = 2.0 * std::sqrt(slope * m);
  spec.C = C;
  spec.abutments = model::AbutmentSet::kPlusX;
  spec.gap_plus_m = 1.0;
  const model::Model model = WithoutContacts(model::BuildDeckModel(spec));
  CompliantSpring s;
  s.name = "block";
  s.body = 0;
  s.point_m = Eigen::Vector2d::Zero();
  s.face.body = model::kGround;
  s.face.normal = Eigen::Vector2d(-1.0, 0.0);
  s.face.tangent = Eigen::Vector2d(0.0, 1.0);
  s.face.point_m = Eigen::Vector2d(0.01, 0.0);
  s.law = SpringLaw::kBackfill;
  s.backfill = law;
  s.mu = mu;
  const double k_t = law.k_max_N_per_m, w = std::sqrt(k_t / m), N = m * A, c = 1.8;
  const Drive drive{{t0, 3.5, 4.0, 4.05, 4.25, 4.30}, {0.0, 0.9, 0.9, 0.0, 0.0, 0.3}};
  const double dt = 0.05, t_end = 4.6;
  std::vector<double> ax, ay;
  for (int i = 0; i * dt <= t_end + 1e-9; ++i) {
    const double t = i * dt;
    ax.push_back(-A * std::min(t, 1.0));
    ay.push_back(-drive.At(t));
  }
  records::SampledExcitation ex(dt, ax, ay);
  model::RunControl control;
  control.end_time_s = t_end;
  control.output_interval_s = 0.01;
  const CompliantRunResult out = SimulateCompliant(model, {s}, ex, control);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;

  // The closed form: the slip's start (bisection on the stick motion), its end, the velocity.
  const auto stick_force = [&](double tau) { return m * c * (tau - std::sin(w * tau) / w); };
  double lo = 0.0, hi = 0.5;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (stick_force(mid) < mu * N ? lo : hi) = mid;
  }
  const double t_slip = t0 + lo;
  const double v_slip = c / (w * w) * (1.0 - std::cos(w * lo));
  const auto v_slipping = [&](double t) {
    return v_slip + drive.Integral(t_slip, t) - mu * N / m * (t - t_slip);
  };
  const double d_hold = 0.3;  // the last drive, 0.5 mu N / m
  ASSERT_GT(v_slipping(4.30), 0.0);
  const double t_stick = 4.30 + v_slipping(4.30) / (mu * N / m - d_hold);
  // The run ends within one period of the stick oscillation after t_k: undamped, it would graze
  // the cone again (F_t back at -mu N) at every period.
  ASSERT_GT(t_end - t_stick, 0.1);
  ASSERT_LT(t_end - t_stick, 2.0 * std::numbers::pi / w);
  const auto v_exact = [&](double t) {
    if (t <= t0) return 0.0;
    if (t <= t_slip) return c / (w * w) * (1.0 - std::cos(w * (t - t0)));
    if (t <= t_stick) return v_slipping(t);
    return -((mu * N - m * d_hold) / k_t) * w * std::sin(w * (t - t_stick));
  };
  // The slip: the velocity's integral (piecewise quadratic: Simpson between breakpoints is exact).
  std::vector<double> cuts{t_slip};
  for (double b : drive.t) {
    if (b > t_slip && b < t_stick) cuts.push_back(b);
  }
  cuts.push_back(t_stick);
  double slip = 0.0;
  for (std::size_t i = 1; i < cuts.size(); ++i) {
    const double a = cuts[i - 1], b = cuts[i];
    slip += (b - a) / 6.0 * (v_slipping(a) + 4.0 * v_slipping(0.5 * (a + b)) + v_slipping(b));
  }

  std::printf("slip at %.9f s (closed form %.9f), stick at %.6f s, slip %.9f m (%.9f)\n",
              out.first_slip_time_s[0], t_slip, t_stick, out.wall_slip_m[0], slip);
  EXPECT_NEAR(out.first_slip_time_s[0], t_slip, 1e-7);
  EXPECT_NEAR(out.wall_slip_m[0], slip, 1e-7 * slip);
  const Histories& h = r.histories;
  double worst = 0.0, v_peak = 0.0;
  for (std::size_t k = 0; k < h.t_s.size(); ++k) {
    const double t = h.t_s[k];
    worst = std::max(worst, std::abs(h.u[3 * k + 1] - v_exact(t)));
    v_peak = std::max(v_peak, std::abs(v_exact(t)));
    if (t >= t0) {
      EXPECT_NEAR(h.u[3 * k], 0.0, 1e-9) << "t " << t;  // at rest normal to the wall
    }
  }
  std::printf("largest velocity error along the wall %.3e m/s of %.3f m/s\n", worst, v_peak);
  EXPECT_GT(v_peak, 0.1);
  EXPECT_LT(worst, 1e-6 * v_peak);
  // The deceleration at zero drive (4.05 to 4.25 s) is mu N / m: its samples on one line.
  const auto sample = [&](double t) {
    return h.u[3 * static_cast<std::size_t>(t / 0.01 + 0.5) + 1];
  };
  EXPECT_NEAR((sample(4.10) - sample(4.20)) / 0.1, mu * N / m, 1e-6 * mu * N / m);
  // The friction dissipates mu N times the slip; the ledger closes.
  EXPECT_NEAR(r.energy.friction_J, mu * N * slip, 1e-6 * mu * N * slip);
  EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-6 * r.energy.input_J);
}

// The pilot bridge with compliant abutments as compliant_run_test.cpp has it, with wall friction
// mu on every backfill spring.
std::vector<CompliantSpring> PilotSprings(const model::Model& rigid, double mu) {
  const model::DeckGeometry& g = rigid.body(0).geometry;
  const double wall_m = g.width_m / std::cos(g.skew_rad);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 0, 1, wall, 5, "+x");
  const std::vector<CompliantSpring> minus = WallSprings(rigid, 2, 3, wall, 5, "-x");
  springs.insert(springs.end(), minus.begin(), minus.end());
  for (CompliantSpring& s : springs) s.mu = mu;
  return springs;
}

TEST(CompliantFriction, PilotLedgerClosesWithTheWallFriction) {
  // The pilot deck pounding both frictional backfills (mu = 0.3) under the record-like signal
  // along x and a second component along y: the springs slip and stick on the walls, and the
  // ledger with the friction's dissipation closes to 1e-6 of the input.
  const model::Model rigid = bench::PilotBridge(true, bench::kPilotStudyGap_m);
  const std::vector<double> sig = bench::RecordLikeSignal();
  std::vector<double> sy(sig.size());
  for (std::size_t i = 0; i < sig.size(); ++i) sy[i] = 0.7 * sig[(i * 7) % sig.size()];
  records::SampledExcitation ex(0.01, sig, sy);
  model::RunControl control;
  control.end_time_s = 20.0;
  const CompliantRunResult out =
      SimulateCompliant(WithoutContacts(rigid), PilotSprings(rigid, 0.3), ex, control);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_GT(r.impacts, 3);
  int slipped = 0;
  for (int j = 0; j < out.first_slip_time_s.size(); ++j)
    slipped += !std::isnan(out.first_slip_time_s[j]);
  const EnergyLedger& e = r.energy;
  std::printf(
      "input %.6e J, friction %.6e J, hysteresis %.6e J, slip %.4e m, %d springs slipped, "
      "balance %.3e J\n",
      e.input_J, e.friction_J, out.joint_dissipated_J, out.wall_slip_m.sum(), slipped,
      e.balance_error_J);
  EXPECT_GE(slipped, 2);
  EXPECT_GT(e.friction_J, 1e-4 * e.input_J);
  EXPECT_GT(out.wall_slip_m.sum(), 0.0);
  EXPECT_LT(std::abs(e.balance_error_J), 1e-6 * e.input_J);
  // Without friction the same deck dissipates nothing by friction.
  const CompliantRunResult none =
      SimulateCompliant(WithoutContacts(rigid), PilotSprings(rigid, 0.0), ex, control);
  EXPECT_EQ(none.run.energy.friction_J, 0.0);
  EXPECT_EQ(none.wall_slip_m.sum(), 0.0);
}

TEST(CompliantFriction, RefusesABadCoefficient) {
  const model::Model rigid = bench::PilotBridge(true, bench::kPilotStudyGap_m);
  records::SampledExcitation ex(0.01, std::vector<double>(10, 0.0));
  for (const double mu : {-0.1, std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_THROW(SimulateCompliant(WithoutContacts(rigid), PilotSprings(rigid, mu), ex, {}),
                 InputError);
  }
  std::vector<CompliantSpring> springs = PilotSprings(rigid, 0.2);
  springs[0].k_t_N_per_m = -1.0;
  EXPECT_THROW(SimulateCompliant(WithoutContacts(rigid), springs, ex, {}), InputError);
}

}  // namespace
}  // namespace skewbridge::dynamics::compliant_friction_test
