#pragma once
/// @file
/// What the integrator remembers of each contact's impacts, and the predicates on it that end
/// an accumulation of impacts [docs/theory.md §3.4-§3.6]: pure functions of the history, the
/// instant, the approach speed, the run's scales and the EventPolicy.

#include <limits>

#include "solver/dynamics/event_policy.h"

namespace skewbridge::dynamics {

/// One contact's impact history.
struct ImpactHistory {
  double bounce_t_s = -std::numeric_limits<double>::infinity();  ///< time of its last impact
  double bounce_v_mps = 0.0;  ///< approach speed of that impact (> 0)
  long bounce_seq = -1;       ///< the run's impact-instant count at that impact
  /// When it last left the face (a rebound or a detachment).
  double left_t_s = -std::numeric_limits<double>::infinity();
};

/// The scales the predicates compare with (solver/dynamics/run_scales.h).
struct AccumulationScales {
  double period_min_s = std::numeric_limits<double>::infinity();  ///< shortest natural period
  double gap_tol_m = 0.0;                                         ///< the touch band of a gap
  double v_acc_mps = 0.0;                                         ///< the accumulation threshold
};

/// Zeno [docs/theory.md §3.4; Acary and Brogliato 2008, §2.1]: true when an impact at `t_s` with
/// approach speed `approach_mps` continues a geometric sequence of this contact's impacts, so
/// the sequence is closed at once. `impact_sequence` counts the run's impact instants so far.
///
/// A contact bouncing under a nearly constant force returns after a flight much shorter than
/// any period of the model, each time slower by a constant ratio rho (eps_N for a single
/// contact), so its impacts accumulate after a further time (t_k - t_{k-1}) rho / (1 - rho), at
/// which it is closed. Two consecutive impacts of the same contact, with no other impact between
/// them, a ratio below zeno_ratio and a flight below zeno_flight of the shortest period identify
/// the sequence; its remaining impacts, each a fraction of a flight that is itself a small
/// fraction of a period, are replaced by closing the contact now. Without restitution there is
/// no sequence; with eps_N = 1 the ratio stays near 1 and nothing is extrapolated.
inline bool Accumulating(const ImpactHistory& h, long impact_sequence, double t_s,
                         double approach_mps, const AccumulationScales& s,
                         const EventPolicy& policy) {
  if (!policy.zeno_extrapolation || h.bounce_seq != impact_sequence || !(h.bounce_v_mps > 0.0)) {
    return false;
  }
  const double flight = t_s - h.bounce_t_s;
  const double ratio = approach_mps / h.bounce_v_mps;
  return flight > 0.0 && flight <= policy.zeno_flight * s.period_min_s &&
         ratio <= policy.zeno_ratio;
}

/// Settling [docs/theory.md §3.5]: true when this contact, closing at `t_s` with
/// `approach_mps`, is settling onto its face; its closure then has restitution 0.
///
/// Two ways a deck settles that the accumulation of one contact's impacts does not see, both a
/// deck rocking between two corners of the face, each impact lifting the other corner, at a
/// speed the loads sustain (not a geometric sequence):
/// 1. Inside the touch band: a contact that leaves the face at about the speed it returns with,
///    under a nearly constant acceleration, rises at most approach x flight / 4 in between.
///    Below the gap tolerance that flight was never resolved as one: the contact stayed in
///    touch (EventPolicy::settle_in_touch_band).
/// 2. Slow rocking: this contact's last impact was the one before the other corner's, within a
///    flight below zeno_flight of the shortest period, and the approach is within rocking_speed
///    of the accumulation threshold: each flight moves the deck by about 1e-6 of its response,
///    and the rocking converges to both corners closed (EventPolicy::slow_rocking).
/// Both thresholds scale with the response (gap_tol above its rounding floor, v_acc), so
/// self-similarity holds.
inline bool Settling(const ImpactHistory& h, long impact_sequence, double t_s, double approach_mps,
                     const AccumulationScales& s, const EventPolicy& policy) {
  const double flight = t_s - h.left_t_s;
  if (policy.settle_in_touch_band && flight > 0.0 && 0.25 * approach_mps * flight <= s.gap_tol_m) {
    return true;
  }
  const double since = t_s - h.bounce_t_s;
  return policy.slow_rocking && h.bounce_seq == impact_sequence - 1 && since > 0.0 &&
         since <= policy.zeno_flight * s.period_min_s &&
         approach_mps <= policy.rocking_speed * s.v_acc_mps;
}

/// The predicted bounce [docs/theory.md §3.6]: true when a contact that struck at
/// `approach_mps` and leaves its face at `leave_mps` would return under its normal acceleration
/// `normal_accel()` (m/s^2, negative when the loads press it back; evaluated only when needed)
/// within zeno_flight_at_once of the shortest period: the accumulation is closed at its first
/// impact.
///
/// Accumulating, seen one flight earlier: a contact leaving at gamma_N = rho approach (rho <=
/// zeno_ratio) under a normal acceleration -a (a > 0) returns after 2 gamma_N / a. Below
/// zeno_flight_at_once of the shortest period that return is the second impact of an
/// accumulation, which Accumulating would close; it is closed now instead. Over the flight the
/// contact's normal impulse is the same either way (the rebound's share is then carried by the
/// contact force); what moves is when, within a flight below 0.1 % of a period.
template <class NormalAcceleration>
bool BounceClosesAtOnce(double approach_mps, double leave_mps, NormalAcceleration&& normal_accel,
                        const AccumulationScales& s, const EventPolicy& policy) {
  if (!policy.bounce_at_once || !(approach_mps > s.v_acc_mps) ||
      !(leave_mps <= policy.zeno_ratio * approach_mps)) {
    return false;
  }
  const double a = normal_accel();
  return a < 0.0 && 2.0 * leave_mps <= -a * policy.zeno_flight_at_once * s.period_min_s;
}

}  // namespace skewbridge::dynamics
