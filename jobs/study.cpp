#include "jobs/study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>

#include "solver/common/error.h"
#include "spectra/ida.h"
#include "spectra/limit_states.h"
#include "spectra/round_off.h"

namespace skewbridge::jobs {
namespace {

std::optional<std::size_t> ResponseColumn(const CubeLayout& layout, std::string_view name) {
  for (std::size_t r = 0; r < layout.responses.size(); ++r) {
    if (layout.responses[r].name == name) return r;
  }
  return std::nullopt;
}

// The D / C of the cloud fit per cell, or empty with the reason why there is none.
std::vector<double> DemandOverCapacity(const spectra::LimitState& ls,
                                       const std::vector<double>& demand, std::string* why) {
  using spectra::LimitStateKind;
  if (ls.kind == LimitStateKind::kJointClosing) {
    *why = "the demand is a count of impacts: no cloud regression";
    return {};
  }
  const double capacity = ls.kind == LimitStateKind::kUnseating ? 1.0 : ls.threshold;
  if (!(capacity > 0.0)) {
    *why = "a threshold of 0 or less: no ln(demand / capacity)";
    return {};
  }
  std::vector<double> out(demand.size());
  for (std::size_t c = 0; c < demand.size(); ++c) out[c] = demand[c] / capacity;
  return out;
}

// The position of the incidence_deg axis, or -1.
std::ptrdiff_t IncidenceAxis(const SweepSpec& spec) {
  for (std::size_t k = 0; k < spec.axes.size(); ++k) {
    if (spec.axes[k].key == "incidence_deg") return static_cast<std::ptrdiff_t>(k);
  }
  return -1;
}

// One limit state's cells at the worst incidence angle, over the grid without the angle axis:
// a cell exceeds when it exceeds at some angle, its D / C is the largest over the angles, and it
// is used only when every angle's cell is (done, status ok, a finite outcome). Its IM is the
// first angle's (the record and stripe set it; the angle does not).
spectra::FragilityTable FitWorstIncidence(const SweepSpec& spec, std::size_t k,
                                          const std::string& stripe_axis,
                                          const spectra::FragilityCells& cells,
                                          const std::string& no_cloud,
                                          const spectra::FitShare& share) {
  const spectra::AxisSplit split = spectra::SplitAlong(spec, k);
  const spectra::AxisStatistics z = spectra::ReduceOverAxis(spec, k, cells.exceeded, cells.usable);
  std::vector<double> dc;
  if (!cells.demand_over_capacity.empty()) {
    dc = spectra::ReduceOverAxis(spec, k, cells.demand_over_capacity, cells.usable).max;
  }
  std::vector<double> im(split.Reduced());
  std::vector<std::uint8_t> excluded;
  if (!cells.excluded.empty()) excluded.assign(split.Reduced(), 0);
  for (std::size_t r = 0; r < split.Reduced(); ++r) {
    im[r] = cells.im[split.Cell(r, 0)];
    for (std::size_t i = 0; i < split.size && !excluded.empty(); ++i) {
      excluded[r] = excluded[r] != 0 || cells.excluded[split.Cell(r, i)] != 0 ? 1 : 0;
    }
  }
  return spectra::FitFragilityOverCells(
      spectra::GridWithout(spec, k), stripe_axis, {im, z.max, dc, z.complete, excluded}, no_cloud,
      spectra::kBootstrapResamples, spectra::kBootstrapSeed, share);
}

// The per-cell values that describe the excitation, the model or the scaling rather than the
// bridge's response: the same at every incidence angle, not reduced over it.
bool DescribesTheInput(std::string_view name) {
  static constexpr std::string_view kInputs[] = {
      "a_g",         "w_g", "L_e",         "delta",        "pga",
      "pgv",         "pgd", "T_m",         "arias",        "D5_95",
      "T1",          "im",  "im_unscaled", "scale_factor", "scaled_too_far",
      "w0x_over_wg", "band"};
  return std::find(std::begin(kInputs), std::end(kInputs), name) != std::end(kInputs);
}

// The responses of the bridge over the incidence angle axis (cells done with status ok).
std::optional<OverIncidence> MakeOverIncidence(const SweepSpec& spec, const CubeLayout& layout,
                                               const CubeData& data) {
  const std::ptrdiff_t at = IncidenceAxis(spec);
  if (at < 0) return std::nullopt;
  const auto k = static_cast<std::size_t>(at);
  OverIncidence out;
  out.angles_deg = spec.axes[k].values;
  for (std::size_t a = 0; a < spec.axes.size(); ++a) {
    if (a == k) continue;
    out.axis_order.push_back(spec.axes[a].key);
    out.shape.push_back(spec.axes[a].Size());
  }
  std::vector<std::uint8_t> usable(data.Cells());
  for (std::uint64_t cell = 0; cell < data.Cells(); ++cell) {
    usable[cell] = data.done[cell] != 0 && data.status[cell] == kStatusOk ? 1 : 0;
  }
  for (std::size_t r = 0; r < layout.responses.size(); ++r) {
    if (DescribesTheInput(layout.responses[r].name)) continue;
    out.responses.push_back(layout.responses[r]);
    out.statistics.push_back(spectra::ReduceOverAxis(spec, k, data.responses[r], usable));
  }
  return out;
}

// The fits per combination of every limit state, then, with an incidence_deg axis, every limit
// state's fit at the worst angle (worst_incidence set). The combinations are numbered in that
// order over all the fits and fitted by the ranks in turn.
std::vector<FragilityStudy> MakeFragility(const SweepSpec& spec, const CubeLayout& layout,
                                          const CubeData& data, int rank, int ranks) {
  std::vector<FragilityStudy> out;
  if (spec.limit_states.empty()) return out;
  // The IM of every cell: a stripe axis (im_g, or im_mps for PGV), else the cell's stored
  // measure `im` (records unscaled: a cloud), else its a_g / g.
  std::vector<double> im(data.Cells());
  std::string im_name, im_units, im_description, stripe_axis;
  const std::optional<std::size_t> im_col = ResponseColumn(layout, "im");
  const std::optional<std::size_t> a_g = ResponseColumn(layout, "a_g");
  for (const char* key : {"im_g", "im_mps"}) {
    const Axis* stripes = spec.FindAxis(key);
    if (stripes == nullptr) continue;
    std::size_t k = 0;
    while (spec.axes[k].key != key) ++k;
    for (std::uint64_t c = 0; c < data.Cells(); ++c) {
      im[c] = stripes->values[spec.AxisIndex(c)[k]];
    }
    im_name = stripe_axis = key;
    im_units = stripe_axis == "im_g" ? "g" : "m/s";
    im_description = "the cell's coordinate of the axis " + stripe_axis + " (" + im_units +
                     "): the records scaled to it ([records] scale_to)";
  }
  if (im_name.empty() && im_col) {
    im = data.responses[*im_col];
    im_name = "im";
    im_units = layout.responses[*im_col].unit;
    im_description = "the cell's response im (" + im_units +
                     "): the measure of [records] im "
                     "of the record as applied";
    if (spec.FindAxis("scale") != nullptr) stripe_axis = "scale";
  } else if (im_name.empty() && a_g) {
    for (std::uint64_t c = 0; c < data.Cells(); ++c) {
      im[c] = data.responses[*a_g][c] / records::kStandardGravity_mps2;
    }
    im_name = "a_g";
    im_units = "g";
    im_description =
        "the cell's a_g / g: the excitation's peak acceleration (a record's PGA "
        "times scale) in g";
    // Records scaled by a factor, or pulses of a given amplitude: each value is a stripe.
    if (spec.FindAxis("scale") != nullptr) {
      stripe_axis = "scale";
    } else if (spec.FindAxis("a_g_g") != nullptr) {
      stripe_axis = "a_g_g";
    }
  } else if (im_name.empty()) {
    return out;  // no IM stored (a responses subset without a_g)
  }
  std::vector<std::uint8_t> usable(data.Cells());
  for (std::uint64_t cell = 0; cell < data.Cells(); ++cell) {
    usable[cell] = data.done[cell] != 0 && data.status[cell] == kStatusOk ? 1 : 0;
  }
  // [records] beyond_max_scale = "exclude": the cells flagged scaled_too_far enter no fit (the
  // parser demands the response in a subset; an IDA sweep has none and fits no stripes).
  std::vector<std::uint8_t> excluded;
  const std::optional<std::size_t> far = ResponseColumn(layout, "scaled_too_far");
  if (spec.im.exclude_beyond_max_scale && far) {
    excluded.resize(data.Cells());
    for (std::uint64_t cell = 0; cell < data.Cells(); ++cell) {
      excluded[cell] = data.responses[*far][cell] == 1.0 ? 1 : 0;
    }
  }
  std::size_t jobs = 0;  // the combinations of the fits before this one
  const std::ptrdiff_t incidence = IncidenceAxis(spec);
  for (const bool at_worst : {false, true}) {
    if (at_worst && incidence < 0) break;
    for (const spectra::LimitState& ls : spec.limit_states) {
      const auto [demand_name, exceeded_name] = spectra::LimitStateResponseNames(ls);
      const std::optional<std::size_t> demand = ResponseColumn(layout, demand_name);
      const std::optional<std::size_t> exceeded = ResponseColumn(layout, exceeded_name);
      if (!demand || !exceeded) continue;
      FragilityStudy f;
      f.ls = ls;
      f.worst_incidence = at_worst;
      f.demand_unit = layout.responses[*demand].unit;
      f.im = im_name;
      f.im_units = im_units;
      f.im_description = im_description;
      // A demand in rad below the round-off floor is zero (spectra::kRotationRoundOffFloor_rad):
      // no point of the cloud, and not above a threshold of 0.
      const double floor = spectra::RoundOffFloor(f.demand_unit);
      std::vector<double> demand_read = data.responses[*demand];
      std::vector<double> exceeded_read = data.responses[*exceeded];
      for (std::uint64_t c = 0; c < data.Cells(); ++c) {
        if (std::abs(demand_read[c]) < floor) {
          demand_read[c] = 0.0;
          if (std::isfinite(exceeded_read[c])) exceeded_read[c] = 0.0 > ls.threshold ? 1.0 : 0.0;
        }
      }
      std::string no_cloud;
      const std::vector<double> dc = DemandOverCapacity(ls, demand_read, &no_cloud);
      const spectra::FragilityCells cells{im, exceeded_read, dc, usable, excluded};
      const spectra::FitShare share{rank, ranks, jobs};
      f.table = at_worst ? FitWorstIncidence(spec, static_cast<std::size_t>(incidence), stripe_axis,
                                             cells, no_cloud, share)
                         : spectra::FitFragilityOverCells(spec, stripe_axis, cells, no_cloud,
                                                          spectra::kBootstrapResamples,
                                                          spectra::kBootstrapSeed, share);
      jobs += f.table.theta.size();
      out.push_back(std::move(f));
    }
  }
  return out;
}

}  // namespace

namespace {

// One cell's capacity of a limit state as the IDA fit takes it: records.max_scale applied.
struct IdaCell {
  double capacity = 0.0;  // g or m/s; +inf: censored at `at`
  double at = 0.0;        // the censoring intensity of a +inf capacity
  bool too_far = false;   // reached only beyond records.max_scale
};

// The cell's capacity of the limit state in column `col` (below_col: the highest run below it;
// own_col: the record's own measure for records.max_scale).
IdaCell ReadIdaCell(const SweepSpec& spec, const CubeData& data, std::uint64_t c, std::size_t col,
                    const std::optional<std::size_t>& below_col,
                    const std::optional<std::size_t>& own_col) {
  IdaCell cell;
  cell.capacity = data.responses[col][c];
  // A record that never exceeds the limit state is censored at its highest run (max_im
  // unless the run budget ended the hunt first).
  cell.at = below_col ? data.responses[*below_col][c] : std::numeric_limits<double>::quiet_NaN();
  const double max_scale = spec.im.max_scale;
  if (max_scale > 0.0 && own_col) {
    // Runs scaled beyond max_scale are not trusted: a capacity reached there is flagged
    // and censored at the highest trusted intensity, as is a record never exceeding it.
    const double trusted = max_scale * data.responses[*own_col][c];
    if (std::isfinite(cell.capacity) && cell.capacity > trusted) {
      cell.too_far = true;
      cell.capacity = std::numeric_limits<double>::infinity();
    }
    if (std::isinf(cell.capacity)) cell.at = std::min(cell.at, trusted);
  }
  return cell;
}

// The worst incidence angle of one record: it exceeds the limit state at the lowest capacity
// over the angles (the lowest intensity at which it exceeds it at some angle); a record
// exceeding it at no angle is censored at the lowest of its angles' censoring intensities (up
// to there no angle exceeds it), and flagged too far when some angle reaches it beyond
// records.max_scale.
IdaCell WorstOverAngles(const std::vector<IdaCell>& angles) {
  IdaCell worst;
  worst.capacity = std::numeric_limits<double>::infinity();
  worst.at = std::numeric_limits<double>::infinity();
  for (const IdaCell& a : angles) {
    worst.capacity = std::min(worst.capacity, a.capacity);
    worst.at = std::min(worst.at, a.at);
    worst.too_far = worst.too_far || a.too_far;
  }
  if (std::isfinite(worst.capacity)) {
    worst.too_far = false;
    worst.at = std::numeric_limits<double>::quiet_NaN();
  }
  return worst;
}

}  // namespace

// The lognormal fit of each limit state's capacities over the records, per combination of the
// other axes (cells done with status ok only); with `at_worst_incidence`, per combination of
// the axes other than record and incidence_deg, of each record's capacity at its worst angle
// (WorstOverAngles; a record enters only when its cells of every angle are done with status
// ok). Without an incidence_deg axis nothing is fitted at the worst angle.
std::vector<IdaFragilityStudy> MakeIdaFragility(const SweepSpec& spec, const CubeLayout& layout,
                                                const CubeData& data,
                                                bool at_worst_incidence = false) {
  std::vector<IdaFragilityStudy> out;
  if (!spec.ida.enabled) return out;
  const std::ptrdiff_t incidence = IncidenceAxis(spec);
  if (at_worst_incidence && incidence < 0) return out;
  std::vector<std::size_t> combo_axes;
  IdaFragilityStudy base;
  base.im_units = spectra::IntensityUnit(spec.im);
  for (std::size_t k = 0; k < spec.axes.size(); ++k) {
    if (spec.axes[k].key == "record") continue;
    if (at_worst_incidence && static_cast<std::ptrdiff_t>(k) == incidence) continue;
    combo_axes.push_back(k);
    base.axis_order.push_back(spec.axes[k].key);
    base.shape.push_back(spec.axes[k].Size());
  }
  std::size_t combos = 1;
  for (std::size_t n : base.shape) combos *= n;
  const std::optional<std::size_t> own_col = ResponseColumn(layout, "im_unscaled");
  const double max_scale = spec.im.max_scale;
  const bool exclude = spec.im.exclude_beyond_max_scale;
  const auto usable = [&data](std::uint64_t c) {
    return data.done[c] != 0 && data.status[c] == kStatusOk;
  };
  for (const spectra::LimitState& ls : spec.limit_states) {
    const std::optional<std::size_t> col = ResponseColumn(layout, "ida_capacity_" + ls.name);
    if (!col) continue;
    const std::optional<std::size_t> below_col =
        ResponseColumn(layout, "ida_capacity_below_" + ls.name);
    std::vector<std::vector<double>> capacities(combos), censor_at(combos);
    std::vector<std::int64_t> too_far(combos, 0);
    const auto add = [&](std::size_t combo, const IdaCell& cell) {
      if (cell.too_far) {
        ++too_far[combo];
        // beyond_max_scale = "exclude": the record enters no fit.
        if (exclude) return;
      }
      capacities[combo].push_back(cell.capacity);
      censor_at[combo].push_back(cell.at);
    };
    const auto combo_of = [&](const std::vector<std::size_t>& index) {
      std::size_t combo = 0;
      for (std::size_t k : combo_axes) combo = combo * spec.axes[k].Size() + index[k];
      return combo;
    };
    if (!at_worst_incidence) {
      for (std::uint64_t c = 0; c < data.Cells(); ++c) {
        if (!usable(c)) continue;
        add(combo_of(spec.AxisIndex(c)), ReadIdaCell(spec, data, c, *col, below_col, own_col));
      }
    } else {
      // Every cell at the first angle stands for its record and combination; the other
      // angles' cells are reached along the angle axis.
      const spectra::AxisSplit split =
          spectra::SplitAlong(spec, static_cast<std::size_t>(incidence));
      for (std::size_t r = 0; r < split.Reduced(); ++r) {
        std::vector<IdaCell> angles;
        bool complete = true;
        for (std::size_t i = 0; i < split.size && complete; ++i) {
          const std::uint64_t c = split.Cell(r, i);
          complete = usable(c);
          if (complete) angles.push_back(ReadIdaCell(spec, data, c, *col, below_col, own_col));
        }
        if (!complete) continue;
        add(combo_of(spec.AxisIndex(split.Cell(r, 0))), WorstOverAngles(angles));
      }
    }
    IdaFragilityStudy f = base;
    f.ls = ls;
    for (std::size_t combo = 0; combo < combos; ++combo) {
      const spectra::CapacityFit fit = spectra::FitCapacities(capacities[combo], censor_at[combo]);
      f.theta.push_back(fit.theta);
      f.beta.push_back(fit.beta);
      f.n.push_back(fit.n);
      f.censored.push_back(fit.censored);
      std::string why = fit.reason, note = fit.note;
      if (too_far[combo] > 0) {
        const std::string far =
            exclude ? fmt::format(
                          "; {} record(s) reaching it only beyond records.max_scale = {} left "
                          "out (beyond_max_scale = \"exclude\")",
                          too_far[combo], max_scale)
                    : fmt::format(
                          "; {} of the censored reached it only beyond records.max_scale = {} "
                          "(censored there)",
                          too_far[combo], max_scale);
        if (!why.empty()) why += far;
        if (!note.empty()) note += far;
        // A left-out record changes the fit even when none is censored: always said.
        if (exclude && note.empty()) note = far.substr(2);
      }
      f.reason.push_back(why);
      f.note.push_back(note);
      f.too_far.push_back(too_far[combo]);
    }
    out.push_back(std::move(f));
  }
  return out;
}

std::vector<FragilityStudy> MakeFragilityStudies(const SweepSpec& spec, const CubeLayout& layout,
                                                 const CubeData& data, int rank, int ranks) {
  return MakeFragility(spec, layout, data, rank, ranks);
}

namespace {

template <typename T>
void Put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <typename T>
void PutArray(std::string& out, const std::vector<T>& v) {
  Put(out, static_cast<std::uint64_t>(v.size()));
  out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// Reads what Put and PutArray wrote, in order.
class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  T Get() {
    SB_DEMAND(at_ + sizeof(T) <= bytes_.size(), "a packed fragility message is too short");
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  template <typename T>
  std::vector<T> GetArray() {
    const auto n = Get<std::uint64_t>();
    SB_DEMAND(at_ + n * sizeof(T) <= bytes_.size(), "a packed fragility message is too short");
    std::vector<T> v(n);
    std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return v;
  }
  bool Done() const { return at_ == bytes_.size(); }

 private:
  std::string_view bytes_;
  std::size_t at_ = 0;
};

// The response columns MakeFragility reads.
std::vector<std::size_t> FragilityColumns(const SweepSpec& spec, const CubeLayout& layout) {
  std::vector<std::size_t> cols;
  const auto add = [&](std::string_view name) {
    if (const std::optional<std::size_t> c = ResponseColumn(layout, name)) cols.push_back(*c);
  };
  add("im");
  add("a_g");
  add("scaled_too_far");
  for (const spectra::LimitState& ls : spec.limit_states) {
    const auto [demand_name, exceeded_name] = spectra::LimitStateResponseNames(ls);
    add(demand_name);
    add(exceeded_name);
  }
  std::sort(cols.begin(), cols.end());
  cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
  return cols;
}

}  // namespace

std::string PackFragilityInputs(const SweepSpec& spec, const CubeLayout& layout,
                                const CubeData& data) {
  std::string out;
  PutArray(out, data.done);
  PutArray(out, data.status);
  for (std::size_t c : FragilityColumns(spec, layout)) {
    Put(out, static_cast<std::uint64_t>(c));
    PutArray(out, data.responses[c]);
  }
  return out;
}

CubeData UnpackFragilityInputs(const CubeLayout& layout, std::string_view bytes) {
  Reader in(bytes);
  CubeData data;
  data.done = in.GetArray<std::uint8_t>();
  data.status = in.GetArray<std::int32_t>();
  data.responses.resize(layout.responses.size());
  while (!in.Done()) {
    const auto c = in.Get<std::uint64_t>();
    SB_DEMAND(c < data.responses.size(), "a packed fragility column outside the layout");
    data.responses[c] = in.GetArray<double>();
  }
  return data;
}

namespace {

// The per-combination values of a FragilityTable that the rank fitting the combination computes
// (the counts per stripe every rank computes).
constexpr std::vector<double> spectra::FragilityTable::*kFitDoubles[] = {
    &spectra::FragilityTable::theta,
    &spectra::FragilityTable::beta,
    &spectra::FragilityTable::se_ln_theta,
    &spectra::FragilityTable::se_beta,
    &spectra::FragilityTable::cov_ln_theta_beta,
    &spectra::FragilityTable::theta_lo,
    &spectra::FragilityTable::theta_hi,
    &spectra::FragilityTable::beta_lo,
    &spectra::FragilityTable::beta_hi,
    &spectra::FragilityTable::boot_theta_lo,
    &spectra::FragilityTable::boot_theta_hi,
    &spectra::FragilityTable::boot_beta_lo,
    &spectra::FragilityTable::boot_beta_hi,
    &spectra::FragilityTable::cloud_intercept,
    &spectra::FragilityTable::cloud_slope,
    &spectra::FragilityTable::cloud_sigma,
    &spectra::FragilityTable::cloud_theta,
    &spectra::FragilityTable::cloud_beta};
constexpr std::vector<std::int64_t> spectra::FragilityTable::*kFitCounts[] = {
    &spectra::FragilityTable::boot_used, &spectra::FragilityTable::n_cells,
    &spectra::FragilityTable::n_exceeded, &spectra::FragilityTable::cloud_n,
    &spectra::FragilityTable::cloud_excluded};
constexpr std::vector<std::string> spectra::FragilityTable::*kFitTexts[] = {
    &spectra::FragilityTable::reason, &spectra::FragilityTable::cloud_reason};

}  // namespace

std::string PackFits(const std::vector<FragilityStudy>& studies, int rank, int ranks) {
  std::string out;
  std::size_t first_job = 0;
  for (std::size_t k = 0; k < studies.size(); ++k) {
    const FragilityTable& t = studies[k].table;
    const spectra::FitShare share{rank, ranks, first_job};
    for (std::size_t combo = 0; combo < t.theta.size(); ++combo) {
      if (!share.Mine(combo)) continue;
      Put(out, static_cast<std::uint64_t>(k));
      Put(out, static_cast<std::uint64_t>(combo));
      for (const auto column : kFitDoubles) Put(out, (t.*column)[combo]);
      for (const auto column : kFitCounts) Put(out, (t.*column)[combo]);
      for (const auto column : kFitTexts) {
        const std::string& text = (t.*column)[combo];
        PutArray(out, std::vector<char>(text.begin(), text.end()));
      }
    }
    first_job += t.theta.size();
  }
  return out;
}

void MergeFits(std::vector<FragilityStudy>& studies, std::string_view bytes) {
  Reader in(bytes);
  while (!in.Done()) {
    const auto k = in.Get<std::uint64_t>();
    const auto combo = in.Get<std::uint64_t>();
    SB_DEMAND(k < studies.size() && combo < studies[k].table.theta.size(),
              "a fit of a combination the fragility does not have");
    FragilityTable& t = studies[k].table;
    for (const auto column : kFitDoubles) (t.*column)[combo] = in.Get<double>();
    for (const auto column : kFitCounts) (t.*column)[combo] = in.Get<std::int64_t>();
    for (const auto column : kFitTexts) {
      const std::vector<char> text = in.GetArray<char>();
      (t.*column)[combo].assign(text.begin(), text.end());
    }
  }
}

StudyTables MakeStudyTables(const SweepSpec& spec, const CubeLayout& layout, const CubeData& data,
                            const std::vector<SweepRecord>* records,
                            std::vector<FragilityStudy>* fragility) {
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

  tables.im = spec.im;
  if (const std::optional<std::size_t> col = ResponseColumn(layout, "scaled_too_far")) {
    tables.scaled_too_far = 0;
    for (std::uint64_t cell = 0; cell < data.Cells(); ++cell) {
      if (data.done[cell] != 0 && data.responses[*col][cell] == 1.0) ++tables.scaled_too_far;
    }
  }

  std::vector<FragilityStudy> fits =
      fragility != nullptr ? std::move(*fragility) : MakeFragility(spec, layout, data, 0, 1);
  for (FragilityStudy& f : fits) {
    (f.worst_incidence ? tables.fragility_worst_incidence : tables.fragility)
        .push_back(std::move(f));
  }
  tables.over_incidence = MakeOverIncidence(spec, layout, data);
  tables.ida_fragility = MakeIdaFragility(spec, layout, data);
  tables.ida_fragility_worst_incidence = MakeIdaFragility(spec, layout, data, true);

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
  // A rotation below the round-off floor is zero: out of the log-log statistics.
  std::vector<double> theta = data.responses[*theta_col];
  const double floor = spectra::RoundOffFloor(layout.responses[*theta_col].unit);
  for (double& v : theta) v = spectra::AboveRoundOff(v, floor);
  CorrelationTable table = spectra::CorrelateOverRecords(spec, theta, data.responses[*le_col], band,
                                                         usable, BandEdges(spec).size() + 1);
  table.y = layout.responses[*theta_col].name;
  tables.correlation = std::move(table);
  return tables;
}

}  // namespace skewbridge::jobs
