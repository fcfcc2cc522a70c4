#include "solver/dynamics/run.h"

#include "solver/common/error.h"
#include "solver/dynamics/time_stepping.h"

namespace skewbridge::dynamics {

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
  // A sweep runs thousands of models of one shape on a thread: the thread's workspace is
  // refitted to each (RunReuse) instead of built and freed with its hundred-odd heap blocks.
  thread_local RunReuse reuse;
  return reuse.Run(model, excitation, control, policies, initial);
}

SimulationWorkspace& RunReuse::Fit(const model::Model& model) {
  if (model_ && workspace_ && workspace_->SameShape(model)) {
    *model_ = model;  // the same sizes: the model's storage is kept
    workspace_->Refit();
  } else {
    workspace_.reset();  // it refers to model_
    model_.emplace(model);
    workspace_ = std::make_unique<SimulationWorkspace>(*model_);
  }
  return *workspace_;
}

RunResult RunReuse::Run(const model::Model& model, const Excitation& excitation,
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
  SimulationWorkspace& workspace = Fit(model);
  return Simulate(*model_, excitation, control, workspace, initial, policies.event);
}

}  // namespace skewbridge::dynamics
