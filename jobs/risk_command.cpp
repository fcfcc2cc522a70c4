#include "jobs/risk_command.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "jobs/file_checksum.h"
#include "jobs/h5/cube_file.h"
#include "jobs/h5/risk_file.h"
#include "solver/common/error.h"
#include "spectra/study.h"

namespace skewbridge::jobs {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The fragility's measure, from the cube's description of it and the fragility's IM: a
// [records] scale_to / im measure (im_g, im, ida_capacity) as im_description names it, else
// the excitation's peak a_g / g, the PGA of the applied motion. A single record's Sa is of an
// arbitrary component; a pair's RotD50, RotD100 and GM are SA of those components.
spectra::IntensityMeasureId FragilityMeasure(const h5::RiskSource& s, const std::string& cube,
                                             bool* at_t1) {
  spectra::IntensityMeasureId id;
  id.component = spectra::kRecordComponent;
  *at_t1 = false;
  if (s.im == "a_g") {
    id.measure = "PGA";
    return id;
  }
  const std::optional<spectra::IntensityMeasureSpec> spec =
      spectra::ParseIntensityDescription(s.im_measure, s.im_description);
  if (!spec) {
    throw InputError::AtLine(cube, 0,
                             fmt::format("sweep '{}': the fragility's IM ('{}', '{}') is not a "
                                         "measure a hazard curve can match",
                                         s.sweep, s.im_measure, s.im_description));
  }
  // A pair's measures are spectral accelerations of a stated component [Boore 2010]; AvgSa of
  // RotD50 keeps its own name, which no hazard curve's measure matches.
  if (spec->measure == "RotD50" || spec->measure == "RotD100" || spec->measure == "GM") {
    id.measure = "SA";
    id.component = spec->measure == "RotD50"    ? spectra::HorizontalComponent::kRotD50
                   : spec->measure == "RotD100" ? spectra::HorizontalComponent::kRotD100
                                                : spectra::HorizontalComponent::kGeometricMean;
  } else {
    id.measure = spec->measure == "Sa" ? "SA" : spec->measure;
  }
  id.damping = spec->xi;
  id.period_s = spec->period_s;
  *at_t1 = spec->at_t1;
  return id;
}

// Per combination of the fragility's axes: each cell's combination index, or -1 for a cell
// that is not usable (failed, or not done).
std::vector<std::ptrdiff_t> CombinationOfCells(const h5::RiskSource& s) {
  std::vector<std::size_t> pos;  // the cube axis of each combination axis
  for (const std::string& key : s.axis_order) {
    const auto it = std::find(s.cube_axes.begin(), s.cube_axes.end(), key);
    SB_DEMAND(it != s.cube_axes.end(), "a fragility axis that the cube does not have");
    pos.push_back(static_cast<std::size_t>(it - s.cube_axes.begin()));
  }
  std::size_t cells = 1;
  for (std::size_t n : s.cube_shape) cells *= n;
  std::vector<std::ptrdiff_t> out(cells, -1);
  std::vector<std::size_t> index(s.cube_shape.size());
  for (std::size_t c = 0; c < cells; ++c) {
    std::size_t rest = c;
    for (std::size_t k = s.cube_shape.size(); k-- > 0;) {
      index[k] = rest % s.cube_shape[k];
      rest /= s.cube_shape[k];
    }
    std::size_t combo = 0;
    for (std::size_t j = 0; j < pos.size(); ++j)
      combo = combo * s.cube_shape[pos[j]] + index[pos[j]];
    if (c < s.status.size() && s.status[c] == 0.0) out[c] = static_cast<std::ptrdiff_t>(combo);
  }
  return out;
}

std::string Label(const h5::AxisSummary& axis, std::size_t k) {
  return axis.labels.empty() ? fmt::format("{:g}", axis.values[k]) : axis.labels[k];
}

}  // namespace

std::vector<RiskRun> RunRisk(const RiskArgs& args) {
  const std::string cube = args.cube.string();
  const spectra::HazardCurve hazard = spectra::ReadHazardCurve(args.hazard, args.hazard_options);
  const FileChecksum sum = ChecksumFile(args.hazard);
  if (!(args.period_tolerance >= 0.0)) {
    throw InputError::AtField("--period-tolerance", fmt::format("{}", args.period_tolerance),
                              "must be a fraction >= 0");
  }
  std::vector<h5::SweepSummary> summaries = h5::SummarizeCube(args.cube);
  std::vector<const h5::SweepSummary*> chosen;
  for (const h5::SweepSummary& s : summaries) {
    const bool fitted =
        std::find(s.children.begin(), s.children.end(), "fragility") != s.children.end();
    if (!args.sweep.empty() ? s.name == args.sweep : fitted) chosen.push_back(&s);
  }
  if (chosen.empty()) {
    throw InputError::AtLine(cube, 0,
                             args.sweep.empty()
                                 ? "holds no sweep with a fragility (a complete sweep with "
                                   "[limit_states] fits one)"
                                 : "holds no sweep named '" + args.sweep + "'");
  }
  std::vector<RiskRun> runs;
  for (const h5::SweepSummary* summary : chosen) {
    const h5::RiskSource src = h5::ReadRiskSource(args.cube, summary->name);
    if (src.im_units != "g") {
      throw InputError::AtLine(cube, 0,
                               fmt::format("sweep '{}': the fragility's IM is in {}, a hazard "
                                           "curve's in g",
                                           src.sweep, src.im_units));
    }
    bool at_t1 = false;
    const spectra::IntensityMeasureId base = FragilityMeasure(src, cube, &at_t1);
    const std::vector<std::ptrdiff_t> combo_of = CombinationOfCells(src);
    std::size_t combos = 1;
    std::vector<std::size_t> shape;
    for (const std::string& key : src.axis_order) {
      const auto it = std::find(src.cube_axes.begin(), src.cube_axes.end(), key);
      shape.push_back(src.cube_shape[static_cast<std::size_t>(it - src.cube_axes.begin())]);
      combos *= shape.back();
    }
    // Per combination: T1 (geometric mean of its cells'), the largest scale factor and the
    // cells beyond records.max_scale.
    std::vector<double> log_t1(combos, 0.0), t1_lo(combos, INFINITY), t1_hi(combos, 0.0);
    std::vector<std::int64_t> t1_n(combos, 0);
    spectra::RiskRecordFacts facts;
    facts.selected_for_site = args.records_selected_for_site;
    facts.max_scale = src.max_scale;
    facts.cells_beyond_max_scale.assign(combos, 0);
    facts.largest_scale.assign(combos, kNaN);
    for (std::size_t c = 0; c < combo_of.size(); ++c) {
      if (combo_of[c] < 0) continue;
      const auto k = static_cast<std::size_t>(combo_of[c]);
      if (c < src.t1_s.size() && std::isfinite(src.t1_s[c]) && src.t1_s[c] > 0.0) {
        log_t1[k] += std::log(src.t1_s[c]);
        t1_lo[k] = std::min(t1_lo[k], src.t1_s[c]);
        t1_hi[k] = std::max(t1_hi[k], src.t1_s[c]);
        ++t1_n[k];
      }
      if (c < src.scale_factor.size() && std::isfinite(src.scale_factor[c])) {
        const double f = src.scale_factor[c];
        facts.largest_scale[k] =
            std::isnan(facts.largest_scale[k]) ? f : std::max(facts.largest_scale[k], f);
        if (src.max_scale > 0.0 && f > src.max_scale) ++facts.cells_beyond_max_scale[k];
      }
    }
    // The measure check, per combination (the period of Sa(T1) is each combination's T1).
    std::vector<std::string> notes;
    std::set<std::string> seen;
    double im_factor = 1.0;
    std::string fragility_imt = base.Describe();
    bool described = !at_t1;
    for (std::size_t k = 0; k < combos; ++k) {
      spectra::IntensityMeasureId f = base;
      if (at_t1) {
        if (t1_n[k] == 0) continue;  // no usable cell: no fit, no measure to check
        f.period_s = std::exp(log_t1[k] / static_cast<double>(t1_n[k]));
        if (t1_hi[k] > t1_lo[k] * (1.0 + 1e-9)) {
          throw InputError::AtLine(
              cube, 0,
              fmt::format("sweep '{}': T1 varies from {:g} to {:g} s within "
                          "one combination of {}: one hazard period cannot "
                          "match it",
                          src.sweep, t1_lo[k], t1_hi[k], fmt::join(src.axis_order, ", ")));
        }
        if (!described) fragility_imt = f.Describe();
        described = true;
      }
      spectra::MeasureMatch m;
      try {
        m = spectra::MatchMeasures(hazard.imt, f, args.period_tolerance, args.conversion);
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}: {}", args.hazard.string(), e.what()));
      }
      im_factor = m.im_factor;
      for (const std::string& note : m.notes) {
        if (seen.insert(note).second) notes.push_back(note);
      }
    }
    const spectra::HazardPoints points =
        spectra::UsableHazard(hazard.im, hazard.rate_per_yr, im_factor);
    if (points.im.empty()) {
      throw InputError::AtLine(args.hazard.string(), 0,
                               "fewer than two levels with a finite, positive rate: nothing to "
                               "integrate");
    }
    std::vector<spectra::RiskFragility> fragilities;
    for (const h5::StoredFragility& stored : src.limit_states) {
      SB_DEMAND(stored.theta.size() == combos, "a fragility of another shape than its axes");
      spectra::RiskFragility f;
      f.name = stored.name;
      f.theta = stored.theta;
      f.beta = stored.beta;
      f.se_ln_theta = stored.se_ln_theta;
      f.se_beta = stored.se_beta;
      f.cov_ln_theta_beta = stored.cov_ln_theta_beta;
      f.reason = stored.reason;
      f.im_lo.assign(combos, kNaN);
      f.im_hi.assign(combos, kNaN);
      for (std::size_t k = 0; k < combos && src.stripes > 0 && !stored.stripe_im.empty(); ++k) {
        for (std::size_t j = 0; j < src.stripes; ++j) {
          const std::size_t at = k * src.stripes + j;
          if (stored.stripe_n[at] == 0 || !std::isfinite(stored.stripe_im[at])) continue;
          f.im_lo[k] = std::isnan(f.im_lo[k]) ? stored.stripe_im[at]
                                              : std::min(f.im_lo[k], stored.stripe_im[at]);
          f.im_hi[k] = std::isnan(f.im_hi[k]) ? stored.stripe_im[at]
                                              : std::max(f.im_hi[k], stored.stripe_im[at]);
        }
      }
      fragilities.push_back(std::move(f));
    }
    RiskRun run;
    run.sweep = src.sweep;
    run.hazard_imt = hazard.imt.Describe();
    run.fragility_imt = fragility_imt;
    run.axis_order = src.axis_order;
    run.shape = shape;
    for (std::size_t k = 0; k < combos; ++k) {
      std::string label;
      std::size_t rest = k;
      for (std::size_t j = src.axis_order.size(); j-- > 0;) {
        const auto axis =
            std::find_if(summary->axes.begin(), summary->axes.end(),
                         [&](const h5::AxisSummary& a) { return a.name == src.axis_order[j]; });
        label = src.axis_order[j] + "=" + Label(*axis, rest % shape[j]) +
                (label.empty() ? "" : "," + label);
        rest /= shape[j];
      }
      run.combination_label.push_back(label.empty() ? "-" : label);
    }
    run.table = spectra::ComputeRiskTable(points, args.options, fragilities, facts, notes);
    runs.push_back(std::move(run));
  }
  // Everything checked and computed: now write.
  for (const RiskRun& run : runs) {
    h5::RiskHazardInfo info;
    info.file = args.hazard.string();
    info.bytes = sum.bytes;
    info.sha256 = sum.sha256;
    info.format = hazard.format;
    info.imt = run.hazard_imt;
    info.fragility_imt = run.fragility_imt;
    info.kind = hazard.kind;
    info.investigation_time_yr = hazard.investigation_time_yr;
    info.site = hazard.site;
    info.lon_deg = hazard.lon_deg;
    info.lat_deg = hazard.lat_deg;
    info.conversion = args.conversion;
    info.period_tolerance = args.period_tolerance;
    info.created_utc = h5::UtcNow();
    h5::WriteRisk(args.cube, run.sweep, run.table, info, run.axis_order, run.shape);
  }
  return runs;
}

}  // namespace skewbridge::jobs
