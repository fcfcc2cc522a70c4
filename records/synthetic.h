#pragma once
/// @file
/// Seeded synthetic accelerograms: Clough-Penzien filtered white noise [Clough and Penzien 1975]
/// modulated by a Saragoni-Hart (gamma) envelope [Saragoni and Hart 1974], with the Kanai-Tajimi
/// ground frequency tuned until the Rathje mean period T_m hits a target, then scaled to a target
/// PGA. Written as .AT2 files so that they pass through the same reader as real records.
///
/// Determinism: std::mt19937_64 is specified bit for bit by the standard, but the std::
/// distributions are not; uniform and normal variates are made here (53-bit uniform, Box-Muller)
/// so that the same seed gives the same bytes with any standard library.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "records/ground_motion.h"

namespace skewbridge::records {

/// Ranges and shape of a synthetic suite. Each record draws its PGA and T_m uniformly in the
/// ranges; D5-95 follows from the envelope.
struct SynthOptions {
  int count = 62;          ///< number of records
  std::uint64_t seed = 1;  ///< one seed for the whole suite
  double pga_min_g = 0.1;  ///< PGA range (g)
  double pga_max_g = 0.6;
  double tm_min_s = 0.2;  ///< T_m range (s), reachable: about 0.08 to 2 s
  double tm_max_s = 1.0;
  double duration_s = 30.0;              ///< record length (s)
  double dt_s = 0.01;                    ///< sample interval (s)
  double zeta_g = 0.6;                   ///< Kanai-Tajimi damping ratio
  double cp_ratio = 0.1;                 ///< Clough-Penzien corner w_f / w_g (high-pass)
  double zeta_f = 0.6;                   ///< Clough-Penzien damping ratio
  double envelope_peak_fraction = 0.25;  ///< envelope peak time / duration
  double tm_tolerance = 2e-3;            ///< relative tolerance of the T_m tuning
};

/// Checks the options. @throws InputError "synth: FIELD: ..." for a bad value.
void ValidateSynthOptions(const SynthOptions& options);

/// Corner of the high-pass that starts the baseline correction (Hz): 60 % of the lowest
/// frequency of the T_m band, whose amplitudes it lowers by 0.8 % at 0.25 Hz and by less than
/// 0.01 % above 0.5 Hz; at 0.1 Hz the 62-record suite still had a PGD of 0.99 m.
inline constexpr double kBaselineHighPass_hz = 0.15;

/// Baseline correction of an accelerogram, so that it ends at rest where it started: a
/// zero-phase high-pass at kBaselineHighPass_hz (order 4) removes the long-period content that
/// carries displacements of metres without touching the T_m band, then a correction c(t) =
/// sum_{k=0..4} b_k (t/T)^k (T the record length) is subtracted from the accelerations, with b
/// chosen so that the displacement of c (integrated by IntegrateMotion's rule, so the discrete sums
/// match what ComputeMeasures reports) fits the record's displacement in least squares, subject to
/// the corrected velocity and displacement being zero at the end. The correction lives below about
/// 5/T (0.17 Hz for 30 s), under the 0.25-20 Hz band of T_m. [Boore 2001, polynomial baseline fits
/// of the displacement]
/// @pre dt_s > 0 and acc_mps2.size() >= 6.
void RemoveBaselineDrift(std::vector<double>& acc_mps2, double dt_s);

/// One record of the suite (index 0 .. count-1): the same (options, index) always gives the
/// same motion, with PGA and T_m (of the motion as written to .AT2) inside the ranges, baseline
/// corrected (RemoveBaselineDrift) so that it ends at rest with no displacement drift.
/// @throws InputError when a target T_m cannot be reached with the given dt and duration.
GroundMotion SynthesizeRecord(const SynthOptions& options, int index);

/// The label (station) of record `index` of a suite: "synth-<seed>-<index>", the index padded
/// to at least three digits and to the digits of count - 1 (so labels sort in index order).
std::string SyntheticLabel(const SynthOptions& options, int index);

/// The whole suite, records named "synth-<seed>-<index>".
std::vector<GroundMotion> SynthesizeSuite(const SynthOptions& options);

/// The .AT2 text of a motion (PEER NGA-West2 layout, 5 values per line in g, E15.7):
/// deterministic, and read back by ReadRecord to the printed 8 significant digits.
std::string FormatAt2(const GroundMotion& motion);

/// Writes FormatAt2(motion) to path. @throws InputError when the file cannot be written.
void WriteAt2(const std::filesystem::path& path, const GroundMotion& motion);

/// Writes the suite to `directory` (created if needed) as synth_NNN.AT2 plus a record-set
/// manifest set.toml listing them. @returns the manifest's path.
/// @throws InputError when a file cannot be written.
std::filesystem::path WriteSuite(const std::filesystem::path& directory,
                                 const SynthOptions& options);

}  // namespace skewbridge::records
