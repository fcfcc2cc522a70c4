#pragma once
/// @file
/// The mode decision at an instant [docs/theory.md §3.1-§3.11]: from the state (t, q, u), every
/// contact's mode and what the integrator remembers of past decisions, to the new modes, the
/// velocity after the impact and the positions and velocities after the projection, the events
/// this instant adds, and a status. One entry point, DecideModes; the forces of a candidate set
/// of modes (for the cone sign and the tie fallback) come from the caller through
/// ConstrainedForces, so a test can supply them.

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "solver/contact/contact_problem.h"
#include "solver/contact/impact_problem.h"
#include "solver/contact/kinematics.h"
#include "solver/dynamics/active_forces.h"
#include "solver/dynamics/contact_modes.h"
#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/impact_history.h"
#include "solver/dynamics/projection.h"
#include "solver/dynamics/run_result.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// What the decision remembers between instants of one run (the caller owns it; a new run
/// starts from DecisionMemory(n_contacts)).
struct DecisionMemory {
  /// n_contacts contacts with no impact yet and no tie.
  explicit DecisionMemory(int n_contacts)
      : history(static_cast<std::size_t>(n_contacts)), tie(static_cast<std::size_t>(n_contacts)) {}

  /// Per contact: its last impact and when it last left its face [§3.4-§3.6].
  std::vector<ImpactHistory> history;
  /// Per contact: the mode the contact problem chose, when a tie band [§3.7] decided otherwise
  /// (the tie fallback takes it when the event function says so); empty: no tie.
  std::vector<std::optional<ContactMode>> tie;
  long impact_sequence = 0;  ///< impact instants so far (ImpactHistory::bounce_seq counts them)
  double last_impact_t_s = -std::numeric_limits<double>::infinity();  ///< the last impact
  /// The instant of the last decision, the decisions there after its first, and whether a jam
  /// [§3.9] was applied there [§3.11].
  double last_event_t_s = -std::numeric_limits<double>::infinity();
  int events_here = 0;       ///< decisions at last_event_t_s after the first
  bool jammed_here = false;  ///< a jam was applied at last_event_t_s
};

/// The run's scales the decision compares with (solver/dynamics/run_scales.h).
struct DecisionScales {
  double v_tol_mps = 0.0;      ///< a normal or slip velocity within it is zero
  double v_acc_mps = 0.0;      ///< accumulation threshold: a slower closure is plastic
  double gap_tol_m = 0.0;      ///< a gap within it is touching
  double force_tol_N = 0.0;    ///< a normal force above -force_tol is zero
  double a_detach_mps2 = 0.0;  ///< tie band of a separating or slip acceleration
  double period_min_s = std::numeric_limits<double>::infinity();  ///< shortest natural period
  double length_scale_m = 1.0;  ///< L_d, for the projection's one-pass test
  /// Impacts closer than this to the last impact are one multi-contact impact
  /// (RunControl::simultaneity_tolerance_s); they do not count towards the minimum separation.
  double simultaneity_s = 0.0;
};

/// The instant of a decision.
struct DecisionInstant {
  double t_s = 0.0;                                    ///< time of the event
  Eigen::Vector2d a_g_mps2 = Eigen::Vector2d::Zero();  ///< ground acceleration at t_s
  /// Contacts the event location found striking within the simultaneity tolerance: candidates
  /// of the first pass whatever their gap [§3.3, §3.12].
  std::span<const int> forced;
};

/// The constrained forces of a set of closed contacts with their modes fixed (the active set of
/// a constrained phase [§3.1]): what the decision cannot compute itself.
class ConstrainedForces {
 public:
  virtual ~ConstrainedForces() = default;
  /// lambda_N and lambda_T (N) of every contact at (t_s, q, u) with the modes `modes`: for a
  /// closed contact the solution of d gamma_N/dt = 0 (and d gamma_T/dt = 0 when sticking,
  /// lambda_T = -mu s lambda_N when sliding with sign s); zero for an open one.
  virtual void Forces(const ContactModes& modes, double t_s,
                      const Eigen::Ref<const Eigen::VectorXd>& q,
                      const Eigen::Ref<const Eigen::VectorXd>& u,
                      Eigen::Ref<Eigen::VectorXd> lambda_N,
                      Eigen::Ref<Eigen::VectorXd> lambda_T) = 0;
};

/// Scratch of the decision, sized once for n contacts.
struct DecisionScratch {
  /// Sized for n_dof degrees of freedom and n_contacts contacts.
  DecisionScratch(int n_dof, int n_contacts);

  Eigen::VectorXd h;                           ///< applied forces -C u - K q - M r a_g (n_dof)
  Eigen::VectorXd lambda_N, lambda_T;          ///< ConstrainedForces' answer (n_c)
  Eigen::VectorXd event_values;                ///< closed-contact event functions (2 n_c)
  std::vector<int> index_set, persistent;      ///< the candidates; those with restitution 0
  std::vector<contact::ClosedContact> closed;  ///< the contact problem's contacts, slip signs
  std::vector<ContactMode> previous;           ///< their modes before the contact problem
  std::vector<int> cone_sign;                  ///< per contact: the slip sign of the cone [§3.8]
};

/// Storage the decision works in, sized once for a model and owned whole: the contact layer's
/// problems and results, the projection's workspace and the scratch. Its kinematics
/// (projection.kin) are the decision's own: a ConstrainedForces answer evaluates into storage of
/// the caller's and leaves them alone. When DecideModes returns kOk, projection.kin holds the
/// kinematics of every contact at the final (q, u).
struct DecisionWorkspace {
  /// Sized for `model`; `rank_threshold` is EventPolicy::rank_threshold (the projection's).
  DecisionWorkspace(const model::Model& model, double rank_threshold);

  contact::ImpactProblem impact;            ///< the velocity-level problem
  contact::ImpactResult impact_result;      ///< its result
  contact::ContactProblem contact_problem;  ///< the acceleration-level problem
  contact::ContactResult contact_result;    ///< its result
  ProjectionWorkspace projection;           ///< the projection's storage and the kinematics
  DecisionScratch scratch;                  ///< the decision's own scratch
};

/// What the decisions of a run add up to (the caller owns it; DecideModes adds to it).
struct DecisionLog {
  long impacts = 0;            ///< impact instants (a multi-contact impact or a jam counts once)
  long plastic_closures = 0;   ///< instants with only closures slower than v_acc
  long detachments = 0;        ///< closed contacts opened
  long stick_transitions = 0;  ///< closed contacts that changed to sticking
  long slip_transitions = 0;   ///< closed contacts that changed to sliding (or reversed)
  double impact_J = 0.0;       ///< kinetic energy lost by completed decisions (J)
  /// Smallest time between two distinct impact instants (s).
  double min_impact_separation_s = std::numeric_limits<double>::infinity();
  std::vector<EventRecord> events;  ///< the event log, in order
};

/// The status of a decision: kOk, or kLcpFailure, kPainleve or kEventCascade with a message
/// naming the instant.
struct DecisionOutcome {
  RunStatus status = RunStatus::kOk;  ///< how the decision ended
  std::string message;                ///< empty when ok
};

/// The mode decision at `instant` [docs/theory.md §3.1, the order of the passes]:
/// 1. the cascade guard [§3.11] (more than policy.max_events_at_one_instant decisions at one
///    instant: kEventCascade, nothing changed);
/// 2. the cone sign of sticking contacts at the cone [§3.8], from `forces`;
/// 3. at most policy.decision_passes passes [§3.11], each: candidates [§3.3], the impact problem
///    (Zeno [§3.4], settling [§3.5], plastic closures), who leaves (the rocking exception
///    [§3.5], the predicted bounce [§3.6]), the contact problem with its tie bands and tie
///    fallback [§3.7] (the event functions from `forces`), a jam of a wedged deck [§3.9] (then
///    the pass once more from the stopped state, once per instant), the projection [§3.10];
///    repeated while an open contact at its face approaches it.
/// On kOk, `q`, `u` and `modes` hold the state the integrator continues from, `memory` the
/// updated histories, ties and counters, and `log` the added events, counts and the kinetic
/// energy lost (impact_J). On a failure the state is where the decision stopped. The applied
/// forces it forms include `added`'s when it is not null (AppliedForces).
/// @pre modes, memory and the scratch sized for `model`; q, u of size n_dof.
DecisionOutcome DecideModes(const model::Model& model, const EventPolicy& policy,
                            const DecisionScales& scales, const DecisionInstant& instant,
                            Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> u,
                            ContactModes& modes, DecisionMemory& memory, ConstrainedForces& forces,
                            DecisionWorkspace& ws, DecisionLog& log, AddedForces* added = nullptr);

/// The kinetic energy 1/2 u^T M u (J) of `model` (M diagonal) at the velocities u, the value of
/// 0.5 * u.dot(M u) with Eigen's sum ((t_0 + t_1) + t_2 for 3 DOF, on scalars).
/// @pre u of size n_dof.
double KineticEnergy(const model::Model& model, const Eigen::Ref<const Eigen::VectorXd>& u);

/// The jam test [§3.9]: true when the contact problem's contacts `closed` include two on
/// opposing faces (normals at more than 90 deg) and at least one of them slides: a deck that
/// can wedge between its abutments.
bool Wedged(const model::Model& model, std::span<const contact::ClosedContact> closed);

/// The mode of a contact from the contact problem's answer with the tie bands [§3.7]: a
/// detachment whose separating acceleration `gammadot_N` (m/s^2) is at most a_detach keeps the
/// contact closed with its friction outcome, and a start of slip whose tangential acceleration
/// `gammadot_T` is within a_detach keeps it sticking; `slip_sign` is the sign it entered the
/// problem with. Returns the mode and, for a tie, in `fallback` the contact problem's own answer
/// (empty otherwise, or when the mode is open).
ContactMode ModeOfOutcome(contact::ContactOutcome outcome, contact::ContactOutcome friction_outcome,
                          double gammadot_N, double gammadot_T, int slip_sign, bool frictionless,
                          double a_detach_mps2, const EventPolicy& policy,
                          std::optional<ContactMode>& fallback);

}  // namespace skewbridge::dynamics
