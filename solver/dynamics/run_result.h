#pragma once
/// @file
/// What one run of the event-driven integrator returns [docs/theory.md §3]: a status, response
/// maxima, residuals, counts, the event log, the energy ledger and optional time histories.

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace skewbridge::dynamics {

/// How a run ended. Anything but kOk is an expected numerical outcome stored as data.
enum class RunStatus {
  kOk,          ///< reached the end time
  kPainleve,    ///< the contact problem ended on a secondary ray (no consistent forces)
  kLcpFailure,  ///< an impact or contact LCP hit its pivot limit or had invalid input
  kStepLimit,   ///< RunControl::max_steps steps without reaching the end
  kNonFinite,   ///< the state (or its energy) stopped being finite: the run ends there
  /// more events at one instant than EventPolicy::max_events_at_one_instant: the mode decision
  /// did not settle on a consistent set of closed contacts (time does not advance)
  kEventCascade,
};

/// Human-readable name of a status ("ok", "painleve", "lcp-failure", "step-limit",
/// "non-finite", "event-cascade").
const char* ToString(RunStatus status);

/// True when the squared norm of `z` is finite: false for a NaN, an Inf or an entry whose
/// square overflows (|z_i| > 1.3e154, where no energy of the state is a number any more). One
/// vectorised dot product: cheap enough for every step.
inline bool StateFinite(const Eigen::Ref<const Eigen::VectorXd>& z) {
  return std::isfinite(z.squaredNorm());
}

/// The message of a kNonFinite run whose state was finite at t_before_s and is not at t_s.
std::string NonFiniteMessage(double t_before_s, double t_s);

/// Kinds of events in the log.
enum class EventKind {
  kImpact,          ///< velocity jump at a contact (impulses logged)
  kPlasticClosure,  ///< approach slower than the accumulation threshold: closed plastically
  kDetachment,      ///< a closed contact opens (lambda_N reaches zero)
  kStick,           ///< a sliding contact sticks (slip velocity reaches zero)
  kSlip,            ///< a sticking contact starts to slip (friction reaches the cone) or reverses
};

/// Name of an event kind ("impact", "plastic-closure", "detachment", "stick", "slip").
const char* ToString(EventKind kind);

/// One entry of the event log; a multi-contact impact gives one entry per contact, same time.
struct EventRecord {
  double t_s = 0.0;
  EventKind kind = EventKind::kImpact;
  int contact = -1;                 ///< model contact index
  double impulse_N_Ns = 0.0;        ///< Lambda_N (impacts)
  double impulse_T_Ns = 0.0;        ///< Lambda_T (impacts)
  double gamma_N_before_mps = 0.0;  ///< approach velocity gamma_N,A (impacts)
  double gamma_N_after_mps = 0.0;   ///< gamma_N,E (impacts)
  double kinetic_loss_J = 0.0;      ///< kinetic energy lost by the whole impact (impacts)
};

/// The energy ledger (J): E_now - E_0 = input - damping - impact - friction up to the balance
/// error, with E = 1/2 u^T M u + 1/2 q^T K q.
struct EnergyLedger {
  double initial_J = 0.0;   ///< mechanical energy at t = 0
  double input_J = 0.0;     ///< -int u^T M r a_g dt (work of the ground)
  double damping_J = 0.0;   ///< int u^T C u dt
  double impact_J = 0.0;    ///< kinetic energy lost at impacts (>= 0)
  double friction_J = 0.0;  ///< int -lambda_T gamma_T dt in sliding phases (>= 0)
  double kinetic_J = 0.0;   ///< 1/2 u^T M u at the end
  double strain_J = 0.0;    ///< 1/2 q^T K q at the end
  double balance_error_J =
      0.0;  ///< (kinetic + strain) - (initial + input - damping - impact - friction)
};

/// Contact state codes in the histories.
enum class ContactState : int { kOpen = 0, kStick = 1, kSlidePositive = 2, kSlideNegative = 3 };

/// Time histories at a fixed output interval (only when RunControl::output_interval_s > 0).
/// Row-major flat arrays: sample s, entry i at [s * width + i].
struct Histories {
  int n_dof = 0;
  int n_contacts = 0;
  std::vector<double> t_s;
  std::vector<double> q;         ///< n_dof per sample (m, m, rad)
  std::vector<double> u;         ///< n_dof per sample (m/s, m/s, rad/s)
  std::vector<double> gap_m;     ///< n_contacts per sample
  std::vector<double> lambda_N;  ///< contact normal forces (N), n_contacts per sample
  std::vector<double> lambda_T;  ///< contact tangential forces (N), n_contacts per sample
  std::vector<int> state;        ///< ContactState per contact and sample
};

/// Everything a run returns.
struct RunResult {
  RunStatus status = RunStatus::kOk;
  std::string message;            ///< empty when ok; otherwise what happened, when and where
  double end_time_s = 0.0;        ///< time reached
  Eigen::VectorXd max_abs_q;      ///< max over time of |q_i| (m, rad), per DOF
  Eigen::VectorXd time_of_max_s;  ///< when each maximum occurred
  /// max over time and over the deck's four corners of the travel normal to the end line,
  /// |n_e . (corner displacement)| with n_e = (cos a, -sin a) (m), per deck (model::CornerTravelAt
  /// at every instant; dynamics/corner_travel.h): exact where model::CornerTravelBound bounds it
  Eigen::VectorXd max_travel_m;
  Eigen::VectorXd q_end;      ///< residual displacements / rotations at the end
  Eigen::VectorXd u_end;      ///< velocities at the end
  long impacts = 0;           ///< impact events (a multi-contact impact counts once)
  long plastic_closures = 0;  ///< impacts slower than the accumulation threshold
  long detachments = 0;
  long stick_transitions = 0;  ///< slide -> stick
  long slip_transitions = 0;   ///< stick -> slide, or slip reversal
  long free_steps = 0;         ///< exact-transition steps
  long rk_steps = 0;           ///< accepted Runge-Kutta steps
  long rk_rejected = 0;        ///< rejected Runge-Kutta steps
  /// Smallest time between two distinct impact instants (s); +inf with fewer than two. Impacts
  /// closer than RunControl::simultaneity_tolerance_s are one multi-contact impact.
  double min_impact_separation_s = std::numeric_limits<double>::infinity();
  std::vector<EventRecord> events;
  EnergyLedger energy;
  Histories histories;
};

}  // namespace skewbridge::dynamics
