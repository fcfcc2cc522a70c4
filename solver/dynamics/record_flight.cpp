#include <algorithm>
#include <cmath>

#include "solver/dynamics/coordinate_maxima.h"
#include "solver/dynamics/integrator.h"
#include "solver/dynamics/run_result.h"

namespace skewbridge::dynamics {

bool Integrator::RecordFlight(long& steps, double& t_finite) {
  LinearFlow& flow = ws_.flow_;
  const bool observe = observer_ != nullptr && log_.events.empty();
  const double output_reach = t_end_ + policy_.output_time_band;
  const long check_mask = policy_.finite_check_steps - 1;
  const int decks = travel_.decks();
  double* max_q = result_.max_abs_q.data();
  double* time_of_max = result_.time_of_max_s.data();
  double* max_travel = result_.max_travel_m.data();
  // A record's samples, read by the next piece of every step without a virtual call.
  const SampleView samples = excitation_.Samples();
  // GapsStayOpen's margin and the flow's modal coordinates (their storage is the flow's own).
  const double gap_margin = 2.0 * scales_.gap_tol_m;
  const double* modal_y = flow.modal_coordinates().data();
  // The history grid's next sample moves only in a step this loop leaves by.
  const bool outputs = next_output_t_ <= output_reach;
  // One deck's corner-reach terms at the step's start (CornerTravelTracker::EndReach).
  double reach0 = 0.0, speed0 = 0.0;
  if (decks == 1) {
    travel_.EndReach(0, z_.data(), z_.data() + n_, reach0, speed0);
  }
  for (;;) {
    // FreeStep's plan, the same operations.
    const double t0 = t_, h0 = h_free_;
    if (observe) {
      observed_z0_ = z_.head(2 * n_);
    }
    const ExcitationPiece& piece = pieces_.At(excitation_, samples, t_);
    SB_DEMAND(piece.t_end > t_, "Excitation::PieceAt(t) returned a piece that ends at or before t");
    const FreeStepPlan step = PlanFreeStep(t_, piece.t_begin, std::min(piece.t_end, t_end_),
                                           NominalFreeStep(piece), h_free_, policy_);
    h_free_ = step.h_s;
    bool common = step.full && piece.omega == 0.0;
    if (common) {
      // FreeStepOf's transition without the harmonic generator (SetGenerator writes its zeros)
      // and the gap floors' check.
      const double tau = step.t_next_s - t_;
      flow.SetGenerator(piece, t_, z_);
      flow.ApplyRecordMotion(StepPropagator(step.h_s, 0.0, false), z_, z_new_);
      ++result_.free_steps;
      if (gaps_exact_) {
        gap_floors_.Restart(ends_.gap0);
      }
      // GapsStayOpen (the bound applies in this loop) with the flight's margin and coordinates.
      if (!gap_floors_.StaysOpen(modal_y, std::max(tau, step.h_s), gap_margin, false)) {
        FinishFreeStep(piece, step, false, false, 0.0, 0.0);
        common = false;
      } else {
        // RecordStep's tests that need no dense output: a step that passes them all raises the
        // maxima at its end only, evaluates no corner and records no history sample.
        const double t1 = step.t_next_s;
        const double* x0 = z_.data();
        const double* x1 = z_new_.data();
        // A deck's three coordinates unrolled.
        bool rare =
            n_ == 3
                ? RaiseMaximaAtEnd(3, x0, x0 + 3, t1, x1, x1 + 3, t1 - t_, max_q, time_of_max)
                : RaiseMaximaAtEnd(n_, x0, x0 + n_, t1, x1, x1 + n_, t1 - t_, max_q, time_of_max);
        if (decks == 1) {
          // One deck: the start's terms are the last step's end's.
          double reach1, speed1;
          travel_.EndReach(0, x1, x1 + n_, reach1, speed1);
          rare = rare || CornerTravelTracker::MayReach(reach0, speed0, reach1, speed1, t1 - t_,
                                                       max_travel[0]);
          reach0 = reach1;
          speed0 = speed1;
        } else {
          for (int d = 0; d < decks && !rare; ++d) {
            rare = travel_.MayReach(d, x0, x0 + n_, x1, x1 + n_, t1 - t_, max_travel[d]);
          }
        }
        rare = rare ||
               (outputs && next_output_t_ <= t1 + policy_.output_time_band * std::max(1.0, t1));
        if (rare) {
          FinishFreeStep(piece, step, true, false, 0.0, 0.0);
          common = false;
        } else {
          double* z = z_.data();
          if (n_ == 3) {
            for (int i = 0; i < 6; ++i) z[i] = x1[i];  // a deck's six moves, no call
          } else {
            std::copy(x1, x1 + 2 * n_, z);
          }
          t_ = t1;
          gaps_exact_ = false;
        }
      }
    } else {
      FreeStepOf(piece, step);
    }
    // Run's work after a free step: the observer, then (for a step of this loop) the finite
    // check, the run's end and the next step's count.
    if (observe && !Failed() && log_.events.empty() && !AnyClosed() &&
        !observer_->Step(t0, observed_z0_, h0, t_, z_.head(2 * n_), result_)) {
      return false;
    }
    if (!common) {
      return true;
    }
    if ((steps & check_mask) == 0) {
      if (!StateFinite(z_) || !std::isfinite(t_)) {
        return true;  // Run's check stops the run
      }
      t_finite = t_;
    }
    if (!(t_ < t_end_) || steps >= control_.max_steps) {
      return true;  // Run ends the run, or counts the step and stops at the limit
    }
    ++steps;
  }
}

}  // namespace skewbridge::dynamics
