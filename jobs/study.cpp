#include "jobs/study.h"

#include <optional>
#include <string_view>

namespace skewbridge::jobs {
namespace {

std::optional<std::size_t> ResponseColumn(const CubeLayout& layout, std::string_view name) {
  for (std::size_t r = 0; r < layout.responses.size(); ++r) {
    if (layout.responses[r].name == name) return r;
  }
  return std::nullopt;
}

}  // namespace

StudyTables MakeStudyTables(const SweepSpec& spec, const CubeLayout& layout, const CubeData& data,
                            const std::vector<SweepRecord>* records) {
  StudyTables tables;
  const std::optional<std::size_t> band_col = ResponseColumn(layout, "band");
  if (band_col) tables.band_edges = BandEdges(spec);
  tables.records = records != nullptr ? *records : LoadSweepRecords(spec);
  if (!tables.records.empty()) {
    if (spec.synthetic_count > 0) {
      tables.records_source = "synthetic";
      tables.records_set = "synthetic count=" + std::to_string(spec.synthetic_count) +
                           " seed=" + std::to_string(spec.synthetic_seed);
    } else {
      tables.records_source = "set";
      tables.records_set = spec.record_folder.empty()
                               ? spec.record_set
                               : spec.record_folder + " (" + spec.record_pattern + ")";
    }
  }

  // A model-file sweep names its responses per deck: with one deck, its rotation is the one.
  std::optional<std::size_t> theta_col = ResponseColumn(layout, "theta_m");
  if (!theta_col && !ResponseColumn(layout, "theta_m_d1")) {
    theta_col = ResponseColumn(layout, "theta_m_d0");
  }
  const std::optional<std::size_t> le_col = ResponseColumn(layout, "L_e");
  const Axis* record_axis = spec.FindAxis("record");
  if (record_axis == nullptr || spec.FindAxis("Pi_delta") == nullptr || !theta_col || !le_col) {
    return tables;
  }

  std::vector<std::uint8_t> usable(data.Cells());
  for (std::uint64_t cell = 0; cell < data.Cells(); ++cell) {
    usable[cell] = data.done[cell] != 0 && data.status[cell] == kStatusOk ? 1 : 0;
  }
  std::vector<double> no_band;
  const std::vector<double>& band = band_col ? data.responses[*band_col] : no_band;
  CorrelationTable table =
      spectra::CorrelateOverRecords(spec, data.responses[*theta_col], data.responses[*le_col], band,
                                    usable, BandEdges(spec).size() + 1);
  table.y = layout.responses[*theta_col].name;
  tables.correlation = std::move(table);
  return tables;
}

}  // namespace skewbridge::jobs
