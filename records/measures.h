#pragma once
/// @file
/// Intensity measures of a ground motion: peaks, the mean period of Rathje et al. (1998) that
/// sets w_g for records [docs/theory.md §5], Arias intensity, significant duration, cumulative
/// absolute velocity and the linear elastic response spectra Sd, PSv, PSa with the average
/// spectral acceleration AvgSa built on them (exact for piecewise-linear excitation).
///
/// Conventions (docs/records.md): the acceleration is linear between samples (the same
/// assumption as the solver's SampledExcitation), starts at rest at t = 0 and is integrated as
/// given, with no baseline correction: the agencies' processed records are already corrected,
/// and a second correction would change the motion the solver sees.

#include <span>
#include <vector>

#include "records/ground_motion.h"

namespace skewbridge::records {

/// Band of the mean period [Rathje et al. 1998]: 0.25 <= f <= 20 Hz.
inline constexpr double kMeanPeriodMinFrequency_hz = 0.25;
inline constexpr double kMeanPeriodMaxFrequency_hz = 20.0;

/// The measures of one record (SI units).
struct IntensityMeasures {
  double pga_mps2 = 0.0;                ///< max |a| (m/s^2)
  double pgv_mps = 0.0;                 ///< max |v| (m/s), v from a by exact integration
  double pgd_m = 0.0;                   ///< max |d| (m)
  double mean_period_s = 0.0;           ///< T_m (s) [Rathje et al. 1998]
  double omega_g_radps = 0.0;           ///< w_g = 2 pi / T_m (rad/s) [docs/theory.md §5]
  double persistency_m = 0.0;           ///< L_e = a_g / w_g^2 = PGA / w_g^2 (m)
  double arias_mps = 0.0;               ///< I_a = pi / (2 g) int a^2 dt (m/s)
  double significant_duration_s = 0.0;  ///< D5-95: time between 5 % and 95 % of I_a (s)
  double cav_mps = 0.0;                 ///< CAV = int |a| dt over the record (m/s) [EPRI 1988]
};

/// Period range and count of AvgSa [Eads et al. 2015]: periods from 0.2 T1 to 3 T1.
inline constexpr double kAvgSaFromT1 = 0.2;
inline constexpr double kAvgSaToT1 = 3.0;
/// Number of periods of AvgSa, equally spaced in T over [0.2 T1, 3 T1], both ends included.
/// The count is this tool's choice: on the 39 shared records at T1 = 1 s, 50 periods give
/// AvgSa within 1.6 % of a 0.005-s spacing (10 periods: up to 10.5 %; docs/records.md).
inline constexpr int kAvgSaPeriodCount = 50;

/// Velocity (m/s) and displacement (m) at the samples, exact for piecewise-linear a with
/// v(0) = d(0) = 0: v_{k+1} = v_k + dt (a_k + a_{k+1}) / 2,
/// d_{k+1} = d_k + dt v_k + dt^2 (2 a_k + a_{k+1}) / 6. No baseline correction.
/// @throws InputError when acc is empty or dt <= 0.
void IntegrateMotion(std::span<const double> acc_mps2, double dt_s, std::vector<double>& vel_mps,
                     std::vector<double>& disp_m);

/// Length of the DFT used for T_m: the record zero-padded to the next power of two >= n (the
/// usual FFT practice; T_m depends on this grid, see docs/records.md).
std::size_t MeanPeriodDftLength(std::size_t n);

/// Mean period T_m = sum(C_i^2 / f_i) / sum(C_i^2) over the DFT frequencies f_i = i / (N dt)
/// with 0.25 <= f_i <= 20 Hz, C_i = |X_i| the Fourier amplitudes of the zero-padded record
/// (N = MeanPeriodDftLength(n)) computed with FFTW [Rathje et al. 1998, eq. 3].
/// @throws InputError when acc is empty, dt <= 0, or no amplitude falls in the band.
double MeanPeriod(std::span<const double> acc_mps2, double dt_s);

/// Arias intensity I_a = pi / (2 g) int a^2 dt (m/s), the integral exact for linear a.
double AriasIntensity(std::span<const double> acc_mps2, double dt_s);

/// Significant duration between fractions `from` and `to` of the Arias intensity (s), the
/// crossing times interpolated linearly between samples [Trifunac and Brady 1975].
/// @returns 0 for a record with no energy.
double SignificantDuration(std::span<const double> acc_mps2, double dt_s, double from = 0.05,
                           double to = 0.95);

/// 5 %-damped (or xi) pseudo-acceleration spectrum S_a(T) = w^2 max_k |u(t_k)| (m/s^2) of
/// u'' + 2 xi w u' + w^2 u = -a(t), u(0) = u'(0) = 0, w = 2 pi / T, over the record's samples,
/// with the exact recurrence for piecewise-linear a [Nigam and Jennings 1969].
/// @throws InputError when a period is <= 0, xi is outside [0, 1), acc is empty or dt <= 0.
std::vector<double> PseudoAccelerationSpectrum(std::span<const double> acc_mps2, double dt_s,
                                               std::span<const double> periods_s, double xi = 0.05);

/// The linear elastic response spectrum of one damping ratio at the given periods, from the
/// relative displacement u of u'' + 2 xi w u' + w^2 u = -a(t), u(0) = u'(0) = 0, w = 2 pi / T,
/// at the record's samples, exact for piecewise-linear a [Nigam and Jennings 1969]:
/// Sd = max_k |u(t_k)|, PSv = w Sd, PSa = w^2 Sd (pseudo-velocity and pseudo-acceleration).
struct ResponseSpectrum {
  double xi = 0.05;               ///< damping ratio
  std::vector<double> periods_s;  ///< the periods T (s)
  std::vector<double> sd_m;       ///< spectral displacement Sd (m)
  std::vector<double> psv_mps;    ///< pseudo-spectral velocity PSv = w Sd (m/s)
  std::vector<double> psa_mps2;   ///< pseudo-spectral acceleration PSa = w^2 Sd (m/s^2)
};

/// The response spectrum at `periods_s` (any order) and damping `xi` [Nigam and Jennings 1969].
/// @throws InputError when a period is <= 0 or not finite, xi is outside [0, 1), acc is empty
/// or dt <= 0.
ResponseSpectrum ElasticResponseSpectrum(std::span<const double> acc_mps2, double dt_s,
                                         std::span<const double> periods_s, double xi = 0.05);

/// The relative displacement u(t_k) (m) of u'' + 2 xi w u' + w^2 u = -a(t), u(0) = u'(0) = 0,
/// w = 2 pi / T, at every sample of the record (u[0] = 0), by the recurrence of
/// ElasticResponseSpectrum (whose Sd is max_k |u[k]|) [Nigam and Jennings 1969].
/// @throws InputError as ElasticResponseSpectrum.
std::vector<double> OscillatorDisplacement(std::span<const double> acc_mps2, double dt_s,
                                           double period_s, double xi = 0.05);

/// Rotation angles of RotD: 0, 1, ..., 179 deg [Boore 2010].
inline constexpr int kRotDAngles = 180;

/// Orientation-independent peaks of two oscillator histories [Boore 2010, BSSA 100:1830]: at
/// every angle theta = 0, 1, ..., 179 deg (from H1 towards H2) the peak over time of
/// |u1 cos theta + u2 sin theta|; RotD00, RotD50 and RotD100 are the minimum, the median (the
/// mean of the 90th and 91st of the 180 sorted peaks) and the maximum over the angles.
struct RotDValues {
  double rotd0 = 0.0;              ///< smallest peak over the angles (units of u)
  double rotd50 = 0.0;             ///< median peak over the angles
  double rotd100 = 0.0;            ///< largest peak over the angles
  double rotd100_angle_deg = 0.0;  ///< the (first) angle of the largest peak, 0-179 deg
};

/// RotD of two response histories of one length [Boore 2010]. @pre u1.size() == u2.size() > 0.
RotDValues RotDFromHistories(std::span<const double> u1, std::span<const double> u2);

/// The spectral measures of a pair of horizontal components at each period (m/s^2), all
/// pseudo-accelerations w^2 max |u|: Sa of H1 and H2, their geometric mean GM = sqrt(Sa1 Sa2),
/// RotD00, RotD50, RotD100 and the angle of RotD100 (deg from H1 towards H2) [Boore 2010].
struct PairSpectrum {
  double xi = 0.05;                       ///< damping ratio
  std::vector<double> periods_s;          ///< the periods T (s)
  std::vector<double> sa_h1_mps2;         ///< PSa of H1
  std::vector<double> sa_h2_mps2;         ///< PSa of H2
  std::vector<double> gm_mps2;            ///< geometric mean sqrt(PSa_H1 PSa_H2)
  std::vector<double> rotd0_mps2;         ///< RotD00
  std::vector<double> rotd50_mps2;        ///< RotD50
  std::vector<double> rotd100_mps2;       ///< RotD100
  std::vector<double> rotd100_angle_deg;  ///< angle of RotD100, 0-179 deg
};

/// The pair's measures at `periods_s` and damping `xi`: both oscillator histories by
/// OscillatorDisplacement, combined at every angle by RotDFromHistories [Boore 2010].
/// @throws InputError when h1 and h2 differ in length, or as ElasticResponseSpectrum.
PairSpectrum PairResponseSpectrum(std::span<const double> h1_mps2, std::span<const double> h2_mps2,
                                  double dt_s, std::span<const double> periods_s, double xi = 0.05);

/// The periods of AvgSa: `count` periods equally spaced in T from from_t1 T1 to to_t1 T1, both
/// ends included (one period, from_t1 T1, when count = 1) [Eads et al. 2015].
/// @throws InputError when T1 <= 0, 0 < from_t1 <= to_t1 does not hold, or count < 1.
std::vector<double> AvgSaPeriods(double t1_s, double from_t1 = kAvgSaFromT1,
                                 double to_t1 = kAvgSaToT1, int count = kAvgSaPeriodCount);

/// Average spectral acceleration AvgSa = (prod_i PSa(T_i))^(1/n), the geometric mean of the
/// pseudo-acceleration over the periods T_i (m/s^2) [Eads et al. 2015, eq. 2]; 0 when one
/// ordinate is 0. @throws InputError as ElasticResponseSpectrum, or for no period.
double AverageSpectralAcceleration(std::span<const double> acc_mps2, double dt_s,
                                   std::span<const double> periods_s, double xi = 0.05);

/// AvgSa of a pair's RotD50: the geometric mean of RotD50(T_i) over the periods T_i (m/s^2)
/// [Eads et al. 2015; Boore 2010]; 0 when one ordinate is 0. @throws InputError as
/// PairResponseSpectrum, or for no period.
double AverageRotD50(std::span<const double> h1_mps2, std::span<const double> h2_mps2, double dt_s,
                     std::span<const double> periods_s, double xi = 0.05);

/// Cumulative absolute velocity CAV = int_0^{t_end} |a(t)| dt (m/s), the plain integral of
/// EPRI NP-5930 (1988), not the standardized CAV of EPRI TR-100082 (1991, which counts only
/// the 1-s windows whose peak exceeds 0.025 g); exact for piecewise-linear a (a sign change
/// inside a step is integrated as two triangles).
/// @throws InputError when acc is empty or dt <= 0.
double CumulativeAbsoluteVelocity(std::span<const double> acc_mps2, double dt_s);

/// All measures of a record.
/// @throws InputError as MeanPeriod (a record with no energy in 0.25-20 Hz has no T_m).
IntensityMeasures ComputeMeasures(const GroundMotion& motion);

}  // namespace skewbridge::records
