#pragma once
/// @file
/// The event-driven integrator's state machine (Simulate, solver/dynamics/simulate.h): the class
/// shared by the files that define its members. Internal to the dynamics module.

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "solver/common/error.h"
#include "solver/contact/kinematics.h"
#include "solver/dynamics/active_forces.h"
#include "solver/dynamics/contact_modes.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/event_location.h"
#include "solver/dynamics/gap_floors.h"
#include "solver/dynamics/mode_decision.h"
#include "solver/dynamics/peak_bound.h"
#include "solver/dynamics/simulate.h"
#include "solver/dynamics/spring_set.h"
#include "solver/dynamics/step_grid.h"

namespace skewbridge::dynamics {

/// The state machine of one run (see simulate.h); simulate.cpp holds its
/// members but RecordFlight, record_flight.cpp the record's free flight; lives for one Simulate
/// call. It is the mode decision's source of constrained forces (ActiveForces).
class Integrator final : private ConstrainedForces {
 public:
  // `springs`, when not null, are a compliant wall's beside the rigid contacts (SimulateMixed).
  Integrator(const model::Model& model, const Excitation& excitation,
             const model::RunControl& control, SimulationWorkspace& ws, const InitialState& initial,
             const EventPolicy& policy, FreeStepObserver* observer, SpringSet* springs = nullptr);
  // Gives the workspace its run storage back (RunStorage).
  ~Integrator();
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  // The springs' stored energy at the end and their work less it (J), after Run with springs.
  double joint_stored_J() const { return joint_stored_J_; }
  double joint_dissipated_J() const { return joint_dissipated_J_; }

  RunResult Run();

 private:
  using Vec = Eigen::VectorXd;
  using View = Eigen::Map<const Vec>;  // a vector in the state's storage, nothing built per use

  auto q() { return z_.head(n_); }
  auto u() { return z_.segment(n_, n_); }
  bool AnyClosed() const { return modes_.any_closed(); }
  bool Failed() const { return result_.status != RunStatus::kOk; }
  void Fail(RunStatus status, const std::string& message) {
    result_.status = status;
    result_.message = message;
  }

  // The result at the end of the run: the final state, the decisions' events and counts, the
  // energy ledger, and the non-finite status if the state or its energy is no number;
  // `t_finite_s` is the last time the state was checked finite.
  RunResult Finish(double t_finite_s);
  // Exchanges the state's storage with the workspace's RunStorage (the constructor borrows it,
  // the destructor gives it back).
  void SwapStorage();
  // Contact-free phase: one exact step of the flow, up to its end or its first impact; there
  // the decision.
  void FreeStep();
  // FreeStep past its plan: the step `step` on `piece` (the cursor's), h_free_ set.
  void FreeStepOf(const ExcitationPiece& piece, const FreeStepPlan& step);
  // FreeStep past its transition: z_new_ holds the step's end, the generator of `piece` is in
  // z_, `open` says whether GapsStayOpen proved the step's gaps open (its drifts then joined the
  // gap floors), `dense_built` whether the dense output of the step is built; input_J and
  // damping_J are the work of a full step with the ledger. Events, maxima, corner travels,
  // history samples, the decision.
  void FinishFreeStep(const ExcitationPiece& piece, const FreeStepPlan& step, bool open,
                      bool dense_built, double input_J, double damping_J);
  // Whether the free steps may run RecordFlight: a modal flow with the gap bound, no ledger, no
  // springs.
  bool RecordFlightApplies() const {
    return !control_.energy_ledger && ws_.flow_.modal() && ws_.gap_bound_.applies() &&
           springs_ == nullptr;
  }
  // The springs' part of a run (mixed_run.cpp), each called only with springs: out of line and
  // in a translation unit of its own, so that the rigid law's steps compile as they do without
  // them.
  // Whether every spring is open and off its closing point at z_ (a free step may follow).
  bool SpringsFree() const;
  // Their transitions at z_ [docs/theory.md §3.22], a strike counted.
  void SettleSprings();
  // Each engaged spring's largest force and deformation raised to its values at z_.
  void SpringMaxima();
  // The first closing of an open spring in the free step `step` on `piece` from t_, whose end
  // state z_new_ holds (+inf: none), searched as an impact on the flow's dense output; that is
  // built (unless `dense_built` says it is) when a search needs it, and always when a closing is
  // found.
  double FreeStepSpringClosing(const ExcitationPiece& piece, const FreeStepPlan& step,
                               bool dense_built);
  // The first spring event of the Runge-Kutta step from t_ to t1 (+inf: none), on its dense
  // output; spring_e0_ holds the event values at the step's start. The time is taken on the
  // root's far side, so that the transition sees the event function crossed.
  double FirstSpringEvent(double t1);
  // After a spring closed first in a free step: its transition; the contacts' gaps and rates at
  // the new start.
  void SpringClosedInFreeStep();
  // Rhs with the springs: Rhs on (q, u) and the three work integrals (the springs' forces are
  // in du through the hook), then the springs' power and their friction's in dy's last two
  // entries (W).
  void SpringsRhs(double t, const Eigen::Ref<const Vec>& y, KinematicsOf which, Eigen::Ref<Vec> dy);
  // The Runge-Kutta step of length h from (t_, y_) with the springs (SpringsRhs), their event
  // values at its start into spring_e0_.
  void SpringsStep(double h);
  // The run's end with springs: their stored energy and dissipation, the wall friction's
  // dissipation in e's friction, their strikes among the impacts, e's balance error.
  void FinishSprings(EnergyLedger& e);
  // A record's free flight [docs/theory.md §3.21]: from the step `steps` on (counted by Run and
  // within the limit), free steps as FreeStep takes them, each in a tight loop while it is a
  // full step whose gaps the bound keeps open or in which no contact is suspected of an
  // impact, whose maxima and corner travels need no search and that holds no history sample; a
  // step that is not is finished by FinishFreeStep (or taken by FreeStepOf), and the flight
  // returns after it when a contact closed or the run failed (Run's next step is not a free
  // one) or an observer watches (the observer's use is decided at the flight's entry, and the
  // step may have logged an event), else goes on.
  // Between steps it does what Run does (the step limit, the finite check every
  // finite_check_steps steps into `t_finite`, the observer); returns false when the observer
  // stops the run.
  bool RecordFlight(long& steps, double& t_finite);
  // What DeckRecordSteps takes from RecordFlight once per flight: deck 0's corner-reach
  // constants, a ramp's longest free step h_max_s (FreeStepMax, s), and lengths (s) between
  // one_step_min_s and one_step_max_s, for which FreeStepOfLength is the length itself.
  struct DeckFlight {
    CornerTravelTracker::ReachConstants reach;
    double h_max_s = 0.0;
    double one_step_min_s = std::numeric_limits<double>::infinity(), one_step_max_s = 0.0;
  };
  // RecordFlight's steps of one deck (three coordinates) on the ramps of a sampled record
  // (`samples`), without an observer: each step's operations in RecordFlight's order, with the
  // state, the piece, the plan's nominal step, the maxima and the counts held in locals and
  // written back before a step leaves the loop; the gap floors' drifts from the modal
  // coordinates' lanes; a step whose coordinates' velocity roots or corners' rate roots alone
  // would need a search stays in the loop, its searches deferred (ResolveDeferredPeaks). reach0 and
  // speed0 carry the deck's corner-reach terms at the step's start. Returns true when the flight
  // ends (a step finished by FinishFreeStep or FreeStepOf, the run's end, the step limit or the
  // finite check), false before a step that is not the record's next ramp (RecordFlight takes
  // that one).
  // kHasY: whether the record has y samples (samples.ay_mps2 not null); without, the y
  // generator is the constant +0 it would compute.
  template <bool kHasY>
  bool DeckRecordSteps(long& steps, double& t_finite, const SampleView& samples,
                       const DeckFlight& flight, double& reach0, double& speed0);
  // DeckRecordSteps without and with y samples, each compiled twice (the processor's AVX
  // encoding where it has one, else the baseline) and chosen when the program loads.
  __attribute__((target_clones("avx", "default"))) bool DeckRecordStepsX(
      long& steps, double& t_finite, const SampleView& samples, const DeckFlight& flight,
      double& reach0, double& speed0);
  __attribute__((target_clones("avx", "default"))) bool DeckRecordStepsXY(
      long& steps, double& t_finite, const SampleView& samples, const DeckFlight& flight,
      double& reach0, double& speed0);
  // The root searches DeckRecordSteps deferred (ws_.run_storage_.deferred_peaks) folded into
  // the deck's running maxima max_q and time_of_max and its corners' max_travel (m) (each the
  // fold of every step's end), the bits of the in-order scan (ResolveDeferredMaxima,
  // ResolveDeferredTravel); the list emptied. Uses the dense output, the peak bound and z_eval_.
  void ResolveDeferredPeaks(double max_q[3], double time_of_max[3], double& max_travel);
  // Whether every gap provably stays above twice the touch band over the full free step of
  // length tau_s just applied (GapFloors, [docs/theory.md §3.18]); `harmonic` false when the
  // step's piece has no harmonic part (omega 0: the modal coordinates' harmonic columns zeros).
  bool GapsStayOpen(double tau_s, bool harmonic) {
    if (!ws_.gap_bound_.applies()) {
      return false;
    }
    if (gaps_exact_) {
      gap_floors_.Restart(ends_.gap0);
    }
    // Clear of the touch band with the rounding of the gaps' evaluation to spare.
    return gap_floors_.StaysOpen(ws_.flow_.modal_coordinates().data(), tau_s,
                                 2.0 * scales_.gap_tol_m, harmonic);
  }
  // FreeStepSize of `piece`, computed again only when its length or rate differ from the last
  // piece's (a record's ramps share them): the same value without its divisions.
  double NominalFreeStep(const ExcitationPiece& piece) {
    const double length = piece.t_end - piece.t_begin;
    if (!(length == nominal_length_s_ && piece.omega == nominal_omega_radps_)) {
      nominal_h_s_ = FreeStepSize(piece, ws_.omega_max_radps_, policy_);
      nominal_length_s_ = length;
      nominal_omega_radps_ = piece.omega;
    }
    return nominal_h_s_;
  }
  // The flow's propagator of a full step h_s at omega_radps (with its energy forms if `energy`):
  // the last step's when the key is the same, else LinearFlow::Propagator. Nothing but the free
  // steps asks the workspace's flow for a propagator during a run, so the last one stays valid,
  // and it is the cache's most recently used entry: not asking again keeps its eviction order.
  const FreePropagator& StepPropagator(double h_s, double omega_radps, bool energy) {
    if (propagator_ == nullptr || h_s != propagator_->tau_s ||
        omega_radps != propagator_->omega_radps || (energy && !propagator_->has_energy)) {
      propagator_ = &ws_.flow_.Propagator(h_s, omega_radps, energy);
    }
    return *propagator_;
  }
  // Constrained phase: one Runge-Kutta step, up to its end or its first event (an impact of an
  // open contact or an event function of a closed one); there the decision, else the
  // projection.
  void ConstrainedStep();
  // The step [t_, t1] done, its end state (q, u) in the heads of z_new_: the maxima, the corner
  // travels and the history samples inside it, then (t_, z_) moved to its end.
  // component_at(t, i) and state_at(t) read the step's dense output (ScanCoordinateMaxima,
  // RecordOutputs).
  template <class ComponentAt, class StateAt>
  void RecordStep(double t1, ComponentAt&& component_at, StateAt&& state_at);

  // Forces of the active set `modes` at (t, q, u) into `storage`: du/dt, lambda per contact,
  // the friction power [solver/dynamics/active_forces.h], with the kinematics of `which`
  // contacts: a constrained phase's stages and event searches need the closed ones' only (the
  // open ones' gaps are read at the step's ends).
  void ActiveForces(const ContactModes& modes, double t, const Eigen::Ref<const Vec>& q,
                    const Eigen::Ref<const Vec>& u, KinematicsOf which, Eigen::Ref<Vec> du,
                    ActiveForcesStorage& storage) {
    EvaluateActiveForces(model_, modes, policy_, scales_.force_tol_N, GroundAcceleration(t), q, u,
                         which, du, storage, added_);
  }
  // The constrained phase's right-hand side: dy/dt of y = (q, u, the three work integrals).
  void Rhs(double t, const Eigen::Ref<const Vec>& y, KinematicsOf which, Eigen::Ref<Vec> dy);
  // Event-function values of the closed contacts at the last ActiveForces call.
  void ClosedEventValues(Eigen::Ref<Vec> values) const;

  // The mode decision at the current state [docs/theory.md §3.1]; `forced` lists the contacts
  // the event location found striking together.
  void ResolveContacts(const std::vector<int>& forced);
  // ConstrainedForces: lambda_N, lambda_T of ActiveForces at (t, q, u) with the modes `modes`.
  void Forces(const ContactModes& modes, double t, const Eigen::Ref<const Vec>& q,
              const Eigen::Ref<const Vec>& u, Eigen::Ref<Vec> lambda_N,
              Eigen::Ref<Vec> lambda_T) override;
  void Project();

  // Whether contact c is open and its gaps and rates at the ends (ends_) of a step of tau_s (s)
  // make an impact suspected (ImpactSuspected with `dip_margin`) [docs/theory.md §3.12].
  bool Suspected(int c, double tau_s, double dip_margin) const {
    return ImpactSuspected(ends_.gap0[c], ends_.gN0[c], ends_.gap1[c], ends_.gN1[c], tau_s,
                           dip_margin) &&
           !modes_.closed(c);
  }
  // The first impact of an open contact in the step [t0, t1] (+inf: none) [docs/theory.md
  // §3.12]: each contact Suspected of one is searched by FirstGapRoot on the
  // dense output: positions_at(t) gives q at t, state_at(t) a vector whose heads are q and u.
  template <class PositionsAt, class StateAt>
  double FirstImpact(double t0, double t1, double dip_margin, PositionsAt&& positions_at,
                     StateAt&& state_at);
  // The impact time of the open contact c in [t0, t1] (FirstGapRoot on the dense output).
  template <class PositionsAt, class StateAt>
  double GapRoot(int c, double t0, double t1, PositionsAt&& positions_at, StateAt&& state_at);
  // The time tolerance of a maximum's root search in a step ending at t1 (s).
  double MaximumTimeTolerance(double t1) const {
    return policy_.maximum_time_tolerance * std::max(1.0, std::abs(t1)) +
           policy_.event_time_floor_s;
  }
  // The history samples in (t0, t1]; state_at(t) as for FirstImpact.
  template <class StateAt>
  void RecordOutputs(double t0, double t1, StateAt&& state_at);
  void RecordSample(double t, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u);
  // 1/2 u^T M u (J), M diagonal.
  double Kinetic() { return 0.5 * u().dot(model_.mass_diagonal().cwiseProduct(u())); }
  // The gap of contact c at q, and its normal rate gamma_N at (q, u), for the event searches.
  double GapAt(int c, const Eigen::Ref<const Vec>& q) const {
    return contact::Gap(model_, c, q, rates_);
  }
  double NormalRateAt(int c, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u) {
    return contact::NormalRate(model_, c, q, u, rates_);
  }
  // Gaps and normal rates of every contact at (q, u), without the rest of the kinematics.
  void GapsAndRates(const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u, Vec& gap,
                    Vec& gamma_N) {
    contact::GapsAndRates(model_, q, u, gap, gamma_N, rates_);
  }
  Eigen::Vector2d GroundAcceleration(double t) const { return excitation_.At(t); }

  // The open contacts' gaps (m) and normal rates (m/s) at a step's two ends: what impact
  // suspicion and FirstGapRoot start from. The end of one step is the start of the next,
  // unless a decision there gives its own.
  struct StepEnds {
    Vec gap0, gN0, gap1, gN1;
  };
  // The closed contacts' event functions (2 n_c, ClosedEventValues): at the step's start, its
  // end, and a trial time inside it.
  struct ClosedEvents {
    Vec f0, f1, f_eval;
  };

  // The run's inputs. The workspace is the model's, owned whole by one run at a time: the flow,
  // the dense outputs, the constrained phase's force evaluations (ws_.forces_) and the mode
  // decision's storage (ws_.decision_), whose kinematics are its own: a ConstrainedForces
  // answer writes ws_.forces_ only.
  const model::Model& model_;
  const Excitation& excitation_;
  const model::RunControl& control_;
  const EventPolicy policy_;
  SimulationWorkspace& ws_;
  // A compliant wall's springs beside the contacts; null: none. They are the forces added to the
  // applied forces wherever these are formed (AppliedForces); without them every force keeps
  // the model's bits.
  SpringSet* springs_ = nullptr;
  AddedForces* added_ = nullptr;
  int ny_ = 0;  // the size of y: (q, u, three work integrals[, springs', friction's work])
  Vec spring_e0_, spring_e1_, spring_scratch_h_;       // the springs' event values at a step's ends
  double joint_work_J_ = 0.0, wall_friction_J_ = 0.0;  // the springs' and their friction's work
  double joint_stored_J_ = 0.0, joint_dissipated_J_ = 0.0;
  long strikes_ = 0;  // springs closing while none was engaged
  int n_, nc_;
  // The run's tolerances and scales [docs/theory.md §3.2], which the decision, the projection,
  // the event functions and the event searches compare with.
  DecisionScales scales_;
  double t_ = 0.0, t_end_ = 0.0;  // the time and the end of the run (s)
  double h_rk_ = 0.0;             // the next Runge-Kutta step the error control proposes (s)
  double h_free_ = 0.0;           // the last nominal free step (s)
  double next_output_t_ = std::numeric_limits<double>::infinity();  // the next history sample (s)
  // Samples of the output grid before this run's first (the run from rest recorded them up to
  // the start time InitialState::t_s).
  std::size_t output_offset_ = 0;
  // The state (q, u and the excitation's states of the free flow), a step's end, and the free
  // step's dense output at a trial time.
  Vec z_, z_new_, z_eval_;
  // The constrained phase's Runge-Kutta state y = (q, u, work integrals), its rate, its dense
  // output at a trial time, and its absolute tolerances.
  Vec y_, dy_, y_eval_, atol_;
  Vec cu_, du_;    // C u (K q in Finish); du/dt of the last force evaluation
  StepEnds ends_;  // the open contacts' gaps and rates at the step's ends
  // ends_.gap0 and gN0 hold the gaps and rates at t_; when false, free steps skipped them and
  // gap_floors_ bounds the gaps at t_ from below instead.
  bool gaps_exact_ = true;
  GapFloors& gap_floors_;  // the workspace's, reset for the run
  // Spares ScanCoordinateMaxima's and travel_'s root searches of a full free step [docs/theory.md
  // §3.20].
  FreeStepPeaks peaks_;
  // The key of NominalFreeStep's last value (NaN: none yet) and the value (s).
  double nominal_length_s_ = std::numeric_limits<double>::quiet_NaN();
  double nominal_omega_radps_ = std::numeric_limits<double>::quiet_NaN();
  double nominal_h_s_ = 0.0;
  const FreePropagator* propagator_ = nullptr;  // the last full step's (StepPropagator)
  PieceCursor pieces_;                          // the free steps' excitation piece
  // The gaps' and rates' scratch, every contact's mode and the closed set: the workspace's
  // (RunStorage), so a run neither copies nor allocates them.
  contact::GapRateScratch& rates_;
  ClosedEvents events_;  // the closed contacts' event functions
  ContactModes& modes_;
  std::vector<int> forced_;  // contacts striking together at the located impact
  RunResult result_;
  // The decks' corner travels (result_.max_travel_m): the workspace's, moved in for the run.
  CornerTravelTracker travel_;
  DecisionMemory& memory_;  // what the mode decision remembers (the workspace's RunStorage)
  DecisionLog log_;         // the events and counts the decisions add
  // A history sample's force evaluation (with histories only): recording leaves ws_.forces_ as
  // it was, so a run takes the same decisions whether it records histories or not.
  std::unique_ptr<ActiveForcesStorage> sample_forces_;
  // Sees the free steps until the first event (Simulate's observer), and the state at the
  // start of the step it is shown.
  FreeStepObserver* observer_ = nullptr;
  Vec observed_z0_;
  long initial_steps_ = 0;  // free steps before the run's start (InitialState::free_steps)
};

}  // namespace skewbridge::dynamics
