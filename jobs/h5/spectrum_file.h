#pragma once
/// @file
/// The HDF5 file of `skewbridge records spectrum --out FILE.h5`: the elastic response spectra
/// (Sd, PSv, PSa) of a list of records at given periods and damping ratios
/// (docs/hdf5-layout.md, "Response spectra"). scripts/report draws it.

#include <filesystem>
#include <string>
#include <vector>

namespace skewbridge::jobs::h5 {

/// The spectra of R records at X damping ratios and P periods; the arrays sd_m, psv_mps and
/// psa_mps2 hold R * X * P values, row-major over (record, xi, period).
struct SpectrumTable {
  std::string command;             ///< the command line that made it, for provenance
  std::vector<std::string> label;  ///< per record: its label (a set's label, or the file name)
  std::vector<std::string> file;   ///< per record: the file read
  std::vector<std::string> set;    ///< per record: the set (manifest or folder) or "" alone
  std::vector<double> dt_s;        ///< per record: the sample interval (s)
  std::vector<double> pga_mps2;    ///< per record: PGA (m/s^2), the spectrum's T -> 0 limit
  std::vector<double> periods_s;   ///< the periods (s), increasing
  std::vector<double> xi;          ///< the damping ratios
  std::vector<double> sd_m;        ///< spectral displacement (m)
  std::vector<double> psv_mps;     ///< pseudo-spectral velocity w Sd (m/s)
  std::vector<double> psa_mps2;    ///< pseudo-spectral acceleration w^2 Sd (m/s^2)
  /// Per pair of horizontal components (whose H1 and H2 are records of the table): its label.
  std::vector<std::string> pair_label;
  std::vector<std::string> pair_set;  ///< per pair: its set
  /// Per pair, Q * X * P values row-major over (pair, xi, period), all pseudo-accelerations
  /// (m/s^2) [Boore 2010]: Sa of H1 and H2, GM = sqrt(Sa_H1 Sa_H2), RotD00, RotD50, RotD100,
  /// and the angle of RotD100 (deg from H1 towards H2).
  std::vector<double> sa_h1_mps2, sa_h2_mps2, gm_mps2, rotd0_mps2, rotd50_mps2, rotd100_mps2,
      rotd100_angle_deg;
};

/// Writes the table to `path` whole: built in memory, saved to PATH.tmp and renamed, so no
/// partial file is ever left under the name. @throws H5Error naming the file and the reason.
/// @pre the arrays have the sizes the table's comments give.
void WriteSpectrumFile(const std::filesystem::path& path, const SpectrumTable& table);

}  // namespace skewbridge::jobs::h5
