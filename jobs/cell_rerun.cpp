#include "jobs/cell_rerun.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "jobs/cube.h"
#include "jobs/h5/cube_file.h"
#include "solver/common/error.h"
#include "spectra/model_file_evaluator.h"
#include "spectra/spectra_evaluator.h"

namespace skewbridge::jobs {
namespace {

// Relative distance within which a typed number is the axis coordinate it names.
constexpr double kCoordinateTolerance = 1e-9;
// Coordinates an allowed-values list shows before it says how many there are in all.
constexpr std::size_t kListedCoordinates = 12;

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string CoordinateText(const spectra::Axis& axis, std::size_t i) {
  return axis.kind == spectra::ParameterKind::kNumber ? fmt::format("{}", axis.values[i])
                                                      : axis.labels[i];
}

// "0.2, 0.4, 0.6" or the first kListedCoordinates and "... (N in all)".
std::string AllowedValues(const spectra::Axis& axis) {
  std::string out;
  const std::size_t n = axis.Size();
  for (std::size_t i = 0; i < std::min(n, kListedCoordinates); ++i) {
    out += (i == 0 ? "" : ", ") + CoordinateText(axis, i);
  }
  if (n > kListedCoordinates) out += fmt::format(", ... ({} in all)", n);
  return out;
}

std::string AxisNames(const spectra::CellGrid& grid) {
  std::string out;
  for (const spectra::Axis& a : grid.axes) out += (out.empty() ? "" : ", ") + a.key;
  return out.empty() ? "none (the sweep has one cell)" : out;
}

// The coordinate of `axis` that `value` names, or npos.
std::size_t FindCoordinate(const spectra::Axis& axis, std::string_view value) {
  if (axis.kind == spectra::ParameterKind::kLabel) {
    const auto it = std::find(axis.labels.begin(), axis.labels.end(), value);
    return it == axis.labels.end() ? std::string_view::npos
                                   : static_cast<std::size_t>(it - axis.labels.begin());
  }
  double x = 0.0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), x);
  if (ec != std::errc() || end != value.data() + value.size() || !std::isfinite(x)) {
    return std::string_view::npos;
  }
  std::size_t best = std::string_view::npos;
  double best_distance = 0.0;
  for (std::size_t i = 0; i < axis.values.size(); ++i) {
    const double c = axis.values[i];
    const double distance = std::abs(x - c);
    if (distance <= kCoordinateTolerance * std::max(std::abs(c), std::abs(x)) &&
        (best == std::string_view::npos || distance < best_distance)) {
      best = i;
      best_distance = distance;
    }
  }
  return best;
}

std::string ReadFileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::uint64_t CellIndexOf(const spectra::CellGrid& grid, std::string_view text) {
  constexpr std::size_t kUnset = std::string_view::npos;
  std::vector<std::size_t> index(grid.axes.size(), kUnset);
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string_view pair = Trim(text.substr(start, comma - start));
    start = comma + 1;
    if (pair.empty()) continue;
    const std::size_t eq = pair.find('=');
    if (eq == std::string_view::npos) {
      throw InputError::AtField("--cell", std::string(pair),
                                "not AXIS=VALUE; the sweep's axes: " + AxisNames(grid));
    }
    const std::string key(Trim(pair.substr(0, eq)));
    const std::string_view value = Trim(pair.substr(eq + 1));
    const auto axis = std::find_if(grid.axes.begin(), grid.axes.end(),
                                   [&](const spectra::Axis& a) { return a.key == key; });
    if (axis == grid.axes.end()) {
      throw InputError::AtField("--cell", key,
                                "not an axis of the sweep; its axes: " + AxisNames(grid));
    }
    const std::size_t k = static_cast<std::size_t>(axis - grid.axes.begin());
    if (index[k] != kUnset) {
      throw InputError::AtField("--cell", key, "given twice");
    }
    index[k] = FindCoordinate(*axis, value);
    if (index[k] == kUnset) {
      throw InputError::AtField(
          "--cell", key,
          fmt::format("{} is not a coordinate of the axis; allowed: {}",
                      value.empty() ? "(nothing)" : std::string(value), AllowedValues(*axis)));
    }
  }
  std::uint64_t cell = 0;
  for (std::size_t k = 0; k < grid.axes.size(); ++k) {
    const spectra::Axis& axis = grid.axes[k];
    if (index[k] == kUnset) {
      if (axis.Size() != 1) {
        throw InputError::AtField("--cell", axis.key,
                                  "missing: name its coordinate, one of " + AllowedValues(axis));
      }
      index[k] = 0;
    }
    cell = cell * axis.Size() + index[k];
  }
  return cell;
}

std::string CellCoordinates(const spectra::CellGrid& grid, std::uint64_t cell) {
  const std::vector<std::size_t> index = grid.AxisIndex(cell);
  std::string out;
  for (std::size_t k = 0; k < grid.axes.size(); ++k) {
    out += (k == 0 ? "" : ", ") + grid.axes[k].key + "=" + CoordinateText(grid.axes[k], index[k]);
  }
  return out;
}

CellRerun PrepareCellRerun(const std::filesystem::path& cube, const CellChoice& choice) {
  const std::string where = cube.string();
  const std::vector<h5::SweepSummary> sweeps = h5::SummarizeCube(cube);
  std::string names;
  for (const h5::SweepSummary& s : sweeps) names += (names.empty() ? "" : ", ") + s.name;
  const h5::SweepSummary* summary = nullptr;
  if (choice.sweep.empty()) {
    if (sweeps.size() != 1) {
      throw InputError::AtLine(where, 0, "holds several sweeps; choose one with --sweep: " + names);
    }
    summary = &sweeps.front();
  } else {
    for (const h5::SweepSummary& s : sweeps) {
      if (s.name == choice.sweep) summary = &s;
    }
    if (summary == nullptr) {
      throw InputError::AtField("--sweep", choice.sweep,
                                "no such sweep in " + where + "; it holds: " + names);
    }
  }
  if (summary->family == "multi-span") {
    throw InputError::AtLine(where, 0,
                             "sweep '" + summary->name + "' is of family " + summary->family +
                                 "; a cell is re-run for the model-file, subsystem and "
                                 "pilot-bridge families");
  }
  if (summary->spec_text.empty()) {
    throw InputError::AtLine(where, 0, "sweep '" + summary->name + "' stores no specification");
  }

  CellRerun out;
  // The stored text, parsed where the sweep read it: its relative paths name the same files.
  const std::filesystem::path source = summary->spec_source;
  try {
    out.spec = ParseSweepSpec(summary->spec_text, summary->spec_source, source.parent_path());
  } catch (const InputError& e) {
    throw InputError(where + ": cannot rebuild sweep '" + summary->name +
                     "' from its stored specification (paths are relative to the folder of " +
                     summary->spec_source + ", where the sweep read it): " + e.what());
  }
  if (out.spec.ida.enabled) {
    throw InputError::AtLine(where, 0,
                             "sweep '" + summary->name +
                                 "' is an incremental dynamic analysis: each cell is many runs; "
                                 "run one with `skewbridge run MODEL --record-set SET --label L "
                                 "--target-sa-g X`");
  }
  // A result never outlives its inputs: every file as the cube's checksums say it was.
  const std::string change =
      DescribeIdentityChange(summary->spec_canonical, summary->inputs_canonical, out.spec);
  if (!change.empty()) {
    throw InputError::AtLine(where, 0,
                             "cannot re-run a cell of sweep '" + summary->name + "': " + change);
  }

  const std::uint64_t cells = out.spec.CellCount();
  if (choice.index && !choice.coordinates.empty()) {
    throw InputError::AtField("--cell-index", std::to_string(*choice.index),
                              "give --cell or --cell-index, not both");
  }
  if (choice.index) {
    if (*choice.index >= cells) {
      throw InputError::AtField(
          "--cell-index", std::to_string(*choice.index),
          fmt::format("sweep '{}' has {} cells: allowed 0 to {}", summary->name, cells, cells - 1));
    }
    out.index = *choice.index;
  } else if (!choice.coordinates.empty()) {
    out.index = CellIndexOf(out.spec, choice.coordinates);
  } else {
    throw InputError::AtField(
        "--from-cube", where,
        "needs --cell AXIS=VALUE,... or --cell-index N; the sweep's axes: " + AxisNames(out.spec));
  }
  out.coordinates = CellCoordinates(out.spec, out.index);

  std::vector<std::string> stored_names;
  const CubeData data = h5::ReadCubeData(cube, summary->name, &stored_names);
  SB_DEMAND(data.Cells() == cells, "a cube's cell count differs from its specification's");
  out.done = data.done[out.index] != 0;
  out.status = data.status[out.index];
  out.response_names = stored_names;
  for (const std::vector<double>& column : data.responses) {
    out.responses.push_back(column[out.index]);
  }

  const std::vector<std::size_t> axis_index = out.spec.AxisIndex(out.index);
  if (out.spec.family == "model-file") {
    auto evaluator = std::make_unique<spectra::ModelFileEvaluator>(out.spec);
    spectra::ModelFileCell c = evaluator->MakeCell(axis_index, true);
    out.model = std::move(c.model);
    out.compliant = c.compliant;
    out.excitation = std::move(c.excitation);
    out.control = c.control;
    out.record = c.record;
    out.scale = c.scale;
    out.trace_excitation = evaluator->StripeTraceExcitation(axis_index);
    out.model_text = ReadFileText(out.spec.model_path);
    out.evaluator = std::move(evaluator);
  } else {
    auto evaluator = std::make_unique<spectra::SpectraEvaluator>(out.spec);
    spectra::SpectraEvaluator::CellRun c = evaluator->MakeRun(axis_index);
    out.model.emplace(std::move(c.run->model));
    out.excitation = std::move(c.excitation);
    out.control = c.run->control;
    out.record = c.record;
    out.evaluator = std::move(evaluator);
  }
  const CubeLayout layout = MakeCubeLayout(*out.evaluator, {}, out.spec.source);
  out.status_name = fmt::format("status {}", out.status);
  for (const auto& [code, name] : layout.status_names) {
    if (code == out.status) out.status_name = name;
  }
  return out;
}

}  // namespace skewbridge::jobs
