#include "solver/dynamics/simulate.h"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include "solver/common/error.h"
#include "solver/dynamics/active_forces.h"
#include "solver/dynamics/active_system.h"
#include "solver/dynamics/contact_modes.h"
#include "solver/dynamics/coordinate_maxima.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/event_location.h"
#include "solver/dynamics/gap_floors.h"
#include "solver/dynamics/gauss_legendre.h"
#include "solver/dynamics/indeterminate_split.h"
#include "solver/dynamics/integrator.h"
#include "solver/dynamics/mode_decision.h"
#include "solver/dynamics/peak_bound.h"
#include "solver/dynamics/projection.h"
#include "solver/dynamics/root_finding.h"
#include "solver/dynamics/run_scales.h"
#include "solver/dynamics/step_grid.h"
#include "solver/lcp/small_lp.h"

namespace skewbridge::dynamics {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

Integrator::Integrator(const model::Model& model, const Excitation& excitation,
                       const model::RunControl& control, SimulationWorkspace& ws,
                       const InitialState& initial, const EventPolicy& policy,
                       FreeStepObserver* observer, SpringSet* springs)
    : model_(model),
      excitation_(excitation),
      control_(control),
      policy_(policy),
      ws_(ws),
      n_(model.n_dof()),
      nc_(model.n_contacts()),
      gap_floors_(ws.gap_floors_),
      peaks_(ws.flow_.modal() ? &ws.flow_.modal_flow() : nullptr),
      rates_(ws.run_storage_.rates),
      modes_(ws.run_storage_.modes),
      memory_(ws.run_storage_.memory),
      observer_(observer) {
  SB_DEMAND(&ws.model() == &model, "Simulate: workspace built for another model");
  // The state's storage is the workspace's (RunStorage): the assignments below size and write
  // every entry a new run's would have, allocating only when the sizes differ.
  SwapStorage();
  // A recycled result's vectors (SimulationWorkspace::Recycle): each is assigned whole below or
  // in Finish; the rest of result_ is a new RunResult's.
  RunResult& spare = ws.run_storage_.result;
  result_.max_abs_q.swap(spare.max_abs_q);
  result_.time_of_max_s.swap(spare.time_of_max_s);
  result_.max_travel_m.swap(spare.max_travel_m);
  result_.q_end.swap(spare.q_end);
  result_.u_end.swap(spare.u_end);
  result_.events.swap(spare.events);
  result_.events.clear();
  modes_ = ws.run_storage_.fresh_modes;
  memory_ = ws.run_storage_.fresh_memory;
  log_.events.clear();
  forced_.clear();
  gap_floors_.Reset();
  // A sweep's runs share one policy: its members are checked once per workspace, and again
  // whenever a run brings a member of other bits (the verdict depends on the members alone; the
  // padding between them is not compared).
  // The workspace's problems and active systems take the policy's thresholds here and nowhere
  // else: under a policy of the validated members they hold them already.
  if (!ws.policy_validated_ || !SameMembers(ws.validated_policy_, policy)) {
    ws.policy_validated_ = false;
    ValidatePolicy(policy);
    // The contact layer's thresholds [docs/theory.md §3.15] and the rank threshold.
    ws.decision_.impact.SetPolicy(policy.contact);
    ws.decision_.contact_problem.SetPolicy(policy.contact);
    ws.forces_.sys.SetRankThreshold(policy.rank_threshold);
    ws.decision_.projection.sys.SetRankThreshold(policy.rank_threshold);
    ws.validated_policy_ = policy;
    ws.policy_validated_ = true;
  }
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
  if (initial.t_s != 0.0) {
    if (!(initial.t_s > 0.0) || !std::isfinite(initial.t_s) || initial.free_steps < 0 ||
        !(initial.h_free_s >= 0.0)) {
      throw InputError::AtField("initial state", "t_s",
                                "must be finite and > 0, with free_steps >= 0 and h_free_s >= 0");
    }
    t_ = initial.t_s;
    h_free_ = initial.h_free_s;
    initial_steps_ = initial.free_steps;
  }
  springs_ = springs;
  added_ = springs;
  // With springs, y carries their work and their friction's besides the three work integrals.
  ny_ = 2 * n_ + 3 + (springs != nullptr ? 2 : 0);
  y_ = Vec::Zero(ny_);
  dy_ = y_eval_ = y_;
  atol_ = Vec::Constant(ny_, kInf);
  if (springs != nullptr) {
    spring_e0_ = spring_e1_ = Vec::Zero(springs->n_events());
    spring_scratch_h_ = Vec::Zero(n_);
  }
  // The workspace's Runge-Kutta storage for y (a run with springs lengthens it, the next run
  // without shortens it again).
  if (ws_.rk_.size() != ny_) ws_.rk_.Resize(ny_);
  du_ = cu_ = Vec::Zero(n_);
  ends_.gap0 = ends_.gN0 = ends_.gap1 = ends_.gN1 = Vec::Zero(nc_);
  events_.f0 = events_.f1 = events_.f_eval = Vec::Zero(2 * nc_);
  forced_.reserve(static_cast<std::size_t>(nc_));
  rates_.Resize(model);

  t_end_ = control.EndTime(excitation.Duration());
  // The scales of the response, and the tolerances relative to them [docs/theory.md §3.2].
  const RunScales scales = ComputeRunScales(
      ExcitationPeak(excitation, policy_.ramp_horizon_s),
      t_ > 0.0 ? 0.0 : z_.segment(n_, n_).cwiseAbs().maxCoeff(),
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
  double omega_top = scales.omega_top_radps;
  if (springs != nullptr) {
    // The springs' own frequency joins the step control's velocity scale (as a compliant run's).
    omega_top =
        std::max(omega_top, std::sqrt(springs->StiffnessSum_Npm() / MaxTranslationalMass(model)));
  }
  atol_.head(n_).setConstant(control.absolute_tolerance);
  atol_.segment(n_, n_).setConstant(control.absolute_tolerance * omega_top);
  h_rk_ = scales.first_rk_step_s;

  result_.max_abs_q = z_.head(n_).cwiseAbs();
  result_.time_of_max_s = Vec::Constant(n_, t_);
  result_.free_steps = initial_steps_;
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
    if (t_ > 0.0) {
      // The grid's samples the run from rest recorded with the step ending at t_ (RecordOutputs).
      const double reach = t_ + policy_.output_time_band * std::max(1.0, t_);
      const double dt = control.output_interval_s;
      output_offset_ = static_cast<std::size_t>(std::max(0.0, std::floor(t_ / dt) - 1.0));
      while (dt * static_cast<double>(output_offset_) <= reach) ++output_offset_;
      next_output_t_ = dt * static_cast<double>(output_offset_);
    }
  }
  // The workspace's tracker, taken last, when nothing can throw any more (the destructor gives it
  // back).
  travel_ = std::move(ws.travel_);
  travel_.Start(z_.head(n_), result_.max_travel_m);
}

Integrator::~Integrator() {
  SwapStorage();
  ws_.travel_ = std::move(travel_);
}

void Integrator::SwapStorage() {
  RunStorage& s = ws_.run_storage_;
  for (auto [own, kept] : {std::pair{&z_, &s.z},
                           {&z_new_, &s.z_new},
                           {&z_eval_, &s.z_eval},
                           {&y_, &s.y},
                           {&dy_, &s.dy},
                           {&y_eval_, &s.y_eval},
                           {&atol_, &s.atol},
                           {&cu_, &s.cu},
                           {&du_, &s.du},
                           {&ends_.gap0, &s.gap0},
                           {&ends_.gN0, &s.gN0},
                           {&ends_.gap1, &s.gap1},
                           {&ends_.gN1, &s.gN1},
                           {&events_.f0, &s.f0},
                           {&events_.f1, &s.f1},
                           {&events_.f_eval, &s.f_eval},
                           {&observed_z0_, &s.observed_z0}}) {
    own->swap(*kept);
  }
  forced_.swap(s.forced);
  log_.events.swap(s.events);
}

RunResult Integrator::Run() {
  // The step loop [docs/theory.md §3.1]: the mode decision at t = 0, then one free step (no
  // contact closed) or one constrained step at a time, each ending at its end or at its first
  // event, where the step calls the decision (ResolveContacts) again.
  ws_.flow_.SetGenerator(excitation_.PieceAt(t_), t_, z_);
  // From rest (every entry of q and u +0.0) the energy is +0.0: each product of the finite M and
  // K with +0.0 is a zero, and a sum with a +0.0 in it is +0.0, so the forms give those bits.
  const bool at_rest = std::all_of(z_.data(), z_.data() + 2 * n_,
                                   [](double v) { return std::bit_cast<std::uint64_t>(v) == 0; });
  result_.energy.initial_J = at_rest ? 0.0 : ws_.flow_.MechanicalEnergy(z_);
  RecordOutputs(0.0, 0.0, [&](double) -> const Vec& { return z_; });
  forced_.clear();
  ResolveContacts(forced_);
  long steps = initial_steps_;
  double t_finite = t_;  // the last time the state was checked finite (s)
  const bool record_flight = RecordFlightApplies();
  while (!Failed() && t_ < t_end_) {
    if (++steps > control_.max_steps) {
      Fail(RunStatus::kStepLimit,
           fmt::format("step limit of {} reached at t = {:g} s", control_.max_steps, t_));
      break;
    }
    if (AnyClosed() || (springs_ != nullptr && !SpringsFree())) {
      ConstrainedStep();
    } else if (record_flight) {
      if (!RecordFlight(steps, t_finite)) {
        break;
      }
    } else if (observer_ != nullptr && log_.events.empty()) {
      const double t0 = t_, h0 = h_free_;
      observed_z0_ = z_.head(2 * n_);
      FreeStep();
      if (!Failed() && log_.events.empty() && !AnyClosed() &&
          !observer_->Step(t0, observed_z0_, h0, t_, z_.head(2 * n_), result_)) {
        break;
      }
    } else {
      FreeStep();
    }
    // Every finite_check_steps steps (a fraction of a second of most runs) the state must
    // still be finite; so the check costs a few instructions a step, and a run that went
    // non-finite stops within that many steps, its message naming the window.
    if ((steps & (policy_.finite_check_steps - 1)) == 0) {
      if (!StateFinite(z_) || !std::isfinite(t_)) {
        break;
      }
      t_finite = t_;
    }
  }
  return Finish(t_finite);
}

RunResult Integrator::Finish(double t_finite_s) {
  if (!StateFinite(z_) || !std::isfinite(t_)) {
    // Whatever else stopped the run, a state that is no number is the first thing to report.
    Fail(RunStatus::kNonFinite, NonFiniteMessage(t_finite_s, t_));
    t_ = std::isfinite(t_) ? t_ : t_finite_s;
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
  // A copy: the log's storage goes back to the workspace for the next run.
  result_.events = log_.events;
  EnergyLedger& e = result_.energy;
  e.impact_J = log_.impact_J;
  e.kinetic_J = Kinetic();
  // K q into the scratch cu_ (no later step reads it): the product's kernel, no temporary.
  cu_.noalias() = model_.K() * q();
  e.strain_J = 0.5 * q().dot(cu_);
  if (springs_ == nullptr) {
    e.balance_error_J = (e.kinetic_J + e.strain_J) -
                        (e.initial_J + e.input_J - e.damping_J - e.impact_J - e.friction_J);
  } else {
    FinishSprings(e);
  }
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
  // Advance: the exact flow over one step of the piece's grid, the previous step reused and
  // snapped [docs/theory.md §3.14].
  const ExcitationPiece& piece = pieces_.At(excitation_, t_);
  // The Excitation contract: the piece at t extends beyond t. A piece ending at t would make
  // zero-length steps until the step budget runs out, so stop at once instead.
  SB_DEMAND(piece.t_end > t_, "Excitation::PieceAt(t) returned a piece that ends at or before t");
  const FreeStepPlan step = PlanFreeStep(t_, piece.t_begin, std::min(piece.t_end, t_end_),
                                         NominalFreeStep(piece), h_free_, policy_);
  h_free_ = step.h_s;
  FreeStepOf(piece, step);
}

void Integrator::FreeStepOf(const ExcitationPiece& piece, const FreeStepPlan& step) {
  LinearFlow& flow = ws_.flow_;
  const double tau = step.t_next_s - t_;
  flow.SetGenerator(piece, t_, z_);
  double input = 0.0, damping = 0.0;
  const bool ledger = control_.energy_ledger;
  if (step.full) {
    const FreePropagator& p = StepPropagator(step.h_s, piece.omega, ledger);
    // z_new_'s generator is never read: the next step sets z_'s from its piece.
    if (ledger) {
      flow.ApplyMotion(p, z_, z_new_, &input, &damping);
    } else {
      flow.ApplyStepMotion(p, z_, z_new_);
    }
  } else {
    ws_.free_dense_.Build(flow, piece.omega, z_, tau);
    ws_.free_dense_.Evaluate(tau, z_new_);
  }
  ++result_.free_steps;
  // A full step whose gaps provably stay open (§3.18) needs neither its end's gaps nor the
  // impact search.
  const bool open = step.full && GapsStayOpen(std::max(tau, step.h_s), piece.omega != 0.0);
  FinishFreeStep(piece, step, open, !step.full, input, damping);
}

void Integrator::FinishFreeStep(const ExcitationPiece& piece, const FreeStepPlan& step, bool open,
                                bool dense_built, double input, double damping) {
  LinearFlow& flow = ws_.flow_;
  const double tau = step.t_next_s - t_;
  auto ensure_dense = [&]() {
    if (!dense_built) {
      ws_.free_dense_.Build(flow, piece.omega, z_, tau);
      dense_built = true;
    }
  };
  const bool ledger = control_.energy_ledger;
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

  // Locate the first event: the first impact of an open contact, and the contacts that strike
  // with it [§3.12]; the step ends there (an open step has none).
  double t_event = kInf;
  if (!open) {
    if (!gaps_exact_) {
      // The bound carried the gaps over the steps before: the step's start has none of its own.
      GapsAndRates(q(), u(), ends_.gap0, ends_.gN0);
    }
    GapsAndRates(z_new_.head(n_), z_new_.segment(n_, n_), ends_.gap1, ends_.gN1);
    t_event = FirstImpact(t_, step.t_next_s, policy_.dip_margin, positions_at, state_at);
  }
  // A spring closing first (before an impact, not with it) ends the step without a contact
  // decision.
  bool spring_first = false;
  if (springs_ != nullptr) [[unlikely]] {
    const double t_spring = FreeStepSpringClosing(piece, step, dense_built);
    spring_first = t_spring < t_event;
    if (spring_first) {
      t_event = t_spring;
      dense_built = true;  // the search built it
    }
  }
  forced_.clear();
  if (t_event < kInf) {
    if (!spring_first) {
      SimultaneousContacts(
          t_event, step.t_next_s, scales_.simultaneity_s, scales_.gap_tol_m, modes_, positions_at,
          [this](int c, const Eigen::Ref<const Vec>& qq) { return GapAt(c, qq); }, forced_);
    }
    ws_.free_dense_.EvaluateHead(t_event - t_, 2 * n_, z_new_);  // what state_at(t_event) gives
  }
  const double t1 = t_event < kInf ? t_event : step.t_next_s;

  // Record: the work over the step, its maxima, corner travels and history samples.
  if (ledger && (!step.full || t_event < kInf)) {
    // Energy of a partial step by Gauss-Legendre quadrature of the exact (Taylor) solution.
    ensure_dense();
    input = damping = 0.0;
    const double len = t1 - t_;
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
  // The velocity-zero and corner-rate searches read the dense output only: one entry, or a
  // corner rate's four at once.
  const auto component_at = [&](double t, const auto& i, auto&... out) {
    ensure_dense();
    if constexpr (sizeof...(out) == 0) {
      return ws_.free_dense_.EvaluateComponent(t - t_, i);
    } else {
      ws_.free_dense_.EvaluateComponents(t - t_, i, out...);
    }
  };
  peaks_.Arm(step.full, flow.modal_coordinates().data(), std::max(tau, step.h_s), piece.omega,
             result_.max_travel_m.data());
  RecordStep(t1, component_at, state_at);
  peaks_.Disarm();

  // Decide: the mode decision at an impact; otherwise the step's end starts the next step.
  if (spring_first) [[unlikely]] {
    SpringClosedInFreeStep();
  } else if (t_event < kInf) {
    ResolveContacts(forced_);
  } else if (open) {
    gaps_exact_ = false;
  } else {
    ends_.gap0 = ends_.gap1;
    ends_.gN0 = ends_.gN1;
    gaps_exact_ = true;
  }
}

template <class ComponentAt, class StateAt>
void Integrator::RecordStep(double t1, ComponentAt&& component_at, StateAt&& state_at) {
  // One view of each end's positions and velocities for both scans, nothing built per step.
  const View q0(z_.data(), n_), u0(z_.data() + n_, n_);
  const View q1(z_new_.data(), n_), u1(z_new_.data() + n_, n_);
  ScanCoordinateMaxima(n_, t_, q0, u0, t1, q1, u1, MaximumTimeTolerance(t1), component_at, peaks_,
                       result_.max_abs_q, result_.time_of_max_s);
  // The corner travels, at the same exactness: step ends and the roots of each corner's rate.
  travel_.Scan(t_, q0, u0, t1, q1, u1, MaximumTimeTolerance(t1), component_at, result_.max_travel_m,
               peaks_);
  RecordOutputs(t_, t1, state_at);
  z_.head(2 * n_) = z_new_.head(2 * n_);
  t_ = t1;
}

template <class PositionsAt, class StateAt>
inline double Integrator::FirstImpact(double t0, double t1, double dip_margin,
                                      PositionsAt&& positions_at, StateAt&& state_at) {
  double t_event = kInf;
  for (int c = 0; c < nc_; ++c) {
    // The suspicion first: it is false for most contacts in most steps.
    if (Suspected(c, t1 - t0, dip_margin)) {
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
  return FirstGapRoot(t0, t1, ends_.gap0[c], ends_.gN0[c], ends_.gap1[c], ends_.gN1[c], gap,
                      gamma_N, scales_.gap_tol_m, scales_.v_tol_mps, policy_);
}

template <class StateAt>
void Integrator::RecordOutputs(double t0, double t1, StateAt&& state_at) {
  // The run's end first: without histories next_output_t_ is +inf.
  while (next_output_t_ <= t_end_ + policy_.output_time_band &&
         next_output_t_ <= t1 + policy_.output_time_band * std::max(1.0, t1)) {
    const Vec& s = state_at(std::max(t0, std::min(next_output_t_, t1)));
    RecordSample(next_output_t_, s.head(n_), s.segment(n_, n_));
    next_output_t_ = control_.output_interval_s *
                     static_cast<double>(output_offset_ + result_.histories.t_s.size());
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
    // du_: scratch, read by no later step
    ActiveForces(modes_, t, qq, uu, KinematicsOf::kAllContacts, du_, forces);
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

void Integrator::Rhs(double t, const Eigen::Ref<const Vec>& y, KinematicsOf which,
                     Eigen::Ref<Vec> dy) {
  const auto qq = y.head(n_);
  const auto uu = y.segment(n_, n_);
  ActiveForces(modes_, t, qq, uu, which, du_, ws_.forces_);
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
  dy[2 * n_ + 2] = ws_.forces_.friction_power_W;
}

void Integrator::ClosedEventValues(Eigen::Ref<Vec> values) const {
  const ActiveForcesStorage& f = ws_.forces_;
  dynamics::ClosedEventValues(model_, modes_, f.kin.gamma_T, f.lambda_N, f.lambda_T,
                              scales_.force_tol_N, scales_.v_tol_mps, values);
}

void Integrator::ConstrainedStep() {
  // Advance: one Dormand-Prince step of the active set's motion, cut at the piece's end
  // [docs/theory.md §3.14]; a rejected step only shortens the next try.
  const ExcitationPiece piece = excitation_.PieceAt(t_);
  SB_DEMAND(piece.t_end > t_, "Excitation::PieceAt(t) returned a piece that ends at or before t");
  const double h = ConstrainedStepLength(t_, std::min(piece.t_end, t_end_), h_rk_, policy_);
  if (springs_ != nullptr) [[unlikely]] {
    // A spring may sit on the end of its piece at the step's start without an event located
    // there: its transition first. The springs' two work integrals start at zero with the rest.
    SettleSprings();
    y_.tail(5).setZero();
  }
  y_.head(2 * n_) = z_.head(2 * n_);
  y_.tail(3).setZero();
  // The stages need the closed contacts' kinematics only; the step's start needs every
  // contact's (the open ones' gaps and rates there).
  const auto rhs = [this](double t, const Eigen::Ref<const Vec>& y, Eigen::Ref<Vec> dy) {
    Rhs(t, y, KinematicsOf::kClosedContacts, dy);
  };
  if (springs_ == nullptr) [[likely]] {
    Rhs(t_, y_, KinematicsOf::kAllContacts, dy_);
  } else {
    SpringsRhs(t_, y_, KinematicsOf::kAllContacts, dy_);
  }
  ClosedEventValues(events_.f0);
  ends_.gap0 = ws_.forces_.kin.gap_m;
  ends_.gN0 = ws_.forces_.kin.gamma_N;
  gaps_exact_ = true;
  DormandPrince45& rk = ws_.rk_;
  if (springs_ == nullptr) [[likely]] {
    rk.Step(rhs, t_, y_, dy_, h);
  } else {
    SpringsStep(h);
  }
  // The norm of (q, u) alone: the work integrals' terms are zero (infinite tolerance).
  const double err = rk.ErrorNorm(atol_, control_.relative_tolerance, 2 * n_ + 3);
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
  ClosedEventValues(events_.f1);
  GapsAndRates(y1.head(n_), y1.segment(n_, n_), ends_.gap1, ends_.gN1);
  // The step's dense output, in y_eval_: q alone (what a gap needs), or the whole state.
  const auto positions_at = [&](double t) {
    rk.DenseHeadAt(t, n_, y_eval_);
    return y_eval_.head(n_);
  };
  const auto state_at = [&](double t) -> const Vec& {
    rk.DenseAt(t, y_eval_);
    return y_eval_;
  };

  // Locate the first event [§3.12]: the first impact of an open contact, every dip searched
  // (kEveryDip: the Hermite margin of the free step rests on its length, which a Runge-Kutta
  // step does not have), then the first closed-contact event function to fire, on the active
  // set's forces along the dense output.
  const double t_impact = FirstImpact(t_, t1, kEveryDip, positions_at, state_at);
  const auto event_value_at = [&](double t, int e) {
    const Vec& y = state_at(t);
    ActiveForces(modes_, t, y.head(n_), y.segment(n_, n_), KinematicsOf::kClosedContacts, du_,
                 ws_.forces_);
    ClosedEventValues(events_.f_eval);
    return events_.f_eval[e];
  };
  double t_event = std::min(
      t_impact, FirstClosedEvent(t_, t1, events_.f0, events_.f1, modes_, event_value_at, policy_));
  // A spring's event first (before the contacts' events, not with them): its transition alone.
  bool spring_first = false;
  if (springs_ != nullptr) [[unlikely]] {
    const double t_spring = FirstSpringEvent(t1);
    spring_first = t_spring < t_event;
    if (spring_first) t_event = t_spring;
  }
  forced_.clear();
  if (t_impact < kInf && t_impact == t_event) {
    // An impact first: the open contacts that strike with it, as in the free step.
    SimultaneousContacts(
        t_impact, t1, scales_.simultaneity_s, scales_.gap_tol_m, modes_, positions_at,
        [this](int c, const Eigen::Ref<const Vec>& qq) { return GapAt(c, qq); }, forced_);
  }
  const double t_new = t_event < kInf ? std::max(t_event, t_) : t1;
  rk.DenseAt(t_new, y_eval_);
  if (t_event == kInf) {
    y_eval_ = y1;
  }

  // Record: the work integrals, the maxima, corner travels and history samples.
  result_.energy.input_J += y_eval_[2 * n_];
  result_.energy.damping_J += y_eval_[2 * n_ + 1];
  result_.energy.friction_J += y_eval_[2 * n_ + 2];
  if (springs_ != nullptr) [[unlikely]] {
    joint_work_J_ += y_eval_[2 * n_ + 3];
    wall_friction_J_ += y_eval_[2 * n_ + 4];
  }
  z_new_.head(2 * n_) = y_eval_.head(2 * n_);
  const auto component_at = [&](double t, int i) { return rk.DenseComponentAt(t, i); };
  RecordStep(t_new, component_at, state_at);
  // The springs' maxima at the step's end (a free step has every spring open).
  if (springs_ != nullptr) [[unlikely]] {
    SpringMaxima();
  }
  h_rk_ = t_event < kInf ? h : h * DormandPrince45::StepFactor(err);

  // Decide: the mode decision at an event; otherwise the projection onto the closed contacts.
  // A spring's event alone: its transition, and the projection of the closed contacts.
  if (spring_first) [[unlikely]] {
    SettleSprings();
    if (AnyClosed()) Project();
  } else if (t_event < kInf) {
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
                  memory_, *this, ws_.decision_, log_, added_);
  if (outcome.status != RunStatus::kOk) {
    Fail(outcome.status, outcome.message);
    return;
  }
  // The decision left its kinematics of every contact at its final state: the gaps of the next
  // step's start need no further evaluation.
  ends_.gap0 = ws_.decision_.projection.kin.gap_m;
  ends_.gN0 = ws_.decision_.projection.kin.gamma_N;
  gaps_exact_ = true;
  // The springs after the decision, with the velocities it left [docs/theory.md §3.22].
  if (springs_ != nullptr) [[unlikely]] {
    SettleSprings();
  }
}

void Integrator::Forces(const ContactModes& modes, double t, const Eigen::Ref<const Vec>& qq,
                        const Eigen::Ref<const Vec>& uu, Eigen::Ref<Vec> lambda_N,
                        Eigen::Ref<Vec> lambda_T) {
  ActiveForces(modes, t, qq, uu, KinematicsOf::kAllContacts, du_, ws_.forces_);
  lambda_N = ws_.forces_.lambda_N;
  lambda_T = ws_.forces_.lambda_T;
}

RunResult Simulate(const model::Model& model, const Excitation& excitation,
                   const model::RunControl& control, SimulationWorkspace& workspace,
                   const InitialState& initial, const EventPolicy& policy,
                   FreeStepObserver* observer) {
  Integrator integrator(model, excitation, control, workspace, initial, policy, observer);
  return integrator.Run();
}

}  // namespace skewbridge::dynamics
