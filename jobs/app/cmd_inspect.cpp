#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jobs/app/commands.h"
#include "jobs/h5/cube_file.h"
#include "jobs/h5/risk_file.h"
#include "jobs/sweep_spec.h"
#include "solver/common/error.h"

namespace skewbridge::app {
namespace {

std::string AxisRange(const jobs::h5::AxisSummary& axis) {
  if (!axis.labels.empty()) {
    std::string out;
    for (std::size_t i = 0; i < axis.labels.size() && i < 6; ++i) {
      out += (i ? ", " : "") + axis.labels[i];
    }
    return axis.labels.size() > 6 ? out + ", ..." : out;
  }
  if (axis.values.empty()) {
    return "";
  }
  return fmt::format("{:g} .. {:g}", axis.values.front(), axis.values.back());
}

// A numeric dataset of a sweep group, or nothing when the group does not hold it (the record
// table and the statistics exist only in final cubes of record-driven sweeps).
std::optional<std::vector<double>> ReadIfPresent(const std::string& path, const std::string& sweep,
                                                 const std::string& dataset) {
  try {
    return jobs::h5::ReadSweepArray(path, sweep, dataset);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// A string dataset of a sweep group (one entry per combination), or nothing when absent.
std::vector<std::string> ReadStringsIfPresent(const std::string& path, const std::string& sweep,
                                              const std::string& dataset) {
  try {
    return jobs::h5::ReadSweepStrings(path, sweep, dataset);
  } catch (const InputError&) {
    return {};
  }
}

// Why a combination has no fit: its stored reason (fragility/<ls>/reason).
std::string NoFitReason(const std::vector<std::string>& reasons, std::size_t row) {
  if (row < reasons.size() && !reasons[row].empty()) return reasons[row];
  return "no reason stored";
}

// Coordinate k of an axis as printed: the label, or the number to 6 digits.
std::string Coordinate(const jobs::h5::AxisSummary& axis, std::size_t k) {
  if (!axis.labels.empty()) {
    return axis.labels[k];
  }
  return fmt::format("{:g}", axis.values[k]);
}

// The record table's size and the theta_m-L_e statistics of correlation/ (docs/hdf5-layout.md),
// one row per combination of the axes other than record (for the study: per Pi_delta).
void PrintRecordStudy(const std::string& path, const jobs::h5::SweepSummary& s) {
  bool has_record_axis = false;
  std::vector<const jobs::h5::AxisSummary*> others;
  for (const jobs::h5::AxisSummary& a : s.axes) {
    if (a.name == "record") {
      has_record_axis = true;
    } else {
      others.push_back(&a);
    }
  }
  const std::optional<std::vector<double>> l_e = ReadIfPresent(path, s.name, "records/L_e_m");
  if (!l_e) {
    if (has_record_axis) {
      std::printf("  record table: none (written into the final cube only)\n");
    }
    return;
  }
  std::printf("  record table: %zu record(s) (records/)\n", l_e->size());
  const std::vector<std::string> columns = {"n",        "pearson_theta_Le", "spearman_theta_Le",
                                            "loglog_n", "loglog_slope",     "loglog_intercept",
                                            "loglog_r2"};
  std::vector<std::vector<double>> values;
  for (const std::string& c : columns) {
    std::optional<std::vector<double>> v = ReadIfPresent(path, s.name, "correlation/" + c);
    if (!v) {
      return;  // a record axis without Pi_delta: the table and no statistics
    }
    values.push_back(std::move(*v));
  }
  std::string row_label;
  for (const jobs::h5::AxisSummary* a : others) {
    row_label += (row_label.empty() ? "" : ",") + a->name;
  }
  std::printf("  correlation of theta_m with L_e over the records (correlation/), per %s:\n",
              row_label.c_str());
  std::printf("    %-22s %6s %12s %12s %8s %12s %12s %12s\n", row_label.c_str(), "n", "pearson",
              "spearman", "loglog_n", "slope", "intercept", "r2");
  const std::size_t rows = values.front().size();
  for (std::size_t k = 0; k < rows; ++k) {
    // Row-major over the remaining axes, the last one fastest.
    std::string label;
    std::size_t rest = k;
    for (std::size_t j = others.size(); j-- > 0;) {
      const std::size_t n = others[j]->size;
      label = Coordinate(*others[j], rest % n) + (label.empty() ? "" : "," + label);
      rest /= n;
    }
    std::printf("    %-22s %6.0f %12.6g %12.6g %8.0f %12.6g %12.6g %12.6g\n", label.c_str(),
                values[0][k], values[1][k], values[2][k], values[3][k], values[4][k], values[5][k],
                values[6][k]);
  }
}

// A unit as printed after a value: nothing for dimensionless numbers and labels, the degree
// sign for the skew angle, else the unit in brackets.
std::string UnitSuffix(const std::string& unit) {
  if (unit.empty() || unit == "1" || unit == "-") {
    return "";
  }
  return " " + unit;
}

// The [fixed] parameters of the sweep with their units and the parameter table's meaning;
// a parameter on no axis and not fixed takes the family's default (docs/sweep-format.md).
void PrintFixed(const jobs::h5::SweepSummary& s) {
  if (s.fixed.empty()) {
    std::printf("  fixed: none (parameters on no axis take the family's defaults)\n");
    return;
  }
  std::printf("  fixed (parameters on no axis and not listed take the family's defaults):\n");
  for (const jobs::h5::FixedSummary& f : s.fixed) {
    const std::string value =
        f.is_label ? f.label : fmt::format("{:g}{}", f.value, UnitSuffix(f.unit));
    const jobs::ParameterInfo* info = jobs::FindParameter(f.key);
    std::printf("    %-14s %-16s %s\n", f.key.c_str(), value.c_str(),
                info != nullptr ? std::string(info->description).c_str() : "");
  }
}

// "records.max_scale = X" as the sweep's canonical text holds it, or "records.max_scale".
std::string MaxScaleText(const jobs::h5::SweepSummary& s) {
  const std::string key = "records.max_scale = ";
  const std::size_t at = s.spec_canonical.find(key);
  if (at == std::string::npos) return "records.max_scale";
  const std::size_t end = s.spec_canonical.find('\n', at);
  return s.spec_canonical.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

// Whether the sweep group holds member `name`.
bool Has(const jobs::h5::SweepSummary& s, const std::string& name) {
  return std::find(s.children.begin(), s.children.end(), name) != s.children.end();
}

// The responses over the incidence angle (over_incidence/: max, median and angle_of_max_deg of
// each response over the incidence_deg axis, on the grid without it): the angles and, per limit
// state of `names`, the cells exceeding it at some angle and at every angle, the largest demand
// and the angle that most often gives it.
void PrintOverIncidence(const std::string& path, const jobs::h5::SweepSummary& s,
                        const std::vector<std::string>& names) {
  if (!Has(s, "over_incidence")) return;
  std::string angles, rest_label;
  for (const jobs::h5::AxisSummary& a : s.axes) {
    if (a.name == "incidence_deg") {
      angles = fmt::format("{} angles, {}", a.size, AxisRange(a));
    } else {
      rest_label += (rest_label.empty() ? "" : ",") + a.name;
    }
  }
  std::printf(
      "  over the incidence angle (over_incidence/: max, median, angle_of_max_deg of each "
      "response over incidence_deg, %s deg), per %s\n",
      angles.c_str(), rest_label.c_str());
  for (const std::string& name : names) {
    const std::string ls = "ls_" + name;
    const auto some = ReadIfPresent(path, s.name, "over_incidence/max/" + ls);
    const auto median = ReadIfPresent(path, s.name, "over_incidence/median/" + ls);
    const auto demand = ReadIfPresent(path, s.name, "over_incidence/max/" + ls + "_demand");
    const auto at =
        ReadIfPresent(path, s.name, "over_incidence/angle_of_max_deg/" + ls + "_demand");
    if (!some || !median || !demand || !at) {
      std::printf("    %-18s (not reduced)\n", name.c_str());
      continue;
    }
    std::size_t with_value = 0, at_some = 0, at_half = 0;
    for (std::size_t c = 0; c < some->size(); ++c) {
      if (!std::isfinite((*some)[c])) continue;
      ++with_value;
      at_some += (*some)[c] == 1.0 ? 1 : 0;
      at_half += (*median)[c] >= 0.5 ? 1 : 0;
    }
    double largest = -std::numeric_limits<double>::infinity();
    std::map<double, std::size_t> governs;  // angle of the largest demand -> cells
    for (std::size_t c = 0; c < demand->size(); ++c) {
      if (std::isnan((*demand)[c]) || std::isnan((*at)[c])) continue;
      largest = std::max(largest, (*demand)[c]);
      // A zero demand at every angle has no governing angle.
      if ((*demand)[c] > 0.0) ++governs[(*at)[c]];
    }
    std::string mode = "-";
    std::size_t mode_count = 0, positive = 0;
    for (const auto& [angle, count] : governs) {
      positive += count;
      if (count > mode_count) {
        mode_count = count;
        mode = fmt::format("{:g}", angle);
      }
    }
    std::printf(
        "    %-18s exceeded at some angle in %zu of %zu cells, at half the angles or more in "
        "%zu; largest demand %s; its angle most often %s deg (%zu of %zu cells with a "
        "demand)\n",
        name.c_str(), at_some, with_value, at_half,
        largest > -std::numeric_limits<double>::infinity() ? fmt::format("{:.6g}", largest).c_str()
                                                           : "-",
        mode.c_str(), mode_count, positive);
  }
}

// The fit axes less the incidence angle: the axes of the worst-angle fits.
std::vector<const jobs::h5::AxisSummary*> WithoutIncidence(
    const std::vector<const jobs::h5::AxisSummary*>& axes) {
  std::vector<const jobs::h5::AxisSummary*> rest;
  for (const jobs::h5::AxisSummary* a : axes) {
    if (a->name != "incidence_deg") rest.push_back(a);
  }
  return rest;
}

// The axes' names joined by commas, "sweep" when there is none (one fit for the sweep).
std::string AxisNames(const std::vector<const jobs::h5::AxisSummary*>& axes) {
  std::string names;
  for (const jobs::h5::AxisSummary* a : axes) names += (names.empty() ? "" : ",") + a->name;
  return names.empty() ? "sweep" : names;
}

// The IDA fits of group `group` (fragility/ or fragility_worst_incidence/), one row per limit
// state and combination of `others` (row-major, the last one fastest).
void PrintIdaFits(const std::string& path, const jobs::h5::SweepSummary& s,
                  const std::vector<std::string>& names, const std::string& group,
                  const std::vector<const jobs::h5::AxisSummary*>& others) {
  std::string row_label;
  for (const jobs::h5::AxisSummary* a : others) {
    row_label += (row_label.empty() ? "" : ",") + a->name;
  }
  std::printf("    %-18s %-22s %8s %9s %9s %12s %10s\n", "limit state",
              row_label.empty() ? "-" : row_label.c_str(), "records", "censored", "too_far",
              "theta", "beta");
  for (const std::string& name : names) {
    const std::string g = group + "/" + name + "/";
    const auto theta = ReadIfPresent(path, s.name, g + "theta");
    const auto beta = ReadIfPresent(path, s.name, g + "beta");
    const auto n = ReadIfPresent(path, s.name, g + "n_records");
    const auto censored = ReadIfPresent(path, s.name, g + "n_censored");
    // Capacities beyond records.max_scale (absent from cubes written before it was stored).
    const auto too_far = ReadIfPresent(path, s.name, g + "n_scaled_too_far");
    if (!theta || !beta || !n || !censored) {
      std::printf("    %-18s (not fitted)\n", name.c_str());
      continue;
    }
    const std::vector<std::string> reasons = ReadStringsIfPresent(path, s.name, g + "reason");
    for (std::size_t row = 0; row < theta->size(); ++row) {
      std::string label;
      std::size_t rest = row;
      for (std::size_t j = others.size(); j-- > 0;) {
        const std::size_t size = others[j]->size;
        label = Coordinate(*others[j], rest % size) + (label.empty() ? "" : "," + label);
        rest /= size;
      }
      if (label.empty()) label = "-";
      if (!std::isfinite((*theta)[row])) {
        std::printf("    %-18s %-22s %8.0f %9.0f %9.0f  no fit: %s\n", name.c_str(), label.c_str(),
                    (*n)[row], (*censored)[row], too_far ? (*too_far)[row] : 0.0,
                    NoFitReason(reasons, row).c_str());
        continue;
      }
      std::printf("    %-18s %-22s %8.0f %9.0f %9.0f %12.6g %10.6g\n", name.c_str(), label.c_str(),
                  (*n)[row], (*censored)[row], too_far ? (*too_far)[row] : 0.0, (*theta)[row],
                  (*beta)[row]);
    }
  }
}

// The stripe fits of group `group` (fragility/ or fragility_worst_incidence/), one row per
// limit state and combination of `others` (row-major, the last one fastest); `excluding`: a
// column of the cells left out beyond records.max_scale.
void PrintStripeFits(const std::string& path, const jobs::h5::SweepSummary& s,
                     const std::vector<std::string>& names, const std::string& group,
                     const std::vector<const jobs::h5::AxisSummary*>& others, bool excluding) {
  std::string row_label;
  for (const jobs::h5::AxisSummary* a : others) {
    row_label += (row_label.empty() ? "" : ",") + a->name;
  }
  std::printf("    %-18s %-22s %8s %9s %12s %10s %12s %12s%s\n", "limit state",
              row_label.empty() ? "-" : row_label.c_str(), "cells", "exceeded", "theta", "beta",
              "theta_lo", "theta_hi", excluding ? "     excluded" : "");
  for (const std::string& name : names) {
    const std::string g = group + "/" + name + "/";
    const std::optional<std::vector<double>> theta = ReadIfPresent(path, s.name, g + "theta");
    const std::optional<std::vector<double>> beta = ReadIfPresent(path, s.name, g + "beta");
    const std::optional<std::vector<double>> n = ReadIfPresent(path, s.name, g + "n_cells");
    const std::optional<std::vector<double>> k = ReadIfPresent(path, s.name, g + "n_exceeded");
    const std::optional<std::vector<double>> lo = ReadIfPresent(path, s.name, g + "theta_lo");
    const std::optional<std::vector<double>> hi = ReadIfPresent(path, s.name, g + "theta_hi");
    if (!theta || !beta || !n || !k || !lo || !hi) {
      std::printf("    %-18s (not fitted)\n", name.c_str());
      continue;
    }
    const std::vector<std::string> reasons = ReadStringsIfPresent(path, s.name, g + "reason");
    const std::optional<std::vector<double>> excluded =
        ReadIfPresent(path, s.name, g + "n_excluded_beyond_max_scale");
    std::size_t combinations = 1;
    for (const jobs::h5::AxisSummary* a : others) combinations *= a->size;
    for (std::size_t row = 0; row < theta->size(); ++row) {
      std::string label = "-";
      if (!others.empty() && theta->size() == combinations) {
        label.clear();
        std::size_t rest = row;
        for (std::size_t j = others.size(); j-- > 0;) {
          const std::size_t size = others[j]->size;
          label = Coordinate(*others[j], rest % size) + (label.empty() ? "" : "," + label);
          rest /= size;
        }
      }
      const std::string left_out =
          excluded ? fmt::format("{:13.0f}", (*excluded)[row]) : std::string();
      if (!std::isfinite((*theta)[row])) {
        std::printf("    %-18s %-22s %8.0f %9.0f  no fit%s: %s\n", name.c_str(), label.c_str(),
                    (*n)[row], (*k)[row],
                    excluded ? fmt::format(" ({:.0f} excluded)", (*excluded)[row]).c_str() : "",
                    NoFitReason(reasons, row).c_str());
        continue;
      }
      std::printf("    %-18s %-22s %8.0f %9.0f %12.6g %10.6g %12.6g %12.6g%s\n", name.c_str(),
                  label.c_str(), (*n)[row], (*k)[row], (*theta)[row], (*beta)[row], (*lo)[row],
                  (*hi)[row], left_out.c_str());
    }
  }
}

// The limit states of an IDA sweep ([ida], docs/sweep-format.md): per limit state the records
// whose search reached it and the range of their capacities, then, in a final cube, the
// lognormal fit of the capacities (fragility/<name>/: theta, beta, records, censored) per
// combination of the axes other than record. False when the cube holds no IDA capacities.
bool PrintIdaLimitStates(const std::string& path, const jobs::h5::SweepSummary& s) {
  std::vector<std::string> names;
  std::string unit;
  for (const jobs::ResponseInfo& r : s.responses) {
    if (r.name.starts_with("ida_capacity_") && !r.name.starts_with("ida_capacity_below_") &&
        !r.name.starts_with("ida_capacity_scale_")) {
      names.push_back(r.name.substr(13));
      unit = r.unit;
    }
  }
  if (names.empty()) return false;
  std::printf("  limit states (IDA, hunt-and-fill; capacity = lowest intensity exceeding it):\n");
  for (const std::string& name : names) {
    const std::vector<double> cap = ReadIfPresent(path, s.name, "responses/ida_capacity_" + name)
                                        .value_or(std::vector<double>{});
    std::size_t reached = 0, beyond = 0;
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (double c : cap) {
      if (std::isinf(c)) ++beyond;
      if (!std::isfinite(c)) continue;
      ++reached;
      lo = std::min(lo, c);
      hi = std::max(hi, c);
    }
    std::printf("    %-18s reached by %zu cells (capacity %s), not up to ida.max_im by %zu\n",
                name.c_str(), reached,
                reached ? fmt::format("{:.4g} to {:.4g}{}", lo, hi, UnitSuffix(unit)).c_str() : "-",
                beyond);
  }
  if (std::find(s.children.begin(), s.children.end(), "fragility") == s.children.end()) {
    std::printf("  fragility: none (fitted into the final cube only)\n");
    return true;
  }
  std::string row_label;
  std::vector<const jobs::h5::AxisSummary*> others;
  for (const jobs::h5::AxisSummary& a : s.axes) {
    if (a.name == "record") continue;
    others.push_back(&a);
    row_label += (row_label.empty() ? "" : ",") + a.name;
  }
  std::printf(
      "  fragility (fragility/, method ida): theta [%s] = geometric mean of the capacities, "
      "beta = std of their logs (censored records: maximum likelihood), per %s\n",
      unit.c_str(), row_label.empty() ? "sweep" : row_label.c_str());
  if (s.spec_canonical.find("records.beyond_max_scale = \"exclude\"") != std::string::npos) {
    std::printf(
        "    records whose capacity lies beyond %s are left out of the fit "
        "(records.beyond_max_scale = \"exclude\"); column too_far counts them\n",
        MaxScaleText(s).c_str());
  }
  PrintIdaFits(path, s, names, "fragility", others);
  if (Has(s, "fragility_worst_incidence")) {
    const std::vector<const jobs::h5::AxisSummary*> rest = WithoutIncidence(others);
    const std::string rest_label = AxisNames(rest);
    std::printf(
        "  fragility at the worst incidence angle (fragility_worst_incidence/, method ida): a "
        "record's capacity is the lowest over the angles, per %s\n",
        rest_label.c_str());
    PrintIdaFits(path, s, names, "fragility_worst_incidence", rest);
  }
  PrintOverIncidence(path, s, {});
  return true;
}

// The limit states of a sweep ([limit_states], docs/sweep-format.md): per limit state the cells
// that exceeded it (response ls_<name>: 1 or 0, NaN for a failed cell) and the largest demand
// (ls_<name>_demand); then, in a final cube, the fitted fragility (fragility/<name>/: median
// theta [g], dispersion beta, cells and exceedances, per combination of the axes other than
// record and the stripe axis). A cube without them says so, so that their absence is never
// read as "no exceedance".
void PrintLimitStates(const std::string& path, const jobs::h5::SweepSummary& s) {
  std::vector<std::string> names;
  std::map<std::string, std::string> demand_unit;
  for (const jobs::ResponseInfo& r : s.responses) {
    const bool demand = r.name.size() > 7 && r.name.ends_with("_demand");
    if (r.name.starts_with("ls_") && !demand) {
      names.push_back(r.name.substr(3));
    } else if (r.name.starts_with("ls_")) {
      demand_unit[r.name.substr(3, r.name.size() - 10)] = r.unit;
    }
  }
  if (names.empty() && PrintIdaLimitStates(path, s)) return;
  if (names.empty()) {
    std::printf("  limit states: none declared\n");
    return;
  }
  std::printf("  limit states (cells done with a value; largest demand):\n");
  for (const std::string& name : names) {
    const std::optional<std::vector<double>> exceeded =
        ReadIfPresent(path, s.name, "responses/ls_" + name);
    const std::optional<std::vector<double>> demand =
        ReadIfPresent(path, s.name, "responses/ls_" + name + "_demand");
    std::size_t with_value = 0;
    std::size_t over = 0;
    for (double e : exceeded.value_or(std::vector<double>{})) {
      with_value += std::isfinite(e) ? 1 : 0;
      over += e == 1.0 ? 1 : 0;
    }
    double largest = -std::numeric_limits<double>::infinity();
    for (double d : demand.value_or(std::vector<double>{})) {
      // +inf is a value: any travel over a zero seat.
      largest = std::isnan(d) ? largest : std::max(largest, d);
    }
    const std::string unit = demand_unit.count(name) ? demand_unit[name] : "";
    std::printf("    %-18s exceeded in %zu of %zu cells; demand up to %s\n", name.c_str(), over,
                with_value,
                largest > -std::numeric_limits<double>::infinity()
                    ? fmt::format("{:.6g}{}", largest, UnitSuffix(unit)).c_str()
                    : "- (no cell with a value)");
  }
  if (std::find(s.children.begin(), s.children.end(), "fragility") == s.children.end()) {
    std::printf("  fragility: none (fitted into the final cube only)\n");
    return;
  }
  // The combinations: the axes other than record and the stripe axis, row-major. The stripes
  // are im_g or im_mps, else scale, else a pulse family's a_g_g (jobs/study.cpp).
  const auto has_axis = [&s](std::string_view name) {
    return std::any_of(s.axes.begin(), s.axes.end(),
                       [name](const jobs::h5::AxisSummary& a) { return a.name == name; });
  };
  const bool a_g_g_stripes = !has_axis("im_g") && !has_axis("im_mps") && !has_axis("scale");
  std::vector<const jobs::h5::AxisSummary*> others;
  for (const jobs::h5::AxisSummary& a : s.axes) {
    if (a.name != "record" && a.name != "im_g" && a.name != "im_mps" && a.name != "scale" &&
        !(a.name == "a_g_g" && a_g_g_stripes)) {
      others.push_back(&a);
    }
  }
  std::string row_label;
  for (const jobs::h5::AxisSummary* a : others) {
    row_label += (row_label.empty() ? "" : ",") + a->name;
  }
  std::printf("  fragility (fragility/): P = Phi(ln(IM / theta) / beta), theta [g], per %s\n",
              row_label.empty() ? "sweep" : row_label.c_str());
  // records.beyond_max_scale = "exclude": the cells scaled beyond max_scale are in no fit.
  const bool excluding = std::any_of(names.begin(), names.end(), [&](const std::string& name) {
    return ReadIfPresent(path, s.name, "fragility/" + name + "/n_excluded_beyond_max_scale")
        .has_value();
  });
  if (excluding) {
    std::printf(
        "    cells scaled beyond %s are left out of every fit (records.beyond_max_scale = "
        "\"exclude\"); column excluded counts them\n",
        MaxScaleText(s).c_str());
  }
  PrintStripeFits(path, s, names, "fragility", others, excluding);
  if (Has(s, "fragility_worst_incidence")) {
    const std::vector<const jobs::h5::AxisSummary*> rest = WithoutIncidence(others);
    const std::string rest_label = AxisNames(rest);
    std::printf(
        "  fragility at the worst incidence angle (fragility_worst_incidence/): a record at a "
        "stripe exceeds when it exceeds at some angle, theta [g], per %s\n",
        rest_label.c_str());
    PrintStripeFits(path, s, names, "fragility_worst_incidence", rest, excluding);
  }
  PrintOverIncidence(path, s, names);
}

// The files the cells were computed from (inputs/), as the sweep read them when it was begun:
// role, size, SHA-256 (as sha256sum prints it) and the path relative to the spec's folder.
void PrintInputs(const jobs::h5::SweepSummary& s) {
  if (s.inputs.empty()) {
    std::printf("  inputs: none stored\n");
    return;
  }
  std::printf(
      "  inputs: %zu file(s) the cells were computed from, when the sweep was begun "
      "(paths relative to the spec's folder):\n",
      s.inputs.size());
  std::printf("    %-10s %12s  %-64s  %s\n", "role", "bytes", "sha256", "file");
  for (const jobs::InputFile& input : s.inputs) {
    std::printf("    %-10s %12llu  %-64s  %s\n", input.role.c_str(),
                static_cast<unsigned long long>(input.bytes), input.sha256.c_str(),
                input.file.c_str());
  }
}

// The annual rates of `skewbridge risk` (risk/, docs/risk.md): the hazard's identity, the
// measures matched, what every rate assumes, and per limit state and combination lambda_LS with
// its 16-84 %, P in 50 years, the return period and Cornell's closed form beside it.
void PrintRisk(const std::string& path, const jobs::h5::SweepSummary& s) {
  if (std::find(s.children.begin(), s.children.end(), "risk") == s.children.end()) return;
  const jobs::h5::RiskSummary r = jobs::h5::ReadRiskSummary(path, s.name);
  std::printf("  risk (risk/, annual rates over a hazard curve):\n");
  for (const std::string& line : r.attrs) std::printf("    %s\n", line.c_str());
  for (const std::string& note : r.notes) std::printf("    assumes: %s\n", note.c_str());
  // Row-major over the combination axes, the last one fastest.
  std::vector<const jobs::h5::AxisSummary*> axes;
  std::string row_label;
  for (const std::string& key : r.axis_order) {
    for (const jobs::h5::AxisSummary& a : s.axes) {
      if (a.name == key) axes.push_back(&a);
    }
    row_label += (row_label.empty() ? "" : ",") + key;
  }
  auto label_of = [&axes](std::size_t row) {
    std::string label;
    for (std::size_t j = axes.size(); j-- > 0;) {
      label = Coordinate(*axes[j], row % axes[j]->size) + (label.empty() ? "" : "," + label);
      row /= axes[j]->size;
    }
    return label.empty() ? std::string("-") : label;
  };
  std::printf("    %-18s %-22s %12s %12s %12s %10s %10s %12s\n", "limit state",
              row_label.empty() ? "-" : row_label.c_str(), "lambda[1/yr]", "16%", "84%", "P(50 yr)",
              "T_R [yr]", "Cornell");
  auto number = [](double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : "-"; };
  for (const jobs::h5::StoredRisk& ls : r.limit_states) {
    for (std::size_t row = 0; row < ls.rate_per_yr.size(); ++row) {
      if (!ls.reason[row].empty()) {
        std::printf("    %-18s %-22s  no rate: %s\n", ls.name.c_str(), label_of(row).c_str(),
                    ls.reason[row].c_str());
        continue;
      }
      std::printf("    %-18s %-22s %12s %12s %12s %10s %10s %12s\n", ls.name.c_str(),
                  label_of(row).c_str(), number(ls.rate_per_yr[row]).c_str(),
                  number(ls.rate_p16[row]).c_str(), number(ls.rate_p84[row]).c_str(),
                  number(ls.p_50yr[row]).c_str(), number(ls.return_period_yr[row]).c_str(),
                  number(ls.cornell_rate[row]).c_str());
      if (!ls.flags[row].empty()) std::printf("      flags: %s\n", ls.flags[row].c_str());
    }
  }
}

void PrintCube(const std::string& path) {
  for (const jobs::h5::SweepSummary& s : jobs::h5::SummarizeCube(path)) {
    std::printf("sweep %s (family %s, spec %s, created %s, skewbridge %s)\n", s.name.c_str(),
                s.family.c_str(), s.spec_hash.c_str(), s.created_utc.c_str(),
                s.program_version.c_str());
    std::printf("  axes:\n");
    for (const jobs::h5::AxisSummary& a : s.axes) {
      std::printf("    %-14s %6zu  %s%s\n", a.name.c_str(), a.size, AxisRange(a).c_str(),
                  a.unit.empty() || a.unit == "1" ? "" : (" [" + a.unit + "]").c_str());
    }
    PrintFixed(s);
    PrintInputs(s);
    std::printf("  responses:\n");
    for (const jobs::ResponseInfo& r : s.responses) {
      std::printf("    %-14s [%s] %s\n", r.name.c_str(), r.unit.c_str(), r.description.c_str());
    }
    const double percent = s.cells ? 100.0 * static_cast<double>(s.done) / s.cells : 100.0;
    std::printf("  completion: %llu/%llu cells done (%.1f%%), %s, %lld run(s)\n",
                static_cast<unsigned long long>(s.done), static_cast<unsigned long long>(s.cells),
                percent, s.complete ? "complete" : "NOT complete", static_cast<long long>(s.runs));
    for (const auto& [status, count] : s.done_by_status) {
      const auto example = s.status_examples.find(status);
      std::printf("    %-14s %llu%s\n", status.c_str(), static_cast<unsigned long long>(count),
                  example == s.status_examples.end() ? "" : ("  e.g. " + example->second).c_str());
    }
    PrintRecordStudy(path, s);
    PrintLimitStates(path, s);
    PrintRisk(path, s);
  }
}

}  // namespace

void AddInspectCommand(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "inspect",
      "Summarise a sweep cube: axes, fixed parameters, responses, completion, record statistics");
  cmd->add_option("file", *path, "Cube FILE.h5 (or FILE.h5.partial)")->required();
  cmd->callback([path] {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(*path, ec);
    if (status.type() == std::filesystem::file_type::not_found) {
      throw InputError::AtLine(*path, 0, "the file does not exist");
    }
    if (status.type() == std::filesystem::file_type::directory) {
      throw InputError::AtLine(*path, 0,
                               "is a folder; `inspect` takes a cube file FILE.h5 (or "
                               "FILE.h5.partial)");
    }
    PrintCube(*path);
  });
}

}  // namespace skewbridge::app
