#include "solver/dynamics/compliant_run.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "solver/common/error.h"
#include "solver/dynamics/compliant_integrator.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/event_location.h"
#include "solver/dynamics/gauss_legendre.h"
#include "solver/dynamics/linear_flow.h"
#include "solver/dynamics/root_finding.h"
#include "solver/dynamics/run_scales.h"
#include "solver/dynamics/step_grid.h"
#include "solver/joint/backfill.h"
#include "solver/joint/shear_key.h"

namespace skewbridge::dynamics {
namespace {

// The size of the integrated state: (q, u, input work, damping work, springs' work), and the
// friction's work when a spring has wall friction.
int StateSize(int n_dof, const std::vector<CompliantSpring>& springs) {
  const bool friction = std::any_of(springs.begin(), springs.end(),
                                    [](const CompliantSpring& s) { return s.mu > 0.0; });
  return 2 * n_dof + 3 + (friction ? 1 : 0);
}

// `model`, when it has no rigid contact.
const model::Model& CheckedWithoutContacts(const model::Model& model) {
  if (model.n_contacts() > 0) {
    throw InputError::AtField(model.source(), "abutments",
                              "a model with compliant springs has no rigid contact (one law for "
                              "every abutment)");
  }
  return model;
}

}  // namespace

CompliantIntegrator::CompliantIntegrator(const model::Model& model,
                                         const std::vector<CompliantSpring>& springs,
                                         const Excitation& excitation,
                                         const model::RunControl& control,
                                         const InitialState& initial, const EventPolicy& policy)
    : model_(CheckedWithoutContacts(model)),
      set_(model, springs),
      excitation_(excitation),
      control_(control),
      policy_(policy),
      flow_(model.M(), model.K(), model.C(), model.r(), FlowPath::kAuto, model.modes()),
      dense_(flow_.augmented_size()),
      n_(model.n_dof()),
      ns_(static_cast<int>(springs.size())),
      start_d_m_(springs.size()),
      start_rate_mps_(springs.size()),
      ny_(StateSize(model.n_dof(), springs)),
      rk_(ny_),
      result_(out_.run),
      travel_(model) {
  if (flow_.modal()) {
    const Eigen::VectorXd& w2 = flow_.modal_flow().w2();
    omega_max_radps_ = std::sqrt(std::max(w2.maxCoeff(), 0.0));
    omega_min_radps_ = std::sqrt(std::max(w2.minCoeff(), 0.0));
  } else {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(model.K(), model.M(),
                                                                        Eigen::EigenvaluesOnly);
    omega_max_radps_ = std::sqrt(std::max(eig.eigenvalues().maxCoeff(), 0.0));
    omega_min_radps_ = std::sqrt(std::max(eig.eigenvalues().minCoeff(), 0.0));
  }
  double length_scale = 1.0;
  for (const model::Body& body : model.bodies()) {
    length_scale = std::max({length_scale, body.geometry.length_m, body.geometry.width_m,
                             body.rest_position_m.norm() + body.geometry.length_m});
  }
  ValidatePolicy(policy);
  y_ = Vec::Zero(ny_);
  if (initial.q.size() != 0) {
    if (initial.q.size() != n_) {
      throw InputError::AtField("initial state", "q", "must have n_dof entries");
    }
    y_.head(n_) = initial.q;
  }
  if (initial.u.size() != 0) {
    if (initial.u.size() != n_) {
      throw InputError::AtField("initial state", "u", "must have n_dof entries");
    }
    y_.segment(n_, n_) = initial.u;
  }
  dy_ = y_new_ = y_eval_ = y_;
  z_ = Vec::Zero(flow_.augmented_size());
  z_new_ = z_eval_ = z_;
  e0_ = e1_ = Vec::Zero(set_.n_events());
  if (flow_.modal()) spring_bound_ = SpringGapBound(flow_.modal_flow(), springs);
  if (spring_bound_.applies()) {
    spring_floors_ = std::make_unique<GapFloors>(spring_bound_);
    spring_gaps_ = Vec::Zero(ns_);
  }
  h_ = cu_ = Vec::Zero(n_);
  t_end_ = control.EndTime(excitation.Duration());
  scales_ = ComputeRunScales(
      ExcitationPeak(excitation, policy_.ramp_horizon_s), y_.segment(n_, n_).cwiseAbs().maxCoeff(),
      {omega_min_radps_, omega_max_radps_, length_scale, MaxTranslationalMass(model)},
      control.accumulation_threshold, policy_);
  // The springs' own frequency joins the step control's velocity scale.
  const double k_sum = set_.StiffnessSum_Npm();
  const double omega_spring = std::sqrt(k_sum / MaxTranslationalMass(model));
  const double omega_top = std::max(scales_.omega_top_radps, omega_spring);
  rtol_ = control.relative_tolerance;
  atol_ = Vec::Constant(ny_, kInf);
  atol_.head(n_).setConstant(control.absolute_tolerance);
  atol_.segment(n_, n_).setConstant(control.absolute_tolerance * omega_top);
  h_rk_ = std::min(scales_.first_rk_step_s, 0.01 / omega_top);
  result_.max_abs_q = y_.head(n_).cwiseAbs();
  result_.time_of_max_s = Vec::Zero(n_);
  travel_.Start(y_.head(n_), result_.max_travel_m);
  if (control.output_interval_s > 0.0) {
    result_.histories.n_dof = n_;
    result_.histories.n_contacts = 0;
    next_output_t_ = 0.0;
  }
}

void CompliantIntegrator::Rhs(const ExcitationPiece& piece, double t,
                              const Eigen::Ref<const Vec>& y, Eigen::Ref<Vec> dy) const {
  const auto q = y.head(n_);
  const auto u = y.segment(n_, n_);
  const Eigen::Vector2d a_g = piece.At(t);
  model_.AppliedForces(q, u, a_g, h_);
  double input_W = 0.0;
  const Eigen::MatrixXd& r = model_.r();
  const Vec& mass = model_.mass_diagonal();
  for (int i = 0; i < n_; ++i) {
    input_W -= u[i] * mass[i] * (r(i, 0) * a_g.x() + r(i, 1) * a_g.y());
  }
  cu_.noalias() = model_.C() * u;
  const double damping_W = u.dot(cu_);
  double joint_W, friction_W;
  set_.AddForces(q, u, h_, joint_W, friction_W);
  dy.head(n_) = u;
  dy.segment(n_, n_) = model_.inverse_mass_diagonal().cwiseProduct(h_);
  dy[2 * n_] = input_W;
  dy[2 * n_ + 1] = damping_W;
  dy[2 * n_ + 2] = joint_W;
  if (ny_ > 2 * n_ + 3) dy[2 * n_ + 3] = friction_W;
}

CompliantRunResult CompliantIntegrator::Run() {
  result_.energy.initial_J = model_.MechanicalEnergy(y_.head(n_), y_.segment(n_, n_));
  RecordOutputs(0.0, 0.0, [&](double) -> const Vec& { return y_; });
  SettleAll(y_);
  long steps = 0;
  double t_finite = 0.0;
  while (!Failed() && t_ < t_end_) {
    if (++steps > control_.max_steps) {
      result_.status = RunStatus::kStepLimit;
      result_.message =
          fmt::format("step limit of {} reached at t = {:g} s", control_.max_steps, t_);
      break;
    }
    if (AllFree()) {
      FreeStep();
    } else {
      CompliantStep();
    }
    if ((steps & (policy_.finite_check_steps - 1)) == 0) {
      if (!StateFinite(y_) || !std::isfinite(t_)) break;
      t_finite = t_;
    }
  }
  return Finish(t_finite);
}

void CompliantIntegrator::SettleAll(const Eigen::Ref<const Vec>& y) {
  if (set_.SettleAll(y, t_)) {
    ++result_.impacts;
    result_.min_impact_separation_s =
        std::min(result_.min_impact_separation_s, t_ - last_strike_t_s_);
    last_strike_t_s_ = t_;
  }
}

void CompliantIntegrator::StartKinematics() {
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    if (set_.state(j).broken) continue;
    set_.Kinematics(j, y_.head(n_), y_.segment(n_, n_), start_d_m_[static_cast<std::size_t>(j)],
                    start_rate_mps_[static_cast<std::size_t>(j)], w);
  }
  start_known_ = true;
}

bool CompliantIntegrator::AllFree() {
  if (set_.AnyEngaged()) return false;
  // The bound kept every spring's gap above twice the touch band up to y_: each computed d is
  // below its d_set there.
  if (start_bounded_) return true;
  if (!start_known_) StartKinematics();
  for (int j = 0; j < ns_; ++j) {
    const SpringState& m = set_.state(j);
    if (m.broken) continue;
    if (!(start_d_m_[static_cast<std::size_t>(j)] < m.d_set_m)) return false;
  }
  return true;
}

ModalGapBound SpringGapBound(const ModalFlow& modal, const std::vector<CompliantSpring>& springs) {
  ModalGapBound bound;
  if (springs.empty() || (modal.c().array() < 0.0).any()) return bound;
  const int n = modal.n_modes();
  const int ns = static_cast<int>(springs.size());
  const Eigen::MatrixXd& Phi = modal.Phi();
  std::vector<double> W(static_cast<std::size_t>(ns) * static_cast<std::size_t>(n));
  for (int j = 0; j < ns; ++j) {
    const CompliantSpring& s = springs[static_cast<std::size_t>(j)];
    if (s.face.body != model::kGround) return bound;
    // d = -n . ((x, y) + R(theta) p - A) moves as the gap of a corner at p against the face.
    CornerGapWeights(Phi, 3 * s.body, s.face.normal, s.point_m,
                     W.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(n));
  }
  bound.Set(modal, std::move(W), ns);
  return bound;
}

bool CompliantIntegrator::SpringsStayOpen(double tau_s) {
  if (!spring_floors_) return false;
  if (start_known_) {
    // Exact values at the step's start: the bases start again from them.
    for (int j = 0; j < ns_; ++j) {
      const SpringState& m = set_.state(j);
      spring_gaps_[j] = m.broken ? kInf : m.d_set_m - start_d_m_[static_cast<std::size_t>(j)];
    }
    spring_floors_->Restart(spring_gaps_);
  }
  // Clear of the touch band with the rounding of the deformations' evaluation to spare.
  return spring_floors_->StaysOpen(flow_.modal_coordinates().data(), tau_s,
                                   2.0 * scales_.gap_tol_m);
}

void CompliantIntegrator::FreeStep() {
  fresh_start_ = false;
  LinearFlow& flow = flow_;
  FreeDenseOutput& dense = dense_;
  const ExcitationPiece piece = excitation_.PieceAt(t_);
  SB_DEMAND(piece.t_end > t_, "Excitation::PieceAt(t) returned a piece that ends at or before t");
  const FreeStepPlan step =
      PlanFreeStep(t_, piece.t_begin, std::min(piece.t_end, t_end_),
                   FreeStepSize(piece, omega_max_radps_, policy_), h_free_, policy_);
  h_free_ = step.h_s;
  const double tau = step.t_next_s - t_;
  z_.head(2 * n_) = y_.head(2 * n_);
  flow.SetGenerator(piece, t_, z_);
  bool built = false;
  auto ensure_dense = [&]() {
    if (!built) {
      dense.Build(flow, piece.omega, z_, tau);
      built = true;
    }
  };
  const bool ledger = control_.energy_ledger;
  double input = 0.0, damping = 0.0;
  if (step.full) {
    const FreePropagator& p = flow.Propagator(step.h_s, piece.omega, ledger);
    flow.Apply(p, z_, z_new_, ledger ? &input : nullptr, ledger ? &damping : nullptr);
  } else {
    ensure_dense();
    dense.Evaluate(tau, z_new_);
  }
  ++result_.free_steps;
  const auto state_at = [&](double t) -> const Vec& {
    ensure_dense();
    dense.EvaluateHead(t - t_, 2 * n_, z_eval_);
    return z_eval_;
  };
  // The first closing of a spring: its "gap" d_set - d reaching zero, searched as an impact.
  // A full step whose springs provably stay open (the closing bound, docs/theory.md §3.18) needs
  // neither its end's deformations nor the search: the search would find no root. Otherwise the
  // start's d and d' are AllFree's at y_, whose (q, u) z_ holds (computed now if the steps
  // before skipped them: the same bits).
  const bool open = step.full && SpringsStayOpen(std::max(tau, step.h_s));
  if (open) {
    start_known_ = false;
    start_bounded_ = true;
  } else if (!start_known_) {
    StartKinematics();
  }
  if (!open) start_bounded_ = false;
  double t_event = kInf;
  Eigen::Vector3d w;
  for (int j = 0; j < ns_ && !open; ++j) {
    if (set_.state(j).broken) continue;
    const double d_set = set_.state(j).d_set_m;
    const double d0 = start_d_m_[static_cast<std::size_t>(j)];
    const double r0 = start_rate_mps_[static_cast<std::size_t>(j)];
    double d1, r1;
    set_.Kinematics(j, z_new_.head(n_), z_new_.segment(n_, n_), d1, r1, w);
    // Kept for the next step's start, which is this end unless an event cuts the step.
    start_d_m_[static_cast<std::size_t>(j)] = d1;
    start_rate_mps_[static_cast<std::size_t>(j)] = r1;
    if (!ImpactSuspected(d_set - d0, -r0, d_set - d1, -r1, tau, policy_.dip_margin)) continue;
    const auto gap = [&](double t) {
      const Vec& s = state_at(t);
      double d, rate;
      Eigen::Vector3d ww;
      set_.Kinematics(j, s.head(n_), s.segment(n_, n_), d, rate, ww);
      return d_set - d;
    };
    const auto gamma_N = [&](double t) {
      const Vec& s = state_at(t);
      double d, rate;
      Eigen::Vector3d ww;
      set_.Kinematics(j, s.head(n_), s.segment(n_, n_), d, rate, ww);
      return -rate;
    };
    t_event =
        std::min(t_event, FirstGapRoot(t_, step.t_next_s, d_set - d0, -r0, d_set - d1, -r1, gap,
                                       gamma_N, scales_.gap_tol_m, scales_.v_tol_mps, policy_));
  }
  if (t_event < kInf) {
    ensure_dense();
    dense.EvaluateHead(t_event - t_, 2 * n_, z_new_);
    start_known_ = false;
    start_bounded_ = false;
  }
  const double t1 = t_event < kInf ? t_event : step.t_next_s;
  if (ledger && (!step.full || t_event < kInf)) {
    ensure_dense();
    input = damping = 0.0;
    const double len = t1 - t_;
    for (int i = 0; i < 8; ++i) {
      dense.Evaluate(kGaussNode[i] * len, z_eval_);
      double p_in, p_d;
      flow.Powers(z_eval_, p_in, p_d);
      input += kGaussWeight[i] * len * p_in;
      damping += kGaussWeight[i] * len * p_d;
    }
  }
  y_new_.head(2 * n_) = z_new_.head(2 * n_);
  y_new_[2 * n_] = y_[2 * n_] + input;
  y_new_[2 * n_ + 1] = y_[2 * n_ + 1] + damping;
  y_new_[2 * n_ + 2] = y_[2 * n_ + 2];
  if (ny_ > 2 * n_ + 3) y_new_[2 * n_ + 3] = y_[2 * n_ + 3];
  const auto component_at = [&](double t, int i) {
    ensure_dense();
    return dense.EvaluateComponent(t - t_, i);
  };
  RecordStep(t1, y_new_, component_at, state_at);
  if (t_event < kInf) {
    SettleAll(y_);
    h_rk_ = std::min(h_rk_, step.h_s);
  }
}

void CompliantIntegrator::CompliantStep() {
  start_known_ = false;
  start_bounded_ = false;
  const ExcitationPiece piece = excitation_.PieceAt(t_);
  SB_DEMAND(piece.t_end > t_, "Excitation::PieceAt(t) returned a piece that ends at or before t");
  const double t_stop = std::min(piece.t_end, t_end_);
  const auto rhs = [&](double t, const Eigen::Ref<const Vec>& y, Eigen::Ref<Vec> dy) {
    Rhs(piece, t, y, dy);
  };
  if (!fresh_start_) {
    // A spring may sit on the end of its piece at the step's start without an event having been
    // located there (a free step or a piece ending exactly at it): its transition first.
    SettleAll(y_);
    Rhs(piece, t_, y_, dy_);
    set_.AllEventValues(y_, e0_);
  }
  fresh_start_ = false;
  double h = 0.0, error = 0.0;
  for (;;) {
    h = ConstrainedStepLength(t_, t_stop, h_rk_, policy_);
    rk_.Step(rhs, t_, y_, dy_, h);
    error = rk_.ErrorNorm(atol_, rtol_);
    if (error <= 1.0 || !std::isfinite(error) || h <= 1e-14 * std::max(1.0, t_)) break;
    ++result_.rk_rejected;
    h_rk_ = h * DormandPrince45::StepFactor(error);
  }
  ++result_.rk_steps;
  const double t_full = t_ + h;
  set_.AllEventValues(rk_.y_end(), e1_);
  // The first event function to change sign, located on the dense output; the time taken on its
  // far side so that the transition sees it crossed.
  double t_event = kInf;
  const double x_tol = EventTimeBracket(t_full, policy_);
  for (int e = 0; e < e0_.size(); ++e) {
    if (!(e0_[e] > 0.0 && e1_[e] <= 0.0)) continue;
    const auto value = [&](double t) {
      rk_.DenseHeadAt(t, 2 * n_, y_eval_);
      return set_.EventValueAt(e, y_eval_);
    };
    const RootResult root = FindRootBrent(value, t_, t_full, e0_[e], e1_[e], x_tol);
    t_event = std::min(t_event, root.fx <= 0.0 ? root.x : root.upper);
  }
  if (t_event < kInf) {
    rk_.DenseAt(t_event, y_new_);
  } else {
    y_new_ = rk_.y_end();
  }
  const double t1 = t_event < kInf ? t_event : t_full;
  const auto component_at = [&](double t, int i) { return rk_.DenseComponentAt(t, i); };
  const auto state_at = [&](double t) -> const Vec& {
    rk_.DenseAt(t, y_eval_);
    return y_eval_;
  };
  RecordStep(t1, y_new_, component_at, state_at);
  h_rk_ = h * DormandPrince45::StepFactor(error);
  if (t_event < kInf) {
    SettleAll(y_);
  } else if (t1 < t_stop) {
    // The next step starts inside the same piece with the same branches: the last stage is its
    // first (FSAL), and its event values are this step's end values.
    dy_ = rk_.dy_end();
    e0_ = e1_;
    fresh_start_ = true;
  }
}

template <class ComponentAt, class StateAt>
void CompliantIntegrator::RecordStep(double t1, const Eigen::Ref<const Vec>& y_new,
                                     ComponentAt&& component_at, StateAt&& state_at) {
  const auto q0 = y_.head(n_);
  const auto u0 = y_.segment(n_, n_);
  const auto q1 = y_new.head(n_);
  const auto u1 = y_new.segment(n_, n_);
  const double time_tol =
      policy_.maximum_time_tolerance * std::max(1.0, std::abs(t1)) + policy_.event_time_floor_s;
  for (int i = 0; i < n_; ++i) {
    if (std::abs(q1[i]) > result_.max_abs_q[i]) {
      result_.max_abs_q[i] = std::abs(q1[i]);
      result_.time_of_max_s[i] = t1;
    }
    if (u0[i] * u1[i] < 0.0) {
      const double bound = std::max(std::abs(q0[i]), std::abs(q1[i])) +
                           0.5 * (t1 - t_) * std::max(std::abs(u0[i]), std::abs(u1[i]));
      if (bound > result_.max_abs_q[i]) {
        const auto velocity = [&](double t) { return component_at(t, n_ + i); };
        const RootResult peak = FindRootBrent(velocity, t_, t1, u0[i], u1[i], time_tol);
        const double q_peak = std::abs(component_at(peak.x, i));
        if (q_peak > result_.max_abs_q[i]) {
          result_.max_abs_q[i] = q_peak;
          result_.time_of_max_s[i] = peak.x;
        }
      }
    }
  }
  travel_.Scan(t_, q0, u0, t1, q1, u1, time_tol, component_at, result_.max_travel_m);
  RecordOutputs(t_, t1, state_at);
  y_ = y_new;
  t_ = t1;
  set_.Maxima(y_);
}

template <class StateAt>
void CompliantIntegrator::RecordOutputs(double t0, double t1, StateAt&& state_at) {
  Histories& hist = result_.histories;
  while (next_output_t_ <= t1 + policy_.output_time_band * std::max(1.0, t1) &&
         next_output_t_ <= t_end_ + policy_.output_time_band) {
    const Vec& s = state_at(std::max(t0, std::min(next_output_t_, t1)));
    hist.t_s.push_back(next_output_t_);
    for (int i = 0; i < n_; ++i) {
      hist.q.push_back(s[i]);
      hist.u.push_back(s[n_ + i]);
    }
    next_output_t_ = control_.output_interval_s * static_cast<double>(hist.t_s.size());
  }
}

CompliantRunResult CompliantIntegrator::Finish(double t_finite_s) {
  if (!StateFinite(y_) || !std::isfinite(t_)) {
    result_.status = RunStatus::kNonFinite;
    result_.message = NonFiniteMessage(t_finite_s, t_);
    t_ = std::isfinite(t_) ? t_ : t_finite_s;
  }
  result_.end_time_s = t_;
  result_.q_end = y_.head(n_);
  result_.u_end = y_.segment(n_, n_);
  EnergyLedger& e = result_.energy;
  e.input_J = y_[2 * n_];
  e.damping_J = y_[2 * n_ + 1];
  const double work = y_[2 * n_ + 2];
  // What the springs would give back by unloading: F^2 / (2 K_ur) on the backfill's line or
  // envelope, 1/2 k d^2 for an engaged spring-dashpot; and the stick springs' F_t^2 / (2 k_t).
  double stored, friction_stored;
  set_.EndEnergies(y_.head(n_), y_.segment(n_, n_), stored, friction_stored);
  out_.joint_stored_J = stored;
  out_.joint_dissipated_J = work - stored;
  const bool friction = set_.n_friction() > 0;
  if (friction) {
    // The rest of the friction's work is dissipated.
    out_.joint_stored_J += friction_stored;
    e.friction_J = y_[2 * n_ + 3] - friction_stored;
  }
  e.kinetic_J =
      0.5 * y_.segment(n_, n_).dot(model_.mass_diagonal().cwiseProduct(y_.segment(n_, n_)));
  e.strain_J = 0.5 * y_.head(n_).dot(model_.K() * y_.head(n_));
  e.balance_error_J = (e.kinetic_J + e.strain_J + out_.joint_stored_J) -
                      (e.initial_J + e.input_J - e.damping_J - out_.joint_dissipated_J);
  if (friction) {
    e.balance_error_J =
        (e.kinetic_J + e.strain_J + out_.joint_stored_J) -
        (e.initial_J + e.input_J - e.damping_J - out_.joint_dissipated_J - e.friction_J);
  }
  if (!control_.energy_ledger) {
    e.input_J = e.damping_J = e.balance_error_J = std::numeric_limits<double>::quiet_NaN();
    if (friction) e.friction_J = std::numeric_limits<double>::quiet_NaN();
  }
  set_.MoveResults(out_);
  return std::move(out_);
}

CompliantRunResult SimulateCompliant(const model::Model& model,
                                     const std::vector<CompliantSpring>& springs,
                                     const Excitation& excitation, const model::RunControl& control,
                                     const InitialState& initial, const EventPolicy& policy) {
  CompliantIntegrator integrator(model, springs, excitation, control, initial, policy);
  return integrator.Run();
}

}  // namespace skewbridge::dynamics
