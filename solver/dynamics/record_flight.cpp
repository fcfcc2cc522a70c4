#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include "solver/dynamics/coordinate_maxima.h"
#include "solver/dynamics/integrator.h"
#include "solver/dynamics/run_result.h"

namespace skewbridge::dynamics {

namespace {
// The deferred steps DeckRecordSteps keeps before it resolves them inside the loop (a bound on
// the storage; where they are resolved does not change the maxima).
constexpr std::size_t kMaxDeferredSteps = 4096;
}  // namespace

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
  bool outputs = next_output_t_ <= output_reach;
  // One deck's corner-reach terms at the step's start (CornerTravelTracker::EndReach).
  double reach0 = 0.0, speed0 = 0.0;
  if (decks == 1) {
    travel_.EndReach(0, z_.data(), z_.data() + n_, reach0, speed0);
  }
  // A deck's steps on a record's ramps go through DeckRecordSteps, the rest through this loop.
  const bool deck =
      !observe && n_ == 3 && decks == 1 && samples.count > 0 && ws_.gap_bound_.n_modes == 3;
  DeckFlight deck_flight;
  if (deck) {
    deck_flight.reach = travel_.reach_constants(0);
    // FreeStepOfLength's one-step case without its division: its quotient length / h_max rounds
    // monotonically in the length, so every length in [one_step_min, one_step_max] whose ends'
    // quotients lie in (0, 1] has its quotient there too, and the step is the length itself.
    const double h_max = FreeStepMax(0.0, ws_.omega_max_radps_, policy_);  // a ramp's (omega 0)
    deck_flight.h_max_s = h_max;
    deck_flight.one_step_min_s = h_max * 0x1p-500;
    deck_flight.one_step_max_s = h_max;
    if (!(deck_flight.one_step_min_s / h_max > 0.0 && deck_flight.one_step_max_s / h_max <= 1.0)) {
      deck_flight.one_step_min_s = std::numeric_limits<double>::infinity();  // always divide
    }
  }
  // The last plan's grid index k (NaN before the first): the next step on the same grid has k + 1.
  double grid_k = std::numeric_limits<double>::quiet_NaN();
  // Run's work after a step: the finite check, the run's end and the step limit; true when the
  // run goes on (the next step counted), false when Run would stop it.
  const auto goes_on = [&]() {
    if ((steps & check_mask) == 0) {
      if (!StateFinite(z_) || !std::isfinite(t_)) {
        return false;  // Run's check stops the run
      }
      t_finite = t_;
    }
    if (!(t_ < t_end_) || steps >= control_.max_steps) {
      return false;  // Run ends the run, or counts the step and stops at the limit
    }
    ++steps;
    return true;
  };
  for (;;) {
    if (deck && (samples.ay_mps2 != nullptr
                     ? DeckRecordStepsXY(steps, t_finite, samples, deck_flight, reach0, speed0)
                     : DeckRecordStepsX(steps, t_finite, samples, deck_flight, reach0, speed0))) {
      // After the step that ended it, while no contact closed, the next step is this loop's:
      // Run would come back.
      if (Failed() || AnyClosed() || !goes_on()) {
        ResolveDeferredPeaks(result_.max_abs_q.data(), result_.time_of_max_s.data(),
                             result_.max_travel_m[0]);
        return true;
      }
      travel_.EndReach(0, z_.data(), z_.data() + n_, reach0, speed0);
      outputs = next_output_t_ <= output_reach;
      continue;
    }
    if (deck) {
      // The step below is this loop's: its scan reads the in-order maxima.
      ResolveDeferredPeaks(result_.max_abs_q.data(), result_.time_of_max_s.data(),
                           result_.max_travel_m[0]);
    }
    // FreeStep's plan, the same operations.
    const double t0 = t_, h0 = h_free_;
    if (observe) {
      observed_z0_ = z_.head(2 * n_);
    }
    const ExcitationPiece& piece = pieces_.At(excitation_, samples, t_);
    SB_DEMAND(piece.t_end > t_, "Excitation::PieceAt(t) returned a piece that ends at or before t");
    const FreeStepPlan step =
        PlanFreeStepExpecting(t_, piece.t_begin, std::min(piece.t_end, t_end_),
                              NominalFreeStep(piece), h_free_, policy_, grid_k + 1.0, grid_k);
    h_free_ = step.h_s;
    // A full step is FreeStepOf's (no ledger here), its finish FinishFreeStep's unless the tests
    // below show that it would only raise the maxima at the step's end.
    bool common = step.full;
    if (common) {
      // FreeStepOf's transition (on a piece without harmonic part without the generator's
      // columns: SetGenerator writes their zeros) and the gap floors' check.
      const double tau = step.t_next_s - t_;
      const bool harmonic = piece.omega != 0.0;
      flow.SetGenerator(piece, t_, z_);
      if (harmonic) {
        flow.ApplyStepMotion(StepPropagator(step.h_s, piece.omega, false), z_, z_new_);
      } else {
        flow.ApplyRecordMotion(StepPropagator(step.h_s, 0.0, false), z_, z_new_);
      }
      ++result_.free_steps;
      if (gaps_exact_) {
        gap_floors_.Restart(ends_.gap0);
      }
      // GapsStayOpen (the bound applies in this loop) with the flight's margin and coordinates.
      const bool open =
          gap_floors_.StaysOpen(modal_y, std::max(tau, step.h_s), gap_margin, harmonic);
      bool suspected = false;
      if (!open) {
        // FinishFreeStep's gaps and rates at the step's ends, then FirstImpact's suspicion test
        // of each open contact: where it holds for none, the step has no event, and what is left
        // of FinishFreeStep is what a step the bound proved open does, the ends' gaps kept.
        if (!gaps_exact_) {
          GapsAndRates(q(), u(), ends_.gap0, ends_.gN0);
        }
        GapsAndRates(z_new_.head(n_), z_new_.segment(n_, n_), ends_.gap1, ends_.gN1);
        for (int c = 0; c < nc_ && !suspected; ++c) {
          suspected = Suspected(c, step.t_next_s - t_, policy_.dip_margin);
        }
      }
      if (suspected) {
        FinishFreeStep(piece, step, false, false, 0.0, 0.0);
        common = false;
      } else {
        // RecordStep's tests that need no dense output: a step that passes them all raises the
        // maxima at its end only (a deck's corners there are ScanEnd's), searches no root and
        // records no history sample.
        const double t1 = step.t_next_s;
        const double* x0 = z_.data();
        const double* x1 = z_new_.data();
        // A deck's three coordinates unrolled.
        bool rare =
            n_ == 3
                ? RaiseMaximaAtEnd(3, x0, x0 + 3, t1, x1, x1 + 3, t1 - t_, max_q, time_of_max)
                : RaiseMaximaAtEnd(n_, x0, x0 + n_, t1, x1, x1 + n_, t1 - t_, max_q, time_of_max);
        rare = rare ||
               (outputs && next_output_t_ <= t1 + policy_.output_time_band * std::max(1.0, t1));
        if (decks == 1) {
          // One deck: the start's terms are the last step's end's.
          double reach1, speed1;
          travel_.EndReach(0, x1, x1 + n_, reach1, speed1);
          if (!rare && CornerTravelTracker::MayReach(reach0, speed0, reach1, speed1, t1 - t_,
                                                     max_travel[0])) {
            // A deck's corners reach the maximum: Scan's work at the step's end (ScanEnd, the
            // same evaluations and raise). A step none of whose corners Scan would then search
            // is done; otherwise the maximum is put back and FinishFreeStep scans the step.
            rare = true;
            if (n_ == 3) {
              const double best = max_travel[0];
              double bound[4];
              const std::array<double, 6> s0{x0[0], x0[1], x0[2], x0[3], x0[4], x0[5]};
              const std::array<double, 6> s1{x1[0], x1[1], x1[2], x1[3], x1[4], x1[5]};
              rare = travel_.ScanEnd(0, s0, s1, t1 - t_, max_travel[0], bound) != 0;
              if (rare) {
                max_travel[0] = best;
              }
            }
          }
          reach0 = reach1;
          speed0 = speed1;
        } else {
          for (int d = 0; d < decks && !rare; ++d) {
            rare = travel_.MayReach(d, x0, x0 + n_, x1, x1 + n_, t1 - t_, max_travel[d]);
          }
        }
        if (rare) {
          FinishFreeStep(piece, step, open, false, 0.0, 0.0);
          common = false;
        } else {
          double* z = z_.data();
          if (n_ == 3) {
            for (int i = 0; i < 6; ++i) z[i] = x1[i];  // a deck's six moves, no call
          } else {
            std::copy(x1, x1 + 2 * n_, z);
          }
          t_ = t1;
          if (open) {
            gaps_exact_ = false;
          } else {
            ends_.gap0 = ends_.gap1;
            ends_.gN0 = ends_.gN1;
            gaps_exact_ = true;
          }
        }
      }
    } else {
      FreeStepOf(piece, step);
    }
    // Run's work after a free step: the observer, then the rest (goes_on).
    if (observe && !Failed() && log_.events.empty() && !AnyClosed() &&
        !observer_->Step(t0, observed_z0_, h0, t_, z_.head(2 * n_), result_)) {
      return false;
    }
    if (!common) {
      if (observe || Failed() || AnyClosed()) {
        return true;  // Run takes the next step
      }
      // Run would come back to this loop: the step's start terms, as at the loop's entry.
      if (decks == 1) {
        travel_.EndReach(0, z_.data(), z_.data() + n_, reach0, speed0);
      }
      outputs = next_output_t_ <= output_reach;
    }
    if (!goes_on()) {
      return true;
    }
  }
}

template <bool kHasY>
[[gnu::always_inline]] inline bool Integrator::DeckRecordSteps(long& steps_io, double& t_finite,
                                                               const SampleView& samples,
                                                               const DeckFlight& flight,
                                                               double& reach0_io,
                                                               double& speed0_io) {
  using detail::Lanes2;
  ExcitationPiece& piece = pieces_.last();
  if (!(piece.omega == 0.0)) {
    return false;  // the ramps' harmonic part is RecordFlight's (NextSampledPiece keeps it)
  }
  LinearFlow& flow = ws_.flow_;
  const detail::DeckLanes& lanes = flow.deck_lanes();
  const ModalGapBound& bound = ws_.gap_bound_;
  const long check_mask = policy_.finite_check_steps - 1;
  const double gap_margin = 2.0 * scales_.gap_tol_m;
  const bool outputs = next_output_t_ <= t_end_ + policy_.output_time_band;
  const double h_max = flight.h_max_s;
  const double one_step_min = flight.one_step_min_s, one_step_max = flight.one_step_max_s;
  const long max_steps = control_.max_steps;
  const double t_end = t_end_;
  const double dt = samples.dt_s;
  const double* ax = samples.ax_mps2;
  const double* ay = samples.ay_mps2;
  // The piece, the state ((q_i, u_i) side by side) and its generator, the plan's cache, the
  // propagator's key, the maxima and the counts.
  long index = piece.index;
  double tb = piece.t_begin, te = piece.t_end;
  double ax0 = piece.a_begin[0], ay0 = piece.a_begin[1], sx = piece.slope[0], sy = piece.slope[1];
  double t = t_, h_last = h_free_;
  bool gaps_exact = gaps_exact_;  // the gaps at t are exact (the last step's), not carried
  double nominal_length = nominal_length_s_, nominal_omega = nominal_omega_radps_;
  double nominal_h = nominal_h_s_;
  Lanes2 x[3] = {{z_[0], z_[3]}, {z_[1], z_[4]}, {z_[2], z_[5]}};
  // The generator SetGenerator gave the last step, (a, slope) of x and of y.
  Lanes2 gx = {0.0, 0.0}, gy = {0.0, 0.0};
  bool generated = false;  // whether a step set gx and gy (z_'s generator is then theirs, +0)
  double max_q[3], time_of_max[3];
  for (int i = 0; i < 3; ++i) {
    max_q[i] = result_.max_abs_q[i];
    time_of_max[i] = result_.time_of_max_s[i];
  }
  double max_travel = result_.max_travel_m[0];
  long steps = steps_io, free_steps = result_.free_steps;
  GapFloors::DeckSums floors = gap_floors_.Deck();
  // The corners' reach terms (reach, speed) at the step's start, and the deck's constants.
  Lanes2 reach0 = {reach0_io, speed0_io};
  const CornerTravelTracker::ReachConstants reach_constants = flight.reach;
  // StepPropagator's key of propagator_ (NaN: none, or not a ramp's).
  const FreePropagator* p = propagator_;
  double p_tau =
      p != nullptr && p->omega_radps == 0.0 ? p->tau_s : std::numeric_limits<double>::quiet_NaN();
  // The state and its generator into z_.
  const auto state_back = [&]() __attribute__((always_inline)) {
    for (int i = 0; i < 3; ++i) {
      z_[i] = x[i][0];
      z_[3 + i] = x[i][1];
    }
    if (generated) {
      z_[6] = gx[0];
      z_[7] = gy[0];
      z_[8] = gx[1];
      z_[9] = gy[1];
      for (int i = 10; i < 14; ++i) z_[i] = 0.0;
    }
  };
  // Everything into the members, as RecordFlight's steps would have left them.
  const auto write_back = [&]() __attribute__((always_inline)) {
    state_back();
    gaps_exact_ = gaps_exact;
    t_ = t;
    h_free_ = h_last;
    nominal_length_s_ = nominal_length;
    nominal_omega_radps_ = nominal_omega;
    nominal_h_s_ = nominal_h;
    piece.t_begin = tb;
    piece.t_end = te;
    piece.a_begin = Eigen::Vector2d(ax0, ay0);
    piece.slope = Eigen::Vector2d(sx, sy);
    piece.index = index;
    for (int i = 0; i < 3; ++i) {
      result_.max_abs_q[i] = max_q[i];
      result_.time_of_max_s[i] = time_of_max[i];
    }
    result_.max_travel_m[0] = max_travel;
    result_.free_steps = free_steps;
    steps_io = steps;
    reach0_io = reach0[0];
    speed0_io = reach0[1];
    gap_floors_.Store(floors);
  };
  // How the loop ends: the next step is RecordFlight's, the flight ends, or the step is
  // finished by FreeStepOf or by FinishFreeStep (gaps not proved open, or open).
  enum class Exit { kOther, kEnded, kPartial, kClosing, kRare };
  Exit exit = Exit::kOther;
  FreeStepPlan step;  // the step the loop leaves in (kPartial, kClosing, kRare)
  // The ramps' planner, reset for the first ramp and whenever the nominal step changes; the
  // length it was last reset for (NaN: none yet).
  RampStepPlanner planner(policy_);
  double nominal_key = std::numeric_limits<double>::quiet_NaN();
  const std::size_t count = samples.count;
  // The steps whose velocity-root searches wait for the loop's end (empty between loops).
  std::vector<DeferredPeakStep>& deferred_steps = ws_.run_storage_.deferred_peaks.steps;
  Lanes2 next[3] = {};  // the last step's end (q_i, u_i): zeros until a step
  // The y generator's products in the modal inputs (DeckYForcing): per step with y samples, once
  // without (its generator the constant +0).
  Lanes2 ab_y[3];
  if constexpr (!kHasY) {
    detail::DeckYForcing(lanes, Lanes2{0.0, 0.0}, ab_y);
  }
  // NextSampledPiece's tests of the piece's number and end: a ramp this loop reads ends at
  // (k + 1) dt of its own k, the next ramp's start, so they hold for every later ramp.
  if (index < 0 || te != static_cast<double>(index + 1) * dt) {
    write_back();
    return false;
  }
  // The next ramp's k + 1 as a double: k + 1 < 2^53, so adding 1 is exact and the conversion's
  // value.
  double end_samples = static_cast<double>(static_cast<std::size_t>(index) + 2);
  for (;;) {
    // The record's next ramp (PieceCursor::At, NextSampledPiece's operations); any other piece
    // is RecordFlight's.
    const std::size_t k = static_cast<std::size_t>(index) + 1;
    if (!(t == te) || k + 1 >= count) {
      break;
    }
    double y0 = 0.0, y1 = 0.0;
    if constexpr (kHasY) {
      y0 = ay[k];
      y1 = ay[k + 1];
    }
    tb = te;
    te = end_samples * dt;
    end_samples += 1.0;
    ax0 = ax[k];
    ay0 = y0;
    sx = (ax[k + 1] - ax[k]) / dt;
    sy = kHasY ? (y1 - y0) / dt : 0.0;  // without y: (0 - 0) / dt = +0 (dt > 0)
    index = static_cast<long>(k);
    SB_DEMAND(te > t, "Excitation::PieceAt(t) returned a piece that ends at or before t");
    // NominalFreeStep (a finite piece of rate 0) and the plan (PlanFreeStep at the ramp's start,
    // t == tb); the plan's length and StepPropagator's propagator change only with the nominal
    // step, h_last being the planner's own length after the first step (RampStepPlanner).
    const double length = te - tb;
    if (!(length == nominal_key)) {
      if (!(length == nominal_length && 0.0 == nominal_omega)) {
        nominal_h = length >= one_step_min && length <= one_step_max
                        ? length
                        : FreeStepOfLength(length, h_max);
        nominal_length = length;
        nominal_omega = 0.0;
      }
      nominal_key = length;
      const double h = planner.Reset(nominal_h, h_last);
      if (h != p_tau) {
        p = &StepPropagator(h, 0.0, false);
        p_tau = p->tau_s;
      }
    }
    const FreeStepPlan plan = planner.At(t, tb, std::min(te, t_end));
    h_last = plan.h_s;
    if (!plan.full) {
      step = plan;
      exit = Exit::kPartial;
      break;
    }
    // SetGenerator's generator and ApplyRecordMotion's operations on the registers (the modal
    // coordinates' zeros of either sign: DeckStepLanes).
    // At the ramp's start t == tb, so tau_start = t - tb = +0 (equal finite doubles).
    constexpr double tau_start = 0.0;
    gx = Lanes2{ax0 + sx * tau_start, sx};
    // Without y: +0 + (+0) tau_start = +0, a constant of the loop.
    gy = kHasY ? Lanes2{ay0 + sy * tau_start, sy} : Lanes2{0.0, 0.0};
    generated = true;
    if constexpr (kHasY) {
      detail::DeckYForcing(lanes, gy, ab_y);
    }
    Lanes2 qu[3], ab[3];
    detail::DeckStepLanes(lanes, p->record_pairs.data(), x, gx, ab_y, qu, ab, next);
    ++free_steps;
    if (gaps_exact) {
      gap_floors_.Restart(ends_.gap0);
      floors = gap_floors_.Deck();
    }
    // The gap floors' check (GapsStayOpen) with the drifts from the modal coordinates' lanes.
    const double tau = plan.t_next_s - t;
    double drift[3];
    ModalDrift3Lanes(bound, __builtin_shufflevector(qu[0], qu[1], 0, 2),
                     __builtin_shufflevector(qu[0], qu[1], 1, 3),
                     __builtin_shufflevector(ab[0], ab[1], 0, 2),
                     __builtin_shufflevector(ab[0], ab[1], 1, 3), qu[2][0], qu[2][1], ab[2][0],
                     ab[2][1], std::max(tau, plan.h_s), drift);
    if (!gap_floors_.DeckStaysOpen(floors, drift, gap_margin)) {
      step = plan;
      exit = Exit::kClosing;
      break;
    }
    // RecordFlight's tests that need no dense output. The coordinates whose velocity root and
    // the corners whose rate's root the in-order scan might search are deferred
    // (ResolveDeferredPeaks), not a reason to leave.
    const double t1 = plan.t_next_s;
    double peak_bound[3];
    const int deferred = RaiseMaximaAtEnd3Each(x, next, t1, t1 - t, max_q, time_of_max, peak_bound);
    const bool rare =
        outputs && next_output_t_ <= t1 + policy_.output_time_band * std::max(1.0, t1);
    const Lanes2 reach1 = CornerTravelTracker::EndReach(reach_constants, next);
    int corners = 0;
    double corner_bound[4];
    if (CornerTravelTracker::MayReach(reach0, reach1, t1 - t, max_travel)) {
      // The corners at the step's end (Scan's bits), their roots deferred.
      const std::array<double, 6> s0 = {x[0][0], x[1][0], x[2][0], x[0][1], x[1][1], x[2][1]};
      const std::array<double, 6> s1 = {next[0][0], next[1][0], next[2][0],
                                        next[0][1], next[1][1], next[2][1]};
      corners = travel_.ScanEnd(0, s0, s1, t1 - t, max_travel, corner_bound);
    }
    reach0 = reach1;
    if ((deferred | corners) != 0) [[unlikely]] {
      DeferredPeakStep& d = deferred_steps.emplace_back();
      d.t0_s = t;
      d.t1_s = t1;
      d.h_s = plan.h_s;
      for (int i = 0; i < 3; ++i) {
        d.x0[i] = x[i];
        d.x1[i] = next[i];
        d.end_max[i] = max_q[i];
        d.end_time_s[i] = time_of_max[i];
      }
      d.gx = gx;
      d.gy = gy;
      d.coordinates = deferred;
      d.end_travel_m = max_travel;
      d.corners = corners;
      // The bounds as written (only those of deferred coordinates and corners are, and read).
      std::memcpy(d.bound, peak_bound, sizeof peak_bound);
      std::memcpy(d.corner_bound, corner_bound, sizeof corner_bound);
      if (deferred_steps.size() >= kMaxDeferredSteps) {
        ResolveDeferredPeaks(max_q, time_of_max, max_travel);
      }
    }
    if (rare) {
      step = plan;
      exit = Exit::kRare;
      break;  // the step's history samples are FinishFreeStep's, its roots deferred above
    }
    for (int i = 0; i < 3; ++i) x[i] = next[i];
    t = t1;
    gaps_exact = false;
    // Run's work after the step.
    if ((steps & check_mask) == 0) {
      state_back();
      if (!StateFinite(z_) || !std::isfinite(t)) {
        exit = Exit::kEnded;  // Run's check stops the run
        break;
      }
      t_finite = t;
    }
    // Run ends the run, or counts the step and stops at the limit: two tests, each a branch.
    if (!(t < t_end)) [[unlikely]] {
      exit = Exit::kEnded;
      break;
    }
    if (steps >= max_steps) [[unlikely]] {
      exit = Exit::kEnded;
      break;
    }
    ++steps;
  }
  // The deferred roots are folded in before a step whose scan reads the maxima: a partial step
  // and one whose gaps may close (the run's end and a step on another piece: RecordFlight). A
  // step that left for a history sample was scanned here (its end raised, its roots deferred)
  // and keeps them deferred.
  if (exit == Exit::kPartial || exit == Exit::kClosing) {
    ResolveDeferredPeaks(max_q, time_of_max, max_travel);
  }
  write_back();
  switch (exit) {
    case Exit::kOther:
      return false;
    case Exit::kEnded:
      return true;
    case Exit::kPartial:
      FreeStepOf(piece, step);
      return true;
    case Exit::kClosing:
    case Exit::kRare:
      // The flow's modal coordinates (the modal transform of the step's start taken again) and
      // z_new_ as the step's transition would leave them.
      flow.StoreDeckRecord(x, gx, gy, next, z_new_);
      if (exit == Exit::kClosing) {
        FinishFreeStep(piece, step, false, false, 0.0, 0.0);
      } else {
        // The coordinates' maxima and the travel's hold +inf while FinishFreeStep records the
        // step, so that its scans, done above, raise and search nothing (every comparison with
        // +inf is false, the corners' reach test fails); the ends' fold is theirs again after.
        constexpr double kInf = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 3; ++i) result_.max_abs_q[i] = kInf;
        result_.max_travel_m[0] = kInf;
        FinishFreeStep(piece, step, true, false, 0.0, 0.0);
        for (int i = 0; i < 3; ++i) result_.max_abs_q[i] = max_q[i];
        result_.max_travel_m[0] = max_travel;
      }
      return true;
  }
  return true;
}

__attribute__((target_clones("avx", "default"))) bool Integrator::DeckRecordStepsX(
    long& steps, double& t_finite, const SampleView& samples, const DeckFlight& flight,
    double& reach0, double& speed0) {
  return DeckRecordSteps<false>(steps, t_finite, samples, flight, reach0, speed0);
}

__attribute__((target_clones("avx", "default"))) bool Integrator::DeckRecordStepsXY(
    long& steps, double& t_finite, const SampleView& samples, const DeckFlight& flight,
    double& reach0, double& speed0) {
  return DeckRecordSteps<true>(steps, t_finite, samples, flight, reach0, speed0);
}

void Integrator::ResolveDeferredPeaks(double max_q[3], double time_of_max[3], double& max_travel) {
  DeferredPeaks& deferred = ws_.run_storage_.deferred_peaks;
  if (deferred.steps.empty()) {
    return;
  }
  const LinearFlow& flow = ws_.flow_;
  FreeDenseOutput& dense = ws_.free_dense_;
  // The armed step's modal coordinates (StoreDeckRecord's, the same bits as the step that
  // recorded it had in the flow), which step the bound and the dense output are of, and the
  // travel the bound's hull is compared with (FinishFreeStep's running maximum).
  double Y[18], z_next[6];
  double travel_best = max_travel;
  int armed = -1, built = -1;
  const auto arm = [&](int k) {
    if (armed != k) {
      const DeferredPeakStep& s = deferred.steps[static_cast<std::size_t>(k)];
      detail::Lanes2 qu[3], ab[3];
      detail::DeckModalLanes(flow.deck_lanes(), s.x0, s.gx, s.gy, qu, ab);
      detail::DeckRecordStore(qu, ab, s.x1, Y, z_next);
      peaks_.Arm(true, Y, std::max(s.t1_s - s.t0_s, s.h_s), 0.0, &travel_best);
      armed = k;
    }
  };
  // FinishFreeStep's dense output of step k, built from the step's start and generator as
  // state_back leaves them in z_.
  const auto build = [&](int k) {
    if (built != k) {
      const DeferredPeakStep& s = deferred.steps[static_cast<std::size_t>(k)];
      for (int j = 0; j < 3; ++j) {
        z_eval_[j] = s.x0[j][0];
        z_eval_[3 + j] = s.x0[j][1];
      }
      z_eval_[6] = s.gx[0];
      z_eval_[7] = s.gy[0];
      z_eval_[8] = s.gx[1];
      z_eval_[9] = s.gy[1];
      for (Eigen::Index j = 10; j < z_eval_.size(); ++j) z_eval_[j] = 0.0;
      dense.Build(flow, 0.0, z_eval_, s.t1_s - s.t0_s);
      built = k;
    }
  };
  for (int i = 0; i < 3; ++i) {
    // FinishFreeStep's peak bound and velocity root of coordinate i in step k.
    const auto below = [&](int k, double best) {
      arm(k);
      const DeferredPeakStep& s = deferred.steps[static_cast<std::size_t>(k)];
      return peaks_.PeakBelow(i, s.x0[i][0], s.x0[i][1], s.x1[i][0], s.x1[i][1], s.t1_s - s.t0_s,
                              best);
    };
    const auto search = [&](int k) {
      build(k);
      const DeferredPeakStep& s = deferred.steps[static_cast<std::size_t>(k)];
      const double t0 = s.t0_s;
      const auto velocity = [&](double t) { return dense.EvaluateComponent(t - t0, 3 + i); };
      const RootResult peak =
          FindRootBrent(velocity, t0, s.t1_s, s.x0[i][1], s.x1[i][1], MaximumTimeTolerance(s.t1_s));
      return std::pair<double, double>(std::abs(dense.EvaluateComponent(peak.x - t0, i)), peak.x);
    };
    ResolveDeferredMaxima(i, deferred.steps, deferred.scratch, max_q[i], time_of_max[i], search,
                          below);
  }
  // The corners: FinishFreeStep's travel bound (its hull against the maximum compared with) and
  // Scan's search of corner c's rate root in step k, from the corners at the step's ends.
  int cornered = -1;
  CornerTravelTracker::CornerState c0, c1;
  const auto corners_of = [&](int k) {
    if (cornered != k) {
      const DeferredPeakStep& s = deferred.steps[static_cast<std::size_t>(k)];
      c0 = travel_.Corners(
          0, {s.x0[0][0], s.x0[1][0], s.x0[2][0], s.x0[0][1], s.x0[1][1], s.x0[2][1]});
      c1 = travel_.Corners(
          0, {s.x1[0][0], s.x1[1][0], s.x1[2][0], s.x1[0][1], s.x1[1][1], s.x1[2][1]});
      cornered = k;
    }
  };
  const auto travel_below = [&](int k, int c, double best) {
    arm(k);
    corners_of(k);
    const DeferredPeakStep& s = deferred.steps[static_cast<std::size_t>(k)];
    travel_best = best;
    return travel_.TravelBelow(0, c, c0, c1, s.t1_s - s.t0_s, best, peaks_);
  };
  const auto travel_search = [&](int k, int c) {
    build(k);
    corners_of(k);
    const DeferredPeakStep& s = deferred.steps[static_cast<std::size_t>(k)];
    const double t0 = s.t0_s;
    const auto component_at = [&](double t, const auto& j, auto&... out) {
      if constexpr (sizeof...(out) == 0) {
        return dense.EvaluateComponent(t - t0, j);
      } else {
        dense.EvaluateComponents(t - t0, j, out...);
      }
    };
    return travel_.RootTravel(0, c, t0, s.t1_s, c0, c1, MaximumTimeTolerance(s.t1_s), component_at);
  };
  ResolveDeferredTravel(deferred.steps, deferred.scratch, max_travel, travel_search, travel_below);
  peaks_.Disarm();
  deferred.steps.clear();
}

}  // namespace skewbridge::dynamics
