#pragma once
/// @file
/// The state machine of one compliant run (SimulateCompliant, compliant_run.h), shared by the
/// file that implements it, compliant_run.cpp (the steps, the records, the ledger); each spring's
/// law and wall friction (forces, event functions, transitions) are the SpringSet's (spring_set.h).

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <vector>

#include "solver/common/excitation.h"
#include "solver/dynamics/compliant_run.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/gap_floors.h"
#include "solver/dynamics/linear_flow.h"
#include "solver/dynamics/run_scales.h"
#include "solver/dynamics/runge_kutta.h"
#include "solver/dynamics/spring_set.h"
#include "solver/model/model.h"
#include "solver/model/run_control.h"

namespace skewbridge::dynamics {

/// The state machine of one compliant run (compliant_run.h); lives for one SimulateCompliant call.
class CompliantIntegrator {
 public:
  CompliantIntegrator(const model::Model& model, const std::vector<CompliantSpring>& springs,
                      const Excitation& excitation, const model::RunControl& control,
                      const InitialState& initial, const EventPolicy& policy);

  CompliantRunResult Run();

 private:
  using Vec = Eigen::VectorXd;
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  using Branch = SpringSet::Branch;
  using SpringState = SpringSet::SpringState;

  bool Failed() const { return result_.status != RunStatus::kOk; }
  // Settles every spring at the state y (SpringSet::SettleAll); counts a strike when one closes
  // with none engaged, and keeps the smallest time between the starts of two successive strikes.
  void SettleAll(const Eigen::Ref<const Vec>& y);
  // Whether every spring is open and off its closing point at the state y_ (the free flow
  // applies); leaves every unbroken spring's d and d' at y_ in start_d_m_, start_rate_mps_
  // unless the step before proved the springs open by the closing bound (start_bounded_).
  bool AllFree();
  // d and d' of every unbroken spring at the state y_ into start_d_m_, start_rate_mps_.
  void StartKinematics();
  // Whether every unbroken spring's gap to its closing point, d_set - d, provably stays above
  // twice the touch band over the full free step of length tau_s just applied (GapFloors).
  bool SpringsStayOpen(double tau_s);
  // dy/dt of y = (q, u, input work, damping work, springs' work, friction's work) on `piece`.
  void Rhs(const ExcitationPiece& piece, double t, const Eigen::Ref<const Vec>& y,
           Eigen::Ref<Vec> dy) const;
  void FreeStep();
  void CompliantStep();
  // The step [t_, t1] done, its end state in y_new: maxima, corner travels and samples.
  template <class ComponentAt, class StateAt>
  void RecordStep(double t1, const Eigen::Ref<const Vec>& y_new, ComponentAt&& component_at,
                  StateAt&& state_at);
  template <class StateAt>
  void RecordOutputs(double t0, double t1, StateAt&& state_at);
  CompliantRunResult Finish(double t_finite_s);

  const model::Model& model_;
  SpringSet set_;  // the springs, their memory and friction elements
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
  Vec e0_, e1_;             // the springs' event functions at a step's start and end
  mutable Vec h_, cu_;      // applied forces and C u scratch
  // Per spring, d (m) and d' (m/s) at the state y_, valid for the unbroken springs while
  // start_known_: a free step's end state is the next step's start (the same bits).
  std::vector<double> start_d_m_, start_rate_mps_;
  bool start_known_ = false;
  // The free steps since the last exact start values all proved every spring open by the
  // closing bound: the springs are open at y_, their d and d' there not computed.
  bool start_bounded_ = false;
  ModalGapBound spring_bound_;                // SpringGapBound of a modal flow, else empty
  std::unique_ptr<GapFloors> spring_floors_;  // with spring_bound_ when it applies
  Vec spring_gaps_;                           // per spring, d_set - d at y_ (m; +inf if broken)
  int ny_;                                    // size of y
  DormandPrince45 rk_;
  CompliantRunResult out_;
  RunResult& result_;
  double last_strike_t_s_ = -kInf;  // the start of the last strike (s); -inf before the first
  CornerTravelTracker travel_;
};

}  // namespace skewbridge::dynamics
