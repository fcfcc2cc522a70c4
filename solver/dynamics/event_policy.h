#pragma once
/// @file
/// Every threshold and heuristic rule of the event-driven integrator in one place
/// [docs/theory.md §3.1-§3.16; the table of §3.16]. Each member says its unit, the scale it is
/// relative to and why it has its value. A run uses EventPolicy{} (the defaults below) unless a
/// caller passes another; run files and cubes store the policy that made them (docs/hdf5-layout.md,
/// docs/run-output.md). EventPolicy::Describe (solver/common/schema.h) is the one list of its
/// members: the stored entries, the validation of their ranges and the table of docs/theory.md
/// §3.16 all come from it.
///
/// The run's scales (solver/dynamics/run_scales.h) make the tolerances relative to the
/// response: v_ref = max(a_peak / omega_ref, |u(0)|_inf) (m/s), omega_ref the lowest natural
/// frequency (rad/s), L the deck's length scale (m). Scaling the excitation by k scales v_ref,
/// and with it every velocity, force and (above its rounding floor) gap tolerance, by k, which
/// keeps the self-similarity of [docs/theory.md §4 fact 4].

#include "solver/common/schema.h"
#include "solver/contact/contact_policy.h"

namespace skewbridge::dynamics {

/// The integrator's thresholds and rules (defaults: the values every result so far used).
struct EventPolicy {
  // --- Tolerances of the run, relative to its scales [docs/theory.md §3.2] ---
  /// v_tol = velocity_tolerance v_ref (1): a normal or slip velocity within v_tol of zero is
  /// zero. 1e-10 of the response's velocity is 6 decades above the rounding of a velocity from a
  /// Lemke solve (~1e-16 relative) and far below any approach that the response resolves.
  double velocity_tolerance = 1e-10;
  /// gap_tol = gap_tolerance min(v_ref / omega_ref, L) (1): a gap within gap_tol is touching.
  /// 1e-12 of the response's displacement scale: a contact this close is closed for every
  /// purpose of a response resolved to 1e-6 or coarser.
  double gap_tolerance = 1e-12;
  /// The floor of gap_tol, in ulps of L (1): the rounding of a gap computed from world
  /// coordinates (n . (X + (x, y) + R p - A), a few ulps of the deck's size) with a margin, so
  /// that a full-edge impact, simultaneous in the model, is not split by rounding noise at a
  /// tiny excitation.
  double gap_rounding_ulps = 64.0;
  /// force_tol = force_tolerance m_max v_ref omega_ref (N) and a_detach = force_tolerance v_ref
  /// omega_ref (m/s^2) (1): a normal force above -force_tol, or a separating or slip
  /// acceleration below a_detach, is zero (a tie). 1e-7 of the inertia force of the response,
  /// well above the rounding of the active-set solve and of the contact LCP's tie tolerance, so
  /// that the contact problem at the event confirms the detachment it triggers.
  double force_tolerance = 1e-7;
  /// omega_ref of a free body (no natural frequency) (rad/s): any positive value keeps the
  /// scales finite; 1 rad/s leaves v_ref = a_peak in s.
  double free_body_omega_radps = 1.0;
  /// The time over which an unbounded ramp piece of the excitation enters a_peak (s): the
  /// excitations of this tool end; 1e3 s exceeds any record.
  double ramp_horizon_s = 1e3;

  // --- Steps [docs/theory.md §3.14] ---
  /// Free (exact) steps at most 2 pi / omega / steps_per_period, omega the highest natural or
  /// excitation frequency (1): 20 steps per period make the gap's cubic Hermite model, which
  /// decides whether a step is searched for an impact, accurate to ~1e-4 of the response.
  double steps_per_period = 20.0;
  /// The first Runge-Kutta step of a constrained phase is the free step divided by this (1):
  /// the error control grows it within a few steps.
  double first_rk_step_divisor = 4.0;
  /// The lowest frequency that sets step sizes (rad/s): a free body or a very soft model still
  /// gets finite steps.
  double omega_floor_radps = 1e-3;
  /// The error norm taken for a rejected Runge-Kutta step whose error is not finite (1): the
  /// step then shrinks by the controller's largest factor.
  double nonfinite_step_error = 1e10;
  /// Relative difference of two free steps (of h) below which the step of the previous piece is
  /// reused (1): pieces of a sampled record differ in length by rounding, and one canonical step
  /// keeps the propagator cache hitting; the state moves by e^{A h} over a step a few ulps
  /// longer, far below any tolerance.
  double step_reuse_band = 1e-12;
  /// Relative distance (of h) within which a time is taken as on the free step grid or at the
  /// end of the piece (1): avoids steps of a few ulps.
  double step_snap_band = 1e-9;
  /// Steps between two checks that the state is finite (a power of two): a few instructions a
  /// step, and a run that went non-finite stops within that many steps.
  long finite_check_steps = 16;

  // --- Event location [docs/theory.md §3.12] ---
  /// Event times are bracketed to event_time_tolerance max(1, |t|) + event_time_floor (s): a
  /// slow approach's gap is rounding noise over a band of ~1e-15 m / speed, often 1e-11 s wide;
  /// a tighter bracket costs ~30 evaluations per impact of a corner settling on a closed joint,
  /// for event times that move the state by less than the gap tolerance.
  double event_time_tolerance = 1e-13;
  /// Absolute floor of an event-time bracket (s): keeps the bracket positive at t = 0.
  double event_time_floor_s = 1e-16;
  /// Relative bracket of the time of a displacement maximum (1): the maximum is flat there, so
  /// this is cheap and moves the peak value by nothing measurable.
  double maximum_time_tolerance = 1e-15;
  /// A free step whose gap dips (gamma_N from - to +) is searched for an impact when its
  /// smaller end gap is below dip_margin times the Hermite bound of the dip, |gamma_N| tau / 2
  /// (1): the factor 2 covers the error of the cubic model of the gap over a step of at most
  /// 1/20 of a period.
  double dip_margin = 2.0;
  /// A gap's minimum found within start_minimum_band event-time brackets of the step's start is
  /// the state the decision there has just opened, not an impact (1): the bracket's own width,
  /// doubled, so that the decision is not repeated at the same instant.
  double start_minimum_band = 2.0;
  /// Probes t0 + (t1 - t0) 2^-k, k = 1 .. touch_probes, for a positive gamma_N of a contact that
  /// starts a step at the face (1): 40 halvings reach 1e-12 of the step, below the event-time
  /// bracket.
  int touch_probes = 40;
  /// Relative band of an output sample's time (of max(1, t)) (1): a sample at the step's end
  /// is taken from that step.
  double output_time_band = 1e-12;

  // --- The mode decision at an instant [docs/theory.md §3.1, §3.7-§3.9, §3.11] ---
  /// More calls of the mode decision at one instant than this end the run with
  /// RunStatus::kEventCascade (1): a consistent decision needs a handful (an event, its
  /// re-decision, a tie fallback); dozens mean the rules disagree.
  int max_events_at_one_instant = 64;
  /// Passes of the decision (velocity-level problem, contact problem, projection) at one
  /// instant (1): two suffice unless a projection disturbs a contact at the face.
  int decision_passes = 4;
  /// A closed contact whose slip speed is within stick_band v_tol of zero may stick: the
  /// contact problem decides (1). Wider than the slip event's band (v_tol), so that the contact
  /// the slip event stops is always offered the choice.
  double stick_band = 2.0;
  /// Rule: a sticking contact whose friction has reached the cone enters the contact problem as
  /// sliding against its friction force (the stick-slip event says which way)
  /// [Pfeiffer and Glocker 1996, ch. 6].
  bool cone_sign = true;
  /// Rule: a separating or slip acceleration within a_detach is a tie, kept closed or sticking,
  /// unless the constrained phase's event function says otherwise (then the contact problem's
  /// answer).
  bool tie_bands = true;
  /// Rule: a deck wedged between opposing faces with a sliding corner, whose contact problem
  /// has no solution, stops sliding by a tangential impact [Genot and Brogliato 1999].
  bool jam = true;

  // --- Accumulation of impacts [docs/theory.md §3.4-§3.6] ---
  /// Zeno: the largest ratio of successive approach speeds of one contact for which its impacts
  /// are an accumulation (1). eps_N for a single contact; 0.9 leaves eps_N = 1 (no
  /// accumulation) alone.
  double zeno_ratio = 0.9;
  /// Zeno: the longest flight between two impacts of one contact, of the shortest natural
  /// period, for which they are an accumulation (1): its remaining impacts then fit in a flight
  /// rho / (1 - rho) of at most 9 % of a period.
  double zeno_flight = 1e-2;
  /// A rebound whose predicted flight is below this fraction of the shortest period is closed
  /// at once (1). A tenth of zeno_flight: closing at once skips the whole accumulation
  /// (flight / (1 - rho)), the Zeno rule only what follows its second impact.
  double zeno_flight_at_once = 1e-3;
  /// A deck rocking between two corners (impacts alternating, flights below zeno_flight of the
  /// shortest period) slower than rocking_speed v_acc is settling (1): each flight moves the
  /// deck by about 1e-6 of its response, and the rocking converges to both corners closed.
  double rocking_speed = 100.0;
  /// Rule: a contact's second impact within zeno_flight and zeno_ratio closes it (Zeno
  /// extrapolation) [Acary and Brogliato 2008, §2.1].
  bool zeno_extrapolation = true;
  /// Rule: a return after a flight that stayed inside the touch band (approach x flight / 4 <=
  /// gap_tol) is a closure with restitution 0.
  bool settle_in_touch_band = true;
  /// Rule: slow rocking between two corners (rocking_speed) settles onto both.
  bool slow_rocking = true;
  /// Rule: a rebound that the loads return within zeno_flight_at_once of a period is closed at
  /// its first impact.
  bool bounce_at_once = true;

  // --- Projection and the active set [docs/theory.md §3.10, §3.13] ---
  /// Gauss-Newton passes of the position projection (1): the gap is linear in the translations,
  /// so two reach rounding from any gap a step leaves.
  int position_passes = 2;
  /// Gaps of closed contacts below one_pass_gap L need one pass only (1): the gap's curvature in
  /// the rotation is the arm (at most L), so one pass from sqrt(eps) L leaves rounding.
  double one_pass_gap = 1.5e-8;
  /// Pivots of the active set below rank_threshold times the largest make it singular (1): the
  /// rows of a redundant constraint (two decks' corners on one straight face) are dependent to
  /// rounding (~1e-16), an independent set's smallest pivot is far above 1e-10.
  double rank_threshold = 1e-10;
  /// A kernel direction of a singular active set moves a normal force when its normal entries
  /// exceed this norm (1; the kernel is orthonormal).
  double kernel_normal_threshold = 1e-12;
  /// Relative and absolute slack of the total normal force in the third LP of the indeterminate
  /// split (1, of the forces' scale): the total of LP 2 holds to rounding.
  double split_total_slack = 1e-9;
  /// Rule: open contacts at the face join the velocity projection as inequality rows, so the
  /// projection never drives one into its face.
  bool open_contacts_in_projection = true;

  // --- The contact layer [docs/theory.md §3.15] ---
  /// The thresholds of the impact and contact problems (solver/contact/contact_policy.h: the
  /// contact problem's tie band, the compliance of both retries, the enumeration's size), set
  /// on them at the start of a run.
  contact::ContactPolicy contact;

  /// The members as stored, in this order (schema.h): name, unit, the scale each multiplies and
  /// the values the integrator can run with. A tolerance relative to a scale is below 1 (at 1
  /// every quantity of that scale would be zero); a count of passes or steps is at least 1.
  template <typename Archive>
  void Describe(Archive* a) {
    using schema::Interval;
    const Interval below_one = Interval::Open(0.0, 1.0);
    const Interval zero_to_one = Interval::ClosedOpen(0.0, 1.0);
    const Interval positive = Interval::Above(0.0);
    const Interval non_negative = Interval::AtLeast(0.0);
    const Interval at_least_one = Interval::AtLeast(1.0);
    a->Visit(SB_NVP(velocity_tolerance), {"1", "v_ref", below_one});
    a->Visit(SB_NVP(gap_tolerance), {"1", "min(v_ref / omega_ref, L)", zero_to_one});
    a->Visit(SB_NVP(gap_rounding_ulps), {"ulp", "L", non_negative});
    a->Visit(SB_NVP(force_tolerance), {"1", "m_max v_ref omega_ref", below_one});
    a->Visit(SB_NVP(free_body_omega_radps), {"rad/s", "", positive});
    a->Visit(SB_NVP(ramp_horizon_s), {"s", "", positive});
    a->Visit(SB_NVP(steps_per_period), {"1", "2 pi / omega_max", at_least_one});
    a->Visit(SB_NVP(first_rk_step_divisor), {"1", "free step", positive});
    a->Visit(SB_NVP(omega_floor_radps), {"rad/s", "", positive});
    a->Visit(SB_NVP(nonfinite_step_error), {"1", "error norm", Interval::Above(1.0)});
    a->Visit(SB_NVP(step_reuse_band), {"1", "free step", zero_to_one});
    a->Visit(SB_NVP(step_snap_band), {"1", "free step", zero_to_one});
    a->Visit(SB_NVP(finite_check_steps), {"1", "", Interval::PowerOfTwo()});
    a->Visit(SB_NVP(event_time_tolerance), {"1", "max(1 s, |t|)", zero_to_one});
    a->Visit(SB_NVP(event_time_floor_s), {"s", "", positive});
    a->Visit(SB_NVP(maximum_time_tolerance), {"1", "max(1 s, |t|)", zero_to_one});
    a->Visit(SB_NVP(dip_margin), {"1", "Hermite bound of the dip", non_negative});
    a->Visit(SB_NVP(start_minimum_band), {"1", "event-time bracket", non_negative});
    a->Visit(SB_NVP(touch_probes), {"1", "", non_negative});
    a->Visit(SB_NVP(output_time_band), {"1", "max(1 s, |t|)", zero_to_one});
    a->Visit(SB_NVP(max_events_at_one_instant), {"1", "", non_negative});
    a->Visit(SB_NVP(decision_passes), {"1", "", at_least_one});
    a->Visit(SB_NVP(stick_band), {"1", "v_tol", non_negative});
    a->Visit(SB_NVP(cone_sign));
    a->Visit(SB_NVP(tie_bands));
    a->Visit(SB_NVP(jam));
    a->Visit(SB_NVP(zeno_ratio), {"1", "previous approach speed", zero_to_one});
    a->Visit(SB_NVP(zeno_flight), {"1", "shortest natural period", non_negative});
    a->Visit(SB_NVP(zeno_flight_at_once), {"1", "shortest natural period", non_negative});
    a->Visit(SB_NVP(rocking_speed), {"1", "v_acc", non_negative});
    a->Visit(SB_NVP(zeno_extrapolation));
    a->Visit(SB_NVP(settle_in_touch_band));
    a->Visit(SB_NVP(slow_rocking));
    a->Visit(SB_NVP(bounce_at_once));
    a->Visit(SB_NVP(position_passes), {"1", "", at_least_one});
    a->Visit(SB_NVP(one_pass_gap), {"1", "L", non_negative});
    a->Visit(SB_NVP(rank_threshold), {"1", "largest pivot", below_one});
    a->Visit(SB_NVP(kernel_normal_threshold), {"1", "orthonormal kernel", zero_to_one});
    a->Visit(SB_NVP(split_total_slack), {"1", "largest force", non_negative});
    a->Visit(SB_NVP(open_contacts_in_projection));
    a->Visit(SB_NVP(contact));
  }
};

/// Checks every member of `policy` against its description (EventPolicy::Describe): the
/// integrator relies on finite_check_steps being a power of two (the check is a mask of the
/// step count), on at least one decision pass, position pass and step a period, and on
/// tolerances that are finite and below the scale they multiply.
/// @throws InputError "event policy: MEMBER: must be ALLOWED (got VALUE)" for the first member
/// outside.
void ValidatePolicy(const EventPolicy& policy);

/// Whether every member of `a` has the bits of the same member of `b` (the padding between them
/// aside; the contact policy's by contact::SameBytes): two such policies get the same verdict
/// from ValidatePolicy, so a workspace that holds a validated policy need not validate one with
/// its members' bits again.
bool SameMembers(const EventPolicy& a, const EventPolicy& b);

}  // namespace skewbridge::dynamics
