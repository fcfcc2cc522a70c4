#include "jobs/dry_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <optional>
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
                     "T_m [s]", "L_e [m]",
                     spec.synthetic_count > 0 ? "file" : "file (from the set's folder)");
  for (const spectra::SweepRecord& r : records) {
    out += fmt::format("  {:<22} {:>8.4g} {:>12.4g} {:>9.4g} {:>10.4g}  {}\n", r.label, r.scale,
                       r.measures.pga_mps2, r.measures.mean_period_s, r.measures.persistency_m,
                       r.file.empty() ? "(synthetic, made in memory)" : r.file);
  }
  return out;
}

// The median of `v` (the mean of the two middle values for an even count). @pre !v.empty()
double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A factor in a table cell: 4 significant digits, '*' after it beyond max_scale.
std::string FactorText(double factor, bool too_far) {
  return fmt::format("{:.4g}{}", factor, too_far ? "*" : " ");
}

}  // namespace

std::string ScaleFactorReport(const SweepSpec& spec, const CellEvaluator& evaluator,
                              bool full_table) {
  const std::uint64_t cells = spec.CellCount();
  const spectra::RecordScaling* scaling = evaluator.record_scaling();
  if (cells == 0 || scaling == nullptr || !scaling->Scaling(spec.AxisIndex(0))) return {};
  const spectra::IntensityMeasureSpec& im = spec.im;
  const std::string im_key = im.AxisKey();
  const std::string unit = spectra::IntensityUnit(im);
  const std::size_t none = spec.axes.size();
  std::size_t record_axis = none, im_axis = none;
  for (std::size_t k = 0; k < spec.axes.size(); ++k) {
    if (spec.axes[k].key == "record") record_axis = k;
    if (spec.axes[k].key == im_key) im_axis = k;
  }
  const std::size_t n_records = record_axis == none ? 1 : spec.axes[record_axis].Size();
  const std::size_t n_stripes = im_axis == none ? 1 : spec.axes[im_axis].Size();
  // The other axes' combinations ("k_factor = 4, a_deg = 30"), numbered row-major.
  std::vector<std::size_t> others;
  std::uint64_t n_combos = 1;
  for (std::size_t k = 0; k < spec.axes.size(); ++k) {
    if (k != record_axis && k != im_axis) {
      others.push_back(k);
      n_combos *= spec.axes[k].Size();
    }
  }
  struct Combo {
    std::vector<double> own;      // per record: its own measure (unit)
    std::vector<double> factor;   // [record][stripe]
    std::vector<char> too_far;    // [record][stripe]
    std::vector<double> targets;  // per stripe
    double t1_s = 0.0;
    std::string text;  // the other axes' coordinates
  };
  std::vector<Combo> combos(n_combos);
  for (Combo& c : combos) {
    c.own.assign(n_records, 0.0);
    c.factor.assign(n_records * n_stripes, 0.0);
    c.too_far.assign(n_records * n_stripes, 0);
    c.targets.assign(n_stripes, 0.0);
  }
  std::uint64_t beyond = 0;
  double largest = 0.0;
  for (std::uint64_t cell = 0; cell < cells; ++cell) {
    const std::vector<std::size_t> index = spec.AxisIndex(cell);
    const std::optional<spectra::CellScaling> s = scaling->Scaling(index);
    if (!s) return {};
    std::uint64_t combo = 0;
    std::string text;
    for (std::size_t k : others) {
      combo = combo * spec.axes[k].Size() + index[k];
      text += (text.empty() ? "" : ", ") + spec.axes[k].key + " = " +
              Coordinate(spec.axes[k], index[k]);
    }
    const std::size_t r = record_axis == none ? 0 : index[record_axis];
    const std::size_t j = im_axis == none ? 0 : index[im_axis];
    Combo& c = combos[combo];
    c.own[r] = s->unscaled;
    c.factor[r * n_stripes + j] = s->factor;
    c.too_far[r * n_stripes + j] = s->too_far ? 1 : 0;
    c.targets[j] = s->target;
    c.t1_s = s->t1_s;
    c.text = text;
    beyond += s->too_far ? 1 : 0;
    largest = std::max(largest, s->factor);
  }
  // Combinations whose records have the same own measures share their factors: one group.
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t c = 0; c < combos.size(); ++c) {
    auto same = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
      return combos[g.front()].own == combos[c].own && combos[g.front()].t1_s == combos[c].t1_s;
    });
    if (same == groups.end()) {
      groups.push_back({c});
    } else {
      same->push_back(c);
    }
  }

  std::string measure = im.measure;
  if (im.Spectral()) {
    measure += im.at_t1 ? fmt::format("(T1, xi = {:g})", im.xi)
                        : fmt::format("({:g} s, xi = {:g})", im.period_s, im.xi);
  }
  std::string out = fmt::format(
      "scale factors (records.scale_to): factor = {} / the record's own {} [{}]; max_scale = "
      "{}\n",
      im_key, measure, unit, im.max_scale > 0.0 ? fmt::format("{:g}", im.max_scale) : "none");
  const bool table = full_table || n_records <= kScaleTableRecords;
  for (const std::vector<std::size_t>& group : groups) {
    const Combo& c = combos[group.front()];
    std::string where;
    if (!others.empty() && groups.size() == 1) {
      where = " for every";
      for (std::size_t k : others) where += (k == others.front() ? " " : ", ") + spec.axes[k].key;
    } else if (!others.empty()) {
      for (std::size_t i = 0; i < group.size() && i < 3; ++i) {
        where += (i ? "; " : "") + combos[group[i]].text;
      }
      if (group.size() > 3) where += fmt::format("; and {} more", group.size() - 3);
      where = " for " + where;
    }
    std::size_t group_beyond = 0;
    for (char f : c.too_far) group_beyond += f ? 1 : 0;
    out +=
        fmt::format("  T1 = {:.5g} s{}: {} record(s) x {} stripe(s), {} of {} beyond max_scale\n",
                    c.t1_s, where, n_records, n_stripes, group_beyond, c.too_far.size());
    out += fmt::format("    {:>10} {:>10} {:>10} {:>10} {:>16}\n", im_key + " [" + unit + "]",
                       "min", "median", "max", "beyond max_scale");
    for (std::size_t j = 0; j < n_stripes; ++j) {
      std::vector<double> f(n_records);
      std::size_t far = 0;
      for (std::size_t r = 0; r < n_records; ++r) {
        f[r] = c.factor[r * n_stripes + j];
        far += c.too_far[r * n_stripes + j] ? 1 : 0;
      }
      out += fmt::format("    {:>10.4g} {:>10.4g} {:>10.4g} {:>10.4g} {:>16}\n", c.targets[j],
                         *std::min_element(f.begin(), f.end()), Median(f),
                         *std::max_element(f.begin(), f.end()),
                         fmt::format("{} of {}", far, n_records));
    }
    if (!table) continue;
    std::size_t width = 6;
    for (std::size_t r = 0; r < n_records; ++r) {
      width = std::max(width, record_axis == none
                                  ? spectra::LabelOf(spec, spec.AxisIndex(0), "record").size()
                                  : spec.axes[record_axis].labels[r].size());
    }
    std::string head = fmt::format("    {:<{}} {:>11}", "record", width, "own [" + unit + "]");
    for (std::size_t j = 0; j < n_stripes; ++j) head += fmt::format(" {:>9.4g} ", c.targets[j]);
    out += head.substr(0, head.find_last_not_of(' ') + 1) + "\n";
    for (std::size_t r = 0; r < n_records; ++r) {
      const std::string label = record_axis == none
                                    ? spectra::LabelOf(spec, spec.AxisIndex(0), "record")
                                    : spec.axes[record_axis].labels[r];
      std::string row = fmt::format("    {:<{}} {:>11.5g}", label, width, c.own[r]);
      for (std::size_t j = 0; j < n_stripes; ++j) {
        row += fmt::format(
            " {:>10}", FactorText(c.factor[r * n_stripes + j], c.too_far[r * n_stripes + j] != 0));
      }
      out += row.substr(0, row.find_last_not_of(' ') + 1) + "\n";
    }
  }
  if (table && im.max_scale > 0.0) out += "  (* beyond max_scale)\n";
  if (!table) {
    out += fmt::format("  the full table of the {} records x {} stripes: add --scale-table\n",
                       n_records, n_stripes);
  }
  out += im.max_scale > 0.0
             ? fmt::format("  {} of {} cells beyond max_scale = {:g} (largest factor {:.4g})\n",
                           beyond, cells, im.max_scale, largest)
             : fmt::format("  no max_scale given: no cell is flagged (largest factor {:.4g})\n",
                           largest);
  return out;
}

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
                         std::size_t sample_cells, int root_computes_up_to_ranks, double setup_s,
                         bool full_scale_table) {
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
  out += ScaleFactorReport(spec, evaluator, full_scale_table);
  if (spec.ida.enabled) {
    const spectra::IdaSpec& ida = spec.ida;
    const std::string unit = spectra::IntensityUnit(spec.im);
    out += fmt::format(
        "ida: each cell scales its record by hunt-and-fill: hunt from {:g} {} by steps of {:g} "
        "{} growing by {:g} {} up to {:g} {}, bisect to {:g} {}, fill gaps; at most {} runs per "
        "cell (a timed cell below is its whole search)\n",
        ida.start, unit, ida.step, unit, ida.step_increase, unit, ida.max_im, unit, ida.tolerance,
        unit, ida.max_runs);
  }
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
