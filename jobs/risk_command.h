#pragma once
/// @file
/// `skewbridge risk CUBE --hazard FILE`: the annual rate of every limit state of a final cube's
/// sweeps over a site's hazard curve (docs/risk.md). Reads the hazard and the fragility fits,
/// checks the hazard's measure against each combination's (spectra/hazard_measure.h), computes
/// the table (spectra/risk_table.h) and writes it into the cube's risk/ group with the hazard
/// file's identity in inputs/ (jobs/h5/risk_file.h). Everything is checked before anything is
/// written: a refusal leaves the cube as it was.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "spectra/hazard_curve.h"
#include "spectra/hazard_measure.h"
#include "spectra/risk_table.h"

namespace skewbridge::jobs {

/// The options of one risk run.
struct RiskArgs {
  std::filesystem::path cube;                 ///< a final cube
  std::filesystem::path hazard;               ///< the hazard file
  spectra::HazardReadOptions hazard_options;  ///< --hazard-imt, --hazard-component, ...
  std::string sweep;                          ///< --sweep; "" = every sweep with a fragility
  std::string conversion;                     ///< --convert
  double period_tolerance = spectra::kDefaultPeriodTolerance;  ///< --period-tolerance
  spectra::RiskOptions options;                                ///< --rule, --tail
  bool records_selected_for_site = false;                      ///< --records-selected-for-site
};

/// The table of one sweep, with what is needed to print it.
struct RiskRun {
  std::string sweep;                           ///< the sweep's name
  std::string hazard_imt, fragility_imt;       ///< both measures, described
  std::vector<std::string> axis_order;         ///< the combination axes
  std::vector<std::size_t> shape;              ///< their sizes
  std::vector<std::string> combination_label;  ///< "a_deg=20,seat_over_L=0.001" per combination
  spectra::RiskTable table;                    ///< the rates
};

/// Computes every sweep's table and writes it into the cube.
/// @throws InputError (before anything is written) for an unreadable hazard or cube, a sweep
/// without a fragility, a measure mismatch, or fewer than two usable hazard levels.
std::vector<RiskRun> RunRisk(const RiskArgs& args);

}  // namespace skewbridge::jobs
