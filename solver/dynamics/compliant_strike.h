#pragma once
/// @file
/// A point mass striking a compliant joint: the bridge between the compliant laws of solver/joint
/// and the rigid law's restitution eps_N [docs/compliant.md §3]. The mass arrives at the closing
/// point of the joint with the approach speed v0 (the flight before it is exact and needs no
/// integration), is pushed back by the joint's force alone, and leaves when that force has fallen
/// to zero. Between the law's events the flow m d'' = -F(d, d') is smooth and is integrated with
/// the Dormand-Prince 5(4) pair and its dense output (runge_kutta.h); the events (a turn from
/// loading to unloading, a reloading line reaching the envelope, the force reaching zero) are
/// located on the dense output with Brent's method (root_finding.h). The work of the joint's force
/// is integrated beside the motion, so the energy ledger of the strike is a check of its own.

#include "solver/joint/backfill.h"

namespace skewbridge::dynamics {

/// Accuracy of a strike's integration, relative to its own scales (the approach speed v0, the
/// time T = sqrt(m / K) of the joint's initial stiffness, v0 T, m v0^2 / 2).
struct StrikeTolerances {
  double relative = 1e-10;    ///< rtol of the step control; atol_i = relative x scale_i
  double event_time = 1e-12;  ///< event location's time tolerance, as a fraction of T
  int max_steps = 200000;     ///< steps allowed before the strike is given up (kNoSeparation)
};

/// How a strike ended.
enum class StrikeStatus {
  kSeparated,     ///< the force fell to zero with the mass moving away
  kNoSeparation,  ///< the step budget ran out before (a joint that holds the mass)
};

/// What a strike leaves behind. Speeds are magnitudes.
struct StrikeResult {
  StrikeStatus status = StrikeStatus::kSeparated;
  double approach_speed_mps = 0.0;  ///< v0 at the closing of the joint
  double exit_speed_mps = 0.0;      ///< speed when the force reached zero
  double restitution = 0.0;         ///< equivalent restitution: exit over approach speed
  double contact_duration_s = 0.0;  ///< from the closing to the force reaching zero
  double max_deformation_m = 0.0;   ///< largest deformation beyond the closing point
  double max_force_N = 0.0;         ///< largest force of the joint
  double permanent_set_m = 0.0;     ///< widening of the gap left by the strike (backfill only)
  double dissipated_J = 0.0;        ///< work the joint absorbed: the integral of F dd
  double energy_residual = 0.0;     ///< (m v0^2/2 - m v_exit^2/2 - dissipated) / (m v0^2/2)
  int steps = 0;                    ///< accepted Runge-Kutta steps
  int events = 0;                   ///< located events (turn, envelope reached, force zero)
};

/// A mass m (kg) strikes the hyperbolic backfill spring `law` with the memory `state` at the
/// closing point of the joint (d = d_set, the permanent set of `state`) at speed v0 (m/s):
/// reloading along K_ur up to d_max, loading on the envelope, the turn, unloading along K_ur to
/// zero force. The permanent set reported is that of the memory after the strike.
/// @pre law valid (joint::ValidateHyperbolicGap), mass_kg > 0, approach_speed_mps > 0.
StrikeResult StrikeBackfill(const joint::HyperbolicGap& law, const joint::BackfillState& state,
                            double mass_kg, double approach_speed_mps,
                            const StrikeTolerances& tolerances = {});

/// A mass m (kg) strikes a linear spring-dashpot that pulls on nothing, F = max(0, k d + c d'),
/// at speed v0 (m/s); it leaves when k d + c d' reaches zero [Schwager and Poeschel 2007].
/// @pre k > 0, c >= 0, mass_kg > 0, approach_speed_mps > 0.
StrikeResult StrikeSpringDashpot(double k_N_per_m, double c_Ns_per_m, double mass_kg,
                                 double approach_speed_mps,
                                 const StrikeTolerances& tolerances = {});

}  // namespace skewbridge::dynamics
