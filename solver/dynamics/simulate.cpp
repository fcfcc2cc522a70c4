#include "solver/dynamics/simulate.h"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "solver/common/error.h"
#include "solver/dynamics/active_forces.h"
#include "solver/dynamics/active_system.h"
#include "solver/dynamics/contact_modes.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/event_location.h"
#include "solver/dynamics/indeterminate_split.h"
#include "solver/dynamics/mode_decision.h"
#include "solver/dynamics/projection.h"
#include "solver/dynamics/root_finding.h"
#include "solver/dynamics/run_scales.h"
#include "solver/dynamics/step_grid.h"
#include "solver/lcp/small_lp.h"

namespace skewbridge::dynamics {

const char* ToString(RunStatus status) {
  switch (status) {
    case RunStatus::kOk:
      return "ok";
    case RunStatus::kPainleve:
      return "painleve";
    case RunStatus::kLcpFailure:
      return "lcp-failure";
    case RunStatus::kStepLimit:
      return "step-limit";
    case RunStatus::kNonFinite:
      return "non-finite";
    case RunStatus::kEventCascade:
      return "event-cascade";
  }
  return "unknown";
}

std::string NonFiniteMessage(double t_before_s, double t_s) {
  return fmt::format(
      "the state (q, u) stopped being finite (or its square overflowed) between t = {:g} s and "
      "t = {:g} s (a load or a stiffness beyond any bridge)",
      t_before_s, t_s);
}

const char* ToString(EventKind kind) {
  switch (kind) {
    case EventKind::kImpact:
      return "impact";
    case EventKind::kPlasticClosure:
      return "plastic-closure";
    case EventKind::kDetachment:
      return "detachment";
    case EventKind::kStick:
      return "stick";
    case EventKind::kSlip:
      return "slip";
  }
  return "unknown";
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Gauss-Legendre nodes and weights on [0, 1] (8 points: exact to degree 15).
constexpr double kGaussNode[8] = {0.019855071751231856, 0.10166676129318664, 0.2372337950418355,
                                  0.4082826787521751,   0.5917173212478249,  0.7627662049581645,
                                  0.8983332387068134,   0.9801449282487681};
constexpr double kGaussWeight[8] = {0.05061426814518813, 0.11119051722668724, 0.15685332293894363,
                                    0.18134189168918100, 0.18134189168918100, 0.15685332293894363,
                                    0.11119051722668724, 0.05061426814518813};

}  // namespace

/// The state machine of one run (see simulate.h); lives for one Simulate call. It is the mode
/// decision's source of constrained forces (ActiveForces).
class Integrator final : private ConstrainedForces {
 public:
  Integrator(const model::Model& model, const Excitation& excitation,
             const model::RunControl& control, SimulationWorkspace& ws, const InitialState& initial,
             const EventPolicy& policy);

  RunResult Run();

 private:
  using Vec = Eigen::VectorXd;

  auto q() { return z_.head(n_); }
  auto u() { return z_.segment(n_, n_); }
  bool AnyClosed() const { return modes_.any_closed(); }
  bool Failed() const { return result_.status != RunStatus::kOk; }
  void Fail(RunStatus status, const std::string& message) {
    result_.status = status;
    result_.message = message;
  }

  // The result at the end of the run: the final state, the decisions' events and counts, the
  // energy ledger, and the non-finite status if the state or its energy is no number.
  RunResult Finish();
  // Contact-free phase: one exact step (or up to an impact).
  void FreeStep();
  // Constrained phase: one Runge-Kutta step (or up to an event).
  void ConstrainedStep();

  // Forces of the active set `modes` at (t, q, u) into `storage`: du/dt, lambda per contact,
  // the friction power [solver/dynamics/active_forces.h]. Inside a constrained phase's stages
  // and event searches (closed_only_) only the closed contacts' kinematics are evaluated.
  void ActiveForces(const ContactModes& modes, double t, const Eigen::Ref<const Vec>& q,
                    const Eigen::Ref<const Vec>& u, Eigen::Ref<Vec> du,
                    ActiveForcesStorage& storage) {
    EvaluateActiveForces(model_, modes, policy_, scales_.force_tol_N, GroundAcceleration(t), q, u,
                         closed_only_ ? KinematicsOf::kClosedContacts : KinematicsOf::kAllContacts,
                         du, storage);
  }
  void Rhs(double t, const Eigen::Ref<const Vec>& y, Eigen::Ref<Vec> dy);
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

  // The first impact of an open contact in the step [t0, t1] (+inf: none) [docs/theory.md
  // §3.12]: each contact whose gaps and rates at the step's ends (gap0_, gN0_, gap1_, gN1_) make
  // an impact suspected (ImpactSuspected with `dip_margin`) is searched by FirstGapRoot on the
  // dense output: positions_at(t) gives q at t, state_at(t) a vector whose heads are q and u.
  template <class PositionsAt, class StateAt>
  double FirstImpact(double t0, double t1, double dip_margin, PositionsAt&& positions_at,
                     StateAt&& state_at);
  // The impact time of the open contact c in [t0, t1] (FirstGapRoot on the dense output).
  template <class PositionsAt, class StateAt>
  double GapRoot(int c, double t0, double t1, PositionsAt&& positions_at, StateAt&& state_at);
  // component_at(t, i): entry i of (q, u) at t alone; the root search for a velocity zero needs
  // one entry, not the whole state.
  template <class ComponentAt>
  void ScanMaxima(double t0, const Eigen::Ref<const Vec>& q0, const Eigen::Ref<const Vec>& u0,
                  double t1, const Eigen::Ref<const Vec>& q1, const Eigen::Ref<const Vec>& u1,
                  ComponentAt&& component_at);
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
  double GapAt(int c, const Eigen::Ref<const Vec>& q) const { return contact::Gap(model_, c, q); }
  double NormalRateAt(int c, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u) {
    return contact::NormalRate(model_, c, q, u, rates_);
  }
  // Gaps and normal rates of every contact at (q, u), without the rest of the kinematics.
  void GapsAndRates(const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u, Vec& gap,
                    Vec& gamma_N) {
    contact::GapsAndRates(model_, q, u, gap, gamma_N, rates_);
  }
  Eigen::Vector2d GroundAcceleration(double t) const { return excitation_.At(t); }

  const model::Model& model_;
  const Excitation& excitation_;
  const model::RunControl& control_;
  const EventPolicy policy_;
  SimulationWorkspace& ws_;
  int n_, nc_;
  double t_ = 0.0, t_end_ = 0.0;
  long steps_ = 0;
  double t_finite_ = 0.0;  // the last time the state was checked finite (s)
  Vec z_, z_new_, z_eval_;
  Vec y_, dy_, y_eval_, atol_;
  Vec cu_;  // C u
  Vec q_a_, u_a_, q_b_, u_b_, du_;
  Vec gap0_, gN0_, gap1_, gN1_;
  contact::GapRateScratch rates_;  // scratch of the gaps and normal rates
  Vec f0_, f1_, f_eval_;           // closed-contact event functions: step start, end, trial
  ContactModes modes_;             // every contact's mode and the closed set
  std::vector<int> forced_;        // contacts striking together at the located impact
  // Set inside Runge-Kutta stages and event searches of a constrained phase: ActiveForces then
  // evaluates the kinematics of the closed contacts only (the open ones' gaps are read at the
  // step's ends).
  bool closed_only_ = false;
  double h_rk_ = 0.0;
  double h_free_ = 0.0;  // the last nominal free step (s)
  // The run's tolerances and scales [docs/theory.md §3.2], which the decision, the projection,
  // the event functions and the event searches compare with.
  DecisionScales scales_;
  double next_output_t_ = kInf;
  RunResult result_;
  CornerTravelTracker travel_;   // the decks' corner travels (result_.max_travel_m)
  DecisionMemory memory_;        // what the mode decision remembers between instants
  DecisionLog log_;              // the events and counts the decisions add
  ActiveForcesStorage& forces_;  // the workspace's: the integrator's own force evaluations
  // A history sample's force evaluation (with histories only): recording leaves forces_ as it
  // was, so a run takes the same decisions whether it records histories or not.
  std::unique_ptr<ActiveForcesStorage> sample_forces_;
};

SimulationWorkspace::SimulationWorkspace(const model::Model& model)
    : model_(model),
      flow_(model.M(), model.K(), model.C(), model.r(), FlowPath::kAuto, model.modes()),
      free_dense_(flow_.augmented_size()),
      rk_(2 * model.n_dof() + 3),
      forces_(model, EventPolicy{}.rank_threshold),
      decision_(model, EventPolicy{}.rank_threshold) {
  if (flow_.modal()) {
    // The modal flow's w_k^2 are the eigenvalues below, clamped at 0: one solve, same bits.
    const Eigen::VectorXd& w2 = flow_.modal_flow().w2();
    omega_max_radps_ = std::sqrt(w2.maxCoeff());
    omega_min_radps_ = std::sqrt(w2.minCoeff());
  } else {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(model.K(), model.M(),
                                                                        Eigen::EigenvaluesOnly);
    const Eigen::VectorXd w2 = eig.eigenvalues();
    omega_max_radps_ = std::sqrt(std::max(w2.maxCoeff(), 0.0));
    omega_min_radps_ = std::sqrt(std::max(w2.minCoeff(), 0.0));
  }
  for (const model::Body& body : model.bodies()) {
    length_scale_m_ = std::max({length_scale_m_, body.geometry.length_m, body.geometry.width_m,
                                body.rest_position_m.norm() + body.geometry.length_m});
  }
}

Integrator::Integrator(const model::Model& model, const Excitation& excitation,
                       const model::RunControl& control, SimulationWorkspace& ws,
                       const InitialState& initial, const EventPolicy& policy)
    : model_(model),
      excitation_(excitation),
      control_(control),
      policy_(policy),
      ws_(ws),
      n_(model.n_dof()),
      nc_(model.n_contacts()),
      modes_(model.n_contacts()),
      travel_(model),
      memory_(model.n_contacts()),
      forces_(ws.forces_) {
  SB_DEMAND(&ws.model() == &model, "Simulate: workspace built for another model");
  ValidatePolicy(policy);
  // The contact layer's thresholds of this run [docs/theory.md §3.15]: the workspace's problems
  // keep those of the last run otherwise.
  ws.decision_.impact.SetPolicy(policy.contact);
  ws.decision_.contact_problem.SetPolicy(policy.contact);
  const int naug = ws.flow_.augmented_size();
  z_ = Vec::Zero(naug);
  z_new_ = z_eval_ = z_;
  if (initial.q.size() != 0) {
    if (initial.q.size() != n_) {
      throw InputError::AtField("initial state", "q", "must have n_dof entries");
    }
    z_.head(n_) = initial.q;
  }
  if (initial.u.size() != 0) {
    if (initial.u.size() != n_) {
      throw InputError::AtField("initial state", "u", "must have n_dof entries");
    }
    z_.segment(n_, n_) = initial.u;
  }
  y_ = Vec::Zero(2 * n_ + 3);
  dy_ = y_eval_ = y_;
  atol_ = Vec::Constant(2 * n_ + 3, kInf);
  q_a_ = u_a_ = q_b_ = u_b_ = du_ = cu_ = Vec::Zero(n_);
  gap0_ = gN0_ = gap1_ = gN1_ = Vec::Zero(nc_);
  f0_ = f1_ = f_eval_ = Vec::Zero(2 * nc_);
  forced_.reserve(static_cast<std::size_t>(nc_));
  rates_.Resize(model);
  forces_.sys.SetRankThreshold(policy.rank_threshold);
  ws.decision_.projection.sys.SetRankThreshold(policy.rank_threshold);

  t_end_ = control.EndTime(excitation.Duration());
  // The scales of the response, and the tolerances relative to them [docs/theory.md §3.2].
  const RunScales scales = ComputeRunScales(
      ExcitationPeak(excitation, policy_.ramp_horizon_s), z_.segment(n_, n_).cwiseAbs().maxCoeff(),
      {ws.omega_min_radps_, ws.omega_max_radps_, ws.length_scale_m_, MaxTranslationalMass(model)},
      control.accumulation_threshold, policy_);
  scales_ = {.v_tol_mps = scales.v_tol_mps,
             .v_acc_mps = scales.v_acc_mps,
             .gap_tol_m = scales.gap_tol_m,
             .force_tol_N = scales.force_tol_N,
             .a_detach_mps2 = scales.a_detach_mps2,
             .period_min_s = scales.period_min_s,
             .length_scale_m = ws.length_scale_m_,
             .simultaneity_s = control.simultaneity_tolerance_s};
  const double omega_top = scales.omega_top_radps;
  atol_.head(n_).setConstant(control.absolute_tolerance);
  atol_.segment(n_, n_).setConstant(control.absolute_tolerance * omega_top);
  h_rk_ = scales.first_rk_step_s;

  result_.max_abs_q = z_.head(n_).cwiseAbs();
  result_.time_of_max_s = Vec::Zero(n_);
  travel_.Start(z_.head(n_), result_.max_travel_m);
  log_.events.reserve(1024);
  if (control.output_interval_s > 0.0) {
    const auto samples = static_cast<std::size_t>(t_end_ / control.output_interval_s) + 2;
    Histories& hist = result_.histories;
    hist.n_dof = n_;
    hist.n_contacts = nc_;
    hist.t_s.reserve(samples);
    hist.q.reserve(samples * n_);
    hist.u.reserve(samples * n_);
    hist.gap_m.reserve(samples * nc_);
    hist.lambda_N.reserve(samples * nc_);
    hist.lambda_T.reserve(samples * nc_);
    hist.state.reserve(samples * nc_);
    sample_forces_ = std::make_unique<ActiveForcesStorage>(model, policy.rank_threshold);
    next_output_t_ = 0.0;
  }
}

RunResult Integrator::Run() {
  // The step loop [docs/theory.md §3.1]: the mode decision at t = 0, then one free step (no
  // contact closed) or one constrained step at a time, each ending at its end or at its first
  // event, where the step calls the decision (ResolveContacts) again.
  ws_.flow_.SetGenerator(excitation_.PieceAt(0.0), 0.0, z_);
  result_.energy.initial_J = ws_.flow_.MechanicalEnergy(z_);
  RecordOutputs(0.0, 0.0, [&](double) -> const Vec& { return z_; });
  forced_.clear();
  ResolveContacts(forced_);
  while (!Failed() && t_ < t_end_) {
    if (++steps_ > control_.max_steps) {
      Fail(RunStatus::kStepLimit,
           fmt::format("step limit of {} reached at t = {:g} s", control_.max_steps, t_));
      break;
    }
    if (AnyClosed()) {
      ConstrainedStep();
    } else {
      FreeStep();
    }
    // Every finite_check_steps steps (a fraction of a second of most runs) the state must
    // still be finite; so the check costs a few instructions a step, and a run that went
    // non-finite stops within that many steps, its message naming the window.
    if ((steps_ & (policy_.finite_check_steps - 1)) == 0) {
      if (!StateFinite(z_) || !std::isfinite(t_)) {
        break;
      }
      t_finite_ = t_;
    }
  }
  return Finish();
}

RunResult Integrator::Finish() {
  if (!StateFinite(z_) || !std::isfinite(t_)) {
    // Whatever else stopped the run, a state that is no number is the first thing to report.
    Fail(RunStatus::kNonFinite, NonFiniteMessage(t_finite_, t_));
    t_ = std::isfinite(t_) ? t_ : t_finite_;
  }
  result_.end_time_s = t_;
  result_.q_end = q();
  result_.u_end = u();
  result_.impacts = log_.impacts;
  result_.plastic_closures = log_.plastic_closures;
  result_.detachments = log_.detachments;
  result_.stick_transitions = log_.stick_transitions;
  result_.slip_transitions = log_.slip_transitions;
  result_.min_impact_separation_s = log_.min_impact_separation_s;
  result_.events = std::move(log_.events);
  EnergyLedger& e = result_.energy;
  e.impact_J = log_.impact_J;
  e.kinetic_J = Kinetic();
  e.strain_J = 0.5 * q().dot(model_.K() * q());
  e.balance_error_J = (e.kinetic_J + e.strain_J) -
                      (e.initial_J + e.input_J - e.damping_J - e.impact_J - e.friction_J);
  if (!Failed() && !std::isfinite(e.kinetic_J + e.strain_J)) {
    // A finite state whose energy overflows is no result either.
    Fail(
        RunStatus::kNonFinite,
        fmt::format(
            "the energy of the state is not finite at t = {:g} s (the state overflows its squares)",
            t_));
  }
  if (!control_.energy_ledger) {
    // The free steps' work was not integrated: what remains would look like a ledger but is not.
    e.input_J = e.damping_J = e.balance_error_J = std::numeric_limits<double>::quiet_NaN();
  }
  return std::move(result_);
}

void Integrator::FreeStep() {
  LinearFlow& flow = ws_.flow_;
  const ExcitationPiece piece = excitation_.PieceAt(t_);
  // The Excitation contract: the piece at t extends beyond t. A piece ending at t would make
  // zero-length steps until the step budget runs out, so stop at once instead.
  SB_DEMAND(piece.t_end > t_, "Excitation::PieceAt(t) returned a piece that ends at or before t");
  // The step on the piece's grid, the previous step reused and snapped [docs/theory.md §3.14].
  const FreeStepPlan step =
      PlanFreeStep(t_, piece.t_begin, std::min(piece.t_end, t_end_),
                   FreeStepSize(piece, ws_.omega_max_radps_, policy_), h_free_, policy_);
  h_free_ = step.h_s;
  const double h = step.h_s;
  double t_next = step.t_next_s;
  const double tau = t_next - t_;
  const bool full = step.full;
  flow.SetGenerator(piece, t_, z_);
  bool dense_built = false;
  auto ensure_dense = [&]() {
    if (!dense_built) {
      ws_.free_dense_.Build(flow, piece.omega, z_, tau);
      dense_built = true;
    }
  };
  double input = 0.0, damping = 0.0;
  const bool ledger = control_.energy_ledger;
  if (full) {
    const FreePropagator& p = flow.Propagator(h, piece.omega, ledger);
    flow.Apply(p, z_, z_new_, ledger ? &input : nullptr, ledger ? &damping : nullptr);
  } else {
    ensure_dense();
    ws_.free_dense_.Evaluate(tau, z_new_);
  }
  ++result_.free_steps;

  // The flow's dense output inside the step, in z_eval_: q alone (half the modal series: what a
  // gap needs), or q and u.
  const auto positions_at = [&](double t) {
    ensure_dense();
    ws_.free_dense_.EvaluateHead(t - t_, n_, z_eval_);
    return z_eval_.head(n_);
  };
  const auto state_at = [&](double t) -> const Vec& {
    ensure_dense();
    ws_.free_dense_.EvaluateHead(t - t_, 2 * n_, z_eval_);
    return z_eval_;
  };
  GapsAndRates(z_new_.head(n_), z_new_.segment(n_, n_), gap1_, gN1_);
  const double t_event = FirstImpact(t_, t_next, policy_.dip_margin, positions_at, state_at);
  forced_.clear();
  if (t_event < kInf) {
    // Near-simultaneous: contacts closed within the tolerance after the first are one impact.
    const auto q_late = positions_at(std::min(t_event + control_.simultaneity_tolerance_s, t_next));
    for (int c = 0; c < nc_; ++c) {
      if (GapAt(c, q_late) <= scales_.gap_tol_m) {
        forced_.push_back(c);
      }
    }
    t_next = t_event;
    ws_.free_dense_.EvaluateHead(t_next - t_, 2 * n_, z_new_);  // what state_at(t_next) gives
  }
  if (ledger && (!full || t_event < kInf)) {
    // Energy of a partial step by Gauss-Legendre quadrature of the exact (Taylor) solution.
    ensure_dense();
    input = damping = 0.0;
    const double len = t_next - t_;
    for (int i = 0; i < 8; ++i) {
      ws_.free_dense_.Evaluate(kGaussNode[i] * len, z_eval_);
      double p_in, p_d;
      flow.Powers(z_eval_, p_in, p_d);
      input += kGaussWeight[i] * len * p_in;
      damping += kGaussWeight[i] * len * p_d;
    }
  }
  result_.energy.input_J += input;
  result_.energy.damping_J += damping;
  // The step's ends in place (no copies): the velocity-zero search reads the dense output only.
  const auto component_at = [&](double t, int i) {
    ensure_dense();
    return ws_.free_dense_.EvaluateComponent(t - t_, i);
  };
  ScanMaxima(t_, q(), u(), t_next, z_new_.head(n_), z_new_.segment(n_, n_), component_at);
  // The corner travels, at the same exactness: step ends and the roots of each corner's rate.
  travel_.Scan(t_, q(), u(), t_next, z_new_.head(n_), z_new_.segment(n_, n_),
               MaximumTimeTolerance(t_next), component_at, result_.max_travel_m);
  RecordOutputs(t_, t_next, state_at);
  z_.head(2 * n_) = z_new_.head(2 * n_);
  t_ = t_next;
  if (t_event < kInf) {
    ResolveContacts(forced_);
  } else {
    gap0_ = gap1_;
    gN0_ = gN1_;
  }
}

template <class PositionsAt, class StateAt>
inline double Integrator::FirstImpact(double t0, double t1, double dip_margin,
                                      PositionsAt&& positions_at, StateAt&& state_at) {
  double t_event = kInf;
  for (int c = 0; c < nc_; ++c) {
    // The suspicion first: it is false for most contacts in most steps.
    if (ImpactSuspected(gap0_[c], gN0_[c], gap1_[c], gN1_[c], t1 - t0, dip_margin) &&
        !modes_.closed(c)) {
      t_event = std::min(t_event, GapRoot(c, t0, t1, positions_at, state_at));
    }
  }
  return t_event;
}

template <class PositionsAt, class StateAt>
double Integrator::GapRoot(int c, double t0, double t1, PositionsAt&& positions_at,
                           StateAt&& state_at) {
  const auto gap = [&](double t) { return GapAt(c, positions_at(t)); };
  const auto gamma_N = [&](double t) {
    const Vec& s = state_at(t);
    return NormalRateAt(c, s.head(n_), s.segment(n_, n_));
  };
  return FirstGapRoot(t0, t1, gap0_[c], gN0_[c], gap1_[c], gN1_[c], gap, gamma_N, scales_.gap_tol_m,
                      scales_.v_tol_mps, policy_);
}

template <class ComponentAt>
void Integrator::ScanMaxima(double t0, const Eigen::Ref<const Vec>& q0,
                            const Eigen::Ref<const Vec>& u0, double t1,
                            const Eigen::Ref<const Vec>& q1, const Eigen::Ref<const Vec>& u1,
                            ComponentAt&& component_at) {
  for (int i = 0; i < n_; ++i) {
    if (std::abs(q1[i]) > result_.max_abs_q[i]) {
      result_.max_abs_q[i] = std::abs(q1[i]);
      result_.time_of_max_s[i] = t1;
    }
    if (u0[i] * u1[i] < 0.0) {
      const double bound = std::max(std::abs(q0[i]), std::abs(q1[i])) +
                           0.5 * (t1 - t0) * std::max(std::abs(u0[i]), std::abs(u1[i]));
      if (bound > result_.max_abs_q[i]) {
        const auto velocity = [&](double t) { return component_at(t, n_ + i); };
        const RootResult peak =
            FindRootBrent(velocity, t0, t1, u0[i], u1[i], MaximumTimeTolerance(t1));
        const double q_peak = std::abs(component_at(peak.x, i));
        if (q_peak > result_.max_abs_q[i]) {
          result_.max_abs_q[i] = q_peak;
          result_.time_of_max_s[i] = peak.x;
        }
      }
    }
  }
}

template <class StateAt>
void Integrator::RecordOutputs(double t0, double t1, StateAt&& state_at) {
  while (next_output_t_ <= t1 + policy_.output_time_band * std::max(1.0, t1) &&
         next_output_t_ <= t_end_ + policy_.output_time_band) {
    const Vec& s = state_at(std::max(t0, std::min(next_output_t_, t1)));
    RecordSample(next_output_t_, s.head(n_), s.segment(n_, n_));
    next_output_t_ = control_.output_interval_s * static_cast<double>(result_.histories.t_s.size());
  }
}

void Integrator::RecordSample(double t, const Eigen::Ref<const Vec>& qq,
                              const Eigen::Ref<const Vec>& uu) {
  // The forces at the sample go into the sample's own scratch: the integrator's kinematics,
  // applied forces and lambda stay those of its last evaluation, so a run takes the same
  // decisions whether it records histories or not.
  Histories& hist = result_.histories;
  ActiveForcesStorage& forces = *sample_forces_;
  if (AnyClosed()) {
    ActiveForces(modes_, t, qq, uu, du_, forces);  // du_: scratch, read by no later step
  }
  hist.t_s.push_back(t);
  for (int i = 0; i < n_; ++i) {
    hist.q.push_back(qq[i]);
    hist.u.push_back(uu[i]);
  }
  for (int c = 0; c < nc_; ++c) {
    hist.gap_m.push_back(contact::Gap(model_, c, qq));
    const bool closed = modes_.closed(c);
    hist.lambda_N.push_back(closed ? forces.lambda_N[c] : 0.0);
    hist.lambda_T.push_back(closed ? forces.lambda_T[c] : 0.0);
    hist.state.push_back(static_cast<int>(HistoryState(modes_[c])));
  }
}

void Integrator::Rhs(double t, const Eigen::Ref<const Vec>& y, Eigen::Ref<Vec> dy) {
  const auto qq = y.head(n_);
  const auto uu = y.segment(n_, n_);
  ActiveForces(modes_, t, qq, uu, du_, forces_);
  dy.head(n_) = uu;
  dy.segment(n_, n_) = du_;
  if (!control_.energy_ledger) {
    // The work integrals ride along in y with an infinite absolute tolerance: they never steer
    // the step size, so leaving them at zero changes no response.
    dy.tail(3).setZero();
    return;
  }
  const Eigen::Vector2d ag = GroundAcceleration(t);
  // M is diagonal: -u^T M r a_g without a temporary.
  const Vec& m_diag = model_.mass_diagonal();
  dy[2 * n_] = -(ag(0) * uu.dot(m_diag.cwiseProduct(model_.r().col(0))) +
                 ag(1) * uu.dot(m_diag.cwiseProduct(model_.r().col(1))));
  cu_.noalias() = model_.C() * uu;
  dy[2 * n_ + 1] = uu.dot(cu_);
  dy[2 * n_ + 2] = forces_.friction_power_W;
}

void Integrator::ClosedEventValues(Eigen::Ref<Vec> values) const {
  dynamics::ClosedEventValues(model_, modes_, forces_.kin.gamma_T, forces_.lambda_N,
                              forces_.lambda_T, scales_.force_tol_N, scales_.v_tol_mps, values);
}

void Integrator::ConstrainedStep() {
  const ExcitationPiece piece = excitation_.PieceAt(t_);
  SB_DEMAND(piece.t_end > t_, "Excitation::PieceAt(t) returned a piece that ends at or before t");
  const double h = ConstrainedStepLength(t_, std::min(piece.t_end, t_end_), h_rk_, policy_);
  y_.head(2 * n_) = z_.head(2 * n_);
  y_.tail(3).setZero();
  const auto rhs = [this](double t, const Eigen::Ref<const Vec>& y, Eigen::Ref<Vec> dy) {
    Rhs(t, y, dy);
  };
  Rhs(t_, y_, dy_);
  ClosedEventValues(f0_);
  gap0_ = forces_.kin.gap_m;
  gN0_ = forces_.kin.gamma_N;
  DormandPrince45& rk = ws_.rk_;
  closed_only_ = true;
  rk.Step(rhs, t_, y_, dy_, h);
  closed_only_ = false;
  const double err = rk.ErrorNorm(atol_, control_.relative_tolerance);
  if (!(err <= 1.0)) {
    ++result_.rk_rejected;
    h_rk_ =
        h * DormandPrince45::StepFactor(std::isfinite(err) ? err : policy_.nonfinite_step_error);
    return;
  }
  ++result_.rk_steps;
  const double t1 = t_ + h;
  const Vec& y1 = rk.y_end();
  // The last stage of the step was evaluated at (t1, y1) (first same as last): the closed
  // contacts' forces and kinematics are those of the step's end, so their event functions need
  // no further evaluation; the open contacts need only their gaps and normal rates.
  ClosedEventValues(f1_);
  GapsAndRates(y1.head(n_), y1.segment(n_, n_), gap1_, gN1_);
  // The step's dense output, in y_eval_: q alone (what a gap needs), or the whole state.
  const auto positions_at = [&](double t) {
    rk.DenseHeadAt(t, n_, y_eval_);
    return y_eval_.head(n_);
  };
  const auto state_at = [&](double t) -> const Vec& {
    rk.DenseAt(t, y_eval_);
    return y_eval_;
  };
  // Every dip of an open contact's gap is searched (kEveryDip): the Hermite margin of the free
  // step rests on its length, which a Runge-Kutta step does not have [docs/theory.md §3.12].
  double t_event = FirstImpact(t_, t1, kEveryDip, positions_at, state_at);
  const double x_tol = EventTimeBracket(t1, policy_);
  for (int c = 0; c < nc_; ++c) {
    if (!modes_.closed(c)) {
      continue;
    }
    for (int e = 2 * c; e <= 2 * c + 1; ++e) {
      if (f1_[e] < 0.0 && f0_[e] >= 0.0) {
        const auto fe = [&](double t) {
          const Vec& y = state_at(t);
          closed_only_ = true;
          ActiveForces(modes_, t, y.head(n_), y.segment(n_, n_), du_, forces_);
          closed_only_ = false;
          ClosedEventValues(f_eval_);
          return f_eval_[e];
        };
        const RootResult root = FindRootBrent(fe, t_, t1, f0_[e], f1_[e], x_tol);
        t_event = std::min(t_event, root.fx < 0.0 ? root.x : root.upper);
      } else if (f1_[e] < 0.0) {
        t_event = std::min(t_event, t_);
      }
    }
  }
  const double t_new = t_event < kInf ? std::max(t_event, t_) : t1;
  rk.DenseAt(t_new, y_eval_);
  if (t_event == kInf) {
    y_eval_ = y1;
  }
  result_.energy.input_J += y_eval_[2 * n_];
  result_.energy.damping_J += y_eval_[2 * n_ + 1];
  result_.energy.friction_J += y_eval_[2 * n_ + 2];
  q_a_ = z_.head(n_);
  u_a_ = z_.segment(n_, n_);
  q_b_ = y_eval_.head(n_);
  u_b_ = y_eval_.segment(n_, n_);
  const auto component_at = [&](double t, int i) { return rk.DenseComponentAt(t, i); };
  ScanMaxima(t_, q_a_, u_a_, t_new, q_b_, u_b_, component_at);
  travel_.Scan(t_, q_a_, u_a_, t_new, q_b_, u_b_, MaximumTimeTolerance(t_new), component_at,
               result_.max_travel_m);
  RecordOutputs(t_, t_new, state_at);
  z_.head(n_) = q_b_;
  z_.segment(n_, n_) = u_b_;
  t_ = t_new;
  h_rk_ = t_event < kInf ? h : h * DormandPrince45::StepFactor(err);
  if (t_event < kInf) {
    forced_.clear();
    ResolveContacts(forced_);
  } else {
    Project();
  }
}

void Integrator::Project() {
  // The projection onto the closed contacts' constraints [docs/theory.md §3.10], in the
  // decision's storage (the next step evaluates its own kinematics).
  ProjectOntoContacts(model_, modes_, policy_,
                      {scales_.length_scale_m, scales_.gap_tol_m, scales_.v_tol_mps}, q(), u(),
                      ws_.decision_.projection);
}

void Integrator::ResolveContacts(const std::vector<int>& forced) {
  const DecisionOutcome outcome =
      DecideModes(model_, policy_, scales_, {t_, GroundAcceleration(t_), forced}, q(), u(), modes_,
                  memory_, *this, ws_.decision_, log_);
  if (outcome.status != RunStatus::kOk) {
    Fail(outcome.status, outcome.message);
    return;
  }
  // The decision left its kinematics of every contact at its final state: the gaps of the next
  // step's start need no further evaluation.
  gap0_ = ws_.decision_.projection.kin.gap_m;
  gN0_ = ws_.decision_.projection.kin.gamma_N;
}

void Integrator::Forces(const ContactModes& modes, double t, const Eigen::Ref<const Vec>& qq,
                        const Eigen::Ref<const Vec>& uu, Eigen::Ref<Vec> lambda_N,
                        Eigen::Ref<Vec> lambda_T) {
  ActiveForces(modes, t, qq, uu, du_, forces_);
  lambda_N = forces_.lambda_N;
  lambda_T = forces_.lambda_T;
}

RunResult Simulate(const model::Model& model, const Excitation& excitation,
                   const model::RunControl& control, SimulationWorkspace& workspace,
                   const InitialState& initial, const EventPolicy& policy) {
  Integrator integrator(model, excitation, control, workspace, initial, policy);
  return integrator.Run();
}

}  // namespace skewbridge::dynamics
