#include "spectra/study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "records/record_set.h"
#include "records/synthetic.h"
#include "solver/common/error.h"
#include "solver/common/nearest.h"
#include "spectra/correlation.h"

namespace skewbridge::spectra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> WantedLabels(const CellGrid& spec) {
  if (const Axis* axis = spec.FindAxis("record")) return axis->labels;
  if (const FixedValue* fixed = spec.FindFixed("record")) return {fixed->label};
  return {};
}

void AddReason(std::string& reason, std::string_view what, const std::string& why) {
  if (why.empty()) return;
  reason += (reason.empty() ? "" : "; ") + std::string(what) + ": " + why;
}

// Why `label` names no record of `set`: the set, the nearest labels and, when the label is a
// file name without its extension, that labels keep it.
std::string UnknownLabel(const std::string& label, const CellGrid& spec,
                         const records::RecordSet& set) {
  std::vector<std::string> labels;
  for (const records::RecordEntry& entry : set.records)
    labels.push_back(records::RecordLabel(entry));
  const std::string where = spec.record_folder.empty()
                                ? "the record set " + set.manifest.string()
                                : "the records of folder " + spec.record_folder + " (pattern " +
                                      spec.record_pattern + ")";
  std::string message = "label '" + label + "' is not in " + where + " of " +
                        std::to_string(labels.size()) + " record(s); nearest: ";
  const std::vector<std::string> nearest = NearestNames(label, labels, 3, false);
  for (std::size_t i = 0; i < nearest.size(); ++i) {
    message += (i ? ", " : "") + nearest[i];
  }
  const bool stem_of_a_label = std::any_of(labels.begin(), labels.end(), [&](const auto& l) {
    return std::filesystem::path(l).stem().string() == label;
  });
  if (!spec.record_folder.empty()) {
    message += "; the labels of a folder set are the file names, extension included";
  } else if (stem_of_a_label) {
    message += "; a record without label is labelled by its file name, extension included";
  }
  return message;
}

}  // namespace

std::vector<SweepRecord> LoadSweepRecords(const CellGrid& spec) {
  const std::vector<std::string> wanted = WantedLabels(spec);
  if (wanted.empty()) return {};
  std::vector<SweepRecord> out;
  if (spec.synthetic_count > 0) {
    records::SynthOptions options;
    options.count = spec.synthetic_count;
    options.seed = spec.synthetic_seed;
    records::ValidateSynthOptions(options);
    // Only the wanted indices are made: each record depends on (options, index) alone.
    for (const std::string& label : wanted) {
      int index = -1;
      const std::string prefix = "synth-" + std::to_string(options.seed) + "-";
      if (label.rfind(prefix, 0) == 0 && label.size() > prefix.size() &&
          label.size() - prefix.size() <= 9 &&
          std::all_of(label.begin() + static_cast<std::ptrdiff_t>(prefix.size()), label.end(),
                      [](char c) { return c >= '0' && c <= '9'; })) {
        index = std::stoi(label.substr(prefix.size()));
      }
      records::GroundMotion made;
      if (index >= 0 && index < options.count) made = records::SynthesizeRecord(options, index);
      if (index < 0 || index >= options.count || made.station != label) {
        throw InputError::AtField(spec.source, "record",
                                  "label '" + label + "' is not in the synthetic suite (count " +
                                      std::to_string(options.count) + ", seed " +
                                      std::to_string(options.seed) + ": labels " + prefix +
                                      "000 ...)");
      }
      SweepRecord record;
      record.label = label;
      // SynthesizeRecord already returns its .AT2 text read back, i.e. the samples
      // `records synth` writes; a second trip through the text would give the same bytes
      // (tests/study: LoadSweepRecords.SyntheticRecordsAreTheAt2TextReadBack).
      record.motion = std::move(made);
      record.motion.file = label;
      record.measures = records::ComputeMeasures(record.motion);
      out.push_back(std::move(record));
    }
    CheckMeasureOfRecords(spec, out);
    return out;
  }
  if (spec.record_set_path.empty() && spec.record_folder.empty()) {
    throw InputError::AtField(spec.source, "records.set",
                              "missing: a record axis needs a record set");
  }
  const records::RecordSet set = LoadSpecRecordSet(spec);
  // Both absolute, so that a record named by an absolute path in a manifest given by a relative
  // one (or the reverse) still has a path relative to the manifest's folder.
  const std::filesystem::path base =
      std::filesystem::absolute(set.manifest).parent_path().lexically_normal();
  for (const std::string& label : wanted) {
    const records::RecordEntry* found = nullptr;
    for (const records::RecordEntry& entry : set.records) {
      if (records::RecordLabel(entry) == label) found = &entry;
    }
    if (found == nullptr) {
      throw InputError::AtField(spec.source, "record", UnknownLabel(label, spec, set));
    }
    SweepRecord record;
    record.label = label;
    auto relative_to_set = [&base](const std::filesystem::path& path) {
      const std::filesystem::path file = std::filesystem::absolute(path).lexically_normal();
      const std::filesystem::path relative = file.lexically_relative(base);
      return (relative.empty() ? file : relative).generic_string();
    };
    record.file = relative_to_set(found->file);
    record.scale = found->scale;
    records::RecordComponents components = records::LoadComponents(*found);
    record.motion = std::move(components.motions[0]);
    record.measures = records::ComputeMeasures(record.motion);
    if (components.IsPair()) {
      record.file_h2 = relative_to_set(found->file_h2);
      record.motion_h2 = std::move(components.motions[1]);
      record.measures_h2 = records::ComputeMeasures(*record.motion_h2);
      record.padded_samples = components.padded_samples;
    }
    out.push_back(std::move(record));
  }
  CheckMeasureOfRecords(spec, out);
  return out;
}

void SetSpectralMeasuresAtT1(SweepRecord& record, double t1_s, double xi) {
  record.t1_s = t1_s;
  record.spectral_xi = xi;
  const std::vector<double> one{t1_s};
  const std::span<const double> acc(record.motion.acc_mps2);
  record.sa_t1_mps2 = records::PseudoAccelerationSpectrum(acc, record.motion.dt_s, one, xi)[0];
  record.avgsa_mps2 = records::AverageSpectralAcceleration(acc, record.motion.dt_s,
                                                           records::AvgSaPeriods(t1_s), xi);
  if (!record.IsPair()) return;
  const records::PairSpectrum pair =
      records::PairResponseSpectrum(acc, record.motion_h2->acc_mps2, record.motion.dt_s, one, xi);
  record.rotd50_t1_mps2 = pair.rotd50_mps2[0];
  record.rotd100_t1_mps2 = pair.rotd100_mps2[0];
  record.gm_t1_mps2 = pair.gm_mps2[0];
  record.rotd100_angle_t1_deg = pair.rotd100_angle_deg[0];
}

void CheckMeasureOfRecords(const CellGrid& spec, const std::vector<SweepRecord>& records) {
  const IntensityMeasureSpec& im = spec.im;
  if (im.measure.empty()) return;
  const std::string field = std::string(im.scale ? "records.scale_to" : "records.im") + ".measure";
  for (const SweepRecord& r : records) {
    if (im.OfPair() && !r.IsPair()) {
      throw InputError::AtField(
          spec.source, field,
          "record '" + r.label + "' is a single component and " + im.measure +
              " is a measure of a pair of horizontal components (h1, h2 in the record set, "
              "docs/records.md); allowed for single records: Sa, AvgSa, PGA, PGV");
    }
    if (!im.OfPair() && r.IsPair()) {
      throw InputError::AtField(
          spec.source, field,
          "record '" + r.label + "' is a pair of horizontal components and " + im.measure +
              " is a measure of one component (it would depend on which is H1); allowed for "
              "pairs: RotD50, RotD100, GM, AvgSa_RotD50 [Boore 2010]");
    }
  }
}

double RecordIntensity(const SweepRecord& record, const IntensityMeasureSpec& im, double t1_s) {
  constexpr double g = records::kStandardGravity_mps2;
  const double period = im.at_t1 ? t1_s : im.period_s;
  // Stored by SetSpectralMeasuresAtT1 for this very period and damping: taken as they are.
  const bool stored = period == record.t1_s && im.xi == record.spectral_xi;
  if (im.OfPair()) {
    SB_DEMAND(record.IsPair(), "a pair measure of a single record (CheckMeasureOfRecords)");
    if (im.measure == "AvgSa_RotD50") {
      return records::AverageRotD50(record.motion.acc_mps2, record.motion_h2->acc_mps2,
                                    record.motion.dt_s, records::AvgSaPeriods(period), im.xi) /
             g;
    }
    if (stored) {
      return (im.measure == "RotD50"    ? record.rotd50_t1_mps2
              : im.measure == "RotD100" ? record.rotd100_t1_mps2
                                        : record.gm_t1_mps2) /
             g;
    }
    const std::vector<double> one{period};
    const records::PairSpectrum pair = records::PairResponseSpectrum(
        record.motion.acc_mps2, record.motion_h2->acc_mps2, record.motion.dt_s, one, im.xi);
    return (im.measure == "RotD50"    ? pair.rotd50_mps2[0]
            : im.measure == "RotD100" ? pair.rotd100_mps2[0]
                                      : pair.gm_mps2[0]) /
           g;
  }
  if (im.measure == "PGA") return record.measures.pga_mps2 / g;
  if (im.measure == "PGV") return record.measures.pgv_mps;
  if (stored && (im.measure == "Sa" || im.measure == "AvgSa")) {
    return (im.measure == "Sa" ? record.sa_t1_mps2 : record.avgsa_mps2) / g;
  }
  const std::span<const double> acc(record.motion.acc_mps2);
  if (im.measure == "Sa") {
    const std::vector<double> one{period};
    return records::PseudoAccelerationSpectrum(acc, record.motion.dt_s, one, im.xi)[0] / g;
  }
  SB_DEMAND(im.measure == "AvgSa", "unknown intensity measure");
  return records::AverageSpectralAcceleration(acc, record.motion.dt_s,
                                              records::AvgSaPeriods(period), im.xi) /
         g;
}

std::string IntensityUnit(const IntensityMeasureSpec& im) {
  return im.measure == "PGV" ? "m/s" : "g";
}

std::string IntensityDescription(const IntensityMeasureSpec& im) {
  const std::string at = im.at_t1 ? "T1" : fmt::format("{} s", im.period_s);
  if (im.measure == "Sa") {
    return fmt::format(
        "Sa({}, xi = {}): pseudo-spectral acceleration in g [Nigam and Jennings "
        "1969]",
        at, im.xi);
  }
  if (im.measure == "AvgSa") {
    return fmt::format(
        "AvgSa({}, xi = {}): geometric mean of Sa in g over {} periods equally "
        "spaced from {} to {} times {} [Eads et al. 2015]",
        at, im.xi, records::kAvgSaPeriodCount, records::kAvgSaFromT1, records::kAvgSaToT1, at);
  }
  if (im.measure == "AvgSa_RotD50") {
    return fmt::format(
        "AvgSa_RotD50({}, xi = {}): geometric mean of the pair's RotD50 in g over {} periods "
        "equally spaced from {} to {} times {} [Eads et al. 2015; Boore 2010]",
        at, im.xi, records::kAvgSaPeriodCount, records::kAvgSaFromT1, records::kAvgSaToT1, at);
  }
  if (im.OfPair()) {
    const std::string what = im.measure == "RotD50" ? "median over the rotation angles 0-179 deg"
                             : im.measure == "RotD100"
                                 ? "largest over the rotation angles 0-179 deg"
                                 : "geometric mean over the two components";
    return fmt::format(
        "{}({}, xi = {}): {} of the pair's peak oscillator responses, pseudo-spectral "
        "acceleration in g [Boore 2010]",
        im.measure, at, im.xi, what);
  }
  if (im.measure == "PGA") return "PGA in g";
  return "PGV in m/s (no baseline correction)";
}

std::optional<IntensityMeasureSpec> ParseIntensityDescription(std::string_view measure,
                                                              std::string_view description) {
  IntensityMeasureSpec im;
  im.measure = std::string(measure);
  if (measure == "PGA" || measure == "PGV") {
    if (description != IntensityDescription(im)) return std::nullopt;
    return im;
  }
  if (!im.Spectral()) return std::nullopt;
  // "<measure>(<T1 | period s>, xi = <xi>): ..."
  const std::string head = std::string(measure) + "(";
  if (description.substr(0, head.size()) != head) return std::nullopt;
  const std::size_t comma = description.find(", xi = ", head.size());
  const std::size_t close = description.find("):", head.size());
  if (comma == std::string_view::npos || close == std::string_view::npos || close < comma) {
    return std::nullopt;
  }
  const std::string at(description.substr(head.size(), comma - head.size()));
  const std::string xi(description.substr(comma + 7, close - comma - 7));
  char* end = nullptr;
  im.xi = std::strtod(xi.c_str(), &end);
  if (end != xi.c_str() + xi.size()) return std::nullopt;
  if (at == "T1") {
    im.at_t1 = true;
  } else {
    if (at.size() < 3 || at.substr(at.size() - 2) != " s") return std::nullopt;
    const std::string period = at.substr(0, at.size() - 2);
    im.period_s = std::strtod(period.c_str(), &end);
    if (end != period.c_str() + period.size()) return std::nullopt;
  }
  // The text must be exactly what IntensityDescription writes for what was read.
  if (IntensityDescription(im) != description) return std::nullopt;
  return im;
}

records::RecordSet LoadSpecRecordSet(const CellGrid& spec) {
  if (!spec.record_folder.empty()) {
    records::RecordEntry defaults;
    if (!spec.record_units.empty()) defaults.options.units = records::ParseUnits(spec.record_units);
    if (spec.record_dt_s > 0.0) defaults.options.dt_s = spec.record_dt_s;
    records::FolderPairs pairs;
    pairs.by_name = spec.record_pairs_by_name;
    if (!spec.record_pairs_table.empty()) {
      pairs.table = spec.record_folder_path / spec.record_pairs_table;
    }
    return records::MakeFolderSet(
        spec.record_folder_path, spec.record_pattern, defaults,
        {spec.record_folder_at, spec.record_pattern_at, "records.", spec.record_pairs_at}, pairs);
  }
  return records::LoadRecordSet(spec.record_set_path);
}

std::vector<std::string> AllRecordLabels(const CellGrid& spec) {
  std::vector<std::string> labels;
  if (spec.synthetic_count > 0) {
    records::SynthOptions options;
    options.count = spec.synthetic_count;
    options.seed = spec.synthetic_seed;
    for (int i = 0; i < options.count; ++i) labels.push_back(records::SyntheticLabel(options, i));
    return labels;
  }
  const records::RecordSet set = LoadSpecRecordSet(spec);
  for (const records::RecordEntry& entry : set.records) {
    labels.push_back(records::RecordLabel(entry));
  }
  return labels;
}

bool KnownRecordUnits(std::string_view units) { return records::ParseUnits(units).has_value(); }

std::vector<double> BandEdges(const CellGrid& spec) {
  if (!spec.study_bands.empty()) return spec.study_bands;
  return {kDefaultBandEdges.begin(), kDefaultBandEdges.end()};
}

double BandOf(double ratio, std::span<const double> edges) {
  if (std::isnan(ratio)) return kNaN;
  return static_cast<double>(std::upper_bound(edges.begin(), edges.end(), ratio) - edges.begin());
}

CorrelationTable CorrelateOverRecords(const CellGrid& grid, std::span<const double> theta,
                                      std::span<const double> le, std::span<const double> band,
                                      std::span<const std::uint8_t> usable,
                                      std::size_t band_count) {
  CorrelationTable table;
  std::size_t record_dim = 0;
  for (std::size_t k = 0; k < grid.axes.size(); ++k) {
    if (grid.axes[k].key == "record") {
      record_dim = k;
    } else {
      table.axis_order.push_back(grid.axes[k].key);
      table.shape.push_back(grid.axes[k].Size());
    }
  }
  std::size_t combinations = 1;
  for (std::size_t n : table.shape) combinations *= n;
  table.bands = band.empty() ? 0 : band_count;

  // The cells of each combination, in record order.
  std::vector<std::vector<std::uint64_t>> members(combinations);
  for (std::uint64_t cell = 0; cell < usable.size(); ++cell) {
    const std::vector<std::size_t> index = grid.AxisIndex(cell);
    std::size_t g = 0;
    for (std::size_t k = 0; k < index.size(); ++k) {
      if (k != record_dim) g = g * grid.axes[k].Size() + index[k];
    }
    members[g].push_back(cell);
  }

  for (std::size_t g = 0; g < combinations; ++g) {
    std::vector<double> x;
    std::vector<double> y;
    std::vector<double> cell_band;
    for (std::uint64_t cell : members[g]) {
      if (usable[cell] == 0) continue;
      if (!std::isfinite(theta[cell]) || !std::isfinite(le[cell])) continue;
      x.push_back(le[cell]);
      y.push_back(theta[cell]);
      cell_band.push_back(band.empty() ? kNaN : band[cell]);
    }
    const Statistic pearson = Pearson(x, y);
    const Statistic spearman = Spearman(x, y);
    const LogLogFit fit = FitLogLog(x, y);
    table.n.push_back(static_cast<std::int64_t>(x.size()));
    table.pearson.push_back(pearson.value);
    table.spearman.push_back(spearman.value);
    table.loglog_n.push_back(static_cast<std::int64_t>(fit.n));
    table.loglog_slope.push_back(fit.slope.value);
    table.loglog_intercept.push_back(fit.intercept.value);
    table.loglog_r2.push_back(fit.r2.value);
    std::string reason;
    AddReason(reason, "pearson", pearson.reason);
    AddReason(reason, "spearman", spearman.reason);
    AddReason(reason, "loglog", fit.slope.reason.empty() ? fit.r2.reason : fit.slope.reason);
    table.reason.push_back(reason);

    for (std::size_t b = 0; b < table.bands; ++b) {
      std::vector<double> bx;
      std::vector<double> by;
      for (std::size_t i = 0; i < x.size(); ++i) {
        if (cell_band[i] == static_cast<double>(b)) {
          bx.push_back(x[i]);
          by.push_back(y[i]);
        }
      }
      const auto count = static_cast<std::int64_t>(bx.size());
      table.band_n.push_back(count);
      const bool enough = count >= kMinBandRecords;
      const LogLogFit band_fit = FitLogLog(bx, by);
      table.band_pearson.push_back(enough ? Pearson(bx, by).value : kNaN);
      table.band_spearman.push_back(enough ? Spearman(bx, by).value : kNaN);
      table.band_loglog_slope.push_back(enough ? band_fit.slope.value : kNaN);
      table.band_loglog_intercept.push_back(enough ? band_fit.intercept.value : kNaN);
      table.band_loglog_r2.push_back(enough ? band_fit.r2.value : kNaN);
    }
  }
  return table;
}

std::shared_ptr<const records::PeakPieces> RecordPeakCache::Get(
    const std::vector<SweepRecord>& records, const SweepRecord& record, double horizon_s) const {
  if (record.IsPair() || record.motion.npts() < 2) return nullptr;
  kept_.resize(records.size());
  std::shared_ptr<const records::PeakPieces>& kept =
      kept_[static_cast<std::size_t>(&record - records.data())];
  if (!kept || kept->ramp_horizon_s != horizon_s) {
    kept = std::make_shared<const records::PeakPieces>(
        records::FindPeakPieces(record.motion.acc_mps2, record.motion.dt_s, horizon_s));
  }
  return kept;
}

}  // namespace skewbridge::spectra
