#pragma once
/// @file
/// Intensity measures of a ground motion: peaks, the mean period of Rathje et al. (1998) that
/// sets w_g for records [docs/theory.md §5], Arias intensity, significant duration and the linear
/// elastic pseudo-acceleration spectrum (exact for piecewise-linear excitation).
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
};

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

/// All measures of a record.
/// @throws InputError as MeanPeriod (a record with no energy in 0.25-20 Hz has no T_m).
IntensityMeasures ComputeMeasures(const GroundMotion& motion);

}  // namespace skewbridge::records
