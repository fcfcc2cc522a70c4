// `skewbridge records`: intensity measures of records and record sets, and synthetic suites.
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "jobs/app/commands.h"
#include "records/ground_motion.h"
#include "records/measures.h"
#include "records/record_set.h"
#include "records/synthetic.h"
#include "solver/common/error.h"

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
};

struct Row {
  std::string label;
  GroundMotion motion;
  IntensityMeasures measures;
  int channel = 1;  ///< the CSMIP V2 channel read (meaningful for multi-channel files only)
};

std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<int>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
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
}

std::vector<Row> LoadRows(const InfoArgs& args) {
  std::vector<Row> rows;
  const std::filesystem::path path(args.path);
  CheckInfoPath(path);
  if (args.dt_given && !(args.dt_s > 0.0 && std::isfinite(args.dt_s))) {
    throw InputError::AtField("records info", "--dt",
                              fmt::format("must be a time step > 0 s (got {})", args.dt_s));
  }
  if (path.extension() == ".toml") {
    if (args.dt_given || !args.units.empty() || args.format != "auto") {
      throw InputError::AtField("records info", "--dt/--units/--format",
                                "apply to a single file; give them per record in the set");
    }
    const records::RecordSet set = records::LoadRecordSet(path);
    for (const records::RecordEntry& entry : set.records) {
      Row row{records::RecordLabel(entry), records::LoadRecord(entry), {}, entry.options.channel};
      row.measures = records::ComputeMeasures(row.motion);
      rows.push_back(std::move(row));
    }
    return rows;
  }
  records::ReadOptions options;
  if (args.dt_given) options.dt_s = args.dt_s;
  if (!args.units.empty()) {
    options.units = records::ParseUnits(args.units);
    if (!options.units) {
      throw InputError::AtField("records info", "--units",
                                "unknown units '" + args.units + "' (allowed: g, m/s2, cm/s2)");
    }
  }
  const std::optional<records::Format> format = records::ParseFormat(args.format);
  if (!format) {
    throw InputError::AtField("records info", "--format",
                              "unknown format '" + args.format +
                                  "' (allowed: auto, at2, esm, itsak, cosmos, csmip, smc, smtk, "
                                  "plain, time-acc)");
  }
  options.format = *format;
  options.channel = args.channel;
  Row row{path.filename().string(), records::ReadRecord(path, options), {}, args.channel};
  row.measures = records::ComputeMeasures(row.motion);
  rows.push_back(std::move(row));
  return rows;
}

void PrintInfo(const InfoArgs& args) {
  const std::vector<Row> rows = LoadRows(args);
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
      std::printf(
          "%s",
          fmt::format("  {{\"label\": {}, \"file\": {}, \"format\": {}, \"event\": {}, "
                      "\"station\": {}, \"component\": {}, \"units_in_file\": {}, "
                      "\"npts\": {}, \"dt_s\": {}, \"pga_g\": {}, \"pga_mps2\": {}, "
                      "\"pgv_mps\": {}, \"pgd_m\": {}, \"tm_s\": {}, \"omega_g_radps\": {}, "
                      "\"persistency_m\": {}, \"arias_mps\": {}, \"d5_95_s\": {}}}{}\n",
                      JsonString(r.label), JsonString(r.motion.file), JsonString(r.motion.format),
                      JsonString(r.motion.event), JsonString(r.motion.station),
                      JsonString(r.motion.component), JsonString(r.motion.original_units),
                      r.motion.npts(), r.motion.dt_s, m.pga_mps2 / g, m.pga_mps2, m.pgv_mps,
                      m.pgd_m, m.mean_period_s, m.omega_g_radps, m.persistency_m, m.arias_mps,
                      m.significant_duration_s, i + 1 < rows.size() ? "," : "")
              .c_str());
    }
    std::printf("]\n");
    return;
  }
  if (args.csv) {
    std::printf(
        "label,file,format,npts,dt_s,pga_g,pgv_mps,pgd_m,tm_s,omega_g_radps,persistency_m,"
        "arias_mps,d5_95_s\n");
    for (const Row& r : rows) {
      const IntensityMeasures& m = r.measures;
      std::printf(
          "%s", fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", CsvField(r.label),
                            CsvField(r.motion.file), r.motion.format, r.motion.npts(),
                            r.motion.dt_s, m.pga_mps2 / g, m.pgv_mps, m.pgd_m, m.mean_period_s,
                            m.omega_g_radps, m.persistency_m, m.arias_mps, m.significant_duration_s)
                    .c_str());
    }
    return;
  }
  // The label column is as wide as the longest label (up to 48): ESM labels start with
  // network.station.location.channel, which a fixed 36-character column cut off.
  std::size_t width = 6;
  for (const Row& r : rows) width = std::max(width, std::min<std::size_t>(r.label.size(), 48));
  std::printf(
      "%s", fmt::format("{:<{}} {:<8} {:>7} {:>8} {:>7} {:>8} {:>8} {:>7} {:>8} {:>8} "
                        "{:>8} {:>7}  {}\n",
                        "record", width, "format", "npts", "dt[s]", "PGA[g]", "PGV[m/s]", "PGD[m]",
                        "Tm[s]", "wg[r/s]", "Le[m]", "Ia[m/s]", "D5-95", "channel / component")
                .c_str());
  for (const Row& r : rows) {
    const IntensityMeasures& m = r.measures;
    std::string label = r.label;
    if (label.size() > width) label = label.substr(0, width - 3) + "...";
    // A CSMIP V2 file holds several channels: say which one was read (--channel picks another).
    std::string channel = r.motion.format == "csmip" ? fmt::format("ch {}", r.channel) : "-";
    if (!r.motion.component.empty()) channel += " / " + r.motion.component;
    std::printf("%s",
                fmt::format("{:<{}} {:<8} {:>7} {:>8.5g} {:>7.4f} {:>8.4f} {:>8.4f} "
                            "{:>7.4f} {:>8.3f} {:>8.5f} {:>8.4f} {:>7.2f}  {}\n",
                            label, width, r.motion.format, r.motion.npts(), r.motion.dt_s,
                            m.pga_mps2 / g, m.pgv_mps, m.pgd_m, m.mean_period_s, m.omega_g_radps,
                            m.persistency_m, m.arias_mps, m.significant_duration_s, channel)
                    .c_str());
  }
}

}  // namespace

void AddRecordsCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "records", "Ground motions: intensity measures of records, synthetic suites");
  cmd->require_subcommand(1);

  auto info = std::make_shared<InfoArgs>();
  CLI::App* info_cmd = cmd->add_subcommand(
      "info", "Print PGA, PGV, PGD, T_m, w_g, L_e, Arias and D5-95 of a record or a set (.toml)");
  info_cmd->add_option("path", info->path, "record file, or record-set manifest (.toml)")
      ->required();
  auto* csv = info_cmd->add_flag("--csv", info->csv, "comma-separated output");
  info_cmd->add_flag("--json", info->json, "JSON output")->excludes(csv);
  CLI::Option* dt = info_cmd->add_option("--dt", info->dt_s, "time step (s) of a headerless file");
  info_cmd->add_option("--units", info->units, "units where the file states none: g, m/s2, cm/s2");
  info_cmd->add_option("--format", info->format,
                       "auto, at2, esm, itsak, cosmos, csmip, smc, smtk, plain, time-acc");
  info_cmd->add_option("--channel", info->channel, "CSMIP V2 channel (1-based)");
  info_cmd->callback([info, dt] {
    info->dt_given = dt->count() > 0;
    PrintInfo(*info);
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
