#pragma once
/// @file
/// The scales of one run and the tolerances made from them [docs/theory.md §3.2]: every
/// velocity, force and gap tolerance of the event-driven integrator is a fixed fraction
/// (EventPolicy) of a scale of the response, v_ref = max(a_peak / omega_ref, |u(0)|_inf), so
/// that scaling the excitation by k scales each of them by k and a dimensionless result does
/// not change (self-similarity, [docs/theory.md §4 fact 4; §5]).

#include "solver/common/excitation.h"
#include "solver/dynamics/event_policy.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// The model's own scales.
struct ModelScales {
  double omega_min_radps = 0.0;  ///< lowest natural frequency (0 for a free body)
  double omega_max_radps = 0.0;  ///< highest natural frequency
  double length_m = 1.0;         ///< largest deck dimension or distance from the origin
  double mass_max_kg = 0.0;      ///< largest translational mass (diagonal of M)
};

/// The scales and tolerances of one run.
struct RunScales {
  double omega_ref_radps = 0.0;  ///< omega_min, or EventPolicy::free_body_omega_radps
  double v_ref_mps = 0.0;        ///< max(a_peak / omega_ref, |u(0)|_inf), 1 when both are 0
  double v_acc_mps = 0.0;        ///< accumulation threshold x v_ref (RunControl)
  double v_tol_mps = 0.0;        ///< a velocity within it is zero
  double gap_tol_m = 0.0;        ///< a gap within it is touching
  double force_tol_N = 0.0;      ///< a normal force above -force_tol is zero
  double a_detach_mps2 = 0.0;    ///< a separating or slip acceleration below it is a tie
  double omega_top_radps = 0.0;  ///< omega_max, at least EventPolicy::omega_floor_radps
  double first_rk_step_s = 0.0;  ///< the first Runge-Kutta step of a constrained phase
  double period_min_s = 0.0;     ///< shortest natural period 2 pi / omega_max (+inf: none)
};

/// The largest |a_g| of `excitation` over its pieces (m/s^2): each piece's start, its end (an
/// unbounded ramp taken at most `ramp_horizon_s` far) and start plus harmonic amplitudes:
/// Excitation::Peak, which a record computes from its samples.
double ExcitationPeak(const Excitation& excitation, double ramp_horizon_s);

/// The largest translational mass of `model` (kg): the x and y entries of diag(M).
double MaxTranslationalMass(const model::Model& model);

/// The scales and tolerances of a run with peak ground acceleration `a_peak_mps2`, initial
/// velocities up to `u0_max_mps` and `accumulation_threshold` (RunControl) under `policy`.
/// Scaling a_peak and u0 by k > 0 scales v_ref, v_acc, v_tol, force_tol and a_detach by k, and
/// gap_tol while above its rounding floor (EventPolicy::gap_rounding_ulps) and below
/// gap_tolerance L; the steps and periods do not change.
RunScales ComputeRunScales(double a_peak_mps2, double u0_max_mps, const ModelScales& model,
                           double accumulation_threshold, const EventPolicy& policy);

}  // namespace skewbridge::dynamics
