#pragma once
/// @file
/// A site's seismic hazard curve as input: the annual rate of exceedance lambda(x) of an
/// intensity measure, read from an OpenQuake hazard-curve CSV (one file per IMT) or from a plain
/// two-column file, with the identity of its measure (PGA or SA(T), damping, horizontal
/// component) that spectra/hazard_measure.h checks against a fragility's. Strict readers: a bad
/// line is an InputError naming the file and the line. docs/risk.md describes both formats.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skewbridge::spectra {

/// The horizontal-component definition of a spectral ordinate: which number a measure takes
/// from the two horizontal components of a recording [Baker and Cornell 2006, Earthquake Spectra
/// 22(2):293-312; Boore et al. 2006, BSSA 96(4A):1502-1511; Boore 2010, BSSA 100(4):1830-1835].
enum class HorizontalComponent {
  kUnknown,        ///< not stated
  kArbitrary,      ///< one recorded horizontal component (Sa_arb of Baker and Cornell 2006)
  kGeometricMean,  ///< geometric mean of the two as-recorded components (GMxy)
  kGmRotI50,       ///< the orientation-independent geometric mean GMRotI50 (Boore et al. 2006)
  kRotD50,         ///< the median over all rotation angles, RotD50 (Boore 2010)
  kRotD100,        ///< the maximum over all rotation angles, RotD100 (Boore 2010)
};

/// The component's name as files, options and cubes spell it ("arbitrary", "geometric-mean",
/// "GMRotI50", "RotD50", "RotD100", "unknown").
std::string_view ComponentName(HorizontalComponent component);

/// Parses a component name, case-insensitive; also the aliases "one-component", "single",
/// "as-recorded" (arbitrary), "geomean", "gm", "average-horizontal" (OpenQuake's name for the
/// geometric mean). nullopt for anything else.
std::optional<HorizontalComponent> ParseComponent(std::string_view text);

/// The names ParseComponent accepts, for messages.
std::string ComponentChoices();

/// The identity of an intensity measure: which quantity, at which period and damping, of which
/// horizontal component. Units: g for PGA and SA.
struct IntensityMeasureId {
  std::string measure;    ///< "PGA" or "SA" (a fragility may also carry "AvgSa" or "PGV")
  double period_s = 0.0;  ///< the oscillator period of SA (s); 0 for PGA
  double damping = 0.05;  ///< the damping ratio of SA (1); OpenQuake's SA is 5 % damped
  HorizontalComponent component = HorizontalComponent::kUnknown;  ///< the component definition
  /// e.g. "SA(0.349 s, 5 % damping, arbitrary component)", "PGA (RotD50)".
  std::string Describe() const;
};

/// Parses an intensity-measure type as OpenQuake writes it: "PGA", "SA(0.3)" (period in s),
/// case-insensitive, blanks allowed inside the parentheses. nullopt for anything else (PGV and
/// other types are not hazard measures a fragility here can use).
std::optional<IntensityMeasureId> ParseImt(std::string_view text);

/// A hazard curve: the annual rate of exceedance at increasing intensity levels.
struct HazardCurve {
  std::string path;        ///< the file, as given, for messages
  std::string format;      ///< "openquake-csv" or "two-column"
  IntensityMeasureId imt;  ///< the measure of the levels
  std::vector<double> im;  ///< the intensity levels (g), strictly increasing, > 0
  /// The annual rate of exceedance at each level (1/yr), non-increasing: 0 where the file gives
  /// no exceedance, +inf where an OpenQuake probability is 1 (-ln(1 - 1) / T).
  std::vector<double> rate_per_yr;
  std::vector<long> line;              ///< the file line of each level (its column's header line)
  double investigation_time_yr = 0.0;  ///< OpenQuake: the time T of the probabilities; else 0
  std::string kind;                    ///< OpenQuake: "mean", "quantile-0.84", ...; else ""
  double lon_deg = 0.0;                ///< OpenQuake: the site's longitude; else 0
  double lat_deg = 0.0;                ///< OpenQuake: the site's latitude; else 0
  int site = 0;                        ///< OpenQuake: the row (0-based) of the site read
  int sites = 0;                       ///< OpenQuake: the sites the file holds; else 0
};

/// What the user states about a hazard file beside its contents (command-line options).
struct HazardReadOptions {
  std::string imt;                ///< the IMT ("PGA", "SA(1.0)"); "" = the file's own
  std::string component;          ///< the horizontal component; "" = the file's own, else unknown
  std::optional<double> damping;  ///< the SA damping ratio; nullopt = the file's, else 5 %
  std::optional<int> site;        ///< OpenQuake: the site row (0-based) of a file of several
};

/// Reads an OpenQuake hazard-curve CSV [OpenQuake manual, "Outputs from Classical PSHA"]: a
/// first line `#,,,,,"generated_by=..., kind='mean', investigation_time=1.0, imt='PGA'"`, a header
/// `lon,lat,depth,poe-<iml>,...` (custom_site_id and depth optional), one row per site with the
/// probability of exceedance in the investigation time T at each level; the annual rate is
/// lambda = -ln(1 - poe) / T (Poisson occurrence). The IMT comes from the header comment (an
/// `imt` option must agree with it); the component from the option only (the CSV states none).
/// @throws InputError "FILE:LINE: ..." for a missing or malformed header, a column that is not
/// poe-<positive number> in increasing order, a probability outside [0, 1] or rising with the
/// level, several sites without `site`, or a `site` out of range.
HazardCurve ReadOpenQuakeHazardCsv(const std::filesystem::path& path,
                                   const HazardReadOptions& options);

/// Reads a plain hazard file: lines "IM RATE" (blank, tab or comma separated; IM in g, RATE the
/// annual rate of exceedance, 1/yr), IM strictly increasing and > 0, RATE finite, >= 0 and non-
/// increasing; '#' starts a comment line. Comment lines `# imt = SA(1.0)`, `# component = RotD50`
/// and `# damping = 0.05` (':' also accepted) state the measure; the options may state it
/// instead, and must agree where both do.
/// @throws InputError "FILE:LINE: ..." for a line that is not two finite numbers, levels not
/// increasing, rates rising, fewer than two levels, no IMT from file or option, or a conflict.
HazardCurve ReadTwoColumnHazard(const std::filesystem::path& path,
                                const HazardReadOptions& options);

/// Reads either format: an OpenQuake CSV when a comment line before the data starts with "#,"
/// or names investigation_time, or the first other line starts with "lon," or
/// "custom_site_id,"; else the two-column file.
/// @throws InputError as the reader chosen, or "FILE: cannot be read".
HazardCurve ReadHazardCurve(const std::filesystem::path& path, const HazardReadOptions& options);

}  // namespace skewbridge::spectra
