#include "solver/dynamics/compliant_run.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "solver/common/error.h"
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

constexpr double kInf = std::numeric_limits<double>::infinity();
// Transitions of one spring at one instant before its branch is left as it is (a spring grazing
// its closing point with no velocity would otherwise flip without end).
constexpr int kSettleLimit = 4;

}  // namespace

/// The state machine of one compliant run (compliant_run.h); lives for one SimulateCompliant call.
class CompliantIntegrator {
 public:
  CompliantIntegrator(const model::Model& model, const std::vector<CompliantSpring>& springs,
                      const Excitation& excitation, const model::RunControl& control,
                      const InitialState& initial, const EventPolicy& policy);

  CompliantRunResult Run();

 private:
  using Vec = Eigen::VectorXd;

  // The piece of its law a spring is on.
  enum class Branch {
    kOpen,         // no force
    kLine,         // backfill or key: the line below d_max, F(d_max) - K (d_max - d), K = K_ur, K_0
    kEnvelope,     // backfill: the envelope, loading (d' > 0)
    kDashpot,      // spring-dashpot: k d + c d'
    kKeyRise,      // key: the backbone's rise K_0 d to V_n at D3, loading
    kKeySoften,    // key: the backbone's fall from V_n at D3 to V_res at D_res, loading
    kKeyResidual,  // key: the backbone's fall from V_res at D_res to 0 at DD, loading
  };
  // One spring's kinematics and its law's memory.
  struct SpringState {
    Branch branch = Branch::kOpen;
    double d_max_m = 0.0;   // backfill: the largest deformation reached
    double f_peak_N = 0.0;  // backfill: F(d_max)
    double d_set_m = 0.0;   // backfill: the permanent set, d_max - F(d_max) / K_ur (>= 0)
    bool broken = false;    // key: d_max reached DD; the key carries nothing ever again
  };

  bool Failed() const { return result_.status != RunStatus::kOk; }
  // Deformation d = -g (m), its rate d' (m/s) and the gap's gradient w (on the body's 3 DOFs)
  // of spring j at (q, u).
  void Kinematics(int j, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u, double& d,
                  double& rate, Eigen::Vector3d& w) const;
  // The force of spring j on its current branch, continued past the branch's ends (N).
  double BranchForce(int j, double d, double rate) const;
  // The slope of spring j's unloading-reloading line (N/m): K_ur of a backfill, K_0 of a key.
  double LineStiffness(int j) const;
  // The backbone piece a key loading past d (m) is on, or kOpen after breaking it.
  Branch KeyPieceAbove(int j, double d) const;
  // The turn of spring j from loading to unloading at d (m): the memory takes d, the line follows.
  void CommitTurn(int j, double d);
  // The event functions of spring j (positive while its branch holds): two per spring.
  void EventValues(int j, double d, double rate, double& e1, double& e2) const;
  // All springs' event functions at the state y (2 per spring) into `out`.
  void AllEventValues(const Eigen::Ref<const Vec>& y, Vec& out) const;
  // The transitions of spring j at (d, d') until its event functions are positive or it cannot
  // leave its branch; returns true when it closed from open (a strike's start).
  bool Settle(int j, double d, double rate);
  // Settles every spring at the state y; counts a strike when one closes with none engaged.
  void SettleAll(const Eigen::Ref<const Vec>& y);
  // Whether every spring is open and off its closing point (the free flow applies).
  bool AllFree(const Eigen::Ref<const Vec>& y) const;
  bool AnyEngaged() const;
  // dy/dt of y = (q, u, input work, damping work, springs' work) on the piece `piece`.
  void Rhs(const ExcitationPiece& piece, double t, const Eigen::Ref<const Vec>& y,
           Eigen::Ref<Vec> dy) const;
  void FreeStep();
  void CompliantStep();
  // The step [t_, t1] done, its end state in y_new: maxima, corner travels and samples.
  template <class ComponentAt, class StateAt>
  void RecordStep(double t1, const Eigen::Ref<const Vec>& y_new, ComponentAt&& component_at,
                  StateAt&& state_at);
  void SpringMaxima(const Eigen::Ref<const Vec>& y);
  template <class StateAt>
  void RecordOutputs(double t0, double t1, StateAt&& state_at);
  CompliantRunResult Finish(double t_finite_s);

  const model::Model& model_;
  const std::vector<CompliantSpring>& springs_;
  const Excitation& excitation_;
  const model::RunControl& control_;
  const EventPolicy policy_;
  LinearFlow flow_;
  FreeDenseOutput dense_;
  double omega_min_radps_ = 0.0, omega_max_radps_ = 0.0;
  int n_, ns_;
  RunScales scales_;
  double t_ = 0.0, t_end_ = 0.0;
  double h_rk_ = 0.0, h_free_ = 0.0;
  double next_output_t_ = kInf;
  double rtol_ = 0.0;
  // The next compliant step may take dy_ and e0_ as they are (the last step ended without an
  // event inside its piece, and no free step came between).
  bool fresh_start_ = false;
  // y = (q, u, input work, damping work, springs' work): the state and the running integrals.
  Vec y_, dy_, y_new_, y_eval_, atol_;
  Vec z_, z_new_, z_eval_;  // the free flow's augmented state
  Vec e0_, e1_, e_eval_;    // the springs' event functions at a step's start, end, trial time
  mutable Vec h_, cu_;      // applied forces and C u scratch
  std::vector<SpringState> state_;
  DormandPrince45 rk_;
  CompliantRunResult out_;
  RunResult& result_;
  CornerTravelTracker travel_;
};

CompliantIntegrator::CompliantIntegrator(const model::Model& model,
                                         const std::vector<CompliantSpring>& springs,
                                         const Excitation& excitation,
                                         const model::RunControl& control,
                                         const InitialState& initial, const EventPolicy& policy)
    : model_(model),
      springs_(springs),
      excitation_(excitation),
      control_(control),
      policy_(policy),
      flow_(model.M(), model.K(), model.C(), model.r(), FlowPath::kAuto, model.modes()),
      dense_(flow_.augmented_size()),
      n_(model.n_dof()),
      ns_(static_cast<int>(springs.size())),
      state_(springs.size()),
      rk_(2 * model.n_dof() + 3),
      result_(out_.run),
      travel_(model) {
  if (model.n_contacts() > 0) {
    throw InputError::AtField(model.source(), "abutments",
                              "a model with compliant springs has no rigid contact (one law for "
                              "every abutment)");
  }
  for (const CompliantSpring& s : springs) {
    const std::string where = model.source() + ": spring " + s.name;
    if (s.body < 0 || s.body >= model.n_bodies() || s.face.body != model::kGround ||
        !s.point_m.allFinite() || !s.face.point_m.allFinite() ||
        !(std::abs(s.face.normal.norm() - 1.0) <= 1e-12)) {
      throw InputError::AtField(where, "geometry",
                                "needs a body index, finite points and a unit normal of a ground "
                                "face");
    }
    if (s.law == SpringLaw::kBackfill) {
      joint::ValidateHyperbolicGap(s.backfill, where);
    } else if (s.law == SpringLaw::kShearKey) {
      joint::ValidateShearKey(s.key, where);
    } else if (!(s.k_N_per_m > 0.0 && std::isfinite(s.k_N_per_m) && s.c_Ns_per_m >= 0.0 &&
                 std::isfinite(s.c_Ns_per_m))) {
      throw InputError::AtField(where, "k, c", "must be k > 0, c >= 0, finite");
    }
  }
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
  y_ = Vec::Zero(2 * n_ + 3);
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
  e0_ = e1_ = e_eval_ = Vec::Zero(2 * ns_);
  h_ = cu_ = Vec::Zero(n_);
  t_end_ = control.EndTime(excitation.Duration());
  scales_ = ComputeRunScales(
      ExcitationPeak(excitation, policy_.ramp_horizon_s), y_.segment(n_, n_).cwiseAbs().maxCoeff(),
      {omega_min_radps_, omega_max_radps_, length_scale, MaxTranslationalMass(model)},
      control.accumulation_threshold, policy_);
  // The springs' own frequency joins the step control's velocity scale.
  double k_sum = 0.0;
  for (const CompliantSpring& s : springs) {
    switch (s.law) {
      case SpringLaw::kBackfill:
        k_sum += std::max(s.backfill.k_max_N_per_m, s.backfill.k_ur_N_per_m);
        break;
      case SpringLaw::kSpringDashpot:
        k_sum += s.k_N_per_m;
        break;
      case SpringLaw::kShearKey:
        k_sum += s.key.v_n_N / s.key.d3_m;
        break;
    }
  }
  const double omega_spring = std::sqrt(k_sum / MaxTranslationalMass(model));
  const double omega_top = std::max(scales_.omega_top_radps, omega_spring);
  rtol_ = control.relative_tolerance;
  atol_ = Vec::Constant(2 * n_ + 3, kInf);
  atol_.head(n_).setConstant(control.absolute_tolerance);
  atol_.segment(n_, n_).setConstant(control.absolute_tolerance * omega_top);
  h_rk_ = std::min(scales_.first_rk_step_s, 0.01 / omega_top);
  result_.max_abs_q = y_.head(n_).cwiseAbs();
  result_.time_of_max_s = Vec::Zero(n_);
  out_.max_spring_force_N = Vec::Zero(ns_);
  out_.max_spring_deformation_m = Vec::Zero(ns_);
  out_.key_break_time_s = Vec::Constant(ns_, std::numeric_limits<double>::quiet_NaN());
  travel_.Start(y_.head(n_), result_.max_travel_m);
  if (control.output_interval_s > 0.0) {
    result_.histories.n_dof = n_;
    result_.histories.n_contacts = 0;
    next_output_t_ = 0.0;
  }
}

void CompliantIntegrator::Kinematics(int j, const Eigen::Ref<const Vec>& q,
                                     const Eigen::Ref<const Vec>& u, double& d, double& rate,
                                     Eigen::Vector3d& w) const {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  const int b = 3 * s.body;
  const double c = std::cos(q[b + 2]), sn = std::sin(q[b + 2]);
  const Eigen::Vector2d rp(c * s.point_m.x() - sn * s.point_m.y(),
                           sn * s.point_m.x() + c * s.point_m.y());
  const Eigen::Vector2d& rest = model_.body(s.body).rest_position_m;
  const Eigen::Vector2d& n = s.face.normal;
  const double gap = n.dot(rest + Eigen::Vector2d(q[b], q[b + 1]) + rp - s.face.point_m);
  w << n.x(), n.y(), n.x() * -rp.y() + n.y() * rp.x();
  d = -gap;
  rate = -(w[0] * u[b] + w[1] * u[b + 1] + w[2] * u[b + 2]);
}

double CompliantIntegrator::BranchForce(int j, double d, double rate) const {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  const SpringState& m = state_[static_cast<std::size_t>(j)];
  switch (m.branch) {
    case Branch::kOpen:
      return 0.0;
    case Branch::kLine:
      return m.f_peak_N - LineStiffness(j) * (m.d_max_m - d);
    case Branch::kEnvelope:
      return d / (1.0 / s.backfill.k_max_N_per_m + s.backfill.r_f * d / s.backfill.f_ult_N);
    case Branch::kDashpot:
      return s.k_N_per_m * d + s.c_Ns_per_m * rate;
    case Branch::kKeyRise:
      return s.key.v_n_N * d / s.key.d3_m;
    case Branch::kKeySoften:
      return s.key.v_n_N +
             (s.key.v_res_N - s.key.v_n_N) * (d - s.key.d3_m) / (s.key.d_res_m - s.key.d3_m);
    case Branch::kKeyResidual:
      return s.key.v_res_N * (s.key.dd_m - d) / (s.key.dd_m - s.key.d_res_m);
  }
  return 0.0;
}

double CompliantIntegrator::LineStiffness(int j) const {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  return s.law == SpringLaw::kShearKey ? s.key.v_n_N / s.key.d3_m : s.backfill.k_ur_N_per_m;
}

CompliantIntegrator::Branch CompliantIntegrator::KeyPieceAbove(int j, double d) const {
  const joint::ShearKey& key = springs_[static_cast<std::size_t>(j)].key;
  if (d < key.d3_m) return Branch::kKeyRise;
  if (d < key.d_res_m) return Branch::kKeySoften;
  if (d < key.dd_m) return Branch::kKeyResidual;
  return Branch::kOpen;
}

void CompliantIntegrator::CommitTurn(int j, double d) {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  SpringState& m = state_[static_cast<std::size_t>(j)];
  if (s.law == SpringLaw::kShearKey) {
    m.d_max_m = joint::ShearKeyCommit(s.key, joint::ShearKeyState{m.d_max_m}, d).d_max_m;
    m.f_peak_N = joint::ShearKeyBackbone_N(s.key, m.d_max_m);
    m.d_set_m = std::max(0.0, m.d_max_m - m.f_peak_N / LineStiffness(j));
  } else {
    const joint::BackfillState memory =
        joint::BackfillCommit(s.backfill, joint::BackfillState{m.d_max_m}, d);
    m.d_max_m = memory.d_max_m;
    m.f_peak_N = joint::EnvelopeForce_N(s.backfill, m.d_max_m);
    m.d_set_m = joint::PermanentSet_m(s.backfill, memory);
  }
  m.branch = Branch::kLine;
}

void CompliantIntegrator::EventValues(int j, double d, double rate, double& e1, double& e2) const {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  const SpringState& m = state_[static_cast<std::size_t>(j)];
  e1 = e2 = kInf;
  switch (m.branch) {
    case Branch::kOpen:
      if (m.broken) return;  // a broken key never closes again
      if (s.law != SpringLaw::kSpringDashpot) {
        e1 = m.d_set_m - d;  // closes at the permanent set
      } else {
        // A spring-dashpot left with d > 0 re-engages when k d + c d' turns positive.
        e1 = -std::min(s.k_N_per_m * d, s.k_N_per_m * d + s.c_Ns_per_m * rate);
      }
      return;
    case Branch::kLine:
      e1 = m.d_max_m - d;  // reaches the envelope
      e2 = d - m.d_set_m;  // opens at the permanent set
      return;
    case Branch::kEnvelope:
      e1 = rate;  // turns from loading to unloading
      return;
    case Branch::kDashpot:
      e1 = s.k_N_per_m * d + s.c_Ns_per_m * rate;  // its force reaches zero
      return;
    case Branch::kKeyRise:
      e1 = s.key.d3_m - d;  // reaches the capacity V_n
      e2 = rate;            // turns from loading to unloading
      return;
    case Branch::kKeySoften:
      e1 = s.key.d_res_m - d;  // reaches the residual
      e2 = rate;
      return;
    case Branch::kKeyResidual:
      e1 = s.key.dd_m - d;  // breaks
      e2 = rate;
      return;
  }
}

void CompliantIntegrator::AllEventValues(const Eigen::Ref<const Vec>& y, Vec& out) const {
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    double d, rate;
    Kinematics(j, y.head(n_), y.segment(n_, n_), d, rate, w);
    EventValues(j, d, rate, out[2 * j], out[2 * j + 1]);
  }
}

bool CompliantIntegrator::Settle(int j, double d, double rate) {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  SpringState& m = state_[static_cast<std::size_t>(j)];
  const bool dashpot = s.law == SpringLaw::kSpringDashpot;
  const bool key = s.law == SpringLaw::kShearKey;
  bool closed = false;
  for (int k = 0; k < kSettleLimit; ++k) {
    double e1, e2;
    EventValues(j, d, rate, e1, e2);
    if (e1 > 0.0 && e2 > 0.0) {
      break;
    }
    switch (m.branch) {
      case Branch::kOpen:
        if (m.broken) return closed;
        if (!dashpot) {
          if (!(rate > 0.0)) return closed;  // on the closing point, moving out: stays open
          if (m.d_max_m > 0.0) {
            m.branch = Branch::kLine;
          } else {
            m.branch = key ? Branch::kKeyRise : Branch::kEnvelope;
          }
        } else {
          if (!(d > 0.0 && s.k_N_per_m * d + s.c_Ns_per_m * rate > 0.0)) return closed;
          m.branch = Branch::kDashpot;
        }
        closed = true;
        break;
      case Branch::kLine:
        if (e1 <= 0.0 && rate > 0.0) {
          m.branch = key ? KeyPieceAbove(j, m.d_max_m) : Branch::kEnvelope;
        } else if (e2 <= 0.0 && rate < 0.0) {
          m.branch = Branch::kOpen;
        } else {
          return closed;
        }
        break;
      case Branch::kEnvelope:
        if (rate > 0.0) return closed;
        CommitTurn(j, d);  // the turn: the memory takes the deformation reached
        break;
      case Branch::kDashpot:
        m.branch = Branch::kOpen;
        break;
      case Branch::kKeyRise:
      case Branch::kKeySoften:
      case Branch::kKeyResidual: {
        if (!(rate > 0.0)) {
          CommitTurn(j, d);
          break;
        }
        if (!(e1 <= 0.0)) return closed;
        // The piece's end passed while loading: the next piece, or the break at DD, where the
        // memory takes DD and the key's force, zero there, stays zero.
        const double end = m.branch == Branch::kKeyRise     ? s.key.d3_m
                           : m.branch == Branch::kKeySoften ? s.key.d_res_m
                                                            : s.key.dd_m;
        m.branch = KeyPieceAbove(j, end);
        if (m.branch == Branch::kOpen) {
          m.d_max_m = m.d_set_m = s.key.dd_m;
          m.f_peak_N = 0.0;
          m.broken = true;
          out_.key_break_time_s[j] = t_;
        }
        break;
      }
    }
  }
  return closed;
}

bool CompliantIntegrator::AnyEngaged() const {
  for (const SpringState& m : state_) {
    if (m.branch != Branch::kOpen) return true;
  }
  return false;
}

void CompliantIntegrator::SettleAll(const Eigen::Ref<const Vec>& y) {
  const bool engaged = AnyEngaged();
  bool strike = false;
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    double d, rate;
    Kinematics(j, y.head(n_), y.segment(n_, n_), d, rate, w);
    strike = Settle(j, d, rate) || strike;
  }
  if (strike && !engaged) ++result_.impacts;
}

bool CompliantIntegrator::AllFree(const Eigen::Ref<const Vec>& y) const {
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    const SpringState& m = state_[static_cast<std::size_t>(j)];
    if (m.branch != Branch::kOpen) return false;
    if (m.broken) continue;
    double d, rate;
    Kinematics(j, y.head(n_), y.segment(n_, n_), d, rate, w);
    if (!(d < m.d_set_m)) return false;
  }
  return true;
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
  double joint_W = 0.0;
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    if (state_[static_cast<std::size_t>(j)].branch == Branch::kOpen) continue;
    double d, rate;
    Kinematics(j, q, u, d, rate, w);
    const double f = BranchForce(j, d, rate);
    const int b = 3 * springs_[static_cast<std::size_t>(j)].body;
    h_.segment<3>(b) += f * w;
    joint_W += f * rate;
  }
  dy.head(n_) = u;
  dy.segment(n_, n_) = model_.inverse_mass_diagonal().cwiseProduct(h_);
  dy[2 * n_] = input_W;
  dy[2 * n_ + 1] = damping_W;
  dy[2 * n_ + 2] = joint_W;
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
    if (AllFree(y_)) {
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
  double t_event = kInf;
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    if (state_[static_cast<std::size_t>(j)].broken) continue;
    const double d_set = state_[static_cast<std::size_t>(j)].d_set_m;
    double d0, r0, d1, r1;
    Kinematics(j, z_.head(n_), z_.segment(n_, n_), d0, r0, w);
    Kinematics(j, z_new_.head(n_), z_new_.segment(n_, n_), d1, r1, w);
    if (!ImpactSuspected(d_set - d0, -r0, d_set - d1, -r1, tau, policy_.dip_margin)) continue;
    const auto gap = [&](double t) {
      const Vec& s = state_at(t);
      double d, rate;
      Eigen::Vector3d ww;
      Kinematics(j, s.head(n_), s.segment(n_, n_), d, rate, ww);
      return d_set - d;
    };
    const auto gamma_N = [&](double t) {
      const Vec& s = state_at(t);
      double d, rate;
      Eigen::Vector3d ww;
      Kinematics(j, s.head(n_), s.segment(n_, n_), d, rate, ww);
      return -rate;
    };
    t_event =
        std::min(t_event, FirstGapRoot(t_, step.t_next_s, d_set - d0, -r0, d_set - d1, -r1, gap,
                                       gamma_N, scales_.gap_tol_m, scales_.v_tol_mps, policy_));
  }
  if (t_event < kInf) {
    ensure_dense();
    dense.EvaluateHead(t_event - t_, 2 * n_, z_new_);
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
    AllEventValues(y_, e0_);
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
  AllEventValues(rk_.y_end(), e1_);
  // The first event function to change sign, located on the dense output; the time taken on its
  // far side so that the transition sees it crossed.
  double t_event = kInf;
  const double x_tol = EventTimeBracket(t_full, policy_);
  for (int e = 0; e < 2 * ns_; ++e) {
    if (!(e0_[e] > 0.0 && e1_[e] <= 0.0)) continue;
    const auto value = [&](double t) {
      rk_.DenseHeadAt(t, 2 * n_, y_eval_);
      AllEventValues(y_eval_, e_eval_);
      return e_eval_[e];
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
  SpringMaxima(y_);
}

void CompliantIntegrator::SpringMaxima(const Eigen::Ref<const Vec>& y) {
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    if (state_[static_cast<std::size_t>(j)].branch == Branch::kOpen) continue;
    double d, rate;
    Kinematics(j, y.head(n_), y.segment(n_, n_), d, rate, w);
    out_.max_spring_force_N[j] =
        std::max(out_.max_spring_force_N[j], std::max(0.0, BranchForce(j, d, rate)));
    out_.max_spring_deformation_m[j] = std::max(out_.max_spring_deformation_m[j], d);
  }
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
  // envelope, 1/2 k d^2 for an engaged spring-dashpot.
  double stored = 0.0;
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
    const SpringState& m = state_[static_cast<std::size_t>(j)];
    if (m.branch == Branch::kOpen) continue;
    double d, rate;
    Kinematics(j, y_.head(n_), y_.segment(n_, n_), d, rate, w);
    if (s.law != SpringLaw::kSpringDashpot) {
      const double f = std::max(0.0, BranchForce(j, d, rate));
      stored += f * f / (2.0 * LineStiffness(j));
    } else {
      stored += 0.5 * s.k_N_per_m * d * d;
    }
  }
  out_.joint_stored_J = stored;
  out_.joint_dissipated_J = work - stored;
  e.kinetic_J =
      0.5 * y_.segment(n_, n_).dot(model_.mass_diagonal().cwiseProduct(y_.segment(n_, n_)));
  e.strain_J = 0.5 * y_.head(n_).dot(model_.K() * y_.head(n_));
  e.balance_error_J = (e.kinetic_J + e.strain_J + out_.joint_stored_J) -
                      (e.initial_J + e.input_J - e.damping_J - out_.joint_dissipated_J);
  if (!control_.energy_ledger) {
    e.input_J = e.damping_J = e.balance_error_J = std::numeric_limits<double>::quiet_NaN();
  }
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
