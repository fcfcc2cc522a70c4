// One run with a rigid wall and a compliant one (SimulateMixed, compliant_run.h): the event-driven
// integrator of Simulate carrying the compliant wall's springs. The integrator's springs' part is
// here, apart from its steps (simulate.cpp): the rigid law's steps reach it through calls made
// only with springs, so they compile as they do without them.
#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <vector>

#include "solver/dynamics/compliant_run.h"
#include "solver/dynamics/event_location.h"
#include "solver/dynamics/integrator.h"
#include "solver/dynamics/root_finding.h"
#include "solver/dynamics/spring_set.h"

namespace skewbridge::dynamics {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

bool Integrator::SpringsFree() const {
  if (springs_->AnyEngaged()) return false;
  Eigen::Vector3d w;
  for (int j = 0; j < springs_->size(); ++j) {
    const SpringSet::SpringState& m = springs_->state(j);
    if (m.broken) continue;
    double d, rate;
    springs_->Kinematics(j, z_.head(n_), z_.segment(n_, n_), d, rate, w);
    if (!(d < m.d_set_m)) return false;
  }
  return true;
}

void Integrator::SettleSprings() {
  if (springs_->SettleAll(z_.head(2 * n_), t_)) ++strikes_;
}

double Integrator::FreeStepSpringClosing(const ExcitationPiece& piece, const FreeStepPlan& step,
                                         bool dense_built) {
  const double t1 = step.t_next_s;
  const auto ensure_dense = [&]() {
    if (!dense_built) {
      ws_.free_dense_.Build(ws_.flow_, piece.omega, z_, t1 - t_);
      dense_built = true;
    }
  };
  // The flow's dense output inside the step, in z_eval_ (as the free step's own searches have it).
  const auto state_at = [&](double t) -> const Vec& {
    ensure_dense();
    ws_.free_dense_.EvaluateHead(t - t_, 2 * n_, z_eval_);
    return z_eval_;
  };
  // Each spring's closing as an impact: the gap d_set - d to its closing point, closing at the
  // rate -d'.
  double t_event = kInf;
  Eigen::Vector3d w;
  for (int j = 0; j < springs_->size(); ++j) {
    const SpringSet::SpringState& m = springs_->state(j);
    if (m.broken) continue;
    const double d_set = m.d_set_m;
    double d0, r0, d1, r1;
    springs_->Kinematics(j, z_.head(n_), z_.segment(n_, n_), d0, r0, w);
    springs_->Kinematics(j, z_new_.head(n_), z_new_.segment(n_, n_), d1, r1, w);
    if (!ImpactSuspected(d_set - d0, -r0, d_set - d1, -r1, t1 - t_, policy_.dip_margin)) continue;
    const auto gap = [&](double t) {
      const Vec& s = state_at(t);
      double d, rate;
      Eigen::Vector3d ww;
      springs_->Kinematics(j, s.head(n_), s.segment(n_, n_), d, rate, ww);
      return d_set - d;
    };
    const auto gamma_N = [&](double t) {
      const Vec& s = state_at(t);
      double d, rate;
      Eigen::Vector3d ww;
      springs_->Kinematics(j, s.head(n_), s.segment(n_, n_), d, rate, ww);
      return -rate;
    };
    t_event = std::min(t_event, FirstGapRoot(t_, t1, d_set - d0, -r0, d_set - d1, -r1, gap, gamma_N,
                                             scales_.gap_tol_m, scales_.v_tol_mps, policy_));
  }
  // The step's end is then read from the dense output at the closing.
  if (t_event < kInf) ensure_dense();
  return t_event;
}

double Integrator::FirstSpringEvent(double t1) {
  // The first spring event function to change sign, on the dense output (as a compliant run
  // locates it).
  const DormandPrince45& rk = ws_.rk_;
  springs_->AllEventValues(rk.y_end(), spring_e1_);
  const double x_tol = EventTimeBracket(t1, policy_);
  double t_event = kInf;
  for (int e = 0; e < spring_e0_.size(); ++e) {
    if (!(spring_e0_[e] > 0.0 && spring_e1_[e] <= 0.0)) continue;
    const auto value = [&](double t) {
      rk.DenseHeadAt(t, 2 * n_, y_eval_);
      return springs_->EventValueAt(e, y_eval_);
    };
    const RootResult root = FindRootBrent(value, t_, t1, spring_e0_[e], spring_e1_[e], x_tol);
    t_event = std::min(t_event, root.fx <= 0.0 ? root.x : root.upper);
  }
  return t_event;
}

void Integrator::SpringMaxima() { springs_->Maxima(z_.head(2 * n_)); }

void Integrator::SpringClosedInFreeStep() {
  SettleSprings();
  GapsAndRates(q(), u(), ends_.gap0, ends_.gN0);
  gaps_exact_ = true;
}

void Integrator::SpringsRhs(double t, const Eigen::Ref<const Vec>& y, KinematicsOf which,
                            Eigen::Ref<Vec> dy) {
  Rhs(t, y, which, dy.head(2 * n_ + 3));
  if (!control_.energy_ledger) {
    dy.tail(2).setZero();  // riding along as the other work integrals do
    return;
  }
  // Their forces are in du already, through the hook: here their powers alone.
  double joint_W, friction_W;
  spring_scratch_h_.setZero();
  springs_->AddForces(y.head(n_), y.segment(n_, n_), spring_scratch_h_, joint_W, friction_W);
  dy[2 * n_ + 3] = joint_W;
  dy[2 * n_ + 4] = friction_W;
}

void Integrator::SpringsStep(double h) {
  springs_->AllEventValues(y_, spring_e0_);
  const auto rhs = [this](double t, const Eigen::Ref<const Vec>& y, Eigen::Ref<Vec> dy) {
    SpringsRhs(t, y, KinematicsOf::kClosedContacts, dy);
  };
  ws_.rk_.Step(rhs, t_, y_, dy_, h);
}

void Integrator::FinishSprings(EnergyLedger& e) {
  // The springs as a compliant run has them: what they would give back by unloading is stored
  // (their stick springs' F_t^2 / (2 k_t) too), the rest of their work dissipated; the wall
  // friction's dissipation joins the contacts' friction.
  double stored, friction_stored;
  springs_->EndEnergies(q(), u(), stored, friction_stored);
  joint_stored_J_ = stored + friction_stored;
  joint_dissipated_J_ = joint_work_J_ - stored;
  e.friction_J += wall_friction_J_ - friction_stored;
  result_.impacts += strikes_;
  e.balance_error_J =
      (e.kinetic_J + e.strain_J + joint_stored_J_) -
      (e.initial_J + e.input_J - e.damping_J - e.impact_J - e.friction_J - joint_dissipated_J_);
}

CompliantRunResult SimulateMixed(const model::Model& model,
                                 const std::vector<CompliantSpring>& springs,
                                 const Excitation& excitation, const model::RunControl& control,
                                 const InitialState& initial, const EventPolicy& policy) {
  SpringSet set(model, springs);
  SimulationWorkspace workspace(model);
  Integrator integrator(model, excitation, control, workspace, initial, policy, nullptr, &set);
  CompliantRunResult out;
  out.run = integrator.Run();
  out.joint_stored_J = integrator.joint_stored_J();
  out.joint_dissipated_J = integrator.joint_dissipated_J();
  set.MoveResults(out);
  return out;
}

}  // namespace skewbridge::dynamics
