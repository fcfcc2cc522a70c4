#include "spectra/fragility.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "solver/common/error.h"

namespace skewbridge::spectra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Phi(u) = erfc(-u / sqrt 2) / 2.
double NormalCdf(double u) { return 0.5 * std::erfc(-u / std::numbers::sqrt2); }

// ln Phi(u) and the inverse Mills ratio phi(u) / Phi(u) share Phi(u) and phi(u) = phi(-u):
// the probit terms of a point compute each once. Below u = -30, where erfc underflows, both
// take their asymptotic forms [Abramowitz and Stegun 26.2.12].
struct ProbitTail {
  double cdf;  // Phi(u), for u > -30
  double pdf;  // phi(u), when asked for
};

ProbitTail TailAt(double u, bool with_pdf) {
  ProbitTail t{u > -30.0 ? NormalCdf(u) : 0.0, 0.0};
  if (with_pdf) t.pdf = std::exp(-0.5 * u * u) / std::sqrt(2.0 * std::numbers::pi);
  return t;
}

// ln Phi(u) from TailAt(u); for u below -30 ln phi(u) - ln(-u) - ln(1 - 1/u^2 + 3/u^4).
double LogNormalCdf(double u, const ProbitTail& t) {
  if (u > -30.0) return std::log(t.cdf);
  const double u2 = u * u;
  return -0.5 * u2 - 0.5 * std::log(2.0 * std::numbers::pi) - std::log(-u) +
         std::log1p(-1.0 / u2 + 3.0 / (u2 * u2));
}

// phi(u) / Phi(u) from TailAt(u, true), stable for u far below 0.
double MillsLambda(double u, const ProbitTail& t) {
  if (u > -30.0) return t.pdf / t.cdf;
  const double u2 = u * u;
  return -u / (1.0 - 1.0 / u2 + 3.0 / (u2 * u2));
}

struct Point {
  double ln_x;
  double n;
  double z;
};

// Log-likelihood, gradient and Hessian in (a, b) of the probit model u = a + b ln x.
double Evaluate(const std::vector<Point>& pts, const Eigen::Vector2d& p, Eigen::Vector2d* g,
                Eigen::Matrix2d* h) {
  double l = 0.0;
  if (g != nullptr) g->setZero();
  if (h != nullptr) h->setZero();
  for (const Point& pt : pts) {
    const double u = p(0) + p(1) * pt.ln_x;
    // A point of one trial (a cell) has one outcome: the other's terms are 0 times a finite
    // number (|u| < 1e150, so u^2 does not overflow and every term below is finite), +0 or -0,
    // which leave every sum below with the same bits; they are not computed.
    if (pt.n == 1.0 && (pt.z == 0.0 || pt.z == 1.0) && std::abs(u) < 1e150) {
      const double s = pt.z == 1.0 ? u : -u;  // the outcome's argument: Phi(u) or Phi(-u)
      const ProbitTail ts = TailAt(s, g != nullptr);
      l += LogNormalCdf(s, ts);
      if (g == nullptr) continue;
      const double lam = MillsLambda(s, ts);
      // z = 1: du = lambda(u), d2u = -lambda(u) (u + lambda(u)); z = 0: du = -lambda(-u),
      // d2u = -lambda(-u) (lambda(-u) - u): the expressions of the general case below.
      const double du = pt.z == 1.0 ? lam : -lam;
      const double d2u = pt.z == 1.0 ? -lam * (u + lam) : -(lam * (lam - u));
      const Eigen::Vector2d j(1.0, pt.ln_x);
      *g += du * j;
      *h += d2u * j * j.transpose();
      continue;
    }
    // phi(-u) = phi(u): (-0.5 (-u)) (-u) rounds to the bits of (-0.5 u) u.
    const ProbitTail tp = TailAt(u, g != nullptr);
    ProbitTail tm = TailAt(-u, false);
    tm.pdf = tp.pdf;
    l += pt.z * LogNormalCdf(u, tp) + (pt.n - pt.z) * LogNormalCdf(-u, tm);
    if (g == nullptr) continue;
    // d ln Phi(u)/du = lambda(u); d ln Phi(-u)/du = -lambda(-u); second derivatives
    // -lambda(u) (u + lambda(u)) and -lambda(-u) (lambda(-u) - u).
    const double lp = MillsLambda(u, tp);
    const double lm = MillsLambda(-u, tm);
    const double du = pt.z * lp - (pt.n - pt.z) * lm;
    const double d2u = -pt.z * lp * (u + lp) - (pt.n - pt.z) * lm * (lm - u);
    const Eigen::Vector2d j(1.0, pt.ln_x);
    *g += du * j;
    *h += d2u * j * j.transpose();
  }
  return l;
}

LognormalFit Refused(std::string reason, std::int64_t trials, std::int64_t exceeded) {
  LognormalFit f;
  f.reason = std::move(reason);
  f.theta = f.beta = f.se_ln_theta = f.se_beta = f.cov_ln_theta_beta = f.log_likelihood = kNaN;
  f.trials = trials;
  f.exceeded = exceeded;
  return f;
}

// The extremes of the usable observations' im that the refusals read.
struct ImRange {
  double max_x_non;  // largest im with a non-exceedance
  double min_x_exc;  // smallest im with an exceedance
  double min_x;
  double max_x;
};

// FitLognormalMle from its pooled points (distinct ln x, ascending), the totals of trials and
// exceedances and the im range; `at_level(x)` gives the trials and exceedances at im == x.
template <class AtLevel>
LognormalFit FitPooled(const std::vector<Point>& pts, double n_total, double z_total,
                       const ImRange& range, const AtLevel& at_level) {
  const auto [max_x_non, min_x_exc, min_x, max_x] = range;
  const auto n_all = static_cast<std::int64_t>(n_total);
  const auto z_all = static_cast<std::int64_t>(z_total);
  if (pts.empty()) return Refused("no cell with a positive, finite IM", 0, 0);
  if (min_x == max_x) {
    return Refused(fmt::format("one stripe (IM = {:.6g}, {} of {} exceeded): a median and a "
                               "dispersion need at least two IM levels",
                               min_x, z_all, n_all),
                   n_all, z_all);
  }
  if (z_all == 0) {
    return Refused(fmt::format("no exceedance in {} cells: the median lies above the largest "
                               "IM, {:.6g}; P = 0 at every stripe",
                               n_all, max_x),
                   n_all, z_all);
  }
  if (z_all == n_all) {
    return Refused(fmt::format("exceeded in all {} cells: the median lies below the smallest "
                               "IM, {:.6g}; P = 1 at every stripe",
                               n_all, min_x),
                   n_all, z_all);
  }
  if (min_x_exc > max_x_non) {
    return Refused(fmt::format("the stripes separate (no exceedance up to IM = {:.6g}, every "
                               "cell exceeded from IM = {:.6g} on): beta tends to 0 and the "
                               "median is anywhere between them",
                               max_x_non, min_x_exc),
                   n_all, z_all);
  }
  if (min_x_exc == max_x_non) {
    // One IM level holds both outcomes; below it none exceeded, above it all: the steepest
    // curve through that level fits best, and the words say only what lies on each side.
    const auto [n_at, z_at] = at_level(min_x_exc);
    std::string sides;
    if (min_x < min_x_exc) sides += ", none below it";
    if (max_x > min_x_exc) sides += ", every cell above it";
    return Refused(fmt::format("the stripes separate at IM = {:.6g} ({} of {} exceeded there{}): "
                               "beta tends to 0 and the median is at that level",
                               min_x_exc, static_cast<std::int64_t>(z_at),
                               static_cast<std::int64_t>(n_at), sides),
                   n_all, z_all);
  }

  // Start at the weighted mean and spread of ln x, then Newton with step halving; the probit
  // log-likelihood is concave in (a, b), and without separation its maximum is finite.
  double mean = 0.0, var = 0.0;
  for (const Point& p : pts) mean += p.n * p.ln_x;
  mean /= n_total;
  for (const Point& p : pts) var += p.n * (p.ln_x - mean) * (p.ln_x - mean);
  const double beta0 = std::max(std::sqrt(var / n_total), 0.1);
  Eigen::Vector2d p(-mean / beta0, 1.0 / beta0);
  Eigen::Vector2d g;
  Eigen::Matrix2d h;
  double l = Evaluate(pts, p, &g, &h);
  int it = 0;
  constexpr int kMaxIterations = 200;
  for (; it < kMaxIterations; ++it) {
    const Eigen::Vector2d step = h.ldlt().solve(-g);
    if (!step.allFinite()) break;
    double t = 1.0;
    Eigen::Vector2d next = p + step;
    double l_next = Evaluate(pts, next, nullptr, nullptr);
    while (!(l_next >= l - 1e-12 * std::abs(l)) && t > 1e-10) {
      t *= 0.5;
      next = p + t * step;
      l_next = Evaluate(pts, next, nullptr, nullptr);
    }
    p = next;
    l = Evaluate(pts, p, &g, &h);
    // Converged when the Newton decrement is at the rounding level of l.
    if (std::abs(g.dot(step)) < 1e-14 * std::max(1.0, std::abs(l)) ||
        t * step.norm() < 1e-13 * std::max(1.0, p.norm())) {
      ++it;
      break;
    }
  }
  if (!(p(1) > 0.0) || !p.allFinite()) {
    return Refused(
        "the fraction exceeded does not grow with the IM (the fitted 1 / beta is "
        "not positive)",
        n_all, z_all);
  }
  LognormalFit fit;
  fit.trials = n_all;
  fit.exceeded = z_all;
  fit.iterations = it;
  fit.log_likelihood = l;
  const double a = p(0), b = p(1);
  fit.theta = std::exp(-a / b);
  fit.beta = 1.0 / b;
  // Cov(a, b) = (-H)^-1; (ln theta, beta) = (-a / b, 1 / b), Jacobian J, Cov = J C J^T.
  const Eigen::Matrix2d cov_ab = (-h).inverse();
  Eigen::Matrix2d jac;
  jac << -1.0 / b, a / (b * b), 0.0, -1.0 / (b * b);
  const Eigen::Matrix2d cov = jac * cov_ab * jac.transpose();
  fit.se_ln_theta = std::sqrt(cov(0, 0));
  fit.se_beta = std::sqrt(cov(1, 1));
  fit.cov_ln_theta_beta = cov(0, 1);
  return fit;
}

}  // namespace

double LognormalFragility(double im, double theta, double beta) {
  return NormalCdf(std::log(im / theta) / beta);
}

LognormalFit FitLognormalMle(std::span<const double> im, std::span<const double> trials,
                             std::span<const double> exceeded) {
  SB_DEMAND(im.size() == trials.size() && im.size() == exceeded.size(),
            "fragility data of unequal lengths");
  std::vector<Point> pts;
  double n_total = 0.0, z_total = 0.0;
  double max_x_non = -kInf;  // largest im with a non-exceedance
  double min_x_exc = kInf;   // smallest im with an exceedance
  double min_x = kInf, max_x = -kInf;
  for (std::size_t i = 0; i < im.size(); ++i) {
    if (!(std::isfinite(im[i]) && im[i] > 0.0) || !(trials[i] > 0.0)) continue;
    SB_DEMAND(exceeded[i] >= 0.0 && exceeded[i] <= trials[i], "exceedances outside 0..trials");
    pts.push_back({std::log(im[i]), trials[i], exceeded[i]});
    n_total += trials[i];
    z_total += exceeded[i];
    if (exceeded[i] < trials[i]) max_x_non = std::max(max_x_non, im[i]);
    if (exceeded[i] > 0.0) min_x_exc = std::min(min_x_exc, im[i]);
    min_x = std::min(min_x, im[i]);
    max_x = std::max(max_x, im[i]);
  }
  // Observations at one IM are one binomial point, their trials and exceedances summed: the
  // likelihood is the same function, and a stripe of R records costs one term in place of R.
  std::sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) { return a.ln_x < b.ln_x; });
  std::size_t distinct = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (distinct > 0 && pts[distinct - 1].ln_x == pts[i].ln_x) {
      pts[distinct - 1].n += pts[i].n;
      pts[distinct - 1].z += pts[i].z;
    } else {
      pts[distinct++] = pts[i];
    }
  }
  pts.resize(distinct);
  return FitPooled(pts, n_total, z_total, {max_x_non, min_x_exc, min_x, max_x}, [&](double level) {
    // The trials and exceedances of the observations at im == level.
    double n_at = 0.0, z_at = 0.0;
    for (std::size_t i = 0; i < im.size(); ++i) {
      if (im[i] == level && trials[i] > 0.0) {
        n_at += trials[i];
        z_at += exceeded[i];
      }
    }
    return std::pair<double, double>(n_at, z_at);
  });
}

ResampledLognormalFits::ResampledLognormalFits(std::span<const double> im,
                                               std::span<const double> exceeded)
    : im_(im.begin(), im.end()), exceeded_(exceeded.begin(), exceeded.end()) {
  SB_DEMAND(im.size() == exceeded.size(), "fragility data of unequal lengths");
  // Each usable observation's ln im, as FitLognormalMle takes it, and the distinct values in
  // ascending order: the points FitLognormalMle pools (equal ln x, not equal im, are one point).
  std::vector<double> ln(im.size());
  level_.assign(im.size(), kSkipped);
  for (std::size_t i = 0; i < im.size(); ++i) {
    if (!(std::isfinite(im[i]) && im[i] > 0.0)) continue;
    if (exceeded[i] != 0.0 && exceeded[i] != 1.0) whole_ = false;
    ln[i] = std::log(im[i]);
    ln_im_.push_back(ln[i]);
    level_[i] = 0;
  }
  std::sort(ln_im_.begin(), ln_im_.end());
  ln_im_.erase(std::unique(ln_im_.begin(), ln_im_.end()), ln_im_.end());
  for (std::size_t i = 0; i < im.size(); ++i) {
    if (level_[i] == kSkipped) continue;
    level_[i] = static_cast<std::uint32_t>(std::lower_bound(ln_im_.begin(), ln_im_.end(), ln[i]) -
                                           ln_im_.begin());
  }
}

LognormalFit ResampledLognormalFits::Fit(std::span<const std::uint32_t> draws) const {
  SB_DEMAND(draws.size() == im_.size(), "one draw count per observation");
  if (!whole_) {  // sums of other exceedances depend on their order: FitLognormalMle itself
    std::vector<double> x, ones, e;
    for (std::size_t i = 0; i < im_.size(); ++i) {
      for (std::uint32_t k = 0; k < draws[i]; ++k) {
        x.push_back(im_[i]);
        e.push_back(exceeded_[i]);
      }
    }
    ones.assign(x.size(), 1.0);
    return FitLognormalMle(x, ones, e);
  }
  // FitLognormalMle's sums, over the observations each repeated draws[i] times: every term is
  // a whole number (one trial, 0 or 1 exceedance), so each sum is exact in any order.
  std::vector<double> n(ln_im_.size(), 0.0), z(ln_im_.size(), 0.0);
  double n_total = 0.0, z_total = 0.0;
  ImRange range{-kInf, kInf, kInf, -kInf};
  for (std::size_t i = 0; i < im_.size(); ++i) {
    if (draws[i] == 0 || level_[i] == kSkipped) continue;
    const double d = static_cast<double>(draws[i]);
    const double e = d * exceeded_[i];
    n[level_[i]] += d;
    z[level_[i]] += e;
    n_total += d;
    z_total += e;
    if (exceeded_[i] < 1.0) range.max_x_non = std::max(range.max_x_non, im_[i]);
    if (exceeded_[i] > 0.0) range.min_x_exc = std::min(range.min_x_exc, im_[i]);
    range.min_x = std::min(range.min_x, im_[i]);
    range.max_x = std::max(range.max_x, im_[i]);
  }
  std::vector<Point> pts;
  for (std::size_t g = 0; g < ln_im_.size(); ++g) {
    if (n[g] > 0.0) pts.push_back({ln_im_[g], n[g], z[g]});
  }
  return FitPooled(pts, n_total, z_total, range, [&](double level) {
    double n_at = 0.0, z_at = 0.0;
    for (std::size_t i = 0; i < im_.size(); ++i) {
      if (draws[i] > 0 && im_[i] == level) {
        n_at += static_cast<double>(draws[i]);
        z_at += static_cast<double>(draws[i]) * exceeded_[i];
      }
    }
    return std::pair<double, double>(n_at, z_at);
  });
}

CloudFit FitCloud(std::span<const double> im, std::span<const double> demand_over_capacity) {
  SB_DEMAND(im.size() == demand_over_capacity.size(), "cloud data of unequal lengths");
  CloudFit fit;
  std::vector<double> x, y;
  for (std::size_t i = 0; i < im.size(); ++i) {
    const double d = demand_over_capacity[i];
    if (std::isfinite(im[i]) && im[i] > 0.0 && std::isfinite(d) && d > 0.0) {
      x.push_back(std::log(im[i]));
      y.push_back(std::log(d));
    } else {
      ++fit.excluded;
    }
  }
  fit.n = static_cast<std::int64_t>(x.size());
  auto refuse = [&fit](std::string why) {
    fit.reason = std::move(why);
    fit.intercept = fit.slope = fit.sigma = fit.theta = fit.beta = kNaN;
    return fit;
  };
  if (x.size() < 3) {
    return refuse(
        fmt::format("{} cells with a positive demand and IM: a line and its "
                    "dispersion need at least 3",
                    x.size()));
  }
  const double n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= n;
  my /= n;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (!(sxx > 0.0)) return refuse("every cell has the same IM: no slope");
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  double ssr = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - fit.intercept - fit.slope * x[i];
    ssr += r * r;
  }
  fit.sigma = std::sqrt(ssr / (n - 2.0));
  if (!(fit.slope > 0.0)) {
    const double slope = fit.slope;
    refuse(fmt::format("the demand does not grow with the IM (slope {:.4g})", slope));
    fit.slope = slope;
    return fit;
  }
  fit.theta = std::exp(-fit.intercept / fit.slope);
  fit.beta = fit.sigma / fit.slope;
  return fit;
}

}  // namespace skewbridge::spectra
