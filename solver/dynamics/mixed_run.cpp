// One run with a rigid wall and a compliant one (SimulateMixed, compliant_run.h): the event-driven
// integrator of Simulate carrying the compliant wall's springs.
#include <vector>

#include "solver/dynamics/compliant_run.h"
#include "solver/dynamics/integrator.h"
#include "solver/dynamics/spring_set.h"

namespace skewbridge::dynamics {

CompliantRunResult SimulateMixed(const model::Model& model,
                                 const std::vector<CompliantSpring>& springs,
                                 const Excitation& excitation, const model::RunControl& control,
                                 const InitialState& initial, const EventPolicy& policy) {
  SpringSet set(model, springs);
  SimulationWorkspace workspace(model);
  Integrator integrator(model, excitation, control, workspace, initial, policy, nullptr, &set);
  CompliantRunResult out;
  out.run = integrator.Run();
  out.joint_stored_J = integrator.joint_stored_J();
  out.joint_dissipated_J = integrator.joint_dissipated_J();
  set.MoveResults(out);
  return out;
}

}  // namespace skewbridge::dynamics
