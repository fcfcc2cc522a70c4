#include "spectra/ida.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Core>

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

namespace {

// phi(z) / (1 - Phi(z)), the hazard of the standard normal (its inverse Mills ratio), with the
// asymptotic series where 1 - Phi underflows.
double NormalHazard(double z) {
  if (z > 30.0) return z + 1.0 / z - 2.0 / (z * z * z);
  const double q = 0.5 * std::erfc(z / std::sqrt(2.0));
  return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi) / q;
}

// ln(1 - Phi(z)) of the standard normal.
double LogNormalSurvival(double z) {
  if (z > 30.0) return -0.5 * z * z - std::log(z * std::sqrt(2.0 * std::numbers::pi));
  return std::log(0.5 * std::erfc(z / std::sqrt(2.0)));
}

// The log-likelihood, without its constants, of a normal (mu, sigma = exp(s)) over the
// observed `y` and the right-censored `u` (each known only to exceed u_j).
double CensoredLogLikelihood(std::span<const double> y, std::span<const double> u, double mu,
                             double s) {
  const double sigma = std::exp(s);
  double ll = 0.0;
  for (double v : y) ll += -s - 0.5 * (v - mu) * (v - mu) / (sigma * sigma);
  for (double v : u) ll += LogNormalSurvival((v - mu) / sigma);
  return ll;
}

}  // namespace

CapacityFit FitCapacities(std::span<const double> capacities, std::span<const double> censor_at) {
  SB_DEMAND(censor_at.empty() || censor_at.size() == capacities.size(),
            "FitCapacities: censor_at must be empty or one per capacity");
  CapacityFit f;
  std::vector<double> logs, cens;
  for (std::size_t i = 0; i < capacities.size(); ++i) {
    const double c = capacities[i];
    if (std::isnan(c)) continue;
    if (std::isinf(c)) {
      ++f.censored;
      const double at = censor_at.empty() ? kNaN : censor_at[i];
      if (at > 0.0 && std::isfinite(at)) cens.push_back(std::log(at));
    } else if (c > 0.0) {
      logs.push_back(std::log(c));
    }
  }
  f.n = static_cast<std::int64_t>(logs.size());
  const std::int64_t total = f.n + f.censored;
  if (f.censored > static_cast<std::int64_t>(cens.size())) {
    f.theta = f.beta = kNaN;
    f.reason = fmt::format(
        "{} of {} records never reach the limit state and the highest intensity run is not "
        "known for {} of them: no censored fit",
        f.censored, total, f.censored - static_cast<std::int64_t>(cens.size()));
    return f;
  }
  if (logs.size() < 2) {
    f.theta = f.beta = kNaN;
    f.reason = fmt::format(
        "{} finite capacities ({} of {} records never reach the limit state up to "
        "ida.max_im): a fit needs 2; raise ida.max_im",
        logs.size(), f.censored, total);
    return f;
  }
  double mean = 0.0;
  for (double x : logs) mean += x;
  mean /= static_cast<double>(logs.size());
  double ss = 0.0;
  for (double x : logs) ss += (x - mean) * (x - mean);
  if (f.censored == 0) {
    // The method of moments: theta the geometric mean, beta with n - 1 (the uncensored
    // maximum-likelihood beta is this times sqrt((n - 1) / n)).
    f.theta = std::exp(mean);
    f.beta = std::sqrt(ss / static_cast<double>(logs.size() - 1));
    return f;
  }
  if (ss <= 0.0) {
    f.theta = f.beta = kNaN;
    f.reason = fmt::format(
        "the {} finite capacities are all equal and {} records are censored: the censored "
        "likelihood has no maximum (beta -> 0)",
        logs.size(), f.censored);
    return f;
  }
  // Maximum likelihood with right-censored capacities [e.g. Klein and Moeschberger 2003,
  // Survival Analysis, §3.5]: each capacity contributes the lognormal density, each censored
  // record 1 - Phi((ln u_j - mu) / sigma), u_j its highest intensity run. Newton's method on
  // (mu, s = ln sigma) with step halving, from the moments of the finite capacities.
  double mu = mean, s = 0.5 * std::log(ss / static_cast<double>(logs.size()));
  double ll = CensoredLogLikelihood(logs, cens, mu, s);
  bool converged = false;
  for (int it = 0; it < 200 && !converged; ++it) {
    const double sigma = std::exp(s);
    Eigen::Vector2d g = Eigen::Vector2d::Zero();
    Eigen::Matrix2d h = Eigen::Matrix2d::Zero();
    for (double v : logs) {
      const double r = (v - mu) / sigma;
      g(0) += r / sigma;
      g(1) += r * r - 1.0;
      h(0, 0) -= 1.0 / (sigma * sigma);
      h(0, 1) -= 2.0 * r / sigma;
      h(1, 1) -= 2.0 * r * r;
    }
    for (double v : cens) {
      const double z = (v - mu) / sigma;
      const double m = NormalHazard(z), dm = m * (m - z);
      g(0) += m / sigma;
      g(1) += m * z;
      h(0, 0) -= dm / (sigma * sigma);
      h(0, 1) -= (dm * z + m) / sigma;
      h(1, 1) -= z * (dm * z + m);
    }
    h(1, 0) = h(0, 1);
    // Newton's step where the Hessian is negative definite, else the gradient's.
    Eigen::Vector2d step = g;
    const Eigen::LLT<Eigen::Matrix2d> llt(-h);
    if (llt.info() == Eigen::Success) step = llt.solve(g);
    double t = 1.0;
    for (int k = 0; k < 60; ++k, t *= 0.5) {
      const double mu1 = mu + t * step(0), s1 = s + t * step(1);
      const double ll1 = CensoredLogLikelihood(logs, cens, mu1, s1);
      if (ll1 >= ll) {
        converged = std::abs(t * step(0)) < 1e-13 && std::abs(t * step(1)) < 1e-13;
        mu = mu1;
        s = s1;
        ll = ll1;
        break;
      }
      if (k == 59) converged = true;  // no ascent left at double precision
    }
    if (g.lpNorm<Eigen::Infinity>() < 1e-12) converged = true;
  }
  if (!converged || !std::isfinite(mu) || !std::isfinite(s)) {
    f.theta = f.beta = kNaN;
    f.reason = fmt::format(
        "the censored likelihood of {} capacities and {} censored records "
        "did not converge",
        logs.size(), f.censored);
    return f;
  }
  f.theta = std::exp(mu);
  f.beta = std::exp(s);
  f.note = fmt::format(
      "{} of {} records never reach the limit state up to their highest run: maximum-likelihood "
      "fit with right-censored capacities (beta with n)",
      f.censored, total);
  return f;
}

IdaEvaluator::IdaEvaluator(std::unique_ptr<LimitStateEvaluator> inner, const CellGrid& grid)
    : CellEvaluator(inner->policies()),
      inner_(std::move(inner)),
      ida_(grid.ida),
      limit_states_(grid.limit_states),
      im_unit_(IntensityUnit(grid.im)),
      max_scale_(grid.im.max_scale) {
  SB_DEMAND(inner_->record_scaling() != nullptr,
            "an [ida] sweep scales its records to an intensity ([records] scale_to)");
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
  inner_count_ = responses.size();

  // Every response is kept whatever the search's status: a failed run ends the search, and
  // the runs made before it, with the capacities they bracket, are the cell's result.
  using V = const CellValues&;
  ResponseTable<CellValues>& t = table_;
  t.AddAlways({"im_unscaled", im_unit_, "the record's own intensity measure at the cell's T1"},
              [](V v) { return v.own; });
  t.AddAlways({"ida_runs", "1", "runs made by the hunt-and-fill search"},
              [](V v) { return static_cast<double>(v.trace.im.size()); });
  for (std::size_t l = 0; l < limit_states_.size(); ++l) {
    const std::string& name = limit_states_[l].name;
    t.AddAlways(
        {"ida_capacity_" + name, im_unit_,
         "lowest intensity of a run that exceeds " + name + " (inf: none up to ida.max_im)"},
        [l](V v) { return v.trace.capacity[l].im; });
    t.AddAlways({"ida_capacity_below_" + name, im_unit_,
                 "highest intensity below it of a run that does not exceed " + name + " (0: none)"},
                [l](V v) { return v.trace.capacity[l].below; });
    t.AddAlways(
        {"ida_capacity_scale_" + name, "1", "scale factor on the record at ida_capacity_" + name},
        [l](V v) { return v.trace.capacity[l].im / v.own; });
    t.AddAlways({"ida_scaled_too_far_" + name, "1",
                 "1 when ida_capacity_scale_" + name +
                     " > records.max_scale, else 0 (always 0 without it)"},
                [l, max_scale = max_scale_](V v) {
                  const double im = v.trace.capacity[l].im;
                  return max_scale > 0.0 && std::isfinite(im) && im / v.own > max_scale ? 1.0 : 0.0;
                });
  }
  for (int k = 0; k < ida_.max_runs; ++k) {
    const std::string s = RunSuffix(k);
    const std::string run = fmt::format("run {} of the search (NaN when not made)", k);
    const auto made = [k](V v) { return static_cast<std::size_t>(k) < v.trace.im.size(); };
    t.AddAlways({"ida_im" + s, im_unit_, "intensity of " + run},
                [k, made](V v) { return made(v) ? v.trace.im[k] : kNaN; });
    t.AddAlways({"ida_scale" + s, "1", "scale factor on the record in " + run},
                [k, made](V v) { return made(v) ? v.trace.im[k] / v.own : kNaN; });
    for (std::size_t l = 0; l < limit_states_.size(); ++l) {
      const std::string& name = limit_states_[l].name;
      t.AddAlways({"ida_demand_" + name + s, demand_units_[l], name + " demand in " + run},
                  [k, l, made](V v) { return made(v) ? v.trace.demand[k][l] : kNaN; });
      t.AddAlways({"ida_exceeded_" + name + s, "1", "1 when " + run + " exceeds " + name},
                  [k, l, made](V v) { return made(v) ? v.trace.exceeded[k][l] : kNaN; });
    }
  }
}

CellOutcome IdaEvaluator::Evaluate(std::span<const std::size_t> axis_index) const {
  const double own = inner_->record_scaling()->UnscaledIntensity(axis_index);
  SB_DEMAND(own > 0.0 && std::isfinite(own), "an IDA cell's record has no intensity to scale");
  CellOutcome out;
  auto run = [&](double im) {
    CellOutcome o = inner_->EvaluateScaled(axis_index, im / own);
    out.stats.events += o.stats.events;
    out.stats.steps += o.stats.steps;
    out.stats.wall_s += o.stats.wall_s;
    // A run whose responses are not the inner evaluator's fails with that status (it ends the
    // search): its demands are never read.
    const bool complete = CheckResponseCount(o, inner_count_);
    IdaPoint p;
    p.ok = o.status == kStatusOk;
    p.status = o.status;
    p.status_text = fmt::format("at {} = {:.6g} {}: {}", "IM", im, im_unit_, o.status_text);
    if (!complete) return p;
    for (std::size_t l = 0; l < limit_states_.size(); ++l) {
      p.demand.push_back(o.responses[demand_columns_[l]]);
      p.exceeded.push_back(o.responses[exceeded_columns_[l]]);
    }
    return p;
  };
  const IdaTrace t = HuntAndFill(ida_, limit_states_.size(), run);
  out.status = t.status;
  out.status_text = t.status_text;
  out.responses = table_.Values({own, t}, true);
  return out;
}

}  // namespace skewbridge::spectra
