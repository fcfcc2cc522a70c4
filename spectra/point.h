#pragma once
/// @file
/// One point of a dimensionless response spectrum [docs/theory.md §5]: the mapping from the
/// dimensionless groups to a dimensional deck model and excitation, the run, and the
/// normalisation of the maxima. This is the only place where normalisations live.
///
/// The maxima depend on nine groups (Buckingham) [Dimitrakopoulos 2011, §3]:
///
///     x_m w_g^2/a_g, y_m w_g^2/a_g, theta_m rho w_g^2/a_g
///         = Phi(w0/w_g, W0/w0, xi, Pi_delta = delta w_g^2/a_g, eps_N, mu, W/L, delta/L, a)
///
/// The length scale is the persistency L_e = a_g / w_g^2. The deck length follows from
/// delta/L (L = delta / (delta/L), which needs Pi_delta > 0) or, when delta/L is not given,
/// from L/L_e. Every dimensional choice left (the mass, the pulse's a_g and w_g) cancels from
/// the dimensionless results, exactly so in the small-rotation limit [docs/theory.md §4 fact 4].

#include <optional>
#include <string>

#include "records/excitations.h"
#include "solver/dynamics/run_policies.h"
#include "solver/dynamics/run_result.h"
#include "solver/model/builders.h"
#include "solver/model/run_control.h"

namespace skewbridge::spectra {

/// The model family of a sweep.
enum class Family {
  kSubsystem,    ///< single-abutment subsystem: contacts P1, P2, uncoupled K [docs/theory.md §6]
  kPilotBridge,  ///< the two-span pilot bridge of [docs/theory.md §6], both abutments
};

/// How a point is integrated [docs/theory.md §3]: the method of the run (model::ToString spells
/// it).
using Method = model::Method;

/// The dimensionless coordinates of one point, with the defaults of the studies of
/// [docs/theory.md §6] (xi = 5 %, eps_N = 0.5).
struct PointParameters {
  Family family = Family::kSubsystem;
  /// w0/w_g. Subsystem: w0 = w0x = w0y. Pilot bridge under a pulse: w0x/w_g with
  /// w0x = sqrt(K_xx / m), which sets w_g; under a record it is an output.
  double w0_over_wg = 1.0;
  double Pi_delta = 1.0;   ///< delta w_g^2 / a_g >= 0
  double skew_deg = 30.0;  ///< a in [0, 90) deg (subsystem)
  /// Pilot bridge: a in [0, 90) deg; empty = the published 20 deg (PilotBridgeDeck).
  std::optional<double> pilot_skew_deg;
  /// sin 2a / (2 W/L) > 0, needs a > 0. Subsystem: eta0 or W_over_L is required; pilot bridge:
  /// empty keeps the published plan's W/L (PilotBridgeDeck).
  std::optional<double> eta0;
  std::optional<double> W_over_L;      ///< used when eta0 is not given (subsystem)
  double W0_over_w0 = 1.0;             ///< torsional over translational frequency (subsystem)
  double xi = 0.05;                    ///< damping ratio in every mode
  double eps_N = 0.5;                  ///< coefficient of restitution
  double mu = 0.0;                     ///< Coulomb friction coefficient
  std::optional<double> delta_over_L;  ///< gap over deck length (needs Pi_delta > 0)
  double L_over_Le = 250.0;  ///< deck length over the persistency, when delta/L is not given
  records::PulseShape pulse = records::PulseShape::kCosine;  ///< when there is no record
  double pulse_a_g_mps2 = 0.5 * 9.80665;       ///< pulse amplitude a_g (m/s^2), cancels out
  double pulse_w_g_radps = 6.283185307179586;  ///< pulse w_g (rad/s), subsystem; cancels out
  double mass_kg = 1.0e6;                      ///< deck mass (subsystem), cancels out
  Method method = Method::kEventDriven;        ///< the integrator
  /// Time-stepping: step over the excitation period, h w_g / (2 pi), so that the step scales
  /// with 1 / w_g like every time; 1e-4 is h = 1e-4 s for w_g = 2 pi rad/s.
  double time_step_over_Tg = 1e-4;
};

/// The excitation scales of a point: a_g and w_g (for a record, PGA and 2 pi / T_m).
struct ExcitationScales {
  double a_g_mps2 = 0.0;   ///< a_g > 0 (m/s^2)
  double w_g_radps = 0.0;  ///< w_g > 0 (rad/s)
};

/// A point made dimensional: the deck description and the scales that normalise its results.
struct DimensionalPoint {
  model::DeckSpec deck;        ///< builds the Model (BuildDeckModel)
  ExcitationScales scales;     ///< a_g, w_g
  double delta_m = 0.0;        ///< joint gap along x (both abutments for the pilot bridge)
  double rho_m = 0.0;          ///< radius of gyration sqrt(I_m / m)
  double persistency_m = 0.0;  ///< L_e = a_g / w_g^2
  double w0x_radps = 0.0;      ///< sqrt(K_xx / m)
  Method method = Method::kEventDriven;  ///< the integrator
  double time_step_s = 0.0;              ///< time-stepping step h (s)
};

/// The pilot bridge of [docs/theory.md §6; Dimitrakopoulos 2011, §4]: m = 1547 t,
/// I_m = 1 079 100 t m^2, a = 20 deg, L = 89.14 m, W = 19.36 m (eta0 = 1.48), principal axes
/// at +20 deg with 18 and 19 rad/s, torsion 26 rad/s about the centre of rigidity
/// (-0.24, 0.01) m, xi = 5 %, eps_N = 0.5, mu = 0.3, both abutments, gaps 0 (set per point).
model::DeckSpec PilotBridgeDeck();

/// The pilot bridge at another skew a and/or skew ratio eta0: the published m, I_m,
/// substructure (principal axes, frequencies, centre of rigidity), damping, abutments and
/// contact laws, on a plan re-derived from I_m by the uniform-deck rule
/// 12 I_m / m = L^2 + W^2 / cos^2 a [docs/theory.md §2] with W/L = sin 2a / (2 eta0) when eta0
/// is given and the published W/L = 19.36 / 89.14 otherwise:
///     L = sqrt(12 (I_m / m) / (1 + (W/L)^2 / cos^2 a)),  W = (W/L) L.
/// With neither given, or a = 20 deg exactly and no eta0, it is PilotBridgeDeck() itself, whose
/// published L and W reproduce I_m / m to 1.5e-5 (their rounding to four digits).
/// @throws InputError naming "a_deg" (outside [0, 90) deg) or "eta0" (<= 0, or with a = 0).
model::DeckSpec PilotBridgeDeck(std::optional<double> skew_deg, std::optional<double> eta0);

/// The scales of a pulse point: (pulse_a_g, pulse_w_g) for the subsystem; for the pilot
/// bridge w_g = w0x / (w0/w_g).
/// @throws InputError when w0/w_g <= 0.
ExcitationScales PulseScales(const PointParameters& p);

/// Maps a point to its dimensional model [docs/theory.md §5].
/// @throws InputError naming the parameter ("eta0", "Pi_delta", ...) and its allowed range
/// when a value or a combination is impossible (eta0 with a = 0, delta/L with Pi_delta = 0, a
/// deck whose geometry is not a parallelogram, time_step_over_Tg <= 0, ...).
DimensionalPoint ToDimensional(const PointParameters& p, const ExcitationScales& scales);

/// The responses of one point, dimensional and normalised as in [docs/theory.md §5].
struct PointResult {
  dynamics::RunStatus status = dynamics::RunStatus::kOk;
  std::string message;          ///< empty when ok
  double x_m = 0.0;             ///< max |x| (m)
  double y_m = 0.0;             ///< max |y| (m)
  double theta_rad = 0.0;       ///< max |theta| (rad)
  double travel_m = 0.0;        ///< largest corner travel normal to the end line (m), exact
  double x_end_m = 0.0;         ///< residual x(t_end) (m)
  double y_end_m = 0.0;         ///< residual y(t_end) (m)
  double theta_end_rad = 0.0;   ///< residual rotation theta(t_end) (rad)
  double x_norm = 0.0;          ///< x_m w_g^2 / a_g
  double y_norm = 0.0;          ///< y_m w_g^2 / a_g
  double theta_norm = 0.0;      ///< theta_m rho w_g^2 / a_g
  double theta_end_norm = 0.0;  ///< theta(t_end) rho w_g^2 / a_g
  long impacts = 0;             ///< impact events
  long events = 0;              ///< impacts + plastic closures + detachments + stick/slip
  long steps = 0;               ///< integration steps (exact + Runge-Kutta)
  double min_impact_separation_s = 0.0;  ///< smallest separation of distinct impacts (s)
};

/// The run EvaluatePoint makes of a point: the model built from the deck, the run control (the
/// absolute tolerance tied to L_e, the end time of EvaluatePoint, no energy ledger) and the
/// integrator. `skewbridge run --from-cube` runs a cell from it with histories, which leave the
/// maxima as they are.
struct PointRun {
  model::Model model;          ///< BuildDeckModel(point.deck)
  model::RunControl control;   ///< as EvaluatePoint sets it
  bool time_stepping = false;  ///< Moreau-Jean (point.method), else the event-driven integrator
};

/// The model, control and integrator of EvaluatePoint for `point` under `excitation`.
/// @throws InputError as ToDimensional.
PointRun MakePointRun(const DimensionalPoint& point, const Excitation& excitation);

/// Runs the point under `excitation` (the pulse of PulseScales or a record whose scales are
/// given) by point.method with that method's policy in `policies`, and normalises the maxima.
/// The end time is the excitation's duration plus two of the longer of 2 pi / w_g and the
/// longest natural period, so it scales with 1 / w_g.
/// @throws InputError as ToDimensional, or a policy member outside its range.
PointResult EvaluatePoint(const DimensionalPoint& point, const Excitation& excitation,
                          const dynamics::RunPolicies& policies = {});

}  // namespace skewbridge::spectra
