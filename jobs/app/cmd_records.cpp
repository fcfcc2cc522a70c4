// `skewbridge records`: intensity measures of records and record sets, response spectra, and
// synthetic suites.
#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "jobs/app/commands.h"
#include "jobs/app/json_text.h"
#include "jobs/h5/h5_error.h"
#include "jobs/h5/spectrum_file.h"
#include "records/ground_motion.h"
#include "records/measures.h"
#include "records/record_set.h"
#include "records/synthetic.h"
#include "solver/common/error.h"
#include "solver/common/file_kind.h"
#include "solver/common/units.h"

namespace skewbridge::app {
namespace {

using records::GroundMotion;
using records::IntensityMeasures;

struct InfoArgs {
  std::string path;
  bool csv = false;
  bool json = false;
  bool dt_given = false;  ///< whether --dt was on the command line (0 is then refused)
  double dt_s = 0.0;
  std::string units;
  std::string format = "auto";
  int channel = 1;
  std::vector<std::string> periods;  ///< --periods: values or A:B:N (s)
  double xi = 0.05;                  ///< --xi
  double t1_s = 0.0;                 ///< --t1: Sa(T1) and AvgSa; 0 = not asked
  std::string pattern = "*";         ///< --pattern: the files of a folder that are records
  double max_pga_g = records::kMaxPlausiblePga_g;  ///< --max-pga-g (g)
};

struct Row {
  std::string label;
  GroundMotion motion;
  IntensityMeasures measures;
  int channel = 1;  ///< the CSMIP V2 channel read (meaningful for multi-channel files only)
  std::string set;  ///< the set (manifest or folder) the record came from, "" alone
  /// For a component of a pair: the pair's label; "" for a single record.
  std::string pair;
  int component = 0;  ///< 1 (H1) or 2 (H2) for a component of a pair, else 0
};

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

// The read options --dt, --units, --format and --channel give for a file that states none.
records::ReadOptions ReadOptionsOf(const InfoArgs& args, std::string_view command) {
  if (args.dt_given && !(args.dt_s > 0.0 && std::isfinite(args.dt_s))) {
    throw InputError::AtField(command, "--dt",
                              fmt::format("must be a time step > 0 s (got {})", args.dt_s));
  }
  records::ReadOptions options;
  if (args.dt_given) options.dt_s = args.dt_s;
  if (!args.units.empty()) {
    options.units = records::ParseUnits(args.units);
    if (!options.units) {
      throw InputError::AtField(
          command, "--units",
          "unknown units '" + args.units + "' (allowed: " + std::string(AllowedUnitsText()) + ")");
    }
  }
  const std::optional<records::Format> format = records::ParseFormat(args.format);
  if (!format) {
    throw InputError::AtField(command, "--format",
                              "unknown format '" + args.format +
                                  "' (allowed: auto, at2, esm, itsak, cosmos, csmip, smc, smtk, "
                                  "plain, time-acc)");
  }
  options.format = *format;
  options.channel = args.channel;
  if (!(args.max_pga_g > 0.0)) {
    throw InputError::AtField(command, "--max-pga-g", "must be > 0 g (or inf for no bound)");
  }
  options.max_pga_g = args.max_pga_g;
  return options;
}

// Appends the records of one path: a set manifest (.toml), a folder (every file in it, in byte
// order of the names, with the command's read options), or one record file; each measured.
void LoadPath(const std::string& text, const InfoArgs& args, std::string_view command,
              std::vector<Row>& rows) {
  const std::filesystem::path path(text);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw InputError::AtLine(text, 0,
                             "the file does not exist (give record files, folders of records or "
                             "record-set manifests .toml)");
  }
  if (path.extension() == ".toml") {
    if (args.dt_given || !args.units.empty() || args.format != "auto" ||
        args.max_pga_g != records::kMaxPlausiblePga_g) {
      throw InputError::AtField(command, "--dt/--units/--format/--max-pga-g",
                                "apply to a single file; give them per record in the set");
    }
    const records::RecordSet set = records::LoadRecordSet(path);
    for (const records::RecordEntry& entry : set.records) {
      // A pair gives a row per component, labelled "LABEL H1" and "LABEL H2".
      records::RecordComponents components = records::LoadComponents(entry);
      for (std::size_t k = 0; k < components.motions.size(); ++k) {
        const std::string label =
            records::RecordLabel(entry) + (components.IsPair() ? (k == 0 ? " H1" : " H2") : "");
        Row row{label, std::move(components.motions[k]), {}, entry.options.channel, set.name, "",
                0};
        if (components.IsPair()) {
          row.pair = records::RecordLabel(entry);
          row.component = static_cast<int>(k) + 1;
        }
        row.measures = records::ComputeMeasures(row.motion);
        rows.push_back(std::move(row));
      }
    }
    return;
  }
  if (std::filesystem::is_directory(path, ec)) {
    records::RecordEntry defaults;
    defaults.options = ReadOptionsOf(args, command);
    const records::RecordSet set = records::MakeFolderSet(
        path, args.pattern, defaults, {text, text, std::string(command) + " ", ""});
    const std::string name = path.lexically_normal().filename().empty()
                                 ? path.lexically_normal().parent_path().filename().string()
                                 : path.lexically_normal().filename().string();
    for (const records::RecordEntry& entry : set.records) {
      Row row{records::RecordLabel(entry),
              records::LoadRecord(entry),
              {},
              entry.options.channel,
              name,
              "",
              0};
      row.measures = records::ComputeMeasures(row.motion);
      rows.push_back(std::move(row));
    }
    return;
  }
  Row row{path.filename().string(),
          records::ReadRecord(path, ReadOptionsOf(args, command)),
          {},
          args.channel,
          "",
          "",
          0};
  row.measures = records::ComputeMeasures(row.motion);
  rows.push_back(std::move(row));
}

// What `records info` reads: a file that exists, not a folder.
void CheckInfoPath(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) {
    throw InputError::AtLine(path.string(), 0,
                             "the file does not exist (`records info` takes a record file or a "
                             "record-set manifest .toml)");
  }
  if (status.type() == std::filesystem::file_type::directory) {
    throw InputError::AtLine(path.string(), 0,
                             "is a folder; `records info` takes a record file or a record-set "
                             "manifest .toml (a folder of records is a set through a sweep's "
                             "[records] folder and pattern)");
  }
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (HasHdf5Signature(head)) {
    throw InputError::AtLine(path.string(), 0,
                             "this is an HDF5 file (a sweep cube or a run file), not a record; "
                             "`skewbridge inspect` summarises a cube");
  }
}

std::vector<Row> LoadRows(const InfoArgs& args) {
  std::vector<Row> rows;
  CheckInfoPath(args.path);
  LoadPath(args.path, args, "records info", rows);
  return rows;
}

// The periods of --periods: each token a period in s, or A:B:N for N periods from A to B
// spaced geometrically (values, not decades; N >= 2); sorted, duplicates removed.
std::vector<double> ParsePeriods(const std::vector<std::string>& tokens, std::string_view command) {
  auto number = [&](std::string_view t) {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v) || !(v > 0.0)) {
      throw InputError::AtField(command, "--periods",
                                "'" + std::string(t) +
                                    "' is not a period > 0 s (allowed: values in s, or A:B:N for "
                                    "N geometrically spaced periods from A to B)");
    }
    return v;
  };
  std::vector<double> periods;
  for (const std::string& token : tokens) {
    const std::size_t c1 = token.find(':');
    if (c1 == std::string::npos) {
      periods.push_back(number(token));
      continue;
    }
    const std::size_t c2 = token.find(':', c1 + 1);
    const std::string_view t(token);
    if (c2 == std::string::npos)
      throw InputError::AtField(command, "--periods", "'" + token + "': give A:B:N");
    const double a = number(t.substr(0, c1));
    const double b = number(t.substr(c1 + 1, c2 - c1 - 1));
    const double n_value = number(t.substr(c2 + 1));
    if (n_value != std::floor(n_value) || n_value < 2 || n_value > 100000 || !(a < b)) {
      throw InputError::AtField(
          command, "--periods",
          "'" + token + "': A:B:N needs A < B and N a whole number 2..100000");
    }
    const int n = static_cast<int>(n_value);
    for (int i = 0; i < n; ++i) {
      periods.push_back(i + 1 == n ? b : a * std::pow(b / a, static_cast<double>(i) / (n - 1)));
    }
  }
  std::sort(periods.begin(), periods.end());
  periods.erase(std::unique(periods.begin(), periods.end()), periods.end());
  return periods;
}

void RequireDamping(double xi, std::string_view command) {
  if (!(xi >= 0.0 && xi < 1.0)) {
    throw InputError::AtField(command, "--xi",
                              fmt::format("must be a damping ratio in [0, 1) (got {})", xi));
  }
}

// The spectral measures `records info` adds for --periods, --xi and --t1.
struct SpectralColumns {
  std::vector<double> periods_s;
  std::vector<records::ResponseSpectrum> spectra;  ///< per row
  std::vector<double> sa_t1_mps2;                  ///< per row, with --t1
  std::vector<double> avgsa_mps2;                  ///< per row, with --t1
};

SpectralColumns ComputeSpectralColumns(const InfoArgs& args, const std::vector<Row>& rows) {
  SpectralColumns out;
  RequireDamping(args.xi, "records info");
  out.periods_s = ParsePeriods(args.periods, "records info");
  const bool t1 = args.t1_s != 0.0;
  if (t1 && !(std::isfinite(args.t1_s) && args.t1_s > 0.0)) {
    throw InputError::AtField("records info", "--t1",
                              fmt::format("must be a period > 0 s (got {})", args.t1_s));
  }
  for (const Row& r : rows) {
    const std::span<const double> acc(r.motion.acc_mps2);
    out.spectra.push_back(
        records::ElasticResponseSpectrum(acc, r.motion.dt_s, out.periods_s, args.xi));
    if (t1) {
      const std::vector<double> one{args.t1_s};
      out.sa_t1_mps2.push_back(
          records::PseudoAccelerationSpectrum(acc, r.motion.dt_s, one, args.xi)[0]);
      out.avgsa_mps2.push_back(records::AverageSpectralAcceleration(
          acc, r.motion.dt_s, records::AvgSaPeriods(args.t1_s), args.xi));
    }
  }
  return out;
}

// "0.3" for a period in a column name.
std::string PeriodText(double t) { return fmt::format("{}", t); }

void PrintInfo(const InfoArgs& args) {
  const std::vector<Row> rows = LoadRows(args);
  const SpectralColumns sc = ComputeSpectralColumns(args, rows);
  const bool t1 = !sc.sa_t1_mps2.empty();
  for (const Row& row : rows) {
    for (const std::string& note : row.motion.notes) {
      std::fprintf(stderr, "skewbridge: note: %s\n", note.c_str());
    }
  }
  constexpr double g = records::kStandardGravity_mps2;
  if (args.json) {
    std::printf("[\n");
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      const IntensityMeasures& m = r.measures;
      std::string spectral;
      if (!sc.periods_s.empty() || t1) spectral += fmt::format(", \"xi\": {}", args.xi);
      if (!sc.periods_s.empty()) {
        spectral += ", \"spectrum\": [";
        for (std::size_t k = 0; k < sc.periods_s.size(); ++k) {
          const records::ResponseSpectrum& s = sc.spectra[i];
          spectral += fmt::format("{}{{\"T_s\": {}, \"sa_g\": {}, \"sv_mps\": {}, \"sd_m\": {}}}",
                                  k ? ", " : "", sc.periods_s[k], s.psa_mps2[k] / g, s.psv_mps[k],
                                  s.sd_m[k]);
        }
        spectral += "]";
      }
      if (t1) {
        spectral += fmt::format(", \"t1_s\": {}, \"sa_t1_g\": {}, \"avgsa_g\": {}", args.t1_s,
                                sc.sa_t1_mps2[i] / g, sc.avgsa_mps2[i] / g);
      }
      std::printf(
          "%s",
          fmt::format("  {{\"label\": {}, \"file\": {}, \"format\": {}, \"event\": {}, "
                      "\"station\": {}, \"component\": {}, \"units_in_file\": {}, "
                      "\"npts\": {}, \"dt_s\": {}, \"pga_g\": {}, \"pga_mps2\": {}, "
                      "\"pgv_mps\": {}, \"pgd_m\": {}, \"tm_s\": {}, \"omega_g_radps\": {}, "
                      "\"persistency_m\": {}, \"arias_mps\": {}, \"d5_95_s\": {}, "
                      "\"cav_mps\": {}{}}}{}\n",
                      JsonString(r.label), JsonString(r.motion.file), JsonString(r.motion.format),
                      JsonString(r.motion.event), JsonString(r.motion.station),
                      JsonString(r.motion.component), JsonString(r.motion.original_units),
                      r.motion.npts(), r.motion.dt_s, m.pga_mps2 / g, m.pga_mps2, m.pgv_mps,
                      m.pgd_m, m.mean_period_s, m.omega_g_radps, m.persistency_m, m.arias_mps,
                      m.significant_duration_s, m.cav_mps, spectral, i + 1 < rows.size() ? "," : "")
              .c_str());
    }
    std::printf("]\n");
    return;
  }
  if (args.csv) {
    std::string header =
        "label,file,format,npts,dt_s,pga_g,pgv_mps,pgd_m,tm_s,omega_g_radps,persistency_m,"
        "arias_mps,d5_95_s,cav_mps";
    for (const double t : sc.periods_s) {
      const std::string p = PeriodText(t);
      header += ",sa_" + p + "s_g,sv_" + p + "s_mps,sd_" + p + "s_m";
    }
    if (t1) header += ",sa_t1_g,avgsa_g";
    std::printf("%s\n", header.c_str());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      const IntensityMeasures& m = r.measures;
      std::string line =
          fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}", CsvField(r.label),
                      CsvField(r.motion.file), r.motion.format, r.motion.npts(), r.motion.dt_s,
                      m.pga_mps2 / g, m.pgv_mps, m.pgd_m, m.mean_period_s, m.omega_g_radps,
                      m.persistency_m, m.arias_mps, m.significant_duration_s, m.cav_mps);
      for (std::size_t k = 0; k < sc.periods_s.size(); ++k) {
        const records::ResponseSpectrum& s = sc.spectra[i];
        line += fmt::format(",{},{},{}", s.psa_mps2[k] / g, s.psv_mps[k], s.sd_m[k]);
      }
      if (t1) line += fmt::format(",{},{}", sc.sa_t1_mps2[i] / g, sc.avgsa_mps2[i] / g);
      std::printf("%s\n", line.c_str());
    }
    return;
  }
  // The label column is as wide as the longest label (up to 48): ESM labels start with
  // network.station.location.channel, which a fixed 36-character column cut off.
  std::size_t width = 6;
  for (const Row& r : rows) width = std::max(width, std::min<std::size_t>(r.label.size(), 48));
  std::string spectral_head;
  for (const double t : sc.periods_s) {
    spectral_head += fmt::format(" {:>9}", "Sa(" + PeriodText(t) + ")");
  }
  if (t1) spectral_head += fmt::format(" {:>9} {:>9}", "Sa(T1)", "AvgSa");
  std::printf("%s", fmt::format("{:<{}} {:<8} {:>7} {:>8} {:>7} {:>8} {:>8} {:>7} {:>8} {:>8} "
                                "{:>8} {:>7} {:>8}{}  {}\n",
                                "record", width, "format", "npts", "dt[s]", "PGA[g]", "PGV[m/s]",
                                "PGD[m]", "Tm[s]", "wg[r/s]", "Le[m]", "Ia[m/s]", "D5-95",
                                "CAV[m/s]", spectral_head, "channel / component")
                        .c_str());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const IntensityMeasures& m = r.measures;
    std::string label = r.label;
    if (label.size() > width) label = label.substr(0, width - 3) + "...";
    // A CSMIP V2 file holds several channels: say which one was read (--channel picks another).
    std::string channel = r.motion.format == "csmip" ? fmt::format("ch {}", r.channel) : "-";
    if (!r.motion.component.empty()) channel += " / " + r.motion.component;
    std::string spectral;
    for (std::size_t k = 0; k < sc.periods_s.size(); ++k) {
      spectral += fmt::format(" {:>9.4f}", sc.spectra[i].psa_mps2[k] / g);
    }
    if (t1) {
      spectral += fmt::format(" {:>9.4f} {:>9.4f}", sc.sa_t1_mps2[i] / g, sc.avgsa_mps2[i] / g);
    }
    std::printf("%s", fmt::format("{:<{}} {:<8} {:>7} {:>8.5g} {:>7.4f} {:>8.4f} {:>8.4f} "
                                  "{:>7.4f} {:>8.3f} {:>8.5f} {:>8.4f} {:>7.2f} {:>8.4f}{}  {}\n",
                                  label, width, r.motion.format, r.motion.npts(), r.motion.dt_s,
                                  m.pga_mps2 / g, m.pgv_mps, m.pgd_m, m.mean_period_s,
                                  m.omega_g_radps, m.persistency_m, m.arias_mps,
                                  m.significant_duration_s, m.cav_mps, spectral, channel)
                          .c_str());
  }
  if (!sc.periods_s.empty() || t1) {
    std::printf("%s",
                fmt::format("Sa(T): pseudo-acceleration in g at T in s, xi = {} [Nigam and "
                            "Jennings 1969]{}; CAV = int |a| dt [EPRI 1988]\n",
                            args.xi,
                            t1 ? fmt::format("; T1 = {} s, AvgSa over {} periods equally spaced "
                                             "in {}-{} T1 [Eads et al. 2015]",
                                             args.t1_s, records::kAvgSaPeriodCount,
                                             records::kAvgSaFromT1, records::kAvgSaToT1)
                               : "")
                    .c_str());
  }
}

// ", N pairs" for the summary line of `records spectrum`, "" without pairs.
std::string PairsText(std::size_t pairs) {
  return pairs == 0 ? "" : fmt::format("; {} pair(s): GM, RotD00, RotD50, RotD100", pairs);
}

struct SpectrumArgs {
  InfoArgs read;                   ///< --dt, --units, --format, --channel
  std::vector<std::string> paths;  ///< records, folders or sets
  std::vector<double> xi{0.05};
  std::string out;
};

// `records spectrum`: Sd, PSv, PSa of every record at every period and damping ratio, as CSV
// on stdout or in FILE.csv, or an HDF5 file for scripts/report.
void WriteSpectra(const SpectrumArgs& args, const std::string& command_line) {
  constexpr std::string_view kCommand = "records spectrum";
  const std::filesystem::path out(args.out);
  const std::string ext = out.extension().string();
  if (!args.out.empty() && ext != ".csv" && ext != ".h5") {
    throw InputError::AtField(kCommand, "--out", "'" + args.out + "' must end in .csv or .h5");
  }
  if (!args.out.empty()) {
    std::error_code ec;
    const std::filesystem::path folder = out.parent_path().empty() ? "." : out.parent_path();
    if (!std::filesystem::is_directory(folder, ec)) {
      throw InputError::AtField(kCommand, "--out", "no folder " + folder.string());
    }
    if (std::filesystem::is_directory(out, ec)) {
      throw InputError::AtField(kCommand, "--out", args.out + " is a folder");
    }
  }
  std::vector<double> xi = args.xi;
  for (const double x : xi) RequireDamping(x, kCommand);
  std::sort(xi.begin(), xi.end());
  xi.erase(std::unique(xi.begin(), xi.end()), xi.end());
  const std::vector<double> periods = ParsePeriods(
      args.read.periods.empty() ? std::vector<std::string>{"0.01:10:100"} : args.read.periods,
      kCommand);
  std::vector<Row> rows;
  for (const std::string& path : args.paths) LoadPath(path, args.read, kCommand, rows);
  for (const Row& row : rows) {
    for (const std::string& note : row.motion.notes) {
      std::fprintf(stderr, "skewbridge: note: %s\n", note.c_str());
    }
  }
  jobs::h5::SpectrumTable t;
  t.command = command_line;
  t.periods_s = periods;
  t.xi = xi;
  // A pair's measures [Boore 2010] from its two rows (H1 directly followed by H2).
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const Row& h1 = rows[i];
    const Row& h2 = rows[i + 1];
    if (h1.component != 1 || h2.component != 2 || h1.pair != h2.pair) continue;
    t.pair_label.push_back(h1.pair);
    t.pair_set.push_back(h1.set);
    for (const double x : xi) {
      const records::PairSpectrum s = records::PairResponseSpectrum(
          h1.motion.acc_mps2, h2.motion.acc_mps2, h1.motion.dt_s, periods, x);
      auto append = [](std::vector<double>& to, const std::vector<double>& from) {
        to.insert(to.end(), from.begin(), from.end());
      };
      append(t.sa_h1_mps2, s.sa_h1_mps2);
      append(t.sa_h2_mps2, s.sa_h2_mps2);
      append(t.gm_mps2, s.gm_mps2);
      append(t.rotd0_mps2, s.rotd0_mps2);
      append(t.rotd50_mps2, s.rotd50_mps2);
      append(t.rotd100_mps2, s.rotd100_mps2);
      append(t.rotd100_angle_deg, s.rotd100_angle_deg);
    }
  }
  for (const Row& r : rows) {
    t.label.push_back(r.label);
    t.file.push_back(r.motion.file);
    t.set.push_back(r.set);
    t.dt_s.push_back(r.motion.dt_s);
    t.pga_mps2.push_back(r.measures.pga_mps2);
    for (const double x : xi) {
      const records::ResponseSpectrum s =
          records::ElasticResponseSpectrum(r.motion.acc_mps2, r.motion.dt_s, periods, x);
      t.sd_m.insert(t.sd_m.end(), s.sd_m.begin(), s.sd_m.end());
      t.psv_mps.insert(t.psv_mps.end(), s.psv_mps.begin(), s.psv_mps.end());
      t.psa_mps2.insert(t.psa_mps2.end(), s.psa_mps2.begin(), s.psa_mps2.end());
    }
  }
  if (ext == ".h5") {
    try {
      jobs::h5::WriteSpectrumFile(out, t);
    } catch (const jobs::h5::H5Error& e) {
      throw InputError::AtField(kCommand, "--out", std::string("cannot write: ") + e.what());
    }
    std::printf("%s", fmt::format("wrote {} spectra ({} records x {} damping ratios, {} periods{}) "
                                  "to {}\n",
                                  rows.size() * xi.size(), rows.size(), xi.size(), periods.size(),
                                  PairsText(t.pair_label.size()), args.out)
                          .c_str());
    return;
  }
  // With a pair among the records, a column names the measure of each line (H1, H2 of a pair's
  // components; GM, RotD00, RotD50, RotD100 of the pair, with RotD100's angle); without, the
  // table is that of single records.
  const bool with_pairs = !t.pair_label.empty();
  std::string text = with_pairs ? "label,set,measure,xi,T_s,Sd_m,PSv_mps,PSa_mps2,PSa_g,angle_deg\n"
                                : "label,set,xi,T_s,Sd_m,PSv_mps,PSa_mps2,PSa_g\n";
  // One line of the table with pairs; a pair measure's Sd and PSv are PSa / w^2 and PSa / w.
  auto line = [&text](const std::string& label, const std::string& set, std::string_view measure,
                      double x, double period, std::optional<double> sd, double psa,
                      std::optional<double> angle) {
    const double w = 2.0 * std::numbers::pi / period;
    const double d = sd.value_or(psa / (w * w));
    text +=
        fmt::format("{},{},{},{},{},{},{},{},{},{}\n", CsvField(label), CsvField(set), measure, x,
                    period, d, sd ? w * d : psa / w, psa, psa / records::kStandardGravity_mps2,
                    angle ? fmt::format("{}", *angle) : std::string());
  };
  std::size_t k = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::string measure =
        rows[r].component == 0 ? "Sa" : (rows[r].component == 1 ? "H1" : "H2");
    for (const double x : xi) {
      for (const double p : periods) {
        if (with_pairs) {
          line(rows[r].component == 0 ? t.label[r] : rows[r].pair, t.set[r], measure, x, p,
               t.sd_m[k], t.psa_mps2[k], std::nullopt);
        } else {
          text += fmt::format("{},{},{},{},{},{},{},{}\n", CsvField(t.label[r]), CsvField(t.set[r]),
                              x, p, t.sd_m[k], t.psv_mps[k], t.psa_mps2[k],
                              t.psa_mps2[k] / records::kStandardGravity_mps2);
        }
        ++k;
      }
    }
  }
  k = 0;
  for (std::size_t q = 0; q < t.pair_label.size(); ++q) {
    for (const double x : xi) {
      for (const double p : periods) {
        line(t.pair_label[q], t.pair_set[q], "GM", x, p, std::nullopt, t.gm_mps2[k], std::nullopt);
        line(t.pair_label[q], t.pair_set[q], "RotD00", x, p, std::nullopt, t.rotd0_mps2[k],
             std::nullopt);
        line(t.pair_label[q], t.pair_set[q], "RotD50", x, p, std::nullopt, t.rotd50_mps2[k],
             std::nullopt);
        line(t.pair_label[q], t.pair_set[q], "RotD100", x, p, std::nullopt, t.rotd100_mps2[k],
             t.rotd100_angle_deg[k]);
        ++k;
      }
    }
  }
  if (args.out.empty()) {
    std::printf("%s", text.c_str());
    return;
  }
  // Written whole to FILE.tmp, then renamed: never a partial file under the name.
  const std::string tmp = args.out + ".tmp";
  {
    std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
    file << text;
    file.flush();
    if (!file) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw InputError::AtField(kCommand, "--out", "cannot write " + tmp);
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, out, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError::AtField(kCommand, "--out", "cannot write " + args.out + ": " + ec.message());
  }
  std::printf("%s", fmt::format("wrote {} spectra ({} records x {} damping ratios, {} periods{}) "
                                "to {}\n",
                                rows.size() * xi.size(), rows.size(), xi.size(), periods.size(),
                                PairsText(t.pair_label.size()), args.out)
                        .c_str());
}

}  // namespace

void AddRecordsCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "records", "Ground motions: intensity measures of records, synthetic suites");
  cmd->require_subcommand(1);

  auto info = std::make_shared<InfoArgs>();
  CLI::App* info_cmd = cmd->add_subcommand(
      "info",
      "Print PGA, PGV, PGD, T_m, w_g, L_e, Arias, D5-95, CAV (and Sa at --periods, Sa(T1) and "
      "AvgSa with --t1) of a record or a set (.toml)");
  info_cmd->add_option("path", info->path, "record file, or record-set manifest (.toml)")
      ->required();
  auto* csv = info_cmd->add_flag("--csv", info->csv, "comma-separated output");
  info_cmd->add_flag("--json", info->json, "JSON output")->excludes(csv);
  CLI::Option* dt = info_cmd->add_option("--dt", info->dt_s, "time step (s) of a headerless file");
  info_cmd->add_option(
      "--units", info->units,
      "units where the file states none: g, m/s^2 (m/s2, mps2), cm/s^2 (gal, cmps2)");
  info_cmd->add_option("--format", info->format,
                       "auto, at2, esm, itsak, cosmos, csmip, smc, smtk, plain, time-acc");
  info_cmd->add_option("--channel", info->channel, "CSMIP V2 channel (1-based)");
  info_cmd
      ->add_option("--periods", info->periods,
                   "periods (s) for Sa, Sv, Sd: values, or A:B:N for N periods from A to B "
                   "spaced geometrically")
      ->delimiter(',');
  info_cmd->add_option("--xi", info->xi, "damping ratio of the spectra")->capture_default_str();
  info_cmd->add_option("--t1", info->t1_s,
                       "fundamental period T1 (s): adds Sa(T1) and AvgSa over 0.2-3 T1");
  info_cmd->add_option("--max-pga-g", info->max_pga_g,
                       "refuse a PGA above this (g; default 10, inf: no bound)");
  info_cmd->callback([info, dt] {
    info->dt_given = dt->count() > 0;
    PrintInfo(*info);
  });

  auto spectrum = std::make_shared<SpectrumArgs>();
  CLI::App* spectrum_cmd = cmd->add_subcommand(
      "spectrum", "Elastic response spectra (Sd, PSv, PSa) of records, folders or sets");
  spectrum_cmd->add_option("records", spectrum->paths, "record files, folders or sets (.toml)")
      ->required();
  spectrum_cmd
      ->add_option("--periods", spectrum->read.periods,
                   "periods (s): values, or A:B:N for N periods from A to B spaced geometrically "
                   "(default 0.01:10:100)")
      ->delimiter(',');
  spectrum_cmd->add_option("--xi", spectrum->xi, "damping ratios (default 0.05)")->delimiter(',');
  spectrum_cmd->add_option("--out", spectrum->out,
                           "FILE.csv or FILE.h5 (default: CSV on standard output)");
  CLI::Option* spectrum_dt =
      spectrum_cmd->add_option("--dt", spectrum->read.dt_s, "time step (s) of headerless files");
  spectrum_cmd->add_option("--units", spectrum->read.units,
                           "units where a file states none: g, m/s2, cm/s2");
  spectrum_cmd->add_option("--format", spectrum->read.format,
                           "auto, at2, esm, itsak, cosmos, csmip, smc, smtk, plain, time-acc");
  spectrum_cmd->add_option("--channel", spectrum->read.channel, "CSMIP V2 channel (1-based)");
  spectrum_cmd
      ->add_option("--pattern", spectrum->read.pattern,
                   "file-name glob of the records in a folder (*, ?, [...])")
      ->capture_default_str();
  spectrum_cmd->callback([spectrum, spectrum_dt] {
    spectrum->read.dt_given = spectrum_dt->count() > 0;
    std::string line = "skewbridge records spectrum";
    for (const std::string& p : spectrum->paths) line += " " + p;
    for (const std::string& p : spectrum->read.periods) line += " --periods " + p;
    for (const double x : spectrum->xi) line += fmt::format(" --xi {}", x);
    WriteSpectra(*spectrum, line);
  });

  auto synth = std::make_shared<records::SynthOptions>();
  auto out = std::make_shared<std::string>();
  CLI::App* synth_cmd = cmd->add_subcommand(
      "synth", "Write a seeded suite of synthetic accelerograms (.AT2) and its set.toml");
  synth_cmd->add_option("--count", synth->count, "number of records")->required();
  synth_cmd->add_option("--seed", synth->seed, "seed of the suite")->required();
  synth_cmd->add_option("--out", *out, "output folder")->required();
  synth_cmd->add_option("--pga-min-g", synth->pga_min_g, "lowest PGA (g)")->capture_default_str();
  synth_cmd->add_option("--pga-max-g", synth->pga_max_g, "highest PGA (g)")->capture_default_str();
  synth_cmd->add_option("--tm-min-s", synth->tm_min_s, "lowest T_m (s)")->capture_default_str();
  synth_cmd->add_option("--tm-max-s", synth->tm_max_s, "highest T_m (s)")->capture_default_str();
  synth_cmd->add_option("--duration-s", synth->duration_s, "record length (s)")
      ->capture_default_str();
  synth_cmd->add_option("--dt-s", synth->dt_s, "time step (s)")->capture_default_str();
  synth_cmd->callback([synth, out] {
    const auto start = std::chrono::steady_clock::now();
    const std::filesystem::path manifest = records::WriteSuite(*out, *synth);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s", fmt::format("wrote {} records and {} in {:.2f} s\n", synth->count,
                                  manifest.string(), seconds)
                          .c_str());
  });
}

}  // namespace skewbridge::app
