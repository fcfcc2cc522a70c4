#pragma once
/// @file
/// The stripes of one record: the runs of one model under one record at several factors on its
/// accelerations (the stripes of a fragility study), sharing their contact-free response
/// [docs/theory.md §3, smooth phases]. Until a gap closes, the response is linear in the factor,
/// so one run of the linear flow serves every stripe: a stripe whose scaled response reaches no
/// gap takes its maxima, corner travels and end state from it, and a stripe that reaches one goes
/// on with the event-driven integrator from the scaled state at the start of the first free step
/// in which a gap may close. The results agree with each stripe's own run up to the rounding of
/// the scaled state (the samples of a record times a factor are rounded once, the scaled response
/// once); the steps, the events and the status are the run's own.

#include <span>
#include <vector>

#include "solver/common/excitation.h"
#include "solver/dynamics/run_policies.h"
#include "solver/dynamics/run_result.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/model.h"
#include "solver/model/run_control.h"

namespace skewbridge::dynamics {

/// The factor on a record's accelerations of the run that traces the contact-free response: a
/// power of two, so that the record's samples and every operation of the linear flow scale
/// exactly, and small enough that no gap of a bridge closes (2^-40, about 1e-12).
inline constexpr double kStripeTraceFactor = 0x1p-40;

/// Where one stripe's run stands after its contact-free response.
struct StripeStart {
  double factor = 1.0;       ///< the stripe's factor on the record's accelerations
  bool reaches_gap = false;  ///< a gap may close: the event-driven run goes on from `state`
  /// The scaled state at the start of the first free step in which a gap may close, with its
  /// time, step count and nominal step (InitialState::t_s = 0: the run from rest).
  InitialState state;
  /// The stripe's run over [0, state.t_s] (reaches_gap), or its whole run: maxima of |q_i|,
  /// corner travels, end state, free steps; no event.
  RunResult linear;
};

/// The contact-free response of `model` under `trace_excitation`, the record at factor
/// `trace_factor` (kStripeTraceFactor), scaled to each of `factors`: for each, where the
/// event-driven run of the record at that factor must go on, or the whole run when no gap may
/// close. A gap may close in a free step when its smaller end value is within the step's reach,
/// dip_margin |gamma_N|max tau / 2 plus 1e-9 of the model's length: a superset of the steps the
/// integrator searches (ImpactSuspected), so that a stripe restarts before its first impact.
/// control.method must be event-driven; with histories or the energy ledger in `control`, each
/// stripe's `linear` holds its samples and work over [0, state.t_s] (or its whole run).
std::vector<StripeStart> TraceStripes(const model::Model& model, const Excitation& trace_excitation,
                                      double trace_factor, const model::RunControl& control,
                                      const RunPolicies& policies, std::span<const double> factors);

/// The run of one stripe: `excitation` is the record at start.factor. A stripe that reaches no
/// gap is its contact-free response; one that does is the event-driven run from start.state, its
/// maxima and travels over [0, t_s] those of the response, its work of the ledger and history
/// samples those of the response before its own.
RunResult RunStripe(const model::Model& model, const Excitation& excitation,
                    const model::RunControl& control, const RunPolicies& policies,
                    const StripeStart& start);

/// The event-driven run of a record at `factor` on its accelerations as a stripe of that record
/// runs (TraceStripes with that one factor, then RunStripe): `excitation` is the record at
/// `factor`, `trace_excitation` the same record at kStripeTraceFactor, built alike. A sweep's cell
/// and `skewbridge run` of a record take this path so that they give the same bits.
RunResult RunScaledRecord(const model::Model& model, const Excitation& excitation,
                          const Excitation& trace_excitation, double factor,
                          const model::RunControl& control, const RunPolicies& policies);

}  // namespace skewbridge::dynamics
