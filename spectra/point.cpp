#include "spectra/point.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "solver/common/error.h"
#include "solver/dynamics/run.h"
#include "solver/model/builders.h"
#include "solver/model/deck.h"

namespace skewbridge::spectra {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

[[noreturn]] void Reject(std::string_view parameter, std::string_view problem) {
  throw InputError::AtField("point", parameter, problem);
}

std::string Show(double value) { return fmt::format("{}", value); }

void RequirePositive(double value, std::string_view parameter) {
  if (!std::isfinite(value) || value <= 0.0) {
    Reject(parameter, "must be > 0 (got " + Show(value) + ")");
  }
}

// w0x = sqrt(K_xx / m) of a deck whose stiffness is given by principal axes.
double PrincipalW0x(const model::DeckSpec& deck) {
  model::Body body;
  body.mass_kg = deck.mass_kg;
  body.inertia_kgm2 =
      deck.inertia_kgm2.value_or(model::UniformDeckInertia(deck.mass_kg, deck.geometry));
  body.geometry = deck.geometry;
  const Eigen::Matrix3d K =
      model::PrincipalAxesStiffness(body, deck.w1_radps, deck.w2_radps, deck.w_theta_radps,
                                    deck.axis_rad, deck.centre_of_rigidity_m);
  return std::sqrt(K(0, 0) / deck.mass_kg);
}

}  // namespace

model::DeckSpec PilotBridgeDeck() {
  model::DeckSpec deck;
  deck.mass_kg = 1547.0e3;
  deck.inertia_kgm2 = 1'079'100.0e3;
  deck.geometry.length_m = 89.14;
  deck.geometry.width_m = 19.36;
  deck.geometry.skew_rad = 20.0 * kDegree;
  deck.stiffness = model::DeckSpec::StiffnessKind::kPrincipal;
  deck.w1_radps = 18.0;
  deck.w2_radps = 19.0;
  deck.w_theta_radps = 26.0;
  deck.axis_rad = 20.0 * kDegree;
  deck.centre_of_rigidity_m = Eigen::Vector2d(-0.24, 0.01);
  deck.xi = 0.05;
  deck.abutments = model::AbutmentSet::kBoth;
  deck.restitution = 0.5;
  deck.friction = 0.3;
  return deck;
}

model::DeckSpec PilotBridgeDeck(std::optional<double> skew_deg, std::optional<double> eta0) {
  model::DeckSpec deck = PilotBridgeDeck();
  const double published_skew_deg = deck.geometry.skew_rad / kDegree;
  if (skew_deg && (!std::isfinite(*skew_deg) || *skew_deg < 0.0 || *skew_deg >= 90.0)) {
    Reject("a_deg", "must be in [0, 90) deg (got " + Show(*skew_deg) + ")");
  }
  if (eta0) {
    RequirePositive(*eta0, "eta0");
    if (skew_deg && *skew_deg <= 0.0) {
      Reject("eta0", "needs a skew angle a_deg > 0 (eta0 = sin 2a / (2 W/L) is 0 at a = 0)");
    }
  }
  // The published deck itself: its L and W, not their re-derivation (which differs from them
  // by the rounding of the published figures), so that the default given explicitly changes
  // nothing.
  if (!eta0 && (!skew_deg || *skew_deg == published_skew_deg)) {
    return deck;
  }
  const double skew_rad = skew_deg.value_or(published_skew_deg) * kDegree;
  const double W_over_L = eta0 ? std::sin(2.0 * skew_rad) / (2.0 * *eta0)
                               : deck.geometry.width_m / deck.geometry.length_m;
  const double rho2_m2 = *deck.inertia_kgm2 / deck.mass_kg;
  const double c = std::cos(skew_rad);
  const double length_m = std::sqrt(12.0 * rho2_m2 / (1.0 + W_over_L * W_over_L / (c * c)));
  deck.geometry = {length_m, W_over_L * length_m, skew_rad};
  return deck;
}

ExcitationScales PulseScales(const PointParameters& p) {
  RequirePositive(p.w0_over_wg, "w0_over_wg");
  RequirePositive(p.pulse_a_g_mps2, "a_g");
  RequirePositive(p.pulse_w_g_radps, "w_g");
  if (p.family == Family::kPilotBridge) {
    return {p.pulse_a_g_mps2, PrincipalW0x(PilotBridgeDeck()) / p.w0_over_wg};
  }
  return {p.pulse_a_g_mps2, p.pulse_w_g_radps};
}

DimensionalPoint ToDimensional(const PointParameters& p, const ExcitationScales& scales) {
  RequirePositive(scales.a_g_mps2, "a_g");
  RequirePositive(scales.w_g_radps, "w_g");
  if (!std::isfinite(p.Pi_delta) || p.Pi_delta < 0.0) {
    Reject("Pi_delta", "must be >= 0 (got " + Show(p.Pi_delta) + ")");
  }
  if (!std::isfinite(p.xi) || p.xi < 0.0 || p.xi >= 1.0) {
    Reject("xi", "must be in [0, 1) (got " + Show(p.xi) + ")");
  }
  if (!std::isfinite(p.eps_N) || p.eps_N < 0.0 || p.eps_N > 1.0) {
    Reject("eps_N", "must be in [0, 1] (got " + Show(p.eps_N) + ")");
  }
  if (!std::isfinite(p.mu) || p.mu < 0.0) {
    Reject("mu", "must be >= 0 (got " + Show(p.mu) + ")");
  }

  DimensionalPoint out;
  out.scales = scales;
  out.persistency_m = scales.a_g_mps2 / (scales.w_g_radps * scales.w_g_radps);
  out.delta_m = p.Pi_delta * out.persistency_m;
  out.method = p.method;
  if (p.method == Method::kTimeStepping) {
    RequirePositive(p.time_step_over_Tg, "time_step_over_Tg");
    out.time_step_s = p.time_step_over_Tg * 2.0 * std::numbers::pi / scales.w_g_radps;
  }

  model::DeckSpec& deck = out.deck;
  if (p.family == Family::kPilotBridge) {
    deck = PilotBridgeDeck(p.pilot_skew_deg, p.eta0);
  } else {
    RequirePositive(p.w0_over_wg, "w0_over_wg");
    RequirePositive(p.W0_over_w0, "W0_over_w0");
    RequirePositive(p.mass_kg, "mass");
    if (!std::isfinite(p.skew_deg) || p.skew_deg < 0.0 || p.skew_deg >= 90.0) {
      Reject("skew_deg", "must be in [0, 90) deg (got " + Show(p.skew_deg) + ")");
    }
    double length_m = 0.0;
    if (p.delta_over_L) {
      RequirePositive(*p.delta_over_L, "delta_over_L");
      if (p.Pi_delta <= 0.0) {
        Reject("delta_over_L", "needs Pi_delta > 0 (the gap sets the deck length); use L_over_Le");
      }
      length_m = out.delta_m / *p.delta_over_L;
    } else {
      RequirePositive(p.L_over_Le, "L_over_Le");
      length_m = p.L_over_Le * out.persistency_m;
    }
    const double skew_rad = p.skew_deg * kDegree;
    double width_m = 0.0;
    if (p.eta0) {
      RequirePositive(*p.eta0, "eta0");
      if (p.skew_deg <= 0.0) {
        Reject("eta0",
               "needs a skew angle > 0 (eta0 = sin 2a / (2 W/L) is 0 at a = 0); give W_over_L");
      }
      width_m = model::WidthFromEta0(*p.eta0, skew_rad, length_m);
    } else if (p.W_over_L) {
      RequirePositive(*p.W_over_L, "W_over_L");
      width_m = *p.W_over_L * length_m;
    } else {
      Reject("eta0", "missing: give eta0 or W_over_L");
    }
    deck.mass_kg = p.mass_kg;
    deck.geometry = {length_m, width_m, skew_rad};
    deck.stiffness = model::DeckSpec::StiffnessKind::kUncoupled;
    const double w0 = p.w0_over_wg * scales.w_g_radps;
    deck.w0x_radps = w0;
    deck.w0y_radps = w0;
    deck.W0_radps = p.W0_over_w0 * w0;
    deck.abutments = model::AbutmentSet::kPlusX;
  }
  deck.xi = p.xi;
  deck.restitution = p.eps_N;
  deck.friction = p.mu;
  deck.gap_plus_m = out.delta_m;
  deck.gap_minus_m = out.delta_m;

  const double inertia =
      deck.inertia_kgm2.value_or(model::UniformDeckInertia(deck.mass_kg, deck.geometry));
  out.rho_m = std::sqrt(inertia / deck.mass_kg);
  out.w0x_radps = deck.stiffness == model::DeckSpec::StiffnessKind::kPrincipal ? PrincipalW0x(deck)
                                                                               : deck.w0x_radps;
  return out;
}

namespace {

// The control of a point's run, given the lowest natural frequency w_min of its model (rad/s).
model::RunControl PointControl(const DimensionalPoint& point, const Excitation& excitation,
                               double w_min) {
  const double excitation_period_s = 2.0 * std::numbers::pi / point.scales.w_g_radps;
  const double natural_period_s = w_min > 0.0 ? 2.0 * std::numbers::pi / w_min : 0.0;

  model::RunControl control;
  // The absolute tolerance is in state units: tie it to the persistency so that the run is
  // self-similar in a_g [docs/theory.md §4 fact 4].
  control.absolute_tolerance = 1e-11 * point.persistency_m;
  control.end_time_s =
      excitation.Duration() + 2.0 * std::max(excitation_period_s, natural_period_s);
  // A cell stores no energy: the ledger's forms would only cost time (the responses are the same
  // bits without them).
  control.energy_ledger = false;
  control.method = point.method;
  if (point.method == Method::kTimeStepping) {
    control.time_step_s = point.time_step_s;
  }
  return control;
}

}  // namespace

PointRun MakePointRun(const DimensionalPoint& point, const Excitation& excitation) {
  PointRun out{model::BuildDeckModel(point.deck, "point"), {}, false};
  out.time_stepping = point.method == Method::kTimeStepping;
  out.control = PointControl(point, excitation, model::LowestFrequency(out.model));
  return out;
}

PointResult EvaluatePoint(const DimensionalPoint& point, const Excitation& excitation,
                          const dynamics::RunPolicies& policies) {
  model::Model model = model::BuildDeckModel(point.deck, "point");
  const model::RunControl control = PointControl(point, excitation, model::LowestFrequency(model));
  // Moved into the thread's reused workspace: the model is not needed after the run.
  dynamics::RunResult run = dynamics::Run(std::move(model), excitation, control, policies);

  PointResult r;
  r.status = run.status;
  r.message = run.message;
  r.x_m = run.max_abs_q(0);
  r.y_m = run.max_abs_q(1);
  r.theta_rad = run.max_abs_q(2);
  r.travel_m = run.max_travel_m(0);
  r.x_end_m = run.q_end(0);
  r.y_end_m = run.q_end(1);
  r.theta_end_rad = run.q_end(2);
  // [docs/theory.md §5]: lengths over the persistency a_g / w_g^2, rotations times rho.
  const double to_norm = 1.0 / point.persistency_m;
  r.x_norm = r.x_m * to_norm;
  r.y_norm = r.y_m * to_norm;
  r.theta_norm = r.theta_rad * point.rho_m * to_norm;
  r.theta_end_norm = r.theta_end_rad * point.rho_m * to_norm;
  r.impacts = run.impacts;
  r.events = run.impacts + run.plastic_closures + run.detachments + run.stick_transitions +
             run.slip_transitions;
  r.steps = run.free_steps + run.rk_steps;
  r.min_impact_separation_s = run.min_impact_separation_s;
  // Read: its storage goes to the thread's next run.
  dynamics::RecycleResult(std::move(run));
  return r;
}

}  // namespace skewbridge::spectra
