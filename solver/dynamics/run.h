#pragma once
/// @file
/// One way to run a model: the method of RunControl::method picks the integrator; the
/// event-driven runs of a thread reuse one workspace (RunReuse), whose results are those of a
/// new one. `skewbridge run`, every sweep family and the spectra's points call it;
/// the integrators' own entries (Simulate, SimulateTimeStepping) remain for callers that reuse a
/// workspace over many runs or study another policy.

#include <memory>
#include <optional>

#include "solver/common/excitation.h"
#include "solver/dynamics/run_policies.h"
#include "solver/dynamics/run_result.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/model.h"
#include "solver/model/run_control.h"

namespace skewbridge::dynamics {

/// Event-driven runs of one model after another in one workspace: a model of the shape of the
/// last (SimulationWorkspace::SameShape) is copied into the storage the workspace refers to and
/// the workspace refitted (SimulationWorkspace::Refit), another shape gets a new workspace. The
/// results are the bits of a run in a new workspace. One thread's.
class RunReuse {
 public:
  /// Simulate of `model` with policies.event, in the reused workspace.
  /// @throws InputError as Simulate.
  RunResult Run(const model::Model& model, const Excitation& excitation,
                const model::RunControl& control, const RunPolicies& policies = {},
                const InitialState& initial = {});

  /// Run with `model` moved into the workspace's storage instead of copied: the same results.
  RunResult Run(model::Model&& model, const Excitation& excitation,
                const model::RunControl& control, const RunPolicies& policies = {},
                const InitialState& initial = {});

  /// The workspace fitted to a copy of `model` (model() afterwards), for a caller's own Simulate.
  SimulationWorkspace& Fit(const model::Model& model);
  /// Fit with `model` moved in: its values, without copying its matrices.
  SimulationWorkspace& Fit(model::Model&& model);
  /// The copy of the model the workspace refers to. @pre Fit was called.
  const model::Model& model() const { return *model_; }
  /// Gives a finished result's storage to the next run (SimulationWorkspace::Recycle); dropped
  /// before the first Fit.
  void Recycle(RunResult&& result) {
    if (workspace_) workspace_->Recycle(std::move(result));
  }

 private:
  // Fit's work for a model given by const reference (copied) or by rvalue (moved).
  template <class ModelArg>
  SimulationWorkspace& FitFrom(ModelArg&& model);
  // Simulate of model() in the fitted workspace, or of `model` in one of its own when a run is
  // under way.
  template <class ModelArg>
  RunResult RunFrom(ModelArg&& model, const Excitation& excitation,
                    const model::RunControl& control, const RunPolicies& policies,
                    const InitialState& initial);

  std::optional<model::Model> model_;
  std::unique_ptr<SimulationWorkspace> workspace_;
  bool busy_ = false;  // a Run is under way
};

/// One run of `model` under `excitation` from `initial`: the event-driven integrator (Simulate
/// with policies.event) or Moreau-Jean (SimulateTimeStepping with control.time_step_s, theta =
/// 1/2, policies.time_stepping) by control.method. The event-driven runs of a thread share one
/// RunReuse; Moreau-Jean has a workspace built for each run.
/// @throws InputError as the integrator it calls (a policy member outside its range too).
RunResult Run(const model::Model& model, const Excitation& excitation,
              const model::RunControl& control, const RunPolicies& policies = {},
              const InitialState& initial = {});

/// Run with `model` moved into the thread's reused workspace (event-driven) instead of copied:
/// the same results. A caller that needs the model no longer (a sweep's cell) passes it so.
RunResult Run(model::Model&& model, const Excitation& excitation, const model::RunControl& control,
              const RunPolicies& policies = {}, const InitialState& initial = {});

/// Gives a result of Run that the caller has read to the thread's next event-driven run, whose
/// result then takes its vectors' storage instead of allocating it (RunReuse::Recycle).
void RecycleResult(RunResult&& result);

}  // namespace skewbridge::dynamics
