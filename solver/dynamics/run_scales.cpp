#include "solver/dynamics/run_scales.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace skewbridge::dynamics {

double ExcitationPeak(const Excitation& excitation, double ramp_horizon_s) {
  return excitation.Peak(ramp_horizon_s);
}

double MaxTranslationalMass(const model::Model& model) {
  double m_max = 0.0;
  for (int i = 0; i < model.n_dof(); ++i) {
    if (i % 3 != 2) {
      m_max = std::max(m_max, model.mass_diagonal()[i]);
    }
  }
  return m_max;
}

RunScales ComputeRunScales(double a_peak_mps2, double u0_max_mps, const ModelScales& model,
                           double accumulation_threshold, const EventPolicy& policy) {
  RunScales s;
  s.omega_ref_radps =
      model.omega_min_radps > 0.0 ? model.omega_min_radps : policy.free_body_omega_radps;
  double v_ref = a_peak_mps2 / s.omega_ref_radps;
  v_ref = std::max(v_ref, u0_max_mps);
  if (v_ref == 0.0) {
    v_ref = 1.0;
  }
  s.v_ref_mps = v_ref;
  s.v_acc_mps = accumulation_threshold * v_ref;
  s.v_tol_mps = policy.velocity_tolerance * v_ref;
  // A closed contact that carries no load (two identical decks at a closed joint under uniform
  // excitation) has lambda_N = 0 up to the rounding of the active-set solve, of either sign.
  // Zero force with zero relative acceleration keeps the contact closed (the contact LCP's
  // complementarity allows it); a detachment needs lambda_N clearly negative, that is a
  // separating acceleration of the order of force_tolerance a_ref, well above the contact
  // problem's tie tolerance (solver/contact/contact_problem.cpp), so that the contact problem
  // at the event confirms it [docs/theory.md §3.7].
  s.force_tol_N = policy.force_tolerance * model.mass_max_kg * v_ref * s.omega_ref_radps;
  s.a_detach_mps2 = policy.force_tolerance * v_ref * s.omega_ref_radps;
  // The gap tolerance from the response's own length scale, so that it scales with the
  // excitation. It never falls below the rounding of a gap computed from world coordinates (a
  // few ulps of the deck's size): at a tiny excitation a scaled tolerance under that floor would
  // split a full-edge impact, exactly simultaneous in the model, into two impacts by rounding
  // noise alone.
  s.gap_tol_m =
      std::max(policy.gap_tolerance * std::min(v_ref / s.omega_ref_radps, model.length_m),
               policy.gap_rounding_ulps * std::numeric_limits<double>::epsilon() * model.length_m);
  s.omega_top_radps = std::max(model.omega_max_radps, policy.omega_floor_radps);
  s.first_rk_step_s = 2.0 * std::numbers::pi / s.omega_top_radps / policy.steps_per_period /
                      policy.first_rk_step_divisor;
  s.period_min_s = model.omega_max_radps > 0.0 ? 2.0 * std::numbers::pi / model.omega_max_radps
                                               : std::numeric_limits<double>::infinity();
  return s;
}

}  // namespace skewbridge::dynamics
