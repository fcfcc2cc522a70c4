#pragma once
/// @file
/// The state machine of one compliant run (SimulateCompliant, compliant_run.h), shared by the
/// files that implement it: compliant_run.cpp (the steps, the records, the ledger) and
/// compliant_laws.cpp (each spring's law and wall friction: forces, event functions, transitions).

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "solver/common/excitation.h"
#include "solver/dynamics/compliant_run.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/gap_floors.h"
#include "solver/dynamics/linear_flow.h"
#include "solver/dynamics/run_scales.h"
#include "solver/dynamics/runge_kutta.h"
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
  // Transitions of one spring at one instant before its branch is left as it is (a spring grazing
  // its closing point with no velocity would otherwise flip without end).
  static constexpr int kSettleLimit = 4;

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
  // The state of the friction element of a spring with wall friction: free while the spring is
  // open; sticking on its stick spring F_t = -k_t (s - anchor); slipping with F_t = -sigma mu N.
  enum class Friction { kFree, kStick, kSlip };
  struct FrictionState {
    int spring = 0;  // the spring it belongs to
    double mu = 0.0, k_t_N_per_m = 0.0;
    Friction mode = Friction::kFree;
    double anchor_m = 0.0;      // kStick: the stick spring's anchor along the wall (m)
    double sigma = 0.0;         // kSlip: +1 slipping along +t, -1 along -t
    double slip_begin_m = 0.0;  // kSlip: the anchor when the slip began (m)
  };

  bool Failed() const { return result_.status != RunStatus::kOk; }
  // Deformation d = -g (m), its rate d' (m/s) and the gap's gradient w (on the body's 3 DOFs)
  // of spring j at (q, u); with a face on a body, w_face (if not null) takes the gradient on the
  // face body's 3 DOFs (zero for a ground face).
  void Kinematics(int j, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u, double& d,
                  double& rate, Eigen::Vector3d& w, Eigen::Vector3d* w_face = nullptr) const;
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
  // The coordinate dir . ((x, y) + R(theta) p - A) (m) of spring j's point along a unit
  // direction of its face, its rate (m/s) and gradient w on the body's 3 DOFs: the normal gives
  // the gap, the tangent the position along the wall.
  // A face on a body turns with it: dir is then in the body's frame, and w_face (if not null)
  // takes the gradient on the face body's DOFs.
  void Along(int j, const Eigen::Vector2d& dir, const Eigen::Ref<const Vec>& q,
             const Eigen::Ref<const Vec>& u, double& coord, double& rate, Eigen::Vector3d& w,
             Eigen::Vector3d* w_face = nullptr) const;
  // Tangential coordinate s = t . ((x, y) + R(theta) p - A) (m) of spring j along its face, its
  // rate s' (m/s) and gradient w_T.
  void Tangential(int j, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u, double& s,
                  double& rate, Eigen::Vector3d& w_t) const;
  // (cos theta, sin theta) of body b's angle theta = q[3 b + 2] (rad): computed once per angle,
  // since every spring of a body asks for it at the same state (the last two angles are kept).
  std::pair<double, double> Turn(int b, double theta_rad) const;
  // The slope dF/dd of spring j's current branch at d (N/m); 0 when open.
  double BranchSlope(int j, double d) const;
  // The friction force F_t along the tangent of friction element f (N) at (s, N).
  double FrictionForce(const FrictionState& f, double s, double normal_N) const;
  // The event functions of friction element f at the state y: stick: mu N -+ F_t; slip: the
  // plastic slip rate sigma s' - mu N' / k_t.
  void FrictionEventValues(int f, const Eigen::Ref<const Vec>& y, double& e1, double& e2) const;
  // The transitions of friction element f at the state y after its spring has settled.
  void SettleFriction(int f, const Eigen::Ref<const Vec>& y);
  // All springs' event functions at the state y (2 per spring, then 2 per friction element).
  void AllEventValues(const Eigen::Ref<const Vec>& y, Vec& out) const;
  // Event function e of AllEventValues at the state y, computed alone (the same bits).
  double EventValueAt(int e, const Eigen::Ref<const Vec>& y) const;
  // The transitions of spring j at (d, d') until its event functions are positive or it cannot
  // leave its branch; returns true when it closed from open (a strike's start).
  bool Settle(int j, double d, double rate);
  // Settles every spring at the state y; counts a strike when one closes with none engaged, and
  // keeps the smallest time between the starts of two successive strikes.
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
  Vec e0_, e1_;             // the springs' event functions at a step's start and end
  mutable Vec h_, cu_;      // applied forces and C u scratch
  // Per body: the bits of the last two angles Turn was asked for, and their cosines and sines
  // (two: the free step asks for each spring at the step's start and end states in turn).
  struct TurnMemo {
    std::uint64_t theta_bits[2] = {0, 0};
    double c[2] = {1.0, 1.0}, s[2] = {0.0, 0.0};  // cos and sin of +0.0
    int next = 0;                                 // the slot the next new angle replaces
  };
  mutable std::vector<TurnMemo> turn_;
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
  std::vector<SpringState> state_;
  std::vector<FrictionState> friction_;  // one per spring with wall friction
  int ny_;                               // size of y
  DormandPrince45 rk_;
  CompliantRunResult out_;
  RunResult& result_;
  double last_strike_t_s_ = -kInf;  // the start of the last strike (s); -inf before the first
  CornerTravelTracker travel_;
};

}  // namespace skewbridge::dynamics
