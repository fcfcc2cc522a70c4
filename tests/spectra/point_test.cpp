// The dimensionless mapping of docs/theory.md §5 against its definitions, and the normalised
// responses against an independent integration of the contact-free oscillator.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "solver/common/error.h"
#include "solver/model/deck.h"
#include "spectra/point.h"

namespace skewbridge::spectra::point_test {
namespace {

constexpr double kPi = std::numbers::pi;

PointParameters Subsystem(double w0_over_wg, double Pi_delta, double skew_deg, double eta0) {
  PointParameters p;
  p.w0_over_wg = w0_over_wg;
  p.Pi_delta = Pi_delta;
  p.skew_deg = skew_deg;
  p.eta0 = eta0;
  return p;
}

TEST(ToDimensional, BuildsExactlyTheRequestedGroups) {
  PointParameters p = Subsystem(0.7, 1.5, 35.0, 2.0);
  p.W0_over_w0 = 1.3;
  p.delta_over_L = 0.002;
  const ExcitationScales scales{3.1, 5.0};
  const DimensionalPoint d = ToDimensional(p, scales);
  const double a_g = scales.a_g_mps2;
  const double w_g = scales.w_g_radps;
  EXPECT_NEAR(d.delta_m * w_g * w_g / a_g, 1.5, 1e-14);
  EXPECT_NEAR(model::Eta0(d.deck.geometry), 2.0, 1e-14);
  EXPECT_NEAR(d.deck.gap_plus_m / d.deck.geometry.length_m, 0.002, 1e-16);
  EXPECT_NEAR(d.deck.geometry.skew_rad, 35.0 * kPi / 180.0, 1e-15);
  EXPECT_NEAR(d.deck.w0x_radps / w_g, 0.7, 1e-15);
  EXPECT_NEAR(d.deck.w0y_radps / w_g, 0.7, 1e-15);
  EXPECT_NEAR(d.deck.W0_radps / d.deck.w0x_radps, 1.3, 1e-15);
  EXPECT_NEAR(d.persistency_m, a_g / (w_g * w_g), 1e-16);
  // rho of the uniform deck: 12 rho^2 = L^2 + W^2 / cos^2 a [docs/theory.md §2].
  const double L = d.deck.geometry.length_m;
  const double W = d.deck.geometry.width_m;
  const double c = std::cos(d.deck.geometry.skew_rad);
  EXPECT_NEAR(d.rho_m * d.rho_m * 12.0, L * L + W * W / (c * c), 1e-9 * L * L);
  EXPECT_EQ(d.deck.abutments, model::AbutmentSet::kPlusX);
}

TEST(ToDimensional, LengthFromPersistencyWhenNoGapRatio) {
  PointParameters p = Subsystem(1.0, 0.0, 30.0, 1.0);
  p.L_over_Le = 400.0;
  const DimensionalPoint d = ToDimensional(p, {2.0, 4.0});
  EXPECT_NEAR(d.deck.geometry.length_m, 400.0 * 2.0 / 16.0, 1e-12);
  EXPECT_EQ(d.delta_m, 0.0);
}

TEST(ToDimensional, RejectsImpossibleCombinationsNamingTheParameter) {
  auto message = [](const PointParameters& p) {
    try {
      ToDimensional(p, {1.0, 1.0});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(Subsystem(1.0, 1.0, 0.0, 1.0)).find("eta0"), std::string::npos);
  EXPECT_NE(message(Subsystem(1.0, -1.0, 30.0, 1.0)).find("Pi_delta"), std::string::npos);
  EXPECT_NE(message(Subsystem(0.0, 1.0, 30.0, 1.0)).find("w0_over_wg"), std::string::npos);
  EXPECT_NE(message(Subsystem(1.0, 1.0, 95.0, 1.0)).find("skew_deg"), std::string::npos);
  PointParameters gapless = Subsystem(1.0, 0.0, 30.0, 1.0);
  gapless.delta_over_L = 0.01;
  EXPECT_NE(message(gapless).find("delta_over_L"), std::string::npos);
  PointParameters bad_eps = Subsystem(1.0, 1.0, 30.0, 1.0);
  bad_eps.eps_N = 1.5;
  EXPECT_NE(message(bad_eps).find("eps_N"), std::string::npos);
}

TEST(PilotBridge, HasThePublishedSkewRatioAndSetsBothGaps) {
  PointParameters p;
  p.family = Family::kPilotBridge;
  p.Pi_delta = 2.0;
  p.w0_over_wg = 0.8;
  const ExcitationScales scales = PulseScales(p);
  const DimensionalPoint d = ToDimensional(p, scales);
  EXPECT_NEAR(model::Eta0(d.deck.geometry), 1.48, 0.005);  // [docs/theory.md §6]
  EXPECT_NEAR(d.w0x_radps / scales.w_g_radps, 0.8, 1e-14);
  EXPECT_EQ(d.deck.abutments, model::AbutmentSet::kBoth);
  EXPECT_DOUBLE_EQ(d.deck.gap_plus_m, d.deck.gap_minus_m);
  EXPECT_NEAR(d.deck.gap_plus_m * scales.w_g_radps * scales.w_g_radps / scales.a_g_mps2, 2.0,
              1e-13);
  // rho = sqrt(I_m / m) of the published deck.
  EXPECT_NEAR(d.rho_m, std::sqrt(1'079'100.0 / 1547.0), 1e-9);
  // w0x lies between the two translational principal frequencies (18 and 19 rad/s).
  EXPECT_GT(d.w0x_radps, 18.0);
  EXPECT_LT(d.w0x_radps, 19.0);
}

TEST(PilotBridge, TheDefaultSkewGivenExplicitlyIsThePublishedDeckBitForBit) {
  const model::DeckSpec published = PilotBridgeDeck();
  const model::DeckSpec explicit_default = PilotBridgeDeck(20.0, std::nullopt);
  const model::DeckSpec omitted = PilotBridgeDeck(std::nullopt, std::nullopt);
  for (const model::DeckSpec* d : {&explicit_default, &omitted}) {
    EXPECT_EQ(d->geometry.length_m, 89.14);
    EXPECT_EQ(d->geometry.width_m, 19.36);
    EXPECT_EQ(d->geometry.skew_rad, published.geometry.skew_rad);
    EXPECT_EQ(*d->inertia_kgm2, *published.inertia_kgm2);
  }
  // Through the point mapping as a sweep uses it.
  PointParameters p;
  p.family = Family::kPilotBridge;
  PointParameters q = p;
  q.pilot_skew_deg = 20.0;
  const DimensionalPoint a = ToDimensional(p, PulseScales(p));
  const DimensionalPoint b = ToDimensional(q, PulseScales(q));
  EXPECT_EQ(a.deck.geometry.length_m, b.deck.geometry.length_m);
  EXPECT_EQ(a.deck.geometry.width_m, b.deck.geometry.width_m);
  EXPECT_EQ(a.rho_m, b.rho_m);
  EXPECT_EQ(a.w0x_radps, b.w0x_radps);
}

TEST(PilotBridge, OtherSkewsKeepMassInertiaAndSubstructure) {
  const model::DeckSpec published = PilotBridgeDeck();
  const double m = 1547e3, I_m = 1079100e3;
  struct Case {
    std::optional<double> a_deg, eta0;
  };
  for (const Case& c : {Case{0.0, std::nullopt}, Case{35.0, std::nullopt}, Case{60.0, std::nullopt},
                        Case{std::nullopt, 0.8}, Case{45.0, 2.5}, Case{10.0, 1.48}}) {
    SCOPED_TRACE("a_deg " + std::to_string(c.a_deg.value_or(-1)) + " eta0 " +
                 std::to_string(c.eta0.value_or(-1)));
    const model::DeckSpec d = PilotBridgeDeck(c.a_deg, c.eta0);
    const double a_rad = c.a_deg.value_or(20.0) * kPi / 180.0;
    EXPECT_NEAR(d.geometry.skew_rad, a_rad, 1e-15);
    // The uniform-deck rule reproduces the published I_m from the new plan.
    EXPECT_NEAR(model::UniformDeckInertia(m, d.geometry), I_m, 1e-12 * I_m);
    EXPECT_EQ(d.mass_kg, m);
    EXPECT_EQ(*d.inertia_kgm2, I_m);
    if (c.eta0) {
      EXPECT_NEAR(model::Eta0(d.geometry), *c.eta0, 1e-12 * *c.eta0);
    } else {
      EXPECT_NEAR(d.geometry.width_m / d.geometry.length_m, 19.36 / 89.14, 1e-14);
    }
    // The rest is the published bridge.
    EXPECT_EQ(d.stiffness, published.stiffness);
    EXPECT_EQ(d.w1_radps, 18.0);
    EXPECT_EQ(d.w2_radps, 19.0);
    EXPECT_EQ(d.w_theta_radps, 26.0);
    EXPECT_EQ(d.axis_rad, published.axis_rad);
    EXPECT_EQ(d.centre_of_rigidity_m, published.centre_of_rigidity_m);
    EXPECT_EQ(d.abutments, model::AbutmentSet::kBoth);
    EXPECT_EQ(d.friction, 0.3);
  }
  // A hand value: a = 0, W/L = r kept: L = sqrt(12 I_m / m / (1 + r^2)).
  const double r = 19.36 / 89.14;
  EXPECT_NEAR(PilotBridgeDeck(0.0, std::nullopt).geometry.length_m,
              std::sqrt(12.0 * 1079100.0 / 1547.0 / (1.0 + r * r)), 1e-12);
  // The published plan is its own re-derivation to the rounding of its figures (1.5e-5).
  const model::DeckSpec near = PilotBridgeDeck(20.0 + 1e-9, std::nullopt);
  EXPECT_NEAR(near.geometry.length_m, 89.14, 2e-5 * 89.14);
  EXPECT_NEAR(near.geometry.width_m, 19.36, 2e-5 * 19.36);
}

TEST(PilotBridge, ImpossibleSkewsAreRefusedNamingTheKey) {
  const auto message = [](std::optional<double> a_deg, std::optional<double> eta0) {
    try {
      PilotBridgeDeck(a_deg, eta0);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(90.0, std::nullopt).find("a_deg: must be in [0, 90) deg (got 90)"),
            std::string::npos);
  EXPECT_NE(message(-1.0, std::nullopt).find("a_deg"), std::string::npos);
  EXPECT_NE(message(std::nan(""), std::nullopt).find("a_deg"), std::string::npos);
  EXPECT_NE(message(30.0, 0.0).find("eta0: must be > 0"), std::string::npos);
  EXPECT_NE(message(std::nullopt, -2.0).find("eta0"), std::string::npos);
  EXPECT_NE(message(0.0, 1.0).find("eta0: needs a skew angle a_deg > 0"), std::string::npos);
}

// x'' + 2 xi w0 x' + w0^2 x = -a_g(t), integrated with classical RK4 on a fine grid: an
// oracle independent of the solver's exact transition. The pulse and the free vibration are
// two segments, so no step straddles the jump of a_g at the end of the pulse.
double OscillatorPeak(double w0, double xi, double a_g, double w_g, double end_s) {
  const double T = 2.0 * kPi / w_g;
  double x = 0.0;
  double v = 0.0;
  double peak = 0.0;
  auto integrate = [&](double t_begin, double t_end, bool pulse_on) {
    auto f = [&](double t, double xx, double vv, double& dx, double& dv) {
      dx = vv;
      dv = -2.0 * xi * w0 * vv - w0 * w0 * xx - (pulse_on ? a_g * std::cos(w_g * t) : 0.0);
    };
    const int n = static_cast<int>(std::ceil((t_end - t_begin) / (T / 20000.0)));
    const double h = (t_end - t_begin) / n;
    for (int k = 0; k < n; ++k) {
      const double t = t_begin + k * h;
      double k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
      f(t, x, v, k1x, k1v);
      f(t + h / 2, x + h / 2 * k1x, v + h / 2 * k1v, k2x, k2v);
      f(t + h / 2, x + h / 2 * k2x, v + h / 2 * k2v, k3x, k3v);
      f(t + h, x + h * k3x, v + h * k3v, k4x, k4v);
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      peak = std::max(peak, std::abs(x));
    }
  };
  integrate(0.0, T, true);
  integrate(T, end_s, false);
  return peak;
}

TEST(EvaluatePoint, ContactFreeSpectrumOrdinateEqualsTheLinearOscillator) {
  // Gaps far too wide to close: the deck is a linear oscillator along x, y = theta = 0.
  PointParameters p = Subsystem(0.8, 1e6, 30.0, 1.0);
  const ExcitationScales scales = PulseScales(p);
  const DimensionalPoint d = ToDimensional(p, scales);
  const records::PulseExcitation pulse(records::PulseShape::kCosine, scales.a_g_mps2,
                                       scales.w_g_radps);
  const PointResult r = EvaluatePoint(d, pulse);
  ASSERT_EQ(r.status, dynamics::RunStatus::kOk) << r.message;
  EXPECT_EQ(r.impacts, 0);
  const double w0 = 0.8 * scales.w_g_radps;
  const double T = 2.0 * kPi / scales.w_g_radps;
  const double end_s = T + 2.0 * std::max(T, 2.0 * kPi / w0);
  const double oracle = OscillatorPeak(w0, 0.05, scales.a_g_mps2, scales.w_g_radps, end_s);
  EXPECT_NEAR(r.x_m, oracle, 1e-6 * oracle);
  EXPECT_NEAR(r.x_norm, oracle * scales.w_g_radps * scales.w_g_radps / scales.a_g_mps2,
              1e-6 * r.x_norm);
  EXPECT_EQ(r.y_m, 0.0);
  EXPECT_EQ(r.theta_rad, 0.0);
}

TEST(EvaluatePoint, DimensionlessMaximaAreIndependentOfIntensity) {
  // [docs/theory.md §4 fact 4]: at fixed Pi_delta the dimensionless maxima do not depend on a_g;
  // exactly so while rotations are small, which eta0 = 2 at a = 30 deg keeps them here.
  PointParameters p = Subsystem(0.5, 0.5, 30.0, 2.0);
  p.delta_over_L = 0.002;
  const double w_g = 2.0 * kPi;
  PointResult reference;
  for (double a_g : {0.49, 4.9, 49.0}) {
    const DimensionalPoint d = ToDimensional(p, {a_g, w_g});
    const records::PulseExcitation pulse(records::PulseShape::kCosine, a_g, w_g);
    const PointResult r = EvaluatePoint(d, pulse);
    ASSERT_EQ(r.status, dynamics::RunStatus::kOk) << r.message;
    EXPECT_GT(r.impacts, 0);
    if (a_g == 0.49) {
      reference = r;
      continue;
    }
    EXPECT_NEAR(r.x_norm, reference.x_norm, 1e-6 * reference.x_norm);
    EXPECT_NEAR(r.y_norm, reference.y_norm, 1e-6 * reference.y_norm + 1e-12);
    EXPECT_NEAR(r.theta_norm, reference.theta_norm, 1e-6 * reference.theta_norm + 1e-12);
    EXPECT_EQ(r.impacts, reference.impacts);
  }
}

TEST(EvaluatePoint, TimeSteppingAgreesWithEventDrivenWithinOnePercent) {
  // The canonical subsystem point (w0/w_g = 0.5, Pi_delta = 0.5, a = 30 deg, eta0 = 2) by both
  // integrators; the Moreau-Jean scheme is first order, h = 1e-4 T_g keeps it within 1 %.
  PointParameters p = Subsystem(0.5, 0.5, 30.0, 2.0);
  p.delta_over_L = 0.002;
  const ExcitationScales scales = PulseScales(p);
  const records::PulseExcitation pulse(p.pulse, scales.a_g_mps2, scales.w_g_radps);
  const PointResult ed = EvaluatePoint(ToDimensional(p, scales), pulse);
  p.method = Method::kTimeStepping;
  const DimensionalPoint d = ToDimensional(p, scales);
  EXPECT_EQ(d.method, Method::kTimeStepping);
  EXPECT_NEAR(d.time_step_s, 1e-4 * 2.0 * kPi / scales.w_g_radps, 1e-18);
  const PointResult ts = EvaluatePoint(d, pulse);
  ASSERT_EQ(ed.status, dynamics::RunStatus::kOk) << ed.message;
  ASSERT_EQ(ts.status, dynamics::RunStatus::kOk) << ts.message;
  ASSERT_GT(ed.impacts, 0);
  EXPECT_NEAR(ts.x_norm, ed.x_norm, 0.01 * ed.x_norm);
  EXPECT_NEAR(ts.y_norm, ed.y_norm, 0.01 * ed.y_norm);
  EXPECT_NEAR(ts.theta_norm, ed.theta_norm, 0.01 * ed.theta_norm);
  // Different integrators give different step counts: the method really changed.
  EXPECT_NE(ts.steps, ed.steps);
}

TEST(ToDimensional, RejectsANonPositiveTimeStep) {
  PointParameters p = Subsystem(0.5, 0.5, 30.0, 2.0);
  p.method = Method::kTimeStepping;
  p.time_step_over_Tg = 0.0;
  EXPECT_THROW(ToDimensional(p, PulseScales(p)), InputError);
}

}  // namespace
}  // namespace skewbridge::spectra::point_test
