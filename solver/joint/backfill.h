#pragma once
/// @file
/// The hyperbolic backfill law of a compliant abutment, in the semantics of OpenSees'
/// `HyperbolicGapMaterial` [Wilson and Elgamal 2010; Shamsabadi et al. 2007; docs/compliant.md §1]:
/// a compression-only spring behind a gap whose envelope is hyperbolic, which unloads and reloads
/// along one straight line of stiffness K_ur, carries no tension, and keeps a permanent set that
/// widens the gap after every excursion past the largest deformation reached before. The
/// conveniences map the Shamsabadi form (K50, F_ult, y_max) and the Caltrans SDC 2.0 abutment rules
/// onto it. SI inside: N, m, N/m.
///
/// Sign convention: u_m is the closing displacement of the deck towards the wall (m, positive
/// closes the joint, measured from rest); d = u - gap is the deformation beyond the gap; every
/// force is the compression the backfill exerts (N, >= 0).

#include <string_view>

namespace skewbridge::joint {

/// The constants of one hyperbolic gap spring [OpenSees HyperbolicGapMaterial, magnitudes].
struct HyperbolicGap {
  double k_max_N_per_m = 0.0;  ///< initial tangent of the envelope, > 0
  double k_ur_N_per_m = 0.0;   ///< unloading and reloading stiffness, > 0
  double r_f = 0.0;            ///< failure ratio, in (0, 1]
  double f_ult_N = 0.0;        ///< ultimate passive resistance, > 0
  double gap_m = 0.0;          ///< initial gap, >= 0
};

/// The memory of one spring: the largest deformation beyond the gap ever reached (m, >= 0).
/// Commit it at the end of an accepted step (BackfillCommit); a rejected step keeps the old one.
struct BackfillState {
  double d_max_m = 0.0;  ///< largest d = u - gap reached so far; 0 before the first contact
};

/// Which of its three pieces the law is on at a closing displacement u.
enum class BackfillBranch {
  kOpen,      ///< no force: d below the permanent set (or below the gap before any contact)
  kEnvelope,  ///< on the hyperbolic envelope: d >= d_max, loading further
  kLine,      ///< on the unloading / reloading line of stiffness K_ur below d_max
};

/// Checks the constants; throws InputError naming `source` and the field when one is outside its
/// range (k_max, k_ur, f_ult > 0; 0 < r_f <= 1; gap >= 0, all finite).
/// @throws InputError
void ValidateHyperbolicGap(const HyperbolicGap& law, std::string_view source);

/// Envelope force at the deformation d beyond the gap:
///   F(d) = d / (1 / K_max + R_f d / F_ult) for d > 0, 0 for d <= 0   (N).
/// With R_f < 1 the envelope has no cap: it passes F_ult at d = F_ult / (K_max (1 - R_f)) and
/// tends to F_ult / R_f (the OpenSees behaviour, kept).
double EnvelopeForce_N(const HyperbolicGap& law, double d_m);

/// Tangent of the envelope, dF/dd = (1 / K_max) / (1 / K_max + R_f d / F_ult)^2 for d > 0,
/// 0 for d <= 0 (N/m).
double EnvelopeTangent_N_per_m(const HyperbolicGap& law, double d_m);

/// The permanent set reached with the memory `state`: the deformation beyond the initial gap at
/// which the unloading line from the envelope's peak F(d_max) reaches zero force,
///   d_set = d_max - F(d_max) / K_ur, clamped at 0 (m). The joint re-opens (and re-closes) there.
double PermanentSet_m(const HyperbolicGap& law, const BackfillState& state);

/// The branch at the closing displacement u: kEnvelope when d >= d_max and d > 0, kLine when
/// d_set < d < d_max, kOpen otherwise.
BackfillBranch BackfillBranchAt(const HyperbolicGap& law, const BackfillState& state, double u_m);

/// The force of the backfill at the closing displacement u with the memory `state` (N, >= 0):
/// the envelope F(d) for d >= d_max, K_ur (d - d_set) on the line below d_max, 0 below d_set.
double BackfillForce_N(const HyperbolicGap& law, const BackfillState& state, double u_m);

/// The tangent stiffness dF/du at u (N/m): the envelope's tangent, K_ur on the line, 0 when open.
double BackfillTangent_N_per_m(const HyperbolicGap& law, const BackfillState& state, double u_m);

/// The memory after a step that ended at the closing displacement u: d_max grows to u - gap
/// when the step went past it, and never shrinks.
BackfillState BackfillCommit(const HyperbolicGap& law, const BackfillState& state, double u_m);

/// The hyperbola through F_ult at y_max with the secant stiffness K50 at F_ult / 2 [Shamsabadi,
/// Rollins and Kapuskar 2007, the hyperbolic force-displacement (HFD) form], as OpenSees
/// constants: K_max = 2 K50 - F_ult / y_max, R_f = 1 - F_ult / (2 K50 y_max - F_ult), the same
/// F_ult; K_ur = K_max. Needs K50 y_max > F_ult (a hyperbola that softens).
/// @throws InputError naming `source` when K50 y_max <= F_ult or a value is not positive.
HyperbolicGap FromShamsabadi(double k50_N_per_m, double f_ult_N, double y_max_m, double gap_m,
                             std::string_view source);

/// The hyperbola with the initial stiffness K_max that reaches F_ult at y_max:
/// R_f = 1 - F_ult / (K_max y_max), K_ur = K_max. Needs K_max y_max > F_ult.
/// @throws InputError naming `source` when K_max y_max <= F_ult or a value is not positive.
HyperbolicGap FromInitialStiffness(double k_max_N_per_m, double f_ult_N, double y_max_m,
                                   double gap_m, std::string_view source);

/// Shamsabadi's deformation at capacity for a granular backfill: y_max = 0.05 H (m), H the
/// backwall height (m) [Shamsabadi et al. 2007].
double ShamsabadiYMax_m(double backwall_height_m);

/// Caltrans' skew reduction of the abutment's stiffness and capacity, R_sk = exp(-theta / 45 deg),
/// theta the skew angle (rad) [Caltrans SDC 2.0, 2019, §6.3.1].
double CaltransSkewFactor(double skew_rad);

/// The abutment's initial stiffness and passive capacity after the Caltrans SDC 2.0 rules.
struct CaltransAbutment {
  double k_initial_N_per_m = 0.0;  ///< K_abut = w (5.5 h + 20) R_sk kip/in (w, h in ft)
  double p_bw_N = 0.0;             ///< P_bw = w 5.5 h^2.5 / (1 + 2.37 h) R_sk kip (w, h in ft)
};

/// The Caltrans SDC 2.0 abutment rules [Caltrans SDC 2.0, 2019, §6.3.1] for a backwall of width
/// w and height h (m), with the skew reduction R_sk (pass 1 for none); SI in and out.
/// @pre width, height > 0; 0 < r_sk <= 1.
CaltransAbutment CaltransSdc2(double backwall_width_m, double backwall_height_m, double r_sk);

}  // namespace skewbridge::joint
