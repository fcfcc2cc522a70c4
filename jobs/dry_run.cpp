#include "jobs/dry_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <random>

#include "spectra/study.h"

namespace skewbridge::jobs {
namespace {

// A duration as a person reads it: ms below a second, s below two minutes, then min and h.
std::string Duration(double s) {
  if (s < 1.0) {
    return fmt::format("{:.3g} ms", s * 1e3);
  }
  if (s < 120.0) {
    return fmt::format("{:.3g} s", s);
  }
  if (s < 7200.0) {
    return fmt::format("{:.3g} min", s / 60.0);
  }
  return fmt::format("{:.3g} h", s / 3600.0);
}

// The coordinate of axis `axis` at index k, as printed.
std::string Coordinate(const Axis& axis, std::size_t k) {
  return axis.kind == ParameterKind::kLabel ? axis.labels[k] : fmt::format("{:g}", axis.values[k]);
}

// "a_deg = 15, T_g = 0.5" for the cell with these axis indices.
std::string CellText(const SweepSpec& spec, const std::vector<std::size_t>& index) {
  std::string out;
  for (std::size_t k = 0; k < spec.axes.size(); ++k) {
    out += (k ? ", " : "") + spec.axes[k].key + " = " + Coordinate(spec.axes[k], index[k]);
  }
  return out.empty() ? "the single cell" : out;
}

// A unit after a number: nothing for dimensionless, else " unit".
std::string Unit(std::string_view key) {
  const ParameterInfo* info = FindParameter(key);
  if (info == nullptr || info->unit.empty() || info->unit == "1") {
    return "";
  }
  return fmt::format(" {}", info->unit);
}

std::string AxisLine(const Axis& axis) {
  std::string values;
  const std::size_t n = axis.Size();
  for (std::size_t k = 0; k < n; ++k) {
    if (n > 8 && k == 3) {
      values += ", ...";
      k = n - 3;
    }
    values += (k ? ", " : "") + Coordinate(axis, k);
  }
  return fmt::format("  {:<14} {:>6}  {}{} ({})\n", axis.key, n, values, Unit(axis.key),
                     axis.spacing);
}

// The records of the sweep with the manifest's factor and any scale axis or fixed value.
std::string RecordLines(const SweepSpec& spec, const CellEvaluator& evaluator) {
  const std::vector<spectra::SweepRecord>* held = evaluator.Records();
  const std::vector<spectra::SweepRecord> loaded =
      held != nullptr ? std::vector<spectra::SweepRecord>{} : spectra::LoadSweepRecords(spec);
  const std::vector<spectra::SweepRecord>& records = held != nullptr ? *held : loaded;
  if (records.empty()) {
    return "records: none\n";
  }
  std::string source = spec.record_set;
  if (source.empty() && !spec.record_folder.empty()) {
    source = spec.record_folder + " (" + spec.record_pattern + ")";
  }
  if (source.empty() && spec.synthetic_count > 0) {
    source = fmt::format("synthetic count={} seed={}", spec.synthetic_count, spec.synthetic_seed);
  }
  std::string out = fmt::format("records: {} from {}\n", records.size(), source);
  std::string extra;
  if (const Axis* scale = spec.FindAxis("scale")) {
    extra = fmt::format("; every record is also multiplied by each value of the scale axis ({})",
                        scale->Size());
  } else if (const FixedValue* scale = spec.FindFixed("scale")) {
    extra = fmt::format("; every record is also multiplied by the fixed scale {:g}", scale->value);
  }
  out += "  scale = the set's factor on the file's accelerations" + extra +
         "; PGA and L_e include it\n";
  out += fmt::format("  {:<22} {:>8} {:>12} {:>9} {:>10}  {}\n", "label", "scale", "PGA [m/s^2]",
                     "T_m [s]", "L_e [m]", "file");
  for (const spectra::SweepRecord& r : records) {
    out += fmt::format("  {:<22} {:>8.4g} {:>12.4g} {:>9.4g} {:>10.4g}  {}\n", r.label, r.scale,
                       r.measures.pga_mps2, r.measures.mean_period_s, r.measures.persistency_m,
                       r.file.empty() ? "(made in memory)" : r.file);
  }
  return out;
}

}  // namespace

std::vector<std::uint64_t> SampleCells(std::uint64_t cells, std::size_t count, std::uint64_t seed) {
  std::vector<std::uint64_t> out;
  if (count >= cells) {
    for (std::uint64_t c = 0; c < cells; ++c) out.push_back(c);
    return out;
  }
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < count; ++i) {
    // Slice i holds cells [i N / count, (i + 1) N / count); each slice is non-empty.
    const std::uint64_t lo = static_cast<std::uint64_t>(static_cast<long double>(cells) *
                                                        static_cast<long double>(i) / count);
    const std::uint64_t hi = static_cast<std::uint64_t>(static_cast<long double>(cells) *
                                                        static_cast<long double>(i + 1) / count);
    std::uniform_int_distribution<std::uint64_t> pick(lo, std::max(lo, hi - 1));
    out.push_back(pick(rng));
  }
  return out;
}

DryRunEstimate EstimateSweepTime(std::uint64_t cells, const std::vector<double>& times_s, int ranks,
                                 int root_computes_up_to_ranks, double setup_s) {
  DryRunEstimate e;
  e.cells = cells;
  e.sampled = times_s.size();
  e.ranks = ranks;
  e.computing_ranks = ranks <= root_computes_up_to_ranks ? ranks : ranks - 1;
  e.setup_s = setup_s;
  double sum = 0.0;
  e.min_s = times_s.front();
  e.max_s = times_s.front();
  for (double t : times_s) {
    sum += t;
    e.min_s = std::min(e.min_s, t);
    e.max_s = std::max(e.max_s, t);
  }
  const double n = static_cast<double>(times_s.size());
  e.mean_s = sum / n;
  if (times_s.size() > 1) {
    double ss = 0.0;
    for (double t : times_s) ss += (t - e.mean_s) * (t - e.mean_s);
    e.standard_error_s = std::sqrt(ss / (n - 1.0) / n);
  }
  const double per_rank = static_cast<double>(cells) / e.computing_ranks;
  e.total_s = setup_s + per_rank * e.mean_s;
  e.low_s = setup_s + per_rank * std::max(e.min_s, e.mean_s - 2.0 * e.standard_error_s);
  e.high_s = setup_s + per_rank * (e.mean_s + 2.0 * e.standard_error_s);
  return e;
}

std::string DryRunReport(const SweepSpec& spec, const CellEvaluator& evaluator, int ranks,
                         std::size_t sample_cells, int root_computes_up_to_ranks, double setup_s) {
  std::string out = fmt::format("dry run of {} (sweep {}, family {}): nothing is written\n",
                                spec.source, spec.name, spec.family);
  std::string shape;
  for (const Axis& axis : spec.axes) {
    shape += (shape.empty() ? "" : " x ") + fmt::format("{} {}", axis.key, axis.Size());
  }
  const std::uint64_t cells = spec.CellCount();
  out += fmt::format("cells: {}{}\n", cells, shape.empty() ? "" : " = " + shape);
  out += "axes:\n";
  for (const Axis& axis : spec.axes) out += AxisLine(axis);
  out += spec.fixed.empty() ? "fixed: none\n" : "fixed:\n";
  for (const FixedValue& f : spec.fixed) {
    out += fmt::format(
        "  {:<14} {}\n", f.key,
        f.kind == ParameterKind::kLabel ? f.label : fmt::format("{:g}{}", f.value, Unit(f.key)));
  }
  out += RecordLines(spec, evaluator);
  const std::vector<ResponseInfo> responses = evaluator.Responses();
  std::string names;
  for (const ResponseInfo& r : responses) names += (names.empty() ? "" : ", ") + r.name;
  out += fmt::format("responses: {} ({})\n", responses.size(), names);

  const std::uint64_t seed = std::strtoull(spec.Hash().c_str(), nullptr, 16);
  const std::vector<std::uint64_t> sample = SampleCells(cells, sample_cells, seed);
  out += fmt::format(
      "timed here, one after another, on rank 0 ({} of {} cells, one drawn at "
      "random from each of {} equal slices of the cell list):\n",
      sample.size(), cells, sample.size());
  // A sweep that scales each record per cell stores the factor as the response scale_factor;
  // the timed cells show theirs.
  std::size_t scale_at = responses.size();
  for (std::size_t r = 0; r < responses.size(); ++r) {
    scale_at = responses[r].name == "scale_factor" ? r : scale_at;
  }
  std::vector<double> times;
  for (std::uint64_t c : sample) {
    const std::vector<std::size_t> index = spec.AxisIndex(c);
    const auto start = std::chrono::steady_clock::now();
    std::string note;
    try {  // a cell that throws is data in a sweep (status exception); here, a note
      const CellOutcome outcome = evaluator.Evaluate(index);
      if (scale_at < outcome.responses.size()) {  // records scaled cell by cell (stripes)
        note = fmt::format("  scale factor {:.4g}", outcome.responses[scale_at]);
      }
      if (outcome.status != kStatusOk) {
        note += fmt::format(" (status {}: {})", outcome.status, outcome.status_text);
      }
    } catch (const std::exception& err) {
      note = std::string(" (threw: ") + err.what() + ")";
    }
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    times.push_back(t);
    out += fmt::format("  cell {:>8}  {:>10}  {}{}\n", c, Duration(t), CellText(spec, index), note);
  }
  const DryRunEstimate e =
      EstimateSweepTime(cells, times, ranks, root_computes_up_to_ranks, setup_s);
  out += fmt::format("estimate on {} rank(s): {} (about {} to {})\n", e.ranks, Duration(e.total_s),
                     Duration(e.low_s), Duration(e.high_s));
  out += fmt::format(
      "  = set-up {} + {} cells x {} per cell (mean of the sample; min {}, max {}) / {} "
      "computing rank(s){}\n",
      Duration(e.setup_s), e.cells, Duration(e.mean_s), Duration(e.min_s), Duration(e.max_s),
      e.computing_ranks, e.computing_ranks < e.ranks ? " (rank 0 only gathers)" : "");
  out +=
      "  the range is the mean -/+ 2 standard errors of the sample (its low end at least the "
      "shortest cell timed); it assumes cells cost what "
      "the sample did on this machine and one core per rank, and leaves out the final "
      "cube's write (about 1 us per cell)\n";
  return out;
}

}  // namespace skewbridge::jobs
