#pragma once
/// @file
/// The compliant springs of one run [docs/compliant.md §4]: each spring's law and memory, the wall
/// friction elements, their forces on the bodies and work, the event functions that say where a
/// spring or a friction element leaves its piece, the transitions there, and what a run reports of
/// them (maxima, key breaks, wall slips, the energy they store). The compliant integrator
/// (compliant_integrator.h) holds one; it is also the applied forces' hook (AddedForces) for an
/// integrator that carries springs beside rigid contacts.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "solver/dynamics/active_forces.h"
#include "solver/dynamics/compliant_run.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// The springs of one run and their memory; lives for one run. Validates the springs.
class SpringSet final : public AddedForces {
 public:
  using Vec = Eigen::VectorXd;
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  /// Transitions of one spring at one instant before its branch is left as it is (a spring
  /// grazing its closing point with no velocity would otherwise flip without end).
  static constexpr int kSettleLimit = 4;

  /// The piece of its law a spring is on.
  enum class Branch {
    kOpen,         ///< no force
    kLine,         ///< backfill or key: the line below d_max, F(d_max) - K (d_max - d), K_ur, K_0
    kEnvelope,     ///< backfill: the envelope, loading (d' > 0)
    kDashpot,      ///< spring-dashpot: k d + c d'
    kKeyRise,      ///< key: the backbone's rise K_0 d to V_n at D3, loading
    kKeySoften,    ///< key: the backbone's fall from V_n at D3 to V_res at D_res, loading
    kKeyResidual,  ///< key: the backbone's fall from V_res at D_res to 0 at DD, loading
  };
  /// One spring's branch and its law's memory.
  struct SpringState {
    Branch branch = Branch::kOpen;  ///< the piece it is on
    double d_max_m = 0.0;           ///< backfill: the largest deformation reached
    double f_peak_N = 0.0;          ///< backfill: F(d_max)
    double d_set_m = 0.0;           ///< backfill: the permanent set, d_max - F(d_max) / K_ur (>= 0)
    bool broken = false;            ///< key: d_max reached DD; the key carries nothing ever again
  };
  /// The mode of a spring's friction element: free while the spring is open; sticking on its
  /// stick spring F_t = -k_t (s - anchor); slipping with F_t = -sigma mu N.
  enum class Friction { kFree, kStick, kSlip };
  /// The friction element of a spring with wall friction.
  struct FrictionState {
    int spring = 0;                   ///< the spring it belongs to
    double mu = 0.0;                  ///< Coulomb coefficient
    double k_t_N_per_m = 0.0;         ///< stick stiffness (N/m)
    Friction mode = Friction::kFree;  ///< its mode
    double anchor_m = 0.0;            ///< kStick: the stick spring's anchor along the wall (m)
    double sigma = 0.0;               ///< kSlip: +1 slipping along +t, -1 along -t
    double slip_begin_m = 0.0;        ///< kSlip: the anchor when the slip began (m)
  };

  /// The springs on the bodies of `model` (both kept by reference).
  /// @throws InputError naming the spring when one is invalid (body index, face, law constants,
  /// friction).
  SpringSet(const model::Model& model, const std::vector<CompliantSpring>& springs);

  int size() const { return ns_; }  ///< the number of springs
  /// The number of friction elements (springs with wall friction).
  int n_friction() const { return static_cast<int>(friction_.size()); }
  /// The number of event functions: 2 per spring, then 2 per friction element.
  int n_events() const { return 2 * ns_ + 2 * n_friction(); }
  /// Spring j's branch and memory.
  const SpringState& state(int j) const { return state_[static_cast<std::size_t>(j)]; }
  /// The friction elements.
  const std::vector<FrictionState>& friction() const { return friction_; }
  /// Spring j's description.
  const CompliantSpring& spring(int j) const { return springs_[static_cast<std::size_t>(j)]; }

  /// Deformation d = -g (m), its rate d' (m/s) and the gap's gradient w (on the body's 3 DOFs)
  /// of spring j at (q, u); with a face on a body, w_face (if not null) takes the gradient on the
  /// face body's 3 DOFs (zero for a ground face).
  void Kinematics(int j, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u, double& d,
                  double& rate, Eigen::Vector3d& w, Eigen::Vector3d* w_face = nullptr) const;
  /// Tangential coordinate s = t . ((x, y) + R(theta) p - A) (m) of spring j along its face, its
  /// rate s' (m/s) and gradient w_T.
  void Tangential(int j, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u, double& s,
                  double& rate, Eigen::Vector3d& w_t) const;
  /// The force of spring j on its current branch, continued past the branch's ends (N).
  double BranchForce(int j, double d, double rate) const;
  /// The slope of spring j's unloading-reloading line (N/m): K_ur of a backfill, K_0 of a key.
  double LineStiffness(int j) const;
  /// The friction force F_t along the tangent of friction element f (N) at (s, N).
  double FrictionForce(const FrictionState& f, double s, double normal_N) const;
  /// The sum of the springs' largest stiffnesses and the stick springs' (N/m): with the largest
  /// translational mass, the springs' frequency the step control's velocity scale takes.
  double StiffnessSum_Npm() const;
  /// Whether some spring is on a branch other than open.
  bool AnyEngaged() const;

  /// The engaged springs' forces and the friction elements' at (q, u) added to h (N, N m), in the
  /// order of the springs, then of the friction elements; joint_W the springs' power F d' and
  /// friction_W the friction's dissipated power -F_t s' (W).
  void AddForces(const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u, Eigen::Ref<Vec> h,
                 double& joint_W, double& friction_W) const;
  /// AddedForces: AddForces without the powers.
  void AddTo(const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u,
             Eigen::Ref<Vec> h) override;

  /// All event functions at the state y (its heads q and u; n_events() values: 2 per spring,
  /// then 2 per friction element), positive while each piece holds.
  void AllEventValues(const Eigen::Ref<const Vec>& y, Vec& out) const;
  /// Event function e of AllEventValues at the state y, computed alone (the same bits).
  double EventValueAt(int e, const Eigen::Ref<const Vec>& y) const;
  /// Settles every spring and then every friction element at the state y at time t_s (a key's
  /// break and a first slip take it); returns whether a spring closed while none was engaged
  /// before (a strike's start).
  bool SettleAll(const Eigen::Ref<const Vec>& y, double t_s);
  /// Raises each engaged spring's largest force and deformation to its values at the state y.
  void Maxima(const Eigen::Ref<const Vec>& y);
  /// At the end state (q, u): the energy the springs would give back by unloading
  /// (`joint_stored_J`: F^2 / (2 K_ur) on the backfill's line or envelope and a key's, 1/2 k d^2
  /// of an engaged spring-dashpot) and the stick springs' F_t^2 / (2 k_t) (`friction_stored_J`);
  /// a slip going on adds its travel so far to its spring's wall slip. Once, at the run's end.
  void EndEnergies(const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u,
                   double& joint_stored_J, double& friction_stored_J);
  /// The springs' maxima, key breaks, wall slips and first slips into `out`.
  void MoveResults(CompliantRunResult& out);

 private:
  // The coordinate dir . ((x, y) + R(theta) p - A) (m) of spring j's point along a unit
  // direction of its face, its rate (m/s) and gradient w on the body's 3 DOFs: the normal gives
  // the gap, the tangent the position along the wall.
  // A face on a body turns with it: dir is then in the body's frame, and w_face (if not null)
  // takes the gradient on the face body's DOFs.
  void Along(int j, const Eigen::Vector2d& dir, const Eigen::Ref<const Vec>& q,
             const Eigen::Ref<const Vec>& u, double& coord, double& rate, Eigen::Vector3d& w,
             Eigen::Vector3d* w_face = nullptr) const;
  // (cos theta, sin theta) of body b's angle theta = q[3 b + 2] (rad): computed once per angle,
  // since every spring of a body asks for it at the same state (the last two angles are kept).
  std::pair<double, double> Turn(int b, double theta_rad) const;
  // The backbone piece a key loading past d (m) is on, or kOpen after breaking it.
  Branch KeyPieceAbove(int j, double d) const;
  // The turn of spring j from loading to unloading at d (m): the memory takes d, the line follows.
  void CommitTurn(int j, double d);
  // The event functions of spring j (positive while its branch holds): two per spring.
  void EventValues(int j, double d, double rate, double& e1, double& e2) const;
  // The slope dF/dd of spring j's current branch at d (N/m); 0 when open.
  double BranchSlope(int j, double d) const;
  // The event functions of friction element f at the state y: stick: mu N -+ F_t; slip: the
  // plastic slip rate sigma s' - mu N' / k_t.
  void FrictionEventValues(int f, const Eigen::Ref<const Vec>& y, double& e1, double& e2) const;
  // The transitions of friction element f at the state y at t_s after its spring has settled.
  void SettleFriction(int f, const Eigen::Ref<const Vec>& y, double t_s);
  // The transitions of spring j at (d, d') at t_s until its event functions are positive or it
  // cannot leave its branch; returns true when it closed from open (a strike's start).
  bool Settle(int j, double d, double rate, double t_s);

  const model::Model& model_;
  const std::vector<CompliantSpring>& springs_;
  int n_, ns_;
  // Per body: the bits of the last two angles Turn was asked for, and their cosines and sines
  // (two: the free step asks for each spring at the step's start and end states in turn).
  struct TurnMemo {
    std::uint64_t theta_bits[2] = {0, 0};
    double c[2] = {1.0, 1.0}, s[2] = {0.0, 0.0};  // cos and sin of +0.0
    int next = 0;                                 // the slot the next new angle replaces
  };
  mutable std::vector<TurnMemo> turn_;
  std::vector<SpringState> state_;
  std::vector<FrictionState> friction_;  // one per spring with wall friction
  // Per spring: largest force (N) and deformation (m) at step ends, the time a key broke (s; NaN
  // while intact), the wall slip (m), the time of the first slip (s; NaN before).
  Vec max_force_N_, max_deformation_m_, key_break_time_s_, wall_slip_m_, first_slip_time_s_;
};

}  // namespace skewbridge::dynamics
