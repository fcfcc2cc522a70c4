#pragma once
/// @file
/// The free steps' lower bounds of the open contacts' gaps between exact evaluations
/// [docs/theory.md §3.18, the sum by mode]: each contact's base g_c (its exact gap, or the last
/// fold's bound) less sum_k W_ck S_k, S_k the drifts D_k of mode k summed over the steps since.

#include <Eigen/Core>
#include <algorithm>

#include "solver/common/error.h"
#include "solver/dynamics/gap_bound.h"

namespace skewbridge::dynamics {

/// The gap bounds a free step carries over the steps that skipped their gaps (ModalGapBound).
/// Sized and reset once per run (Reset); Restart and StaysOpen allocate nothing.
class GapFloors {
 public:
  /// Storage for `bound`'s contacts and modes, and its largest weight per mode.
  explicit GapFloors(const ModalGapBound& bound) : bound_(bound) { Reset(); }

  /// What a new GapFloors of the bound would be, after the bound was given other values: the
  /// storage kept when its sizes are the same.
  void Reset() {
    base_.setZero(bound_.n_contacts);
    base_min_ = 0.0;
    sum_.setZero(bound_.n_modes);
    trial_.setZero(bound_.n_modes);
    weight_max_.setZero(bound_.n_modes);
    steps_ = 0;
    const int n = bound_.n_modes;
    for (int c = 0; c < bound_.n_contacts; ++c) {
      for (int k = 0; k < n; ++k) {
        weight_max_[k] =
            std::max(weight_max_[k], bound_.weights[static_cast<std::size_t>(c * n + k)]);
      }
    }
  }

  /// New bases: the exact gaps `gaps` (m) at the next step's start, no drift since.
  void Restart(const Eigen::VectorXd& gaps) {
    base_ = gaps;
    base_min_ = base_.minCoeff();
    sum_.setZero();
    steps_ = 0;
  }

  /// Whether every gap stays above `margin_m` over a step of tau_s from the modal coordinates Y
  /// (ModalDrift's layout): its drifts join the sums if so. The smallest base less
  /// sum_k max_c W_ck S_k answers for every contact at once; each contact's own sum only when
  /// that fails. Every kFoldSteps steps the sums go into the bases. `harmonic` false: Y's
  /// harmonic columns are zeros (a record's piece) and a deck's drifts leave them out, the same
  /// bits. Inline: a step that stays open by the smallest base ends here.
  bool StaysOpen(const double* Y, double tau_s, double margin_m, bool harmonic = true) {
    const int n = bound_.n_modes;
    if (n == 3) {
      // A deck's three modes, unrolled.
      SB_ASSERT(harmonic || (Y[12] == 0.0 && Y[13] == 0.0 && Y[14] == 0.0 && Y[15] == 0.0 &&
                             Y[16] == 0.0 && Y[17] == 0.0),
                "GapFloors: harmonic columns must be zeros when left out");
      double drift[3];
      if (harmonic) {
        ModalDrift3<true>(bound_, Y, tau_s, drift);
      } else {
        ModalDrift3Lanes(bound_, Y, tau_s, drift);  // ModalDrift3<false>'s bits
      }
      return DeckStaysOpen(drift, margin_m);
    }
    double* sum = trial_.data();  // S_k with this step's drift; kept if the step stays open
    const double* sum0 = sum_.data();
    const double* w_max = weight_max_.data();
    double closure_max = 0.0;
    ModalDrift(bound_, Y, tau_s, sum);
    for (int k = 0; k < n; ++k) {
      sum[k] += sum0[k];
      closure_max += w_max[k] * sum[k];
    }
    return Keep(closure_max, margin_m);
  }

  /// DeckStaysOpen's state for a loop that holds it in locals between steps (Deck, Store): the
  /// sums S_k, the largest weights max_c W_ck, the smallest base (m) and the sums' count.
  struct DeckSums {
    double sum[3];
    double w_max[3];
    double base_min;
    int steps;
  };
  /// The floors' state of a deck (three modes) as DeckSums.
  DeckSums Deck() const {
    return {{sum_[0], sum_[1], sum_[2]},
            {weight_max_[0], weight_max_[1], weight_max_[2]},
            base_min_,
            steps_};
  }
  /// A deck's state `d` (Deck) back into the floors.
  void Store(const DeckSums& d) {
    for (int k = 0; k < 3; ++k) sum_[k] = d.sum[k];
    steps_ = d.steps;
  }
  /// DeckStaysOpen on the state `d` the caller holds: the same operations, the same outcome;
  /// each contact's check and the fold take the members (written for them and read back).
  [[gnu::always_inline]] bool DeckStaysOpen(DeckSums& d, const double drift[3], double margin_m) {
    const double trial[3] = {d.sum[0] + drift[0], d.sum[1] + drift[1], d.sum[2] + drift[2]};
    const double closure_max =
        d.w_max[0] * trial[0] + d.w_max[1] * trial[1] + d.w_max[2] * trial[2];
    if (!(d.base_min - closure_max * (1.0 + 1e-12) > margin_m)) {
      for (int k = 0; k < 3; ++k) trial_[k] = trial[k];
      if (!EachStaysOpen(margin_m)) {
        return false;
      }
    }
    for (int k = 0; k < 3; ++k) d.sum[k] = trial[k];
    if (++d.steps == kFoldSteps) {
      Store(d);
      Fold();
      d = Deck();
    }
    return true;
  }

  /// StaysOpen of a deck (three modes) from its drifts over the step (ModalDrift3's, m per unit
  /// of eta_k): the same operations.
  bool DeckStaysOpen(const double drift[3], double margin_m) {
    double* sum = trial_.data();  // S_k with this step's drift; kept if the step stays open
    const double* sum0 = sum_.data();
    const double* w_max = weight_max_.data();
    sum[0] = sum0[0] + drift[0];
    sum[1] = sum0[1] + drift[1];
    sum[2] = sum0[2] + drift[2];
    return Keep(w_max[0] * sum[0] + w_max[1] * sum[1] + w_max[2] * sum[2], margin_m);
  }

 private:
  // At most this many drifts are summed before they go into the bases: the sum's rounding (a
  // relative kFoldSteps ulps) stays far below the bound's relative 1e-12.
  static constexpr int kFoldSteps = 256;
  // Whether the gaps stay open with the sums of trial_, whose largest closure over the contacts
  // is at most closure_max (m): they become the sums if so, folded every kFoldSteps steps.
  bool Keep(double closure_max, double margin_m) {
    if (!(base_min_ - closure_max * (1.0 + 1e-12) > margin_m) && !EachStaysOpen(margin_m)) {
      return false;
    }
    sum_.swap(trial_);
    if (++steps_ == kFoldSteps) {
      Fold();
    }
    return true;
  }
  // Each contact's own base less its closure with the sums of trial_, above margin_m.
  [[gnu::noinline]] bool EachStaysOpen(double margin_m) const {
    for (int c = 0; c < bound_.n_contacts; ++c) {
      if (!(base_[c] - GapClosureBound(bound_, c, trial_.data()) > margin_m)) {
        return false;
      }
    }
    return true;
  }
  // The sums into the bases, the sums restarted.
  [[gnu::noinline]] void Fold() {
    for (int c = 0; c < bound_.n_contacts; ++c) {
      base_[c] -= GapClosureBound(bound_, c, sum_.data());
    }
    base_min_ = base_.minCoeff();
    sum_.setZero();
    steps_ = 0;
  }
  const ModalGapBound& bound_;
  Eigen::VectorXd base_;        // per contact, the base g_c (m)
  double base_min_ = 0.0;       // the smallest base (m)
  Eigen::VectorXd sum_;         // per mode, S_k
  Eigen::VectorXd trial_;       // per mode, S_k with the step being checked
  Eigen::VectorXd weight_max_;  // per mode, max_c W_ck (m per unit of eta_k)
  int steps_ = 0;               // the terms of sum_
};

}  // namespace skewbridge::dynamics
