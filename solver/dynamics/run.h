#pragma once
/// @file
/// One way to run a model: the method of RunControl::method picks the integrator, each run has a
/// workspace of its own. `skewbridge run`, every sweep family and the spectra's points call it;
/// the integrators' own entries (Simulate, SimulateTimeStepping) remain for callers that reuse a
/// workspace over many runs or study another policy.

#include "solver/common/excitation.h"
#include "solver/dynamics/run_policies.h"
#include "solver/dynamics/run_result.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/model.h"
#include "solver/model/run_control.h"

namespace skewbridge::dynamics {

/// One run of `model` under `excitation` from `initial`: the event-driven integrator (Simulate
/// with policies.event) or Moreau-Jean (SimulateTimeStepping with control.time_step_s, theta =
/// 1/2, policies.time_stepping) by control.method, with a workspace built for this run.
/// @throws InputError as the integrator it calls (a policy member outside its range too).
RunResult Run(const model::Model& model, const Excitation& excitation,
              const model::RunControl& control, const RunPolicies& policies = {},
              const InitialState& initial = {});

}  // namespace skewbridge::dynamics
