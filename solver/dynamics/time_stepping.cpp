#include "solver/dynamics/time_stepping.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "solver/common/error.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/run_scales.h"
#include "solver/lcp/enumeration.h"
#include "solver/model/builders.h"

namespace skewbridge::dynamics {

using Vec = Eigen::VectorXd;

TimeSteppingWorkspace::TimeSteppingWorkspace(const model::Model& model, double theta)
    // LLT(n) sizes the factor; a default-constructed LLT moved in would copy an uninitialised
    // status (UBSan reports it).
    : model_(model), theta_(theta), llt_(model.n_dof()) {
  if (!(theta > 0.0 && theta <= 1.0)) {
    throw InputError::AtField(model.source(), "theta", "must lie in (0, 1] (1/2: trapezoidal)");
  }
  const int n = model.n_dof();
  const int nc = model.n_contacts();
  W_inverse_.resize(n, n);
  kin_.Resize(model);
  solutions_.resize(static_cast<std::size_t>(3 * nc + 1));
  for (int size = 1; size <= 3 * nc; ++size) {
    solutions_[static_cast<std::size_t>(size)].z.resize(size);
    solutions_[static_cast<std::size_t>(size)].w.resize(size);
  }
  active_.reserve(static_cast<std::size_t>(nc));
  WN_.resize(n, nc);
  WT_.resize(n, nc);
  WinvWN_.resize(n, nc);
  WinvWT_.resize(n, nc);
  A_.resize(3 * nc, 3 * nc);
  b_.resize(3 * nc);
  mu_.resize(nc);
  eps_.resize(nc);
  P_N_.resize(nc);
  P_T_.resize(nc);
  P_N_previous_.resize(nc);
  state_.resize(static_cast<std::size_t>(nc));
  state_previous_.resize(static_cast<std::size_t>(nc));
  K_sparse_ = model.K().sparseView(0.0, 0.0);
  C_sparse_ = model.C().sparseView(0.0, 0.0);
  M_sparse_ = model.M().sparseView(0.0, 0.0);
  triplets_.reserve(static_cast<std::size_t>(6 * nc));
  rhs_.resize(n);
  u_free_.resize(n);
  u1_.resize(n);
  q1_.resize(n);
  u_theta_.resize(n);
  work_.resize(n);
}

void TimeSteppingWorkspace::Factorise(double h_s) {
  if (h_s == factorised_h_s_) {
    return;
  }
  const double ht = h_s * theta_;
  const Eigen::MatrixXd W = model_.M() + ht * model_.C() + (ht * ht) * model_.K();
  llt_.compute(W);
  SB_DEMAND(llt_.info() == Eigen::Success, "W = M + h theta C + h^2 theta^2 K is not SPD");
  W_inverse_ = llt_.solve(Eigen::MatrixXd::Identity(W.rows(), W.cols()));
  factorised_h_s_ = h_s;
}

void TimeSteppingWorkspace::FactoriseSparse(double h_s) {
  if (h_s == factorised_sparse_h_s_) {
    return;
  }
  const double ht = h_s * theta_;
  W_sparse_ = M_sparse_ + ht * C_sparse_ + (ht * ht) * K_sparse_;
  // The pattern of W is the model's: one symbolic analysis (AMD ordering) serves every step.
  if (!pattern_analysed_) {
    cholmod_.analyzePattern(W_sparse_);
    pattern_analysed_ = true;
  }
  cholmod_.factorize(W_sparse_);
  SB_DEMAND(cholmod_.info() == Eigen::Success, "W = M + h theta C + h^2 theta^2 K is not SPD");
  factorised_sparse_h_s_ = h_s;
}

void TimeSteppingWorkspace::GatherSparseJacobians(int k) {
  const int n = model_.n_dof();
  for (Eigen::SparseMatrix<double>* W : {&WN_sparse_, &WT_sparse_}) {
    const Eigen::MatrixXd& dense = W == &WN_sparse_ ? WN_ : WT_;
    triplets_.clear();
    for (int j = 0; j < k; ++j) {
      const model::Contact& c = model_.contact(active_[static_cast<std::size_t>(j)]);
      for (int body : {c.body, c.face.body}) {
        if (body == model::kGround) {
          continue;
        }
        for (int d = 3 * body; d < 3 * body + 3; ++d) {
          triplets_.emplace_back(d, j, dense(d, j));
        }
      }
    }
    W->resize(n, k);
    W->setFromTriplets(triplets_.begin(), triplets_.end());
  }
}

bool UsesSparseLinearAlgebra(const model::Model& model, const model::RunControl& control) {
  if (control.linear_algebra == "dense") {
    return false;
  }
  if (control.linear_algebra == "sparse") {
    return true;
  }
  if (control.linear_algebra != "auto") {
    throw InputError::AtField(
        model.source(), "run.linear_algebra",
        "must be one of auto, dense, sparse (got \"" + control.linear_algebra + "\")");
  }
  return model.n_dof() >= kSparseThresholdDof;
}

Eigen::Vector2d MeanAcceleration(const Excitation& excitation, double t0_s, double t1_s) {
  SB_ASSERT(t1_s > t0_s && t0_s >= 0.0, "MeanAcceleration needs t1 > t0 >= 0");
  Eigen::Vector2d integral = Eigen::Vector2d::Zero();
  double t = t0_s;
  while (t < t1_s) {
    const ExcitationPiece piece = excitation.PieceAt(t);
    double end = std::min(piece.t_end, t1_s);
    if (!(end > t)) {
      end = t1_s;
    }
    // Integral of a_begin + slope tau + c cos(w tau) + s sin(w tau), tau = t - t_begin.
    const double ta = t - piece.t_begin;
    const double tb = end - piece.t_begin;
    integral += piece.a_begin * (tb - ta) + piece.slope * (0.5 * (tb * tb - ta * ta));
    if (piece.omega != 0.0) {
      const double w = piece.omega;
      integral += piece.cos_amplitude * ((std::sin(w * tb) - std::sin(w * ta)) / w) +
                  piece.sin_amplitude * ((std::cos(w * ta) - std::cos(w * tb)) / w);
    } else {
      integral += piece.cos_amplitude * (tb - ta);
    }
    t = end;
  }
  return integral / (t1_s - t0_s);
}

namespace {

int StateOf(double P_N, double gamma_T, double v_tol) {
  if (P_N <= 0.0) {
    return static_cast<int>(ContactState::kOpen);
  }
  if (std::abs(gamma_T) <= v_tol) {
    return static_cast<int>(ContactState::kStick);
  }
  return static_cast<int>(gamma_T > 0.0 ? ContactState::kSlidePositive
                                        : ContactState::kSlideNegative);
}

}  // namespace

RunResult SimulateTimeStepping(const model::Model& model, const Excitation& excitation,
                               const model::RunControl& control, TimeSteppingWorkspace& ws,
                               const InitialState& initial, const TimeSteppingPolicy& policy) {
  SB_DEMAND(&ws.model() == &model, "time-stepping workspace built for another model");
  ValidatePolicy(policy);
  const int n = model.n_dof();
  const int nc = model.n_contacts();
  const double h = control.time_step_s;
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw InputError::AtField(model.source(), "run.time_step_s", "must be a positive number");
  }
  if ((initial.q.size() != 0 && initial.q.size() != n) ||
      (initial.u.size() != 0 && initial.u.size() != n)) {
    throw InputError::AtField(model.source(), "initial state", "needs n_dof entries");
  }
  const double theta = ws.theta();
  const double t_end = control.EndTime(excitation.Duration());
  const bool sparse = UsesSparseLinearAlgebra(model, control);

  RunResult result;
  Vec q = initial.q.size() == n ? initial.q : Vec::Zero(n);
  Vec u = initial.u.size() == n ? initial.u : Vec::Zero(n);
  result.max_abs_q = q.cwiseAbs();
  result.time_of_max_s = Vec::Zero(n);
  CornerTravelTracker travel(model);
  travel.Start(q, result.max_travel_m);
  result.energy.initial_J = model.MechanicalEnergy(q, u);

  const Eigen::VectorXd& mass = model.mass_diagonal();
  // The velocity scale a_peak / omega_1, a_peak and omega_1 as the event-driven integrator takes
  // them (ExcitationPeak, LowestFrequency).
  double v_ref = ExcitationPeak(excitation, policy.ramp_horizon_s);
  {
    const double omega_min = model::LowestFrequency(model);
    v_ref /=
        omega_min > policy.free_body_omega_floor_radps ? omega_min : policy.free_body_omega_radps;
    v_ref = std::max(v_ref, u.cwiseAbs().maxCoeff());
    if (v_ref == 0.0) {
      v_ref = 1.0;
    }
  }
  const double v_tol = policy.velocity_tolerance * v_ref;

  Histories& hist = result.histories;
  hist.n_dof = n;
  hist.n_contacts = nc;
  const bool record = control.output_interval_s > 0.0;
  long next_sample = 0;
  const auto record_until = [&](double t0, const Vec& q0, const Vec& u0, double t1, const Vec& qq1,
                                const Vec& uu1, double step) {
    while (record) {
      const double ts = control.output_interval_s * static_cast<double>(next_sample);
      if (ts > t1 + policy.output_time_band * std::max(1.0, t1) ||
          ts > t_end + policy.output_time_band) {
        break;
      }
      const double s = t1 > t0 ? std::clamp((ts - t0) / (t1 - t0), 0.0, 1.0) : 1.0;
      hist.t_s.push_back(ts);
      for (int i = 0; i < n; ++i) {
        hist.q.push_back((1.0 - s) * q0[i] + s * qq1[i]);
      }
      for (int i = 0; i < n; ++i) {
        hist.u.push_back((1.0 - s) * u0[i] + s * uu1[i]);
      }
      for (int i = 0; i < n; ++i) {
        ws.work_[i] = (1.0 - s) * q0[i] + s * qq1[i];
      }
      for (int c = 0; c < nc; ++c) {
        hist.gap_m.push_back(contact::Gap(model, c, ws.work_));
        hist.lambda_N.push_back(step > 0.0 ? ws.P_N_[c] / step : 0.0);
        hist.lambda_T.push_back(step > 0.0 ? ws.P_T_[c] / step : 0.0);
        hist.state.push_back(step > 0.0 ? ws.state_[static_cast<std::size_t>(c)] : 0);
      }
      ++next_sample;
    }
  };
  ws.P_N_.setZero();
  ws.P_T_.setZero();
  ws.P_N_previous_.setZero();
  std::fill(ws.state_.begin(), ws.state_.end(), 0);
  std::fill(ws.state_previous_.begin(), ws.state_previous_.end(), 0);
  record_until(0.0, q, u, 0.0, q, u, 0.0);

  const long n_steps =
      std::max(1L, static_cast<long>(std::ceil(t_end / h - policy.step_count_band)));
  double last_impact_t = -std::numeric_limits<double>::infinity();
  double t = 0.0;
  for (long k = 0; k < n_steps; ++k) {
    if (k >= control.max_steps) {
      result.status = RunStatus::kStepLimit;
      result.message = fmt::format("step limit of {} steps at t = {:g} s", control.max_steps, t);
      break;
    }
    const double t1 = k + 1 == n_steps ? t_end : static_cast<double>(k + 1) * h;
    const double hk = t1 - t;
    if (sparse) {
      ws.FactoriseSparse(hk);
    } else {
      ws.Factorise(hk);
    }
    const Eigen::Vector2d a_mean = MeanAcceleration(excitation, t, t1);

    // Free velocity: W (u_free - u_k) = h (-C u_k - K (q_k + h theta u_k) - M r abar_g).
    ws.work_ = q + (hk * theta) * u;
    if (sparse) {
      ws.rhs_.noalias() = -(ws.C_sparse_ * u);
      ws.rhs_.noalias() -= ws.K_sparse_ * ws.work_;
    } else {
      ws.rhs_.noalias() = -model.C() * u;
      ws.rhs_.noalias() -= model.K() * ws.work_;
    }
    ws.work_.noalias() = model.r() * a_mean;
    ws.rhs_ -= mass.cwiseProduct(ws.work_);
    ws.rhs_ *= hk;
    ws.u_free_ = u;
    if (sparse) {
      ws.u_free_ += ws.cholmod_.solve(ws.rhs_);
    } else {
      ws.u_free_.noalias() += ws.W_inverse_ * ws.rhs_;
    }

    contact::Evaluate(model, q, u, ws.kin_);
    ws.active_.clear();
    for (int c = 0; c < nc; ++c) {
      if (ws.kin_.gap_m[c] + policy.active_set_lookahead * hk * ws.kin_.gamma_N[c] <= 0.0) {
        ws.active_.push_back(c);
      }
    }
    ws.P_N_previous_ = ws.P_N_;
    ws.state_previous_ = ws.state_;
    ws.P_N_.setZero();
    ws.P_T_.setZero();
    ws.u1_ = ws.u_free_;
    const int ka = static_cast<int>(ws.active_.size());
    if (ka > 0) {
      ++result.rk_steps;
      for (int j = 0; j < ka; ++j) {
        const int c = ws.active_[static_cast<std::size_t>(j)];
        ws.WN_.col(j) = ws.kin_.W_N.col(c);
        ws.WT_.col(j) = ws.kin_.W_T.col(c);
        ws.mu_[j] = model.contact(c).friction;
        ws.eps_[j] = model.contact(c).restitution;
      }
      const auto WN = ws.WN_.leftCols(ka);
      const auto WT = ws.WT_.leftCols(ka);
      auto A = ws.A_.topLeftCorner(3 * ka, 3 * ka);
      A.setZero();
      // [docs/theory.md §3, impact problem] with W^-1 in place of M^-1.
      if (sparse) {
        // W^-1 W_N by the factor; W_N^T (W^-1 W_N) with the sparse W_N (6 rows per column).
        ws.GatherSparseJacobians(ka);
        ws.WinvWN_.leftCols(ka) = ws.cholmod_.solve(ws.WN_.leftCols(ka));
        ws.WinvWT_.leftCols(ka) = ws.cholmod_.solve(ws.WT_.leftCols(ka));
        const auto WinvWN = ws.WinvWN_.leftCols(ka);
        const auto WinvWT = ws.WinvWT_.leftCols(ka);
        A.block(0, 0, ka, ka).noalias() = ws.WN_sparse_.transpose() * WinvWN;
        A.block(0, ka, ka, ka).noalias() = ws.WN_sparse_.transpose() * WinvWT;
        A.block(ka, 0, ka, ka).noalias() = ws.WT_sparse_.transpose() * WinvWN;
        A.block(ka, ka, ka, ka).noalias() = ws.WT_sparse_.transpose() * WinvWT;
      } else {
        ws.WinvWN_.leftCols(ka).noalias() = ws.W_inverse_ * WN;
        ws.WinvWT_.leftCols(ka).noalias() = ws.W_inverse_ * WT;
        const auto WinvWN = ws.WinvWN_.leftCols(ka);
        const auto WinvWT = ws.WinvWT_.leftCols(ka);
        A.block(0, 0, ka, ka).noalias() = WN.transpose() * WinvWN;
        A.block(0, ka, ka, ka).noalias() = WN.transpose() * WinvWT;
        A.block(ka, 0, ka, ka).noalias() = WT.transpose() * WinvWN;
        A.block(ka, ka, ka, ka).noalias() = WT.transpose() * WinvWT;
      }
      for (int j = 0; j < ka; ++j) {
        // Columns of W_N - W_T mu: subtract mu_j times the W_T column block.
        A.block(0, j, ka, 1) -= ws.mu_[j] * A.block(0, ka + j, ka, 1);
        A.block(ka, j, ka, 1) -= ws.mu_[j] * A.block(ka, ka + j, ka, 1);
        A(ka + j, 2 * ka + j) = 1.0;
        A(2 * ka + j, j) = 2.0 * ws.mu_[j];
        A(2 * ka + j, ka + j) = -1.0;
        const int c = ws.active_[static_cast<std::size_t>(j)];
        ws.b_[j] =
            contact::ColumnDot(model, c, WN.col(j), ws.u_free_) + ws.eps_[j] * ws.kin_.gamma_N[c];
        ws.b_[ka + j] = contact::ColumnDot(model, c, WT.col(j), ws.u_free_);
        ws.b_[2 * ka + j] = 0.0;
      }
      {
        // A compliance of normal_compliance of the largest normal entry per unit impulse
        // (gamma_N + eps gamma_N,A = -c P_N at a contact that carries): with a deck clamped
        // between two closed faces the rigid problem has a squeeze of both faces among its
        // solutions (it changes no velocity), and Lemke's algorithm may return one, a prestress
        // whose friction locks the deck. With the compliance both faces cannot yield at once and
        // the solution carries no squeeze, as the event-driven integrator's choice (the least
        // total normal force). Elsewhere it moves the impulses by that relative amount.
        double top = 0.0;
        for (int j = 0; j < ka; ++j) {
          top = std::max(top, std::abs(A(j, j)));
        }
        for (int j = 0; j < ka; ++j) {
          A(j, j) += policy.normal_compliance * top;
        }
      }
      lcp::LcpSolution& sol = ws.solutions_[static_cast<std::size_t>(3 * ka)];
      lcp::LcpStatus status = ws.lemke_.Solve(A, ws.b_.head(3 * ka), sol);
      if (status != lcp::LcpStatus::kSolved && 3 * ka <= lcp::kMaxEnumerationSize) {
        // Two corners of one face have identical tangent rows: Lemke's ray on such a
        // degenerate problem proves nothing, the enumeration of its bases decides.
        status = lcp::SolveByEnumeration(A, ws.b_.head(3 * ka), sol);
      }
      if (status != lcp::LcpStatus::kSolved) {
        result.status = RunStatus::kLcpFailure;
        result.message = fmt::format("time-stepping LCP: {} at t = {:g} s with {} active contacts",
                                     lcp::ToString(status), t, ka);
        break;
      }
      for (int j = 0; j < ka; ++j) {
        const int c = ws.active_[static_cast<std::size_t>(j)];
        ws.P_N_[c] = sol.z[j];
        ws.P_T_[c] = sol.z[ka + j] - ws.mu_[j] * sol.z[j];
        ws.u1_.noalias() += ws.WinvWN_.col(j) * ws.P_N_[c] + ws.WinvWT_.col(j) * ws.P_T_[c];
      }
    } else {
      ++result.free_steps;
    }
    ws.u_theta_ = theta * ws.u1_ + (1.0 - theta) * u;
    ws.q1_ = q + hk * ws.u_theta_;

    // Energy ledger with the theta-point velocity (exact for theta = 1/2).
    EnergyLedger& e = result.energy;
    if (sparse) {
      ws.work_.noalias() = ws.C_sparse_ * ws.u_theta_;
    } else {
      ws.work_.noalias() = model.C() * ws.u_theta_;
    }
    e.damping_J += hk * ws.u_theta_.dot(ws.work_);
    ws.work_.noalias() = model.r() * a_mean;
    e.input_J -= hk * ws.u_theta_.dot(mass.cwiseProduct(ws.work_));

    bool impact = false;
    const double kinetic_before = 0.5 * u.dot(mass.cwiseProduct(u));
    const double kinetic_after = 0.5 * ws.u1_.dot(mass.cwiseProduct(ws.u1_));
    for (int j = 0; j < ka; ++j) {
      const int c = ws.active_[static_cast<std::size_t>(j)];
      e.impact_J -= contact::ColumnDot(model, c, ws.kin_.W_N.col(c), ws.u_theta_) * ws.P_N_[c];
      e.friction_J -= contact::ColumnDot(model, c, ws.kin_.W_T.col(c), ws.u_theta_) * ws.P_T_[c];
      if (ws.P_N_[c] > 0.0 && ws.P_N_previous_[c] <= 0.0) {
        impact = true;
      }
    }
    for (int c = 0; c < nc; ++c) {
      const double gamma_T1 = contact::ColumnDot(model, c, ws.kin_.W_T.col(c), ws.u1_);
      ws.state_[static_cast<std::size_t>(c)] = StateOf(ws.P_N_[c], gamma_T1, v_tol);
      const int before = ws.state_previous_[static_cast<std::size_t>(c)];
      const int now = ws.state_[static_cast<std::size_t>(c)];
      const int open = static_cast<int>(ContactState::kOpen);
      const int stick = static_cast<int>(ContactState::kStick);
      if (before != open && now == open) {
        ++result.detachments;
        result.events.push_back({t1, EventKind::kDetachment, c});
      } else if (before != open && now != open && before != now) {
        if (now == stick) {
          ++result.stick_transitions;
          result.events.push_back({t1, EventKind::kStick, c});
        } else {
          ++result.slip_transitions;
          result.events.push_back({t1, EventKind::kSlip, c});
        }
      }
    }
    if (impact) {
      ++result.impacts;
      if (std::isfinite(last_impact_t)) {
        result.min_impact_separation_s =
            std::min(result.min_impact_separation_s, t - last_impact_t);
      }
      last_impact_t = t;
      for (int j = 0; j < ka; ++j) {
        const int c = ws.active_[static_cast<std::size_t>(j)];
        if (ws.P_N_[c] > 0.0 && ws.P_N_previous_[c] <= 0.0) {
          EventRecord event;
          event.t_s = t;
          event.kind = EventKind::kImpact;
          event.contact = c;
          event.impulse_N_Ns = ws.P_N_[c];
          event.impulse_T_Ns = ws.P_T_[c];
          event.gamma_N_before_mps = ws.kin_.gamma_N[c];
          event.gamma_N_after_mps = contact::ColumnDot(model, c, ws.kin_.W_N.col(c), ws.u1_);
          event.kinetic_loss_J = kinetic_before - kinetic_after;
          result.events.push_back(event);
        }
      }
    }

    for (int i = 0; i < n; ++i) {
      if (std::abs(ws.q1_[i]) > result.max_abs_q[i]) {
        result.max_abs_q[i] = std::abs(ws.q1_[i]);
        result.time_of_max_s[i] = t1;
      }
    }
    travel.Update(ws.q1_, result.max_travel_m);
    record_until(t, q, u, t1, ws.q1_, ws.u1_, hk);
    q = ws.q1_;
    u = ws.u1_;
    if (!StateFinite(q) || !StateFinite(u)) {
      result.status = RunStatus::kNonFinite;
      result.message = NonFiniteMessage(t, t1);
      t = t1;
      break;
    }
    t = t1;
  }

  result.end_time_s = t;
  result.q_end = q;
  result.u_end = u;
  EnergyLedger& e = result.energy;
  e.kinetic_J = 0.5 * u.dot(mass.cwiseProduct(u));
  if (sparse) {
    ws.work_.noalias() = ws.K_sparse_ * q;
  } else {
    ws.work_.noalias() = model.K() * q;
  }
  e.strain_J = 0.5 * q.dot(ws.work_);
  e.balance_error_J = (e.kinetic_J + e.strain_J) -
                      (e.initial_J + e.input_J - e.damping_J - e.impact_J - e.friction_J);
  if (result.status == RunStatus::kOk && !std::isfinite(e.kinetic_J + e.strain_J)) {
    result.status = RunStatus::kNonFinite;
    result.message = fmt::format(
        "the energy of the state is not finite at t = {:g} s (the state overflows its squares)", t);
  }
  return result;
}

}  // namespace skewbridge::dynamics
