#pragma once
/// @file
/// Where the event-driven integrator's steps end [docs/theory.md §3.14]: the free steps on a grid
/// aligned with each excitation piece (step reuse and snapping), and the Runge-Kutta step of a
/// constrained phase snapped to the piece's end. Pure functions of times, lengths and the
/// EventPolicy's bands.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/common/excitation.h"
#include "solver/dynamics/event_policy.h"

namespace skewbridge::dynamics {

/// FreeStepSize's longest step h_max (s) on a piece of harmonic rate piece_omega_radps.
inline double FreeStepMax(double piece_omega_radps, double omega_max_radps,
                          const EventPolicy& policy) {
  const double omega =
      std::max({omega_max_radps, std::abs(piece_omega_radps), policy.omega_floor_radps});
  return 2.0 * std::numbers::pi / omega / policy.steps_per_period;
}

/// FreeStepSize of a finite piece of length_s with the longest step h_max_s (FreeStepMax).
inline double FreeStepOfLength(double length_s, double h_max_s) {
  const double steps = length_s / h_max_s;
  // One step (a record's sample within h_max): ceil is 1 and length / 1 is length.
  return steps > 0.0 && steps <= 1.0 ? length_s : length_s / std::ceil(steps);
}

/// The nominal free step on `piece` (s) [§3.14]: at most 2 pi / omega / steps_per_period, omega
/// the largest of the model's highest natural frequency `omega_max_radps`, the piece's own
/// frequency and omega_floor_radps; a finite piece is cut into equal steps of at most that.
inline double FreeStepSize(const ExcitationPiece& piece, double omega_max_radps,
                           const EventPolicy& policy) {
  const double h_max = FreeStepMax(piece.omega, omega_max_radps, policy);
  if (std::isfinite(piece.t_end)) {
    return FreeStepOfLength(piece.t_end - piece.t_begin, h_max);
  }
  return h_max;
}

/// One free step on a piece's grid.
struct FreeStepPlan {
  double h_s = 0.0;       ///< the nominal step: the grid's spacing
  double t_next_s = 0.0;  ///< where the step ends: the next grid point, or the stop time
  /// The step is a whole h (within step_snap_band h): the cached propagator of h applies.
  bool full = false;
};

/// The free step from `t_s` on the grid piece_begin_s + k h of a piece that stops at `t_stop_s`
/// (its end or the run's) [§3.14]:
/// - step reuse: a nominal step `h_s` within step_reuse_band h of the previous one `h_last_s` is
///   the previous one (pieces of a sampled record differ in length by rounding; one canonical h
///   keeps the propagator cache hitting, and the state moves by e^{A h} over a step a few ulps
///   longer, far below any tolerance);
/// - snapping: a time within step_snap_band h below a grid point counts as on it (the step goes
///   to the point after), and a grid point within step_snap_band h of the stop is the stop, so
///   no sliver step of rounding length follows; the step is full when its length is h within
///   that band.
/// @pre piece_begin_s <= t_s < t_stop_s, h_s > 0.
inline FreeStepPlan PlanFreeStep(double t_s, double piece_begin_s, double t_stop_s, double h_s,
                                 double h_last_s, const EventPolicy& policy) {
  FreeStepPlan plan;
  plan.h_s = std::abs(h_s - h_last_s) <= policy.step_reuse_band * h_s ? h_last_s : h_s;
  const double h = plan.h_s;
  // At the piece's start (a record's steps, one per sample) the quotient is 0 exactly: the same
  // k without the division, and for a band below 1 (as ValidatePolicy wants it) without floor.
  const double k = t_s == piece_begin_s
                       ? (policy.step_snap_band < 1.0 ? 0.0 * policy.step_snap_band
                                                      : std::floor(policy.step_snap_band))
                       : std::floor((t_s - piece_begin_s) / h + policy.step_snap_band);
  plan.t_next_s = piece_begin_s + (k + 1.0) * h;
  if (plan.t_next_s > t_stop_s - policy.step_snap_band * h) {
    plan.t_next_s = t_stop_s;
  }
  plan.full = std::abs((plan.t_next_s - t_s) - h) <= policy.step_snap_band * h;
  return plan;
}

/// The excitation piece of the free steps: where the last step ended its piece (a record's step
/// per sample), the next one by its number (Excitation::NextPiece, the bits of PieceAt there),
/// else Excitation::PieceAt.
class PieceCursor {
 public:
  /// The piece at t_s (PieceAt(t_s)'s bits) of `excitation`, the same for every call.
  const ExcitationPiece& At(const Excitation& excitation, double t_s) {
    if (t_s == piece_.t_end) {
      excitation.NextPiece(piece_);
    } else {
      piece_ = excitation.PieceAt(t_s);
    }
    return piece_;
  }
  /// The last piece At gave, for a caller that moves it on itself (the same bits as At's).
  ExcitationPiece& last() { return piece_; }
  /// At's piece, with the next piece of a sampled excitation read from its samples `view`
  /// (Excitation::Samples) inline: the same bits.
  const ExcitationPiece& At(const Excitation& excitation, const SampleView& view, double t_s) {
    if (t_s == piece_.t_end) {
      if (!NextSampledPiece(view, piece_)) {
        excitation.NextPiece(piece_);
      }
    } else {
      piece_ = excitation.PieceAt(t_s);
    }
    return piece_;
  }

 private:
  ExcitationPiece piece_;  // the last piece (none yet: its end +inf, which no time equals)
};

/// The length of a constrained phase's Runge-Kutta step from `t_s` (s) [§3.14]: the step the
/// error control proposes, `h_rk_s`, cut at the stop `t_stop_s` (the piece's end or the run's),
/// and stretched to the stop when the rest would be below step_snap_band of the step.
/// @pre t_s < t_stop_s, h_rk_s > 0.
inline double ConstrainedStepLength(double t_s, double t_stop_s, double h_rk_s,
                                    const EventPolicy& policy) {
  const double h = std::min(h_rk_s, t_stop_s - t_s);
  return t_stop_s - t_s - h < policy.step_snap_band * h ? t_stop_s - t_s : h;
}

}  // namespace skewbridge::dynamics
