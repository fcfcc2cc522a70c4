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
  SimulationWorkspace workspace(model);
  return Simulate(model, excitation, control, workspace, initial, policies.event);
}

}  // namespace skewbridge::dynamics
