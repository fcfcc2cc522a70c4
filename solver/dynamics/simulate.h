#pragma once
/// @file
/// The event-driven integrator of [docs/theory.md §3; Pfeiffer and Glocker 1996, ch. 6-7;
/// Dimitrakopoulos 2011, §2]:
/// - no closed contact: the exact transition of the linear flow (solver/dynamics/linear_flow.h)
///   on a grid aligned with each excitation piece, steps at most 1/20 of the shortest natural
///   or excitation period, partial steps by the flow's Taylor dense output;
/// - closed contacts: Dormand-Prince 5(4) with the forces of the active set (each closed contact
///   sticking, sliding with a sign, or frictionless) and projection onto g = 0, gamma_N = 0
///   (gamma_T = 0 when sticking) after each step;
/// - events located by Brent's method on the dense output: a gap reaching zero (impact),
///   lambda_N reaching zero (detachment), a slip velocity reaching zero (stick or reversal),
///   friction reaching the cone (slip); excitation kinks are step boundaries;
/// - at every event the mode decision, DecideModes (solver/dynamics/mode_decision.h;
///   docs/theory.md §3.1-§3.11): at impacts the velocity-level LCP, at every change of the active
///   set the acceleration-level LCP (Lemke); a secondary ray there is a Painleve situation,
///   returned as a status.
///
/// Accumulation threshold: an impact with approach speed |gamma_N,A| below
/// v_acc = accumulation_threshold * a_peak / omega_1 (a_peak the largest |a_g| of the excitation,
/// omega_1 the lowest natural frequency, or 1 rad/s for a free body) is plastic: the contact
/// closes. v_acc scales with the excitation, so it keeps the self-similarity of [docs/theory.md §4
/// fact 4].
///
/// Simultaneity: impacts whose roots lie within RunControl::simultaneity_tolerance_s of the
/// first are one multi-contact impact; RunResult::min_impact_separation_s reports how close
/// distinct impacts came.

#include <Eigen/Core>
#include <vector>

#include "solver/common/excitation.h"
#include "solver/contact/contact_problem.h"
#include "solver/contact/impact_problem.h"
#include "solver/contact/kinematics.h"
#include "solver/dynamics/active_forces.h"
#include "solver/dynamics/contact_modes.h"
#include "solver/dynamics/coordinate_maxima.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/gap_bound.h"
#include "solver/dynamics/gap_floors.h"
#include "solver/dynamics/linear_flow.h"
#include "solver/dynamics/mode_decision.h"
#include "solver/dynamics/run_result.h"
#include "solver/dynamics/runge_kutta.h"
#include "solver/model/model.h"
#include "solver/model/run_control.h"

namespace skewbridge::dynamics {

/// The state at the run's start (relative to the ground); the default is rest at t = 0.
struct InitialState {
  Eigen::VectorXd q;  ///< n_dof, empty = zero
  Eigen::VectorXd u;  ///< n_dof, empty = zero
  /// The time of the state (s). A start at t_s > 0 continues a run that began at rest at t = 0
  /// and reached (q, u) at t_s by free steps alone, no contact event among them (a stripe's
  /// contact-free response, solver/dynamics/stripes.h): the tolerances are that run's (its
  /// velocity scale from the excitation, none from u), its step grid goes on with the last
  /// nominal free step h_free_s, and its step count and step limit with free_steps. Only the
  /// event-driven method takes it; its history samples go on with the grid of the run from rest
  /// after the samples that run recorded up to t_s.
  double t_s = 0.0;
  long free_steps = 0;    ///< free steps taken before t_s (t_s > 0)
  double h_free_s = 0.0;  ///< the last nominal free step before t_s (s; 0: none)
};

/// Sees the free steps of a run while no contact has closed and no event has happened, to follow
/// the contact-free response beside the run (solver/dynamics/stripes.h).
class FreeStepObserver {
 public:
  virtual ~FreeStepObserver() = default;
  /// The free step from t0_s to t1_s: z0 and z1 hold (q, u) at its ends (n_dof each), h0_s is
  /// the nominal free step before it, `run` the run over [0, t1_s] (its free step count, maxima
  /// of |q_i| and their times, work of the ledger, history samples). Returns false when it needs
  /// no further step: the run ends there.
  virtual bool Step(double t0_s, const Eigen::Ref<const Eigen::VectorXd>& z0, double h0_s,
                    double t1_s, const Eigen::Ref<const Eigen::VectorXd>& z1,
                    const RunResult& run) = 0;

 protected:
  FreeStepObserver() = default;
  FreeStepObserver(const FreeStepObserver&) = default;
  FreeStepObserver& operator=(const FreeStepObserver&) = default;
};

/// The storage of a run's state that a workspace keeps from one run to the next (the integrator
/// lends it for a run and gives it back), so that a run of the workspace's shape allocates none
/// of it: what a run finds there is overwritten before it is read, so results never depend on
/// it. Internal to the integrator.
struct RunStorage {
  /// Empty storage, and the contacts' modes and decision memory a run of a model with
  /// `n_contacts` contacts starts from.
  explicit RunStorage(int n_contacts) : fresh_modes(n_contacts), fresh_memory(n_contacts) {}

  // The state vectors: z, its step end and dense value; y, its rate and dense value, its
  // tolerances; C u and du/dt; the open contacts' gaps and rates at a step's ends; the closed
  // contacts' event functions at a step's ends and inside.
  Eigen::VectorXd z, z_new, z_eval, y, dy, y_eval, atol, cu, du;
  Eigen::VectorXd gap0, gN0, gap1, gN1, f0, f1, f_eval, observed_z0;
  std::vector<int> forced;  // contacts striking together
  // The gaps' and rates' scratch, the contacts' modes and the decision memory, which a run works
  // in where they are (the integrator refers to them; a run sets the modes and the memory from
  // fresh_modes and fresh_memory first).
  contact::GapRateScratch rates;
  ContactModes modes{0};
  DecisionMemory memory{0};
  std::vector<EventRecord> events;  // the last run's event log (storage only)
  DeferredPeaks deferred_peaks;     // the record loop's deferred root searches (storage only)
  // A caller's finished result (SimulationWorkspace::Recycle): the next run's result takes its
  // vectors' storage, which that run's assignments size and overwrite.
  RunResult result;
  const ContactModes fresh_modes;     // every contact open: a run's first modes
  const DecisionMemory fresh_memory;  // no impact yet: a run's first memory
};

/// Scratch memory and caches of one model: build once, reuse for every run of that model (a
/// sweep does thousands). Results never depend on what ran before (the caches are pure
/// functions of the model). Keeps a reference to the model.
class SimulationWorkspace {
 public:
  /// Sizes everything for `model`.
  explicit SimulationWorkspace(const model::Model& model);

  const model::Model& model() const { return model_; }
  /// Lowest natural frequency (rad/s; 0 for a free body), from the modes the flow solved.
  double omega_min_radps() const { return omega_min_radps_; }

  /// Whether the storage sized for `model()` fits `other` as it is: the same bodies, degrees of
  /// freedom and contacts, each contact on the same body against a face of the same body.
  bool SameShape(const model::Model& other) const;
  /// Makes the workspace what a new one built for model() would be, after model() (the object
  /// this workspace refers to) was given the values of another model of the same shape
  /// (SameShape): the flow, the gap bound and the frequency and length scales computed again,
  /// the contact kinematics zeroed, the rest of the storage kept without allocating. A run in
  /// it gives the bits a run in a new workspace gives.
  void Refit();

  /// Keeps a finished result's storage for the next run here: that run's result takes its maxima,
  /// end state, corner travel and event vectors instead of allocating them (the same values).
  void Recycle(RunResult&& result) { run_storage_.result = std::move(result); }

 private:
  friend class Integrator;
  // The flow's scales and the gap bound of model_ (the constructor's and Refit's).
  void ComputeScales();

  const model::Model& model_;
  LinearFlow flow_;
  FreeDenseOutput free_dense_;
  DormandPrince45 rk_;
  // The constrained phase's force evaluations (every entry written before it is read): the
  // Runge-Kutta stages, the event functions and the decision's ConstrainedForces answers.
  ActiveForcesStorage forces_;
  // The mode decision's storage, with kinematics of its own; the projection after a
  // constrained step works in it too.
  DecisionWorkspace decision_;
  // The free step's bound on the gaps' closure over a step (applies() false: every step
  // computes its gaps).
  ModalGapBound gap_bound_;
  // The free steps' gap floors over gap_bound_ (a run resets them: GapFloors::Reset).
  GapFloors gap_floors_{gap_bound_};
  // The integrator's state storage, lent to each run (RunStorage).
  RunStorage run_storage_{model_.n_contacts()};
  // The decks' corner geometry for their travels, which each run starts again: a run's
  // integrator holds it (moved in and back, no allocation).
  CornerTravelTracker travel_{model_};
  double omega_min_radps_ = 0.0;  // lowest natural frequency (0 for a free body)
  double omega_max_radps_ = 0.0;  // highest natural frequency
  double length_scale_m_ = 1.0;   // largest deck dimension or distance from the origin
  // The last policy a run in this workspace validated (valid: there was one): a run under a
  // policy of the same members' bits (SameMembers) skips ValidatePolicy, whose verdict depends
  // on them alone.
  EventPolicy validated_policy_{};
  bool policy_validated_ = false;
};

/// Integrates one run of `model` under `excitation` with `control` from `initial`, its events
/// decided by `policy` (the defaults unless a study of the rules asks otherwise); `observer`, when
/// given, sees every free step until the first event.
/// @pre workspace built for `model`; excitation duration finite.
/// @throws InputError when the initial state has the wrong size or a bad start time.
RunResult Simulate(const model::Model& model, const Excitation& excitation,
                   const model::RunControl& control, SimulationWorkspace& workspace,
                   const InitialState& initial = {}, const EventPolicy& policy = {},
                   FreeStepObserver* observer = nullptr);

}  // namespace skewbridge::dynamics
