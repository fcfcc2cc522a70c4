// A point mass striking a compliant joint: the linear spring-dashpot that pulls on nothing
// against its closed-form contact duration and restitution [Schwager and Poeschel 2007], the
// hyperbolic backfill against the closed forms of its energy (the envelope's integral, the
// unloading line's quarter period), and the energy ledger of every strike.
#include "solver/dynamics/compliant_strike.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/joint/backfill.h"

namespace skewbridge::dynamics::compliant_strike_test {
namespace {

constexpr double kPi = std::numbers::pi;

// Contact duration and restitution of m x'' + c x' + k x = 0 from x = 0, x' = v0 until
// k x + c x' = 0, for zeta < 1/sqrt(2): tan(w_d t) = -2 zeta sqrt(1 - zeta^2) / (1 - 2 zeta^2).
struct KelvinVoigt {
  double duration_s;
  double restitution;
};
KelvinVoigt ClosedForm(double k, double c, double m) {
  const double w0 = std::sqrt(k / m), zeta = c / (2.0 * std::sqrt(k * m));
  const double root = std::sqrt(1.0 - zeta * zeta), wd = w0 * root;
  const double t = (kPi - std::atan2(2.0 * zeta * root, 1.0 - 2.0 * zeta * zeta)) / wd;
  const double e =
      std::exp(-zeta * w0 * t) * std::abs(std::cos(wd * t) - zeta / root * std::sin(wd * t));
  return {t, e};
}

TEST(CompliantStrike, SpringDashpotMeetsTheClosedForm) {
  const double m = 1547e3, k = 2.0e9, v0 = 0.8;  // the pilot deck against a stiff wall
  for (const double zeta : {0.0, 0.02, 0.1, 0.3, 0.6}) {
    const double c = 2.0 * zeta * std::sqrt(k * m);
    const StrikeResult r = StrikeSpringDashpot(k, c, m, v0);
    const KelvinVoigt expected = ClosedForm(k, c, m);
    ASSERT_EQ(r.status, StrikeStatus::kSeparated);
    EXPECT_NEAR(r.contact_duration_s, expected.duration_s, 1e-9 * expected.duration_s)
        << "zeta " << zeta;
    EXPECT_NEAR(r.restitution, expected.restitution, 1e-9) << "zeta " << zeta;
    // The ledger: the kinetic energy lost is the work the dashpot absorbed.
    EXPECT_NEAR(r.dissipated_J,
                0.5 * m * v0 * v0 * (1.0 - expected.restitution * expected.restitution),
                1e-8 * 0.5 * m * v0 * v0);
    EXPECT_LT(std::abs(r.energy_residual), 1e-9) << "zeta " << zeta;
    EXPECT_EQ(r.events, 2);
  }
  // Undamped: the half period and e = 1.
  const StrikeResult elastic = StrikeSpringDashpot(k, 0.0, m, v0);
  EXPECT_NEAR(elastic.contact_duration_s, kPi * std::sqrt(m / k), 1e-10);
  EXPECT_NEAR(elastic.restitution, 1.0, 1e-9);
  EXPECT_NEAR(elastic.max_deformation_m, v0 * std::sqrt(m / k), 1e-9 * v0 * std::sqrt(m / k));
}

// The envelope's integral G(x) = x / b - (a / b^2) ln(1 + b x / a), a = 1/K_max, b = R_f/F_ult.
double EnvelopeWork_J(const joint::HyperbolicGap& law, double x) {
  const double a = 1.0 / law.k_max_N_per_m, b = law.r_f / law.f_ult_N;
  return x / b - a / (b * b) * std::log1p(b * x / a);
}

// The d where G(d) = energy (bisection).
double DeformationFor(const joint::HyperbolicGap& law, double energy_J) {
  double lo = 0.0, hi = 1.0;
  while (EnvelopeWork_J(law, hi) < energy_J) hi *= 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (EnvelopeWork_J(law, mid) < energy_J ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Time to load from 0 to D on the envelope: t = integral of dd / v(d), with d = D - w^2 so that
// the integrand 2 w / v is smooth (composite Simpson, 4000 panels).
double LoadingTime_s(const joint::HyperbolicGap& law, double m, double d_max) {
  const double a = 1.0 / law.k_max_N_per_m, b = law.r_f / law.f_ult_N;
  auto integrand = [&](double w) {
    if (w == 0.0) return 2.0 / std::sqrt(2.0 * joint::EnvelopeForce_N(law, d_max) / m);
    const double w2 = w * w;
    const double dG = w2 / b - a / (b * b) * std::log1p(b * w2 / (a + b * (d_max - w2)));
    return 2.0 * w / std::sqrt(2.0 * dG / m);
  };
  const int n = 4000;
  const double top = std::sqrt(d_max), h = top / n;
  double sum = integrand(0.0) + integrand(top);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * integrand(i * h);
  return sum * h / 3.0;
}

joint::HyperbolicGap PilotWall() {
  // Wilson and Elgamal's per-metre constants over a 19.36 m backwall.
  joint::HyperbolicGap law;
  law.k_max_N_per_m = 20300e3 * 19.36;
  law.k_ur_N_per_m = law.k_max_N_per_m;
  law.r_f = 0.7;
  law.f_ult_N = 326e3 * 19.36;
  law.gap_m = 0.0254;
  return law;
}

TEST(CompliantStrike, BackfillMeetsItsEnergyClosedForms) {
  const joint::HyperbolicGap law = PilotWall();
  const double m = 1547e3;
  for (const double v0 : {0.1, 0.5, 1.5}) {
    const StrikeResult r = StrikeBackfill(law, joint::BackfillState{}, m, v0);
    ASSERT_EQ(r.status, StrikeStatus::kSeparated);
    const double input = 0.5 * m * v0 * v0;
    const double d_max = DeformationFor(law, input);
    const double f_max = joint::EnvelopeForce_N(law, d_max);
    EXPECT_NEAR(r.max_deformation_m, d_max, 1e-9 * d_max) << "v0 " << v0;
    EXPECT_NEAR(r.max_force_N, f_max, 1e-8 * f_max);
    // Unloading along K_ur from F(d_max) at rest: a quarter period, exit speed F / sqrt(m K_ur).
    const double e = f_max / (std::sqrt(m * law.k_ur_N_per_m) * v0);
    EXPECT_NEAR(r.restitution, e, 1e-8) << "v0 " << v0;
    const double t = LoadingTime_s(law, m, d_max) + 0.5 * kPi * std::sqrt(m / law.k_ur_N_per_m);
    EXPECT_NEAR(r.contact_duration_s, t, 1e-7 * t) << "v0 " << v0;
    EXPECT_NEAR(r.permanent_set_m, d_max - f_max / law.k_ur_N_per_m, 1e-9 * d_max);
    // The hysteresis: the envelope's work less the energy the line gives back.
    const double loop = EnvelopeWork_J(law, d_max) - f_max * f_max / (2.0 * law.k_ur_N_per_m);
    EXPECT_NEAR(r.dissipated_J, loop, 1e-8 * input);
    EXPECT_LT(std::abs(r.energy_residual), 1e-9);
    EXPECT_EQ(r.events, 2);
  }
}

TEST(CompliantStrike, BackfillRemembersTheEarlierExcursion) {
  const joint::HyperbolicGap law = PilotWall();
  const double m = 1547e3, v0 = 0.5;
  const StrikeResult first = StrikeBackfill(law, joint::BackfillState{}, m, v0);
  const joint::BackfillState memory{first.max_deformation_m};
  const double f1 = joint::EnvelopeForce_N(law, first.max_deformation_m);
  // The same strike again starts at the permanent set, reloads along K_ur (giving back nothing
  // lost) and loads the envelope further: F1^2 / (2 K_ur) + G(D2) - G(D1) = m v0^2 / 2.
  const StrikeResult second = StrikeBackfill(law, memory, m, v0);
  const double target = 0.5 * m * v0 * v0 - f1 * f1 / (2.0 * law.k_ur_N_per_m) +
                        EnvelopeWork_J(law, first.max_deformation_m);
  const double d2 = DeformationFor(law, target);
  EXPECT_NEAR(second.max_deformation_m, d2, 1e-9 * d2);
  EXPECT_GT(second.permanent_set_m, first.permanent_set_m);
  EXPECT_EQ(second.events, 3);
  EXPECT_LT(std::abs(second.energy_residual), 1e-9);
  // A strike slower than the line's exit speed turns on the line: elastic, a half period.
  const double slow = 0.5 * first.exit_speed_mps;
  const StrikeResult elastic = StrikeBackfill(law, memory, m, slow);
  EXPECT_NEAR(elastic.restitution, 1.0, 1e-8);
  EXPECT_NEAR(elastic.contact_duration_s, kPi * std::sqrt(m / law.k_ur_N_per_m), 1e-8);
  EXPECT_NEAR(elastic.permanent_set_m, first.permanent_set_m, 1e-15);
}

}  // namespace
}  // namespace skewbridge::dynamics::compliant_strike_test
