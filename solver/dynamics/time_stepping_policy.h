#pragma once
/// @file
/// Every threshold of the Moreau-Jean time-stepping scheme (solver/dynamics/time_stepping.h) in
/// one place [docs/theory.md §3.16, its second table]. Each member says its unit, the scale it is
/// relative to and why it has its value. A run uses TimeSteppingPolicy{} unless a caller passes
/// another; time-stepping run files and cubes store the policy that made them (docs/hdf5-layout.md,
/// docs/run-output.md). TimeSteppingPolicy::Describe (solver/common/schema.h) is the one list of
/// its members: the stored entries, the validation of their ranges and the table of
/// docs/theory.md §3.16 all come from it.
///
/// The scheme's one scale is v_ref = max(a_peak / omega_ref, |u(0)|_inf) (m/s), a_peak the
/// excitation's peak ground acceleration by the same pure function as the event-driven
/// integrator's (ExcitationPeak, solver/dynamics/run_scales.h), omega_ref the lowest natural
/// frequency (model::LowestFrequency). The scheme decides nothing by these thresholds that the
/// event-driven rules decide (no accumulation, no ties, no settling): it stays an independent
/// check of the decisions.

#include "solver/common/schema.h"

namespace skewbridge::dynamics {

/// The time-stepping scheme's thresholds (defaults: the values every result so far used).
struct TimeSteppingPolicy {
  /// v_tol = velocity_tolerance v_ref (1): a loaded contact whose slip velocity at the step's
  /// end is within v_tol of zero sticks (the stick and slip transitions of the event log). 1e-9
  /// of the response's velocity: far above the rounding of a Lemke solve, far below any slip
  /// the step resolves.
  double velocity_tolerance = 1e-9;
  /// A lowest natural frequency at or below it is a free body's (rad/s): omega_ref is then
  /// free_body_omega_radps. 1e-9 rad/s is a period of 200 years, no bridge's.
  double free_body_omega_floor_radps = 1e-9;
  /// omega_ref of a free body (rad/s): any positive value keeps v_ref finite; 1 rad/s leaves
  /// v_ref = a_peak in s.
  double free_body_omega_radps = 1.0;
  /// The time over which an unbounded ramp piece of the excitation enters a_peak (s): the
  /// excitations of this tool end; 1e3 s exceeds any record.
  double ramp_horizon_s = 1e3;
  /// A contact is active in a step when its predicted gap g_k + active_set_lookahead h
  /// gamma_N,k is at most 0 (1, of the step h): the index set I_1 with gamma = 1/2 of
  /// [Acary and Brogliato 2008, §10.1.2], which takes a contact one half-step before it closes.
  double active_set_lookahead = 0.5;
  /// The compliance of the normal rows of the step's LCP, of their largest diagonal entry (1):
  /// with a deck clamped between two closed faces the rigid problem has a squeeze of both faces
  /// among its solutions, a prestress whose friction locks the deck; 1e-9 picks the solution
  /// without it (the event-driven integrator's least total normal force) and moves the
  /// impulses elsewhere by that relative amount.
  double normal_compliance = 1e-9;
  /// An end time within step_count_band steps of the grid ends on the grid point instead of
  /// adding a sliver step (1, of h): t_end / h rounds a few ulps away from a whole number.
  double step_count_band = 1e-9;
  /// A history sample within output_time_band max(1 s, t) of a step's end is taken in that
  /// step, and one within output_time_band (s) of the end time is the last (1).
  double output_time_band = 1e-12;

  /// The members as stored, in this order (schema.h): name, unit, the scale each multiplies and
  /// the values the scheme can run with.
  template <typename Archive>
  void Describe(Archive* a) {
    using schema::Interval;
    const Interval zero_to_one = Interval::ClosedOpen(0.0, 1.0);
    const Interval positive = Interval::Above(0.0);
    a->Visit(SB_NVP(velocity_tolerance), {"1", "v_ref", Interval::Open(0.0, 1.0)});
    a->Visit(SB_NVP(free_body_omega_floor_radps), {"rad/s", "", Interval::AtLeast(0.0)});
    a->Visit(SB_NVP(free_body_omega_radps), {"rad/s", "", positive});
    a->Visit(SB_NVP(ramp_horizon_s), {"s", "", positive});
    a->Visit(SB_NVP(active_set_lookahead), {"1", "time step", Interval::Closed(0.0, 1.0)});
    a->Visit(SB_NVP(normal_compliance), {"1", "largest normal diagonal entry", zero_to_one});
    a->Visit(SB_NVP(step_count_band), {"1", "time step", zero_to_one});
    a->Visit(SB_NVP(output_time_band), {"1", "max(1 s, |t|)", zero_to_one});
  }
};

/// Checks every member of `policy` against its description (TimeSteppingPolicy::Describe).
/// @throws InputError "time-stepping policy: MEMBER: must be ALLOWED (got VALUE)" for the first
/// member outside.
void ValidatePolicy(const TimeSteppingPolicy& policy);

}  // namespace skewbridge::dynamics
