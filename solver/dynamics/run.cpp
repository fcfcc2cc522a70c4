#include "solver/dynamics/run.h"

#include "solver/common/error.h"
#include "solver/dynamics/time_stepping.h"

namespace skewbridge::dynamics {
namespace {

// A sweep runs thousands of models of one shape on a thread: the thread's workspace is
// refitted to each (RunReuse) instead of built and freed with its hundred-odd heap blocks.
RunReuse& ThreadRunReuse() {
  thread_local RunReuse reuse;
  return reuse;
}

}  // namespace

RunResult Run(const model::Model& model, const Excitation& excitation,
              const model::RunControl& control, const RunPolicies& policies,
              const InitialState& initial) {
  switch (control.method) {
    case model::Method::kTimeStepping: {
      if (initial.t_s != 0.0) {
        throw InputError::AtField("initial state", "t_s",
                                  "the time-stepping method starts at t = 0 (event-driven only)");
      }
      TimeSteppingWorkspace workspace(model);
      return SimulateTimeStepping(model, excitation, control, workspace, initial,
                                  policies.time_stepping);
    }
    case model::Method::kEventDriven:
      break;
  }
  return ThreadRunReuse().Run(model, excitation, control, policies, initial);
}

RunResult Run(model::Model&& model, const Excitation& excitation, const model::RunControl& control,
              const RunPolicies& policies, const InitialState& initial) {
  if (control.method != model::Method::kEventDriven) {
    return Run(static_cast<const model::Model&>(model), excitation, control, policies, initial);
  }
  return ThreadRunReuse().Run(std::move(model), excitation, control, policies, initial);
}

void RecycleResult(RunResult&& result) { ThreadRunReuse().Recycle(std::move(result)); }

template <class ModelArg>
SimulationWorkspace& RunReuse::FitFrom(ModelArg&& model) {
  if (model_ && workspace_ && workspace_->SameShape(model)) {
    // The same sizes: a copy keeps the model's storage, a move takes the argument's.
    *model_ = std::forward<ModelArg>(model);
    workspace_->Refit();
  } else {
    workspace_.reset();  // it refers to model_
    model_.emplace(std::forward<ModelArg>(model));
    workspace_ = std::make_unique<SimulationWorkspace>(*model_);
  }
  return *workspace_;
}

SimulationWorkspace& RunReuse::Fit(const model::Model& model) { return FitFrom(model); }

SimulationWorkspace& RunReuse::Fit(model::Model&& model) { return FitFrom(std::move(model)); }

template <class ModelArg>
RunResult RunReuse::RunFrom(ModelArg&& model, const Excitation& excitation,
                            const model::RunControl& control, const RunPolicies& policies,
                            const InitialState& initial) {
  if (busy_) {  // a run inside a run (none today): a workspace of its own
    SimulationWorkspace workspace(model);
    return Simulate(model, excitation, control, workspace, initial, policies.event);
  }
  busy_ = true;
  struct Release {
    bool& busy;
    ~Release() { busy = false; }
  } release{busy_};
  SimulationWorkspace& workspace = FitFrom(std::forward<ModelArg>(model));
  return Simulate(*model_, excitation, control, workspace, initial, policies.event);
}

RunResult RunReuse::Run(const model::Model& model, const Excitation& excitation,
                        const model::RunControl& control, const RunPolicies& policies,
                        const InitialState& initial) {
  return RunFrom(model, excitation, control, policies, initial);
}

RunResult RunReuse::Run(model::Model&& model, const Excitation& excitation,
                        const model::RunControl& control, const RunPolicies& policies,
                        const InitialState& initial) {
  return RunFrom(std::move(model), excitation, control, policies, initial);
}

}  // namespace skewbridge::dynamics
