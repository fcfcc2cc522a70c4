#pragma once
/// @file
/// Event location [docs/theory.md §3.12]: the event functions of the closed contacts, and where
/// an open contact's gap closes inside a step: the first time in (t0, t1] at which g reaches
/// zero, given g and its rate gamma_N at both ends and the dense output as two functions of
/// time, with the touch probes and the start-of-step minimum of the EventPolicy. Independent of
/// how the state is interpolated (exact flow or Runge-Kutta).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "solver/dynamics/contact_modes.h"
#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/root_finding.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// The bracket of an event time ending at t1 (s): event_time_tolerance relative beyond 1 s,
/// plus the absolute floor. A slow approach's gap is rounding noise over a band of ~1e-15 m /
/// speed, often 1e-11 s wide; a tighter bracket costs evaluations for event times that move the
/// state by less than the gap tolerance.
inline double EventTimeBracket(double t1, const EventPolicy& policy) {
  return policy.event_time_tolerance * std::max(1.0, std::abs(t1)) + policy.event_time_floor_s;
}

/// The event functions of the closed contacts [docs/theory.md §3.12], two per contact into
/// `values` (2 n_c): lambda_N + force_tol (detachment when it falls below zero), and a friction
/// function, s gamma_T + v_tol while sliding with sign s (stick or reversal once the slip has
/// clearly passed zero), mu lambda_N + force_tol - |lambda_T| while sticking (slip once the
/// friction clearly exceeds the cone); +1 for an open contact and for a frictionless one's
/// second. `gamma_T` (m/s) are the slip velocities, `lambda_N` and `lambda_T` (N) the forces of
/// the active set with `modes`. The bands make every function non-negative at the start of the
/// phase that the contact problem chose: a slip starts at gamma_T = 0 and a stick may start with
/// its friction on the cone, and a function negative by rounding there would fire the same
/// event again at the same instant.
inline void ClosedEventValues(const model::Model& model, const ContactModes& modes,
                              const Eigen::VectorXd& gamma_T, const Eigen::VectorXd& lambda_N,
                              const Eigen::VectorXd& lambda_T, double force_tol_N, double v_tol_mps,
                              Eigen::Ref<Eigen::VectorXd> values) {
  for (int c = 0; c < modes.size(); ++c) {
    const ContactMode mode = modes[c];
    values[2 * c] = !IsClosed(mode) ? 1.0 : lambda_N[c] + force_tol_N;
    double f = 1.0;
    if (mode == ContactMode::kSlidePositive) {
      f = gamma_T[c] + v_tol_mps;
    } else if (mode == ContactMode::kSlideNegative) {
      f = -gamma_T[c] + v_tol_mps;
    } else if (mode == ContactMode::kStick) {
      f = model.contact(c).friction * lambda_N[c] + force_tol_N - std::abs(lambda_T[c]);
    }
    values[2 * c + 1] = f;
  }
}

/// ImpactSuspected's dip margin that searches every dip (the constrained step's, §3.12).
inline constexpr double kEveryDip = std::numeric_limits<double>::infinity();

/// Whether the gap of an open contact may close inside a step of length `tau_s` (s), from its
/// gap g0, g1 (m) and normal rate gN0, gN1 (m/s) at the step's ends [docs/theory.md §3.12]: a
/// gap that ends below zero, or one that dips (gamma_N from - to +) with
/// min(g0, g1) <= dip_margin max(-gN0, gN1) tau / 2. A gap whose normal acceleration keeps its
/// sign over the step dips at most max(-gN0, gN1) tau / 2 below min(g0, g1); the margin covers
/// one that turns. The free step passes EventPolicy::dip_margin, the constrained step
/// kEveryDip, which suspects every dip (§3.12 derives why the margin holds for the one and not
/// the other). A suspected gap is searched by FirstGapRoot.
inline bool ImpactSuspected(double g0, double gN0, double g1, double gN1, double tau_s,
                            double dip_margin) {
  if (g1 < 0.0) {
    return true;
  }
  if (!(gN0 < 0.0 && gN1 > 0.0)) {
    return false;
  }
  if (dip_margin == kEveryDip) {
    return true;
  }
  // A gap whose acceleration keeps its sign dips at most max(-gN0, gN1) tau / 2 below
  // min(g0, g1) (§3.12); the margin covers an acceleration that turns within the step.
  const double dip = 0.5 * std::max(-gN0, gN1) * tau_s;
  return std::min(g0, g1) <= dip_margin * dip;
}

/// The first impact time of a contact in the step [t0, t1] (s), or +inf when its gap does not
/// close there. g0, g1 (m) and gN0, gN1 (m/s) are the gap and its rate at the step's ends;
/// gap(t) and gamma_N(t) evaluate them inside. `gap_tol_m` is the touch band of a gap,
/// `v_tol_mps` the zero of a velocity (solver/dynamics/run_scales.h).
///
/// - A step that ends with g1 < 0 has a root in it (Brent on g).
/// - A step that ends open but whose rate turns from - to + may dip below zero: the minimum of g
///   (Brent on gamma_N) brackets the root when it is negative. A minimum within
///   start_minimum_band brackets of t0 is the state the decision there has just opened, not an
///   impact.
/// - A contact starting in touch (g0 <= gap_tol) searches from the maximum of its gap inside the
///   step: a contact the contact problem has just opened starts with gamma_N = 0 and a
///   separating acceleration, and if that acceleration reverses within the step, gamma_N is
///   positive only on an early part of it, found by halving towards t0 (touch_probes).
/// The returned time is on the side where the gap has closed, so the impact sees g <= 0.
template <class Gap, class Rate>
double FirstGapRoot(double t0, double t1, double g0, double gN0, double g1, double gN1, Gap&& gap,
                    Rate&& gamma_N, double gap_tol_m, double v_tol_mps, const EventPolicy& policy) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double x_tol = EventTimeBracket(t1, policy);
  double a = t0, ga = g0, gNa = gN0;
  if (ga <= gap_tol_m) {
    double t_pos = gNa > v_tol_mps ? t0 : kInf;
    double gN_pos = gNa;
    if (t_pos == kInf && gN1 < 0.0) {  // t_pos is infinite exactly when gNa <= v_tol
      for (int k = 1; k <= policy.touch_probes; ++k) {
        const double t = t0 + std::ldexp(t1 - t0, -k);
        if (!(t > t0)) {
          break;
        }
        const double v = gamma_N(t);
        if (v > 0.0) {
          t_pos = t;
          gN_pos = v;
          break;
        }
      }
    }
    if (t_pos < kInf && gN1 < 0.0) {
      const RootResult top = FindRootBrent(gamma_N, t_pos, t1, gN_pos, gN1, x_tol);
      a = top.x;
      ga = gap(a);
      gNa = 0.0;
      if (ga <= 0.0 && a > t0) {
        // The gap never opened beyond rounding: the contact closes again where its separation
        // turns round, later than t0, and the contact problem there sees it approaching.
        return a;
      }
    }
    if (ga <= 0.0) {
      return g1 < 0.0 && gNa <= v_tol_mps && gN1 < 0.0 ? a : kInf;
    }
  }
  double b = t1, gb = g1;
  if (gb >= 0.0) {
    if (!(gNa < 0.0 && gN1 > 0.0)) {
      return kInf;
    }
    const RootResult bottom = FindRootBrent(gamma_N, a, t1, gNa, gN1, x_tol);
    const double gm = gap(bottom.x);
    // A minimum at the step's start (within the bracket) is the state the decision there has
    // just opened: its gap, taken from the dense output instead of the state, may sit below
    // zero by rounding, and an impact there would repeat that decision at the same instant.
    if (gm >= 0.0 || bottom.x - t0 <= policy.start_minimum_band * x_tol) {
      return kInf;
    }
    b = bottom.x;
    gb = gm;
  }
  const RootResult root = FindRootBrent(gap, a, b, ga, gb, x_tol);
  return root.fx <= 0.0 ? root.x : root.upper;
}

/// The first time in [t0, t1] (s) at which an event function of a closed contact fires
/// [docs/theory.md §3.12], or +inf when none does. `f0`, `f1` are the 2 n_c event functions
/// (ClosedEventValues) at the step's ends; `value_at(t, e)` evaluates function e at t inside
/// the step. Only the functions of the contacts closed in `modes` are looked at, in index order.
/// A function that starts non-negative and ends negative is bracketed and its root found by
/// Brent's method to EventTimeBracket(t1), the time taken on the side where it is negative (or
/// the bracket's upper end); one already negative at the step's start fires at t0. A function
/// that dips below zero and recovers inside the step is not searched: the bands of
/// ClosedEventValues make its ends the test.
template <class ValueAt>
double FirstClosedEvent(double t0, double t1, const Eigen::VectorXd& f0, const Eigen::VectorXd& f1,
                        const ContactModes& modes, ValueAt&& value_at, const EventPolicy& policy) {
  double t_event = std::numeric_limits<double>::infinity();
  const double x_tol = EventTimeBracket(t1, policy);
  for (int c = 0; c < modes.size(); ++c) {
    if (!modes.closed(c)) {
      continue;
    }
    for (int e = 2 * c; e <= 2 * c + 1; ++e) {
      if (f1[e] < 0.0 && f0[e] >= 0.0) {
        const auto f = [&](double t) { return value_at(t, e); };
        const RootResult root = FindRootBrent(f, t0, t1, f0[e], f1[e], x_tol);
        t_event = std::min(t_event, root.fx < 0.0 ? root.x : root.upper);
      } else if (f1[e] < 0.0) {
        t_event = std::min(t_event, t0);
      }
    }
  }
  return t_event;
}

/// The contacts that strike together with the first impact at `t_event_s` [docs/theory.md §3,
/// nearly simultaneous impacts; §3.12]: the open contacts in `modes` whose gap is at most
/// `gap_tol_m` at t_event + `simultaneity_s` (but not beyond the step's end `t_end_s`),
/// appended to `forced` in index order. `positions_at(t)` gives q at a time inside the step,
/// `gap_of(c, q)` contact c's gap there. The first impact itself is among them (its gap has
/// closed at t_event); the decision takes them all as candidates of one impact (§3.3).
template <class PositionsAt, class GapOf>
void SimultaneousContacts(double t_event_s, double t_end_s, double simultaneity_s, double gap_tol_m,
                          const ContactModes& modes, PositionsAt&& positions_at, GapOf&& gap_of,
                          std::vector<int>& forced) {
  const auto q_late = positions_at(std::min(t_event_s + simultaneity_s, t_end_s));
  for (int c = 0; c < modes.size(); ++c) {
    if (!modes.closed(c) && gap_of(c, q_late) <= gap_tol_m) {
      forced.push_back(c);
    }
  }
}

}  // namespace skewbridge::dynamics
