#include "spectra/ida.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/common/error.h"
#include "spectra/limit_states.h"
#include "spectra/study.h"

namespace skewbridge::spectra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The two-digit run number of the per-run responses: ida_im_00, ida_im_01, ...
std::string RunSuffix(int k) { return fmt::format("_{:02d}", k); }

}  // namespace

std::vector<IdaCapacity> IdaCapacities(const IdaTrace& trace, std::size_t limit_states) {
  std::vector<IdaCapacity> out(limit_states);
  for (std::size_t l = 0; l < limit_states; ++l) {
    double hi = kInf;
    for (std::size_t r = 0; r < trace.im.size(); ++r) {
      if (trace.exceeded[r][l] > 0.5) hi = std::min(hi, trace.im[r]);
    }
    double lo = 0.0;
    for (std::size_t r = 0; r < trace.im.size(); ++r) {
      if (!(trace.exceeded[r][l] > 0.5) && trace.im[r] < hi) lo = std::max(lo, trace.im[r]);
    }
    out[l] = {hi, lo};
  }
  return out;
}

IdaTrace HuntAndFill(const IdaSpec& spec, std::size_t limit_states,
                     const std::function<IdaPoint(double)>& run) {
  SB_DEMAND(spec.enabled && limit_states >= 1, "HuntAndFill needs [ida] and a limit state");
  IdaTrace t;
  const auto budget = static_cast<std::size_t>(spec.max_runs);
  bool failed = false;
  // One run at `im`; false when it failed (the search ends there).
  auto add = [&](double im) {
    IdaPoint p = run(im);
    if (!p.ok) {
      t.status = p.status;
      t.status_text = p.status_text;
      failed = true;
      return false;
    }
    SB_DEMAND(p.demand.size() == limit_states && p.exceeded.size() == limit_states,
              "an IDA run returned the wrong number of limit states");
    t.im.push_back(im);
    t.demand.push_back(std::move(p.demand));
    t.exceeded.push_back(std::move(p.exceeded));
    return true;
  };
  auto all_exceeded = [&] {
    for (const IdaCapacity& c : IdaCapacities(t, limit_states)) {
      if (!std::isfinite(c.im)) return false;
    }
    return true;
  };

  // Hunt: steps that grow until every limit state is exceeded or max_im is run.
  double im = spec.start, step = spec.step;
  while (t.im.size() < budget && add(im) && !all_exceeded() && im < spec.max_im) {
    im = std::min(im + step, spec.max_im);
    step += spec.step_increase;
  }
  // Bisect the widest bracket while one is wider than the tolerance, else fill the widest gap
  // of the curve below the highest capacity (or the highest run): a filling run that exceeds a
  // limit state below its capacity (a demand that is not monotone) opens a bracket again.
  while (!failed && t.im.size() < budget) {
    const std::vector<IdaCapacity> caps = IdaCapacities(t, limit_states);
    double widest = spec.tolerance, middle = 0.0, top = 0.0;
    for (const IdaCapacity& c : caps) {
      if (!std::isfinite(c.im)) continue;
      top = std::max(top, c.im);
      if (c.im - c.below > widest) {
        widest = c.im - c.below;
        middle = 0.5 * (c.im + c.below);
      }
    }
    if (middle == 0.0) {
      std::vector<double> ims{0.0};
      for (double x : t.im) {
        if (x <= top || top == 0.0) ims.push_back(x);
      }
      std::sort(ims.begin(), ims.end());
      double gap = spec.tolerance;
      for (std::size_t i = 1; i < ims.size(); ++i) {
        if (ims[i] - ims[i - 1] > gap) {
          gap = ims[i] - ims[i - 1];
          middle = 0.5 * (ims[i] + ims[i - 1]);
        }
      }
    }
    if (middle == 0.0 || !add(middle)) break;
  }
  t.capacity = IdaCapacities(t, limit_states);
  return t;
}

CapacityFit FitCapacities(std::span<const double> capacities) {
  CapacityFit f;
  std::vector<double> logs;
  for (double c : capacities) {
    if (std::isnan(c)) continue;
    if (std::isinf(c)) {
      ++f.censored;
    } else if (c > 0.0) {
      logs.push_back(std::log(c));
    }
  }
  f.n = static_cast<std::int64_t>(logs.size());
  if (f.censored > 0) {
    // The records that never reach the limit state are its strongest: leaving them out would
    // put the median too low, and the fit of right-censored data is another likelihood.
    f.theta = f.beta = kNaN;
    f.reason = fmt::format(
        "{} of {} records never reach the limit state up to ida.max_im: a fit of the other {} "
        "alone would put the median too low; raise ida.max_im",
        f.censored, f.censored + f.n, f.n);
    return f;
  }
  if (logs.size() < 2) {
    f.theta = f.beta = kNaN;
    f.reason = fmt::format("{} finite capacities ({} beyond the search's max_im): a fit needs 2",
                           logs.size(), f.censored);
    return f;
  }
  double mean = 0.0;
  for (double x : logs) mean += x;
  mean /= static_cast<double>(logs.size());
  double ss = 0.0;
  for (double x : logs) ss += (x - mean) * (x - mean);
  f.theta = std::exp(mean);
  f.beta = std::sqrt(ss / static_cast<double>(logs.size() - 1));
  return f;
}

IdaEvaluator::IdaEvaluator(std::unique_ptr<CellEvaluator> inner, const CellGrid& grid)
    : inner_(std::move(inner)),
      ida_(grid.ida),
      limit_states_(grid.limit_states),
      im_unit_(IntensityUnit(grid.im)) {
  const std::vector<ResponseInfo> responses = inner_->Responses();
  auto column = [&](const std::string& name, const LimitState& ls) {
    for (std::size_t c = 0; c < responses.size(); ++c) {
      if (responses[c].name == name) return c;
    }
    throw InputError::AtField(grid.source, "limit_states." + ls.name,
                              "the sweep stores no response " + name + " for [ida]");
  };
  for (const LimitState& ls : limit_states_) {
    const auto [demand, exceeded] = LimitStateResponseNames(ls);
    demand_columns_.push_back(column(demand, ls));
    exceeded_columns_.push_back(column(exceeded, ls));
    demand_units_.push_back(responses[demand_columns_.back()].unit);
  }
}

std::vector<ResponseInfo> IdaEvaluator::Responses() const {
  std::vector<ResponseInfo> out;
  out.push_back({"im_unscaled", im_unit_, "the record's own intensity measure at the cell's T1"});
  out.push_back({"ida_runs", "1", "runs made by the hunt-and-fill search"});
  for (const LimitState& ls : limit_states_) {
    out.push_back(
        {"ida_capacity_" + ls.name, im_unit_,
         "lowest intensity of a run that exceeds " + ls.name + " (inf: none up to ida.max_im)"});
    out.push_back(
        {"ida_capacity_below_" + ls.name, im_unit_,
         "highest intensity below it of a run that does not exceed " + ls.name + " (0: none)"});
    out.push_back({"ida_capacity_scale_" + ls.name, "1",
                   "scale factor on the record at ida_capacity_" + ls.name});
  }
  for (int k = 0; k < ida_.max_runs; ++k) {
    const std::string s = RunSuffix(k);
    const std::string run = fmt::format("run {} of the search (NaN when not made)", k);
    out.push_back({"ida_im" + s, im_unit_, "intensity of " + run});
    out.push_back({"ida_scale" + s, "1", "scale factor on the record in " + run});
    for (std::size_t l = 0; l < limit_states_.size(); ++l) {
      const std::string& name = limit_states_[l].name;
      out.push_back({"ida_demand_" + name + s, demand_units_[l], name + " demand in " + run});
      out.push_back({"ida_exceeded_" + name + s, "1", "1 when " + run + " exceeds " + name});
    }
  }
  return out;
}

CellOutcome IdaEvaluator::Evaluate(std::span<const std::size_t> axis_index) const {
  const double own = inner_->UnscaledIntensity(axis_index);
  SB_DEMAND(own > 0.0 && std::isfinite(own), "an IDA cell's record has no intensity to scale");
  CellOutcome out;
  auto run = [&](double im) {
    const CellOutcome o = inner_->EvaluateScaled(axis_index, im / own);
    out.stats.events += o.stats.events;
    out.stats.steps += o.stats.steps;
    out.stats.wall_s += o.stats.wall_s;
    IdaPoint p;
    p.ok = o.status == kStatusOk;
    p.status = o.status;
    p.status_text = fmt::format("at {} = {:.6g} {}: {}", "IM", im, im_unit_, o.status_text);
    for (std::size_t l = 0; l < limit_states_.size(); ++l) {
      p.demand.push_back(o.responses[demand_columns_[l]]);
      p.exceeded.push_back(o.responses[exceeded_columns_[l]]);
    }
    return p;
  };
  const IdaTrace t = HuntAndFill(ida_, limit_states_.size(), run);
  out.status = t.status;
  out.status_text = t.status_text;
  out.responses.push_back(own);
  out.responses.push_back(static_cast<double>(t.im.size()));
  for (const IdaCapacity& c : t.capacity) {
    out.responses.push_back(c.im);
    out.responses.push_back(c.below);
    out.responses.push_back(c.im / own);
  }
  for (std::size_t k = 0; k < static_cast<std::size_t>(ida_.max_runs); ++k) {
    const bool made = k < t.im.size();
    out.responses.push_back(made ? t.im[k] : kNaN);
    out.responses.push_back(made ? t.im[k] / own : kNaN);
    for (std::size_t l = 0; l < limit_states_.size(); ++l) {
      out.responses.push_back(made ? t.demand[k][l] : kNaN);
      out.responses.push_back(made ? t.exceeded[k][l] : kNaN);
    }
  }
  return out;
}

}  // namespace skewbridge::spectra
