#pragma once
/// @file
/// A model file's compliant abutments (model::CompliantAbutments, [abutments] law = "compliant")
/// made into the springs of SimulateCompliant, and the one run of a model under either law that
/// `skewbridge run` and the model-file sweeps share [docs/compliant.md §4,
/// docs/model-format.md].

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "solver/common/excitation.h"
#include "solver/dynamics/compliant_run.h"
#include "solver/dynamics/run_policies.h"
#include "solver/dynamics/run_result.h"
#include "solver/model/abutment_law.h"
#include "solver/model/model.h"
#include "solver/model/run_control.h"

namespace skewbridge::dynamics {

/// The springs of `spec` on the decks of `rigid` (a single deck built with its corner contacts
/// P1, P2 against the +x wall and, with both abutments, P3, P4 against -x; a row of decks with the
/// last deck's D<i>.P1, D<i>.P2 and deck 0's D0.P3, D0.P4): per wall w (spec.walls[0] the +x
/// wall, [1] the -x wall) WallSprings(rigid, first, last, WallBackfill(w.backfill, deck),
/// w.springs, "+x" / "-x"), the wall's law from its deck's geometry (its length and skew angle);
/// every spring with its wall's friction w.friction and an n-th of its stick stiffness
/// w.stick_stiffness_Npm (0: the spring's K_max). Then, per abutment with keys (w.shear_keys),
/// AbutmentShearKeys(rigid, first, last, key, "+x" / "-x"). Then per deck-deck joint i
/// (spec.joints) of the compliant law on its two contacts, WallSprings with the joint's backfill on
/// the striking deck's end or SpringDashpots, named "J<i>". The order: the +x wall's springs, the
/// -x wall's, the +x keys (+y, -y), the -x keys, the joints. A wall or joint of the impact law (a
/// mixed model) has none.
/// @pre spec.walls has a law per wall of `rigid`; spec.joints one per joint of `rigid`.
/// @throws InputError naming the model's source when a wall's law or a key is invalid.
std::vector<CompliantSpring> AbutmentSprings(const model::Model& rigid,
                                             const model::CompliantAbutments& spec);

/// The largest response of the springs of one wall over a compliant run.
struct WallMaxima {
  std::string wall;             ///< "+x" or "-x"
  double spring_force_N = 0.0;  ///< the largest force of one of its springs (N)
  double deformation_m = 0.0;   ///< the largest deformation of one of its springs (m)
};

/// The response of one exterior shear key over a compliant run.
struct KeyMaxima {
  std::string name;            ///< the spring's name, "+x.key+y", "+x.key-y", "-x.key+y", ...
  std::string wall;            ///< the abutment: "+x" or "-x"
  double force_N = 0.0;        ///< its largest force (N, at most V_n)
  double deformation_m = 0.0;  ///< its largest deformation beyond the transverse gap (m)
  double break_time_s = 0.0;   ///< when it broke (deformation DD reached, s); +inf if intact
};

/// The response of one backfill or joint spring over a compliant run.
struct SpringMaxima {
  std::string name;            ///< the spring's name, "+x.1" .. "+x.n", "-x.1", .., "J0.1", ..
  double force_N = 0.0;        ///< its largest force (N)
  double deformation_m = 0.0;  ///< its largest deformation beyond its face (m)
  double wall_slip_m = 0.0;    ///< the plastic slip along the wall accumulated (m); 0 without mu
};

/// A run of a model under the joint law its model file gives.
struct LawRun {
  RunResult run;  ///< the run (for a compliant one, CompliantRunResult::run)
  /// per compliant wall (backfill springs only), +x then -x; with a law per abutment the compliant
  /// wall's only
  std::vector<WallMaxima> walls;
  /// per compliant deck-deck joint (named "J0", "J1", ... by its index; a rigid joint of a mixed
  /// row has none): its springs' largest force and deformation; empty for a single deck
  std::vector<WallMaxima> joints;
  std::vector<KeyMaxima> keys;  ///< per shear key, in the springs' order; empty without keys
  /// per backfill or joint spring (not the keys), in the springs' order (AbutmentSprings)
  std::vector<SpringMaxima> springs;
  double joint_stored_J = 0.0;      ///< compliant: CompliantRunResult::joint_stored_J
  double joint_dissipated_J = 0.0;  ///< compliant: CompliantRunResult::joint_dissipated_J
};

/// A run of the rigid law as a LawRun: no walls, joints, keys or springs.
inline LawRun RigidLawRun(RunResult run) {
  LawRun law;
  law.run = std::move(run);
  return law;
}

/// One stored response of a compliant run's joints: a cube's response of a model-file sweep and an
/// attribute of a run file's group `joints` (docs/sweep-format.md, docs/run-output.md).
struct JointResponse {
  std::string name;                            ///< e.g. "spring_force_px"
  std::string unit;                            ///< "N", "m", "s" or "1"
  std::string meaning;                         ///< one line
  std::function<double(const LawRun&)> value;  ///< how it is read from the run
};

/// The responses of the joints of `compliant` (`both`: with the -x abutment), in order: per
/// compliant wall (+x "_px", then -x "_mx"; not the rigid wall of a law per abutment)
/// spring_force and backwall_def; per compliant deck-deck joint i joint_force_j<i>
/// and joint_def_j<i> (not a rigid joint of a mixed row); with shear keys, per abutment
/// key_force, key_def and key_break_time (the earliest break of its two keys, +inf when neither
/// broke), then keys_broken (the keys broken over the run); the keys' responses of both compliant
/// abutments when either has keys (one without: 0, 0 and +inf).
std::vector<JointResponse> JointResponses(const model::CompliantAbutments& compliant, bool both);

/// The model a run under `compliant` integrates, from `model` built with every corner contact:
/// WithoutContacts(model) when every wall and joint is compliant; else (compliant.Mixed(): a law
/// per abutment, or a row of decks with rigid and compliant parts) `model` without the corner
/// contacts of its compliant walls (+x: P1, P2 of the last deck; -x: P3, P4 of deck 0) and
/// compliant deck-deck joints, the rigid ones kept in their order (the same bodies, K, C, r and
/// modes).
/// @pre compliant.joints has one law per deck-deck joint of `model`.
model::Model LawModel(const model::Model& model, const model::CompliantAbutments& compliant);

/// One run of `model` (built with its contacts) under `excitation`: without `compliant`, the
/// rigid law, Run(model, excitation, control, policies) unchanged; with it,
/// SimulateCompliant(WithoutContacts(model), AbutmentSprings(model, *compliant), excitation,
/// control, {}, policies.event), or with rigid and compliant parts (compliant->Mixed(): a law per
/// abutment, or a row with rigid and compliant joints) SimulateMixed(LawModel(model, *compliant),
/// AbutmentSprings(...), ...): the maxima of each
/// compliant wall's backfill springs and of each shear key beside it, and each spring's own
/// maxima and wall slip.
/// @throws InputError as Run and SimulateCompliant (a compliant run needs the event-driven method).
LawRun RunUnderLaw(const model::Model& model,
                   const std::optional<model::CompliantAbutments>& compliant,
                   const Excitation& excitation, const model::RunControl& control,
                   const RunPolicies& policies = {});

}  // namespace skewbridge::dynamics
