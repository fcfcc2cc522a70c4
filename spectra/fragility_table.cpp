#include "spectra/fragility_table.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "solver/common/error.h"
#include "spectra/fragility.h"

namespace skewbridge::spectra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The two-sided 95 % normal quantile.
constexpr double kZ95 = 1.959963984540054;
// A bootstrap interval needs this many successful refits.
constexpr std::int64_t kMinBootstrapFits = 20;

// The p-quantile of sorted values, linear between order statistics (numpy's default).
double Quantile(const std::vector<double>& sorted, double p) {
  const double h = p * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

}  // namespace

FragilityTable FitFragilityOverCells(const CellGrid& grid, const std::string& stripe_axis,
                                     const FragilityCells& cells, const std::string& no_cloud,
                                     int bootstrap_resamples, std::uint64_t bootstrap_seed,
                                     const FitShare& share) {
  const std::uint64_t n_cells = grid.CellCount();
  SB_DEMAND(
      cells.im.size() == n_cells && cells.exceeded.size() == n_cells &&
          cells.usable.size() == n_cells &&
          (cells.demand_over_capacity.empty() || cells.demand_over_capacity.size() == n_cells) &&
          (cells.excluded.empty() || cells.excluded.size() == n_cells),
      "fragility inputs do not match the grid");
  FragilityTable t;
  t.stripe_axis = stripe_axis;
  t.bootstrap_resamples = bootstrap_resamples;
  t.bootstrap_seed = bootstrap_seed;
  std::vector<std::size_t> combo_axes;
  std::ptrdiff_t record_k = -1, stripe_k = -1;
  for (std::size_t k = 0; k < grid.axes.size(); ++k) {
    if (grid.axes[k].key == "record") {
      record_k = static_cast<std::ptrdiff_t>(k);
    } else if (grid.axes[k].key == stripe_axis) {
      stripe_k = static_cast<std::ptrdiff_t>(k);
    } else {
      combo_axes.push_back(k);
      t.axis_order.push_back(grid.axes[k].key);
      t.shape.push_back(grid.axes[k].Size());
    }
  }
  std::size_t combos = 1;
  for (std::size_t s : t.shape) combos *= s;
  t.stripes = stripe_k >= 0 ? grid.axes[static_cast<std::size_t>(stripe_k)].Size() : 0;
  const std::size_t records =
      record_k >= 0 ? grid.axes[static_cast<std::size_t>(record_k)].Size() : 0;

  // The usable cells of every combination, with their record and stripe.
  struct Cell {
    std::uint64_t id;
    std::size_t record;
    std::size_t stripe;
  };
  std::vector<std::vector<Cell>> members(combos);
  if (!cells.excluded.empty()) {
    t.n_excluded.assign(combos, 0);
    t.stripe_excluded.assign(combos * t.stripes, 0);
  }
  for (std::uint64_t c = 0; c < n_cells; ++c) {
    if (!cells.usable[c] || std::isnan(cells.exceeded[c])) continue;
    const std::vector<std::size_t> index = grid.AxisIndex(c);
    std::size_t combo = 0;
    for (std::size_t k : combo_axes) combo = combo * grid.axes[k].Size() + index[k];
    if (!cells.excluded.empty() && cells.excluded[c]) {
      ++t.n_excluded[combo];
      if (stripe_k >= 0) {
        ++t.stripe_excluded[combo * t.stripes + index[static_cast<std::size_t>(stripe_k)]];
      }
      continue;
    }
    members[combo].push_back({c, record_k >= 0 ? index[static_cast<std::size_t>(record_k)] : 0,
                              stripe_k >= 0 ? index[static_cast<std::size_t>(stripe_k)] : 0});
  }

  auto resize = [combos](auto&... v) { (v.assign(combos, {}), ...); };
  resize(t.theta, t.beta, t.se_ln_theta, t.se_beta, t.cov_ln_theta_beta, t.theta_lo, t.theta_hi,
         t.beta_lo, t.beta_hi, t.boot_theta_lo, t.boot_theta_hi, t.boot_beta_lo, t.boot_beta_hi,
         t.boot_used, t.n_cells, t.n_exceeded, t.reason, t.cloud_n, t.cloud_excluded,
         t.cloud_intercept, t.cloud_slope, t.cloud_sigma, t.cloud_theta, t.cloud_beta,
         t.cloud_reason);
  t.stripe_im.assign(combos * t.stripes, kNaN);
  t.stripe_n.assign(combos * t.stripes, 0);
  t.stripe_exceeded.assign(combos * t.stripes, 0);

  for (std::size_t combo = 0; combo < combos; ++combo) {
    const std::vector<Cell>& m = members[combo];
    std::vector<double> im, ones(m.size(), 1.0), z, dc;
    for (const Cell& cell : m) {
      im.push_back(cells.im[cell.id]);
      z.push_back(cells.exceeded[cell.id]);
      if (!cells.demand_over_capacity.empty()) dc.push_back(cells.demand_over_capacity[cell.id]);
    }
    // Counts per stripe, and the stripe's IM (the geometric mean of its cells').
    if (t.stripes > 0) {
      std::vector<double> log_sum(t.stripes, 0.0);
      for (std::size_t i = 0; i < m.size(); ++i) {
        const std::size_t s = combo * t.stripes + m[i].stripe;
        ++t.stripe_n[s];
        t.stripe_exceeded[s] += z[i] > 0.5 ? 1 : 0;
        log_sum[m[i].stripe] += std::log(im[i]);
      }
      for (std::size_t s = 0; s < t.stripes; ++s) {
        const std::size_t at = combo * t.stripes + s;
        if (t.stripe_n[at] > 0) {
          t.stripe_im[at] = std::exp(log_sum[s] / static_cast<double>(t.stripe_n[at]));
        }
      }
    }
    if (!share.Mine(combo)) continue;  // another rank fits it
    const LognormalFit fit = FitLognormalMle(im, ones, z);
    t.theta[combo] = fit.theta;
    t.beta[combo] = fit.beta;
    t.se_ln_theta[combo] = fit.se_ln_theta;
    t.se_beta[combo] = fit.se_beta;
    t.cov_ln_theta_beta[combo] = fit.cov_ln_theta_beta;
    t.theta_lo[combo] = fit.theta * std::exp(-kZ95 * fit.se_ln_theta);
    t.theta_hi[combo] = fit.theta * std::exp(kZ95 * fit.se_ln_theta);
    t.beta_lo[combo] = fit.beta - kZ95 * fit.se_beta;
    t.beta_hi[combo] = fit.beta + kZ95 * fit.se_beta;
    t.n_cells[combo] = fit.trials;
    t.n_exceeded[combo] = fit.exceeded;
    t.reason[combo] = fit.reason;

    // The bootstrap over records: whole records (all their stripes) drawn with replacement.
    t.boot_theta_lo[combo] = t.boot_theta_hi[combo] = kNaN;
    t.boot_beta_lo[combo] = t.boot_beta_hi[combo] = kNaN;
    if (fit.reason.empty() && records > 1 && bootstrap_resamples > 0) {
      std::vector<std::vector<std::size_t>> by_record(records);
      for (std::size_t i = 0; i < m.size(); ++i) by_record[m[i].record].push_back(i);
      std::seed_seq seq{bootstrap_seed, static_cast<std::uint64_t>(combo)};
      std::mt19937_64 gen(seq);
      std::uniform_int_distribution<std::size_t> pick(0, records - 1);
      // A resample is how many times it draws each cell; its fit is FitLognormalMle of the
      // cells so repeated (ResampledLognormalFits), without a logarithm or a sort per resample.
      const ResampledLognormalFits resampled(im, z);
      std::vector<std::uint32_t> draws(m.size());
      std::vector<double> thetas, betas;
      for (int b = 0; b < bootstrap_resamples; ++b) {
        std::fill(draws.begin(), draws.end(), 0u);
        for (std::size_t r = 0; r < records; ++r) {
          for (std::size_t i : by_record[pick(gen)]) ++draws[i];
        }
        const LognormalFit f = resampled.Fit(draws);
        if (f.reason.empty()) {
          thetas.push_back(f.theta);
          betas.push_back(f.beta);
        }
      }
      t.boot_used[combo] = static_cast<std::int64_t>(thetas.size());
      if (t.boot_used[combo] >= kMinBootstrapFits) {
        std::sort(thetas.begin(), thetas.end());
        std::sort(betas.begin(), betas.end());
        t.boot_theta_lo[combo] = Quantile(thetas, 0.025);
        t.boot_theta_hi[combo] = Quantile(thetas, 0.975);
        t.boot_beta_lo[combo] = Quantile(betas, 0.025);
        t.boot_beta_hi[combo] = Quantile(betas, 0.975);
      }
    }

    if (dc.empty()) {
      t.cloud_reason[combo] = no_cloud;
      t.cloud_n[combo] = 0;
      t.cloud_excluded[combo] = static_cast<std::int64_t>(m.size());
      t.cloud_intercept[combo] = t.cloud_slope[combo] = t.cloud_sigma[combo] = kNaN;
      t.cloud_theta[combo] = t.cloud_beta[combo] = kNaN;
    } else {
      const CloudFit cloud = FitCloud(im, dc);
      t.cloud_reason[combo] = cloud.reason;
      t.cloud_n[combo] = cloud.n;
      t.cloud_excluded[combo] = cloud.excluded;
      t.cloud_intercept[combo] = cloud.intercept;
      t.cloud_slope[combo] = cloud.slope;
      t.cloud_sigma[combo] = cloud.sigma;
      t.cloud_theta[combo] = cloud.theta;
      t.cloud_beta[combo] = cloud.beta;
    }
  }
  return t;
}

}  // namespace skewbridge::spectra
