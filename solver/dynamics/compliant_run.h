#pragma once
/// @file
/// The event-driven integrator of a deck whose abutments are compliant [docs/compliant.md §4]:
/// springs normal to the skewed backwalls (CompliantSpring) in place of the rigid unilateral
/// contacts.
/// - while every spring is open and away from its closing point, the exact transition of the
///   linear flow (solver/dynamics/linear_flow.h) on the excitation piece's grid, as Simulate;
///   a spring's closing (its deformation reaching the permanent set of its memory) located by
///   FirstGapRoot on the flow's dense output;
/// - while a spring is engaged (or open but not yet away from its closing point), the nonlinear
///   flow M du/dt = -C u - K q - M r a_g + sum_j F_j w_j with Dormand-Prince 5(4) and its dense
///   output; on each step every spring keeps one smooth piece of its law (the line continued past
///   its ends, the envelope, the spring-dashpot without its cut at zero), and the events where the
///   law changes piece are located by Brent's method on the dense output: the deformation reaching
///   the closing point, the envelope (the largest deformation before) or the permanent set, the
///   turn from loading to unloading (where the memory d_max is committed), a spring-dashpot's force
///   reaching zero;
/// - the energy ledger integrates the work of the springs beside the motion: of it, the energy a
///   spring would give back by unloading, F^2 / (2 K_ur) (1/2 k d^2 for a spring-dashpot), is
///   stored (F^2 / (2 K_0) for a shear key), the rest dissipated by the hysteresis
///   (CompliantRunResult::joint_stored_J, joint_dissipated_J);
/// - a backfill spring with wall friction (CompliantSpring::mu > 0) carries beside its normal force
///   N a tangential elastic-perfectly-plastic element along the wall: a stick spring of stiffness
///   k_t whose force slips at |F_t| = mu N, as OpenSees' zeroLengthContact elements (Kn, Kt, mu)
///   do; the stick -> slip (|F_t| reaching mu N) and slip -> stick (the plastic slip rate reaching
///   zero) transitions are events located on the dense output like the others, and the friction's
///   dissipation is the ledger's friction_J.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "solver/common/excitation.h"
#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/gap_bound.h"
#include "solver/dynamics/run_result.h"
#include "solver/dynamics/simulate.h"
#include "solver/joint/backfill.h"
#include "solver/joint/shear_key.h"
#include "solver/model/model.h"
#include "solver/model/run_control.h"

namespace skewbridge::dynamics {

/// The force law of one compliant spring.
enum class SpringLaw {
  kBackfill,       ///< the hyperbolic backfill law (joint::HyperbolicGap), with memory
  kSpringDashpot,  ///< F = max(0, k d + c d') while engaged: linear, pulls on nothing, no memory
  kShearKey,       ///< the shear key's backbone (joint::ShearKey), with memory; breaks at DD
};

/// A compliant spring between a body-fixed point p of `body` and a face: its deformation is
/// d = -g(q) = -n . ((x, y) + R(theta) p - A), the penetration beyond the face (whose point A
/// carries the joint's gap, as a rigid contact's), and its force F >= 0 pushes the point along the
/// face's normal n [docs/compliant.md §4]. A face on another body (a deck-deck joint) turns and
/// moves with it, g as a rigid contact's (contact/kinematics.h), and the spring pushes that body
/// back with -F at the same point [docs/compliant.md §6].
struct CompliantSpring {
  std::string name;                                   ///< "+x.1".."+x.n", "-x.1".."-x.n"
  int body = 0;                                       ///< body carrying the point p
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();  ///< p in the body frame (m)
  model::Face face;                      ///< the face it pushes on: the ground's or another body's
  SpringLaw law = SpringLaw::kBackfill;  ///< which force law
  joint::HyperbolicGap backfill;  ///< kBackfill: the spring's share (gap_m = 0: the face has it)
  double k_N_per_m = 0.0;         ///< kSpringDashpot: stiffness, > 0
  double c_Ns_per_m = 0.0;        ///< kSpringDashpot: dashpot, >= 0
  joint::ShearKey key;            ///< kShearKey: the key's backbone (gap_m = 0: the face has it)
  /// kBackfill: Coulomb friction coefficient on the wall, >= 0, acting along the face's tangent at
  /// p with the spring's force as the normal force; 0: a frictionless wall.
  double mu = 0.0;
  /// kBackfill with mu > 0: the stick stiffness k_t along the wall (N/m); 0 takes the spring's
  /// K_max [docs/compliant.md §4, Wall friction].
  double k_t_N_per_m = 0.0;
};

/// The springs of a deck of `model` against the face of its rigid contacts `first` and `last`
/// (a wall's two corners, e.g. P1 and P2, or the two corners of a deck-deck joint against the
/// neighbour's end face): n >= 2 springs at evenly spaced points from corner to corner, each with
/// an n-th of the wall's K_max, K_ur and F_ult (`wall`; its R_f; its gap ignored, the face carries
/// it) [docs/compliant.md §4, §6]. Named `prefix`.1 .. `prefix`.n.
/// @pre both contacts on one deck against one face (the ground's or another deck's); n >= 2.
std::vector<CompliantSpring> WallSprings(const model::Model& model, int first, int last,
                                         const joint::HyperbolicGap& wall, int n,
                                         const std::string& prefix);

/// As WallSprings, n >= 2 linear spring-dashpots (SpringLaw::kSpringDashpot) at the same points,
/// each with an n-th of the joint's stiffness k (N/m, > 0) and dashpot c (N s/m, >= 0).
std::vector<CompliantSpring> SpringDashpots(const model::Model& model, int first, int last,
                                            double k_N_per_m, double c_Ns_per_m, int n,
                                            const std::string& prefix);

/// The two exterior shear keys of the abutment of deck `body` whose rigid contacts are `first` and
/// `last` (the two corners of one end, e.g. P1 and P2): one key beside each of the deck's sides
/// (the body-frame lines y = +-W/2), acting on the corner on that side, against a ground face
/// parallel to the deck's axis at `key.gap_m` beyond the side, its normal facing the deck (the two
/// keys face each other) [docs/compliant.md §4]. Each with the backbone of `key` (its gap moved to
/// the face). Named `prefix`.key+y and `prefix`.key-y, the +y key first.
/// @pre both contacts on one deck, on opposite sides (body-frame y of opposite signs); key valid.
std::vector<CompliantSpring> AbutmentShearKeys(const model::Model& model, int first, int last,
                                               const joint::ShearKey& key,
                                               const std::string& prefix);

/// The model without its rigid contacts (the same bodies, K, C, r and modes): the linear system a
/// compliant run's springs act on.
model::Model WithoutContacts(const model::Model& model);

/// The closing bound of a compliant run's free steps [docs/theory.md §3.18]: per spring (as a
/// contact) and mode, the largest change of its deformation d per unit of the modal coordinate,
/// W_jk = |n_x Phi_xk + n_y Phi_yk| + |n| |p_j| |Phi_theta,k| (its point p_j against its face's
/// normal n, as a rigid corner's gap). Does not apply (empty weights) when a spring faces another
/// body or a mode's damping is negative.
ModalGapBound SpringGapBound(const ModalFlow& modal, const std::vector<CompliantSpring>& springs);

/// What a compliant run returns besides the RunResult of a rigid one.
struct CompliantRunResult {
  /// The run: status, maxima, corner travels, counts, the ledger (its balance_error_J includes the
  /// springs' terms below; impact_J is 0, friction_J the wall friction's dissipation). `impacts`
  /// counts strikes: instants at which a spring closes while none is engaged;
  /// min_impact_separation_s is the smallest time between the starts of two successive strikes
  /// (+inf with fewer than two).
  RunResult run;
  Eigen::VectorXd max_spring_force_N;        ///< per spring, largest force (N), at step ends
  Eigen::VectorXd max_spring_deformation_m;  ///< per spring, largest deformation beyond its face
  double joint_stored_J = 0.0;      ///< energy the springs would give back by unloading, at the end
  double joint_dissipated_J = 0.0;  ///< the springs' work less what they store
  /// Per spring, the time a shear key broke (its deformation reaching DD, s); NaN for a key left
  /// intact and for a spring of another law.
  Eigen::VectorXd key_break_time_s;
  /// Per spring, the plastic slip along the wall accumulated over the run (m): the travel of the
  /// friction element's anchor; 0 without friction.
  Eigen::VectorXd wall_slip_m;
  /// Per spring, the time of its first stick -> slip transition (s); NaN if it never slipped.
  Eigen::VectorXd first_slip_time_s;
};

/// One run of the linear model `model` (no rigid contact) with the compliant `springs` under
/// `excitation` from `initial`, the event-driven method; the ledger closes as
/// kinetic + strain + joint_stored = initial + input - damping - joint_dissipated - friction
/// (joint_stored includes the stick springs' F_t^2 / (2 k_t); friction is RunResult's
/// energy.friction_J).
/// @throws InputError when the model has rigid contacts, a spring is invalid (law constants, body
/// index, a face not on the ground), or the initial state has the wrong size.
CompliantRunResult SimulateCompliant(const model::Model& model,
                                     const std::vector<CompliantSpring>& springs,
                                     const Excitation& excitation, const model::RunControl& control,
                                     const InitialState& initial = {},
                                     const EventPolicy& policy = {});

/// One run of `model` with its rigid contacts (those of the rigid wall) and the compliant
/// `springs` (those of the other wall) under `excitation` from `initial`: the event-driven
/// integrator of Simulate carrying the springs [docs/compliant.md §4, docs/theory.md §3.22]. A free
/// (exact) step only with every contact open and every spring open and off its closing point, a
/// spring's closing searched as an impact; otherwise the constrained Runge-Kutta step with the
/// springs' forces in the applied forces and their events beside the contacts'. The result's
/// `run` counts the springs' strikes among its impacts and the wall friction's dissipation in its
/// friction_J; its ledger closes as kinetic + strain + joint_stored = initial + input - damping -
/// impact - friction - joint_dissipated. With no spring ever engaged it is Simulate's run.
/// @throws InputError as Simulate, and when a spring is invalid.
CompliantRunResult SimulateMixed(const model::Model& model,
                                 const std::vector<CompliantSpring>& springs,
                                 const Excitation& excitation, const model::RunControl& control,
                                 const InitialState& initial = {}, const EventPolicy& policy = {});

}  // namespace skewbridge::dynamics
