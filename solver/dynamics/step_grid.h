#pragma once
/// @file
/// Where the event-driven integrator's steps end [docs/theory.md §3.14]: the free steps on a grid
/// aligned with each excitation piece (step reuse and snapping), and the Runge-Kutta step of a
/// constrained phase snapped to the piece's end. Pure functions of times, lengths and the
/// EventPolicy's bands.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
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

/// PlanFreeStep's step length: the previous step h_last_s (s) where the nominal h_s is within
/// reuse_band (the policy's step_reuse_band, relative to h_s) of it, else h_s.
inline double ReusedStep(double h_s, double h_last_s, double reuse_band) {
  return std::abs(h_s - h_last_s) <= reuse_band * h_s ? h_last_s : h_s;
}

/// PlanFreeStep's grid index of the step from `t_s` on the grid piece_begin_s + k h (s): the
/// floor of the quotient plus step_snap_band. At the piece's start (a record's steps, one per
/// sample) the quotient is 0 exactly: the same k without the division, and for a band below 1 (as
/// ValidatePolicy wants it) without floor.
inline double GridIndex(double t_s, double piece_begin_s, double h, const EventPolicy& policy) {
  return t_s == piece_begin_s ? (policy.step_snap_band < 1.0 ? 0.0 * policy.step_snap_band
                                                             : std::floor(policy.step_snap_band))
                              : std::floor((t_s - piece_begin_s) / h + policy.step_snap_band);
}

/// PlanFreeStep's plan of length h (s) from `t_s` with grid index k: the end the grid point
/// piece_begin_s + (k + 1) h, or the stop where that point is within step_snap_band h of it, and
/// whether the step is full.
inline FreeStepPlan GridStep(double t_s, double piece_begin_s, double t_stop_s, double h, double k,
                             const EventPolicy& policy) {
  FreeStepPlan plan;
  plan.h_s = h;
  plan.t_next_s = piece_begin_s + (k + 1.0) * h;
  if (plan.t_next_s > t_stop_s - policy.step_snap_band * h) {
    plan.t_next_s = t_stop_s;
  }
  plan.full = std::abs((plan.t_next_s - t_s) - h) <= policy.step_snap_band * h;
  return plan;
}

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
  const double h = ReusedStep(h_s, h_last_s, policy.step_reuse_band);
  return GridStep(t_s, piece_begin_s, t_stop_s, h, GridIndex(t_s, piece_begin_s, h, policy),
                  policy);
}

/// PlanFreeStep for a caller that expects the grid index k (the last step's k plus one, on the
/// same grid): the same plan. The step's end is taken from `k_expected` where the quotient's
/// floor equals it (the same end: (k + 1) h of equal k), so that it does not wait for the
/// division and the floor; the test is a branch the processor predicts, not an operand. `k_s`
/// receives the floor's k (the next step's expectation less one).
inline FreeStepPlan PlanFreeStepExpecting(double t_s, double piece_begin_s, double t_stop_s,
                                          double h_s, double h_last_s, const EventPolicy& policy,
                                          double k_expected, double& k_s) {
  const double h = ReusedStep(h_s, h_last_s, policy.step_reuse_band);
  const double k = GridIndex(t_s, piece_begin_s, h, policy);
  double k_end = k_expected;
  if (!(k == k_expected)) [[unlikely]] {
    k_end = k;
    // An opaque move: the compiler keeps the branch instead of a select, which would make the
    // step's end an operand of the floor again.
    asm("" : "+x"(k_end));
  }
  k_s = k;
  return GridStep(t_s, piece_begin_s, t_stop_s, h, k_end, policy);
}

/// PlanFreeStep at a piece's start (t_s == piece_begin_s, a record's step per sample) with the
/// products that depend on the step alone taken once per step length: the same operations on the
/// same operands, so the same plan. The length Reset gives is a fixed point of the reuse rule:
/// PlanFreeStep(..., h_s, h_last_s) takes h_last_s or h_s, and with that length as h_last_s it
/// takes the same bits again, so a loop whose nominal step stays h_s needs Reset only when h_s
/// changes.
class RampStepPlanner {
 public:
  /// The planner of `policy`'s bands (k at a piece's start and its successor, as PlanFreeStep
  /// takes them).
  explicit RampStepPlanner(const EventPolicy& policy)
      : snap_(policy.step_snap_band),
        reuse_(policy.step_reuse_band),
        k_next_((snap_ < 1.0 ? 0.0 * snap_ : std::floor(snap_)) + 1.0),
        next_h_(k_next_ * h_),
        snap_h_(snap_ * h_) {}
  /// The step length (s) for the nominal step h_s after a step of h_last_s (PlanFreeStep's
  /// reuse), and its products (k + 1) h and step_snap_band h for At (taken again only for a
  /// length of other bits than the last one's).
  double Reset(double h_s, double h_last_s) {
    const double h = ReusedStep(h_s, h_last_s, reuse_);
    if (std::bit_cast<std::uint64_t>(h) != std::bit_cast<std::uint64_t>(h_)) {
      h_ = h;
      next_h_ = k_next_ * h;
      snap_h_ = snap_ * h;
    }
    return h_;
  }
  /// PlanFreeStep(t_s, piece_begin_s, t_stop_s, h_s, h_last_s, policy) for Reset's h_s and
  /// h_last_s (or its own length as h_last_s).
  /// @pre t_s == piece_begin_s.
  FreeStepPlan At(double t_s, double piece_begin_s, double t_stop_s) const {
    FreeStepPlan plan;
    plan.h_s = h_;
    plan.t_next_s = piece_begin_s + next_h_;
    if (plan.t_next_s > t_stop_s - snap_h_) {
      plan.t_next_s = t_stop_s;
    }
    plan.full = std::abs((plan.t_next_s - t_s) - h_) <= snap_h_;
    return plan;
  }

 private:
  double snap_, reuse_;  // the policy's step_snap_band and step_reuse_band
  double k_next_;        // k + 1 at a piece's start
  double h_ = std::numeric_limits<double>::quiet_NaN();  // the step's length (s): none yet
  double next_h_;                                        // (k + 1) h (s)
  double snap_h_;                                        // step_snap_band h (s)
};

/// The excitation piece of the free steps: where the last step ended its piece (a record's step
/// per sample), the next one by its number (Excitation::NextPiece, the bits of PieceAt there);
/// while the time stays inside a piece the excitation promised to hold (Excitation::PieceHolds:
/// a pulse's pieces, the rest after a record), that piece; else Excitation::PieceAt.
class PieceCursor {
 public:
  /// The piece at t_s (PieceAt(t_s)'s bits) of `excitation`, the same for every call.
  const ExcitationPiece& At(const Excitation& excitation, double t_s) {
    if (t_s == piece_.t_end) {
      excitation.NextPiece(piece_);
      holds_ = false;
    } else if (!Keeps(t_s)) {
      Ask(excitation, t_s);
    }
    return piece_;
  }
  /// The last piece At gave, for a caller that moves it on itself (the same bits as At's); the
  /// next At asks the excitation again unless the piece ends there.
  ExcitationPiece& last() {
    holds_ = false;
    return piece_;
  }
  /// At's piece, with the next piece of a sampled excitation read from its samples `view`
  /// (Excitation::Samples) inline: the same bits.
  const ExcitationPiece& At(const Excitation& excitation, const SampleView& view, double t_s) {
    if (t_s == piece_.t_end) {
      if (!NextSampledPiece(view, piece_)) {
        excitation.NextPiece(piece_);
      }
      holds_ = false;
    } else if (!Keeps(t_s)) {
      Ask(excitation, t_s);
    }
    return piece_;
  }

 private:
  // The kept piece is PieceAt(t_s)'s bits: promised, and t_s inside it (false for NaN).
  bool Keeps(double t_s) const { return holds_ && t_s >= piece_.t_begin && t_s < piece_.t_end; }
  void Ask(const Excitation& excitation, double t_s) {
    piece_ = excitation.PieceAt(t_s);
    holds_ = excitation.PieceHolds(piece_);
  }

  ExcitationPiece piece_;  // the last piece (none yet: its end +inf, which no time equals)
  bool holds_ = false;     // the excitation's PieceHolds of piece_
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
