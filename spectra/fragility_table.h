#pragma once
/// @file
/// The fragility functions of one limit state over a sweep's cells, per combination of the axes
/// other than the record axis and the intensity (stripe) axis: the maximum-likelihood lognormal
/// fit with its standard errors, a bootstrap over the records, the counts per stripe and the
/// cloud fit of ln(demand / capacity) on ln(IM) (spectra/fragility.h; docs/hdf5-layout.md).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "spectra/grid.h"

namespace skewbridge::spectra {

/// The bootstrap's defaults: resamples of the records, and the seed of its generator.
inline constexpr int kBootstrapResamples = 200;
inline constexpr std::uint64_t kBootstrapSeed = 20150301;

/// Per-cell inputs of one limit state, each indexed by the row-major cell index of the grid.
struct FragilityCells {
  std::span<const double> im;                    ///< intensity measure of the cell (> 0)
  std::span<const double> exceeded;              ///< 0, 1, or NaN (failed)
  std::span<const double> demand_over_capacity;  ///< D / C of the cloud fit; empty: none
  std::span<const std::uint8_t> usable;          ///< 1 when done with status ok
  /// 1 for a usable cell that the fits leave out (scaled beyond [records] max_scale with
  /// beyond_max_scale = "exclude"), counted per combination and stripe; empty: none.
  std::span<const std::uint8_t> excluded;
};

/// One limit state's fragility table; per-combination arrays are row-major over `shape`, the
/// stripe arrays [combination][stripe].
struct FragilityTable {
  std::string stripe_axis;              ///< the IM axis whose values are the stripes, or ""
  std::vector<std::string> axis_order;  ///< the combination axes, in cube order
  std::vector<std::size_t> shape;       ///< their sizes ({} for one combination)
  std::size_t stripes = 0;              ///< size of the stripe axis (0 without one)
  int bootstrap_resamples = 0;          ///< resamples drawn per combination
  std::uint64_t bootstrap_seed = 0;     ///< seed of the generator (std::mt19937_64)
  std::vector<double> theta, beta;      ///< maximum-likelihood median (IM unit) and dispersion
  std::vector<double> se_ln_theta, se_beta, cov_ln_theta_beta;  ///< observed information
  std::vector<double> theta_lo, theta_hi;            ///< 95 %: exp(ln theta -/+ 1.96 se_ln_theta)
  std::vector<double> beta_lo, beta_hi;              ///< 95 %: beta -/+ 1.96 se_beta
  std::vector<double> boot_theta_lo, boot_theta_hi;  ///< 2.5 and 97.5 % of the bootstrap
  std::vector<double> boot_beta_lo, boot_beta_hi;
  std::vector<std::int64_t> boot_used;            ///< resamples that gave a fit
  std::vector<std::int64_t> n_cells, n_exceeded;  ///< cells used and exceedances among them
  std::vector<std::string> reason;                ///< "" or why theta and beta are NaN
  std::vector<double> stripe_im;                  ///< geometric mean IM of the stripe's cells
  std::vector<std::int64_t> stripe_n, stripe_exceeded;
  std::vector<std::int64_t> cloud_n, cloud_excluded;
  std::vector<double> cloud_intercept, cloud_slope, cloud_sigma, cloud_theta, cloud_beta;
  std::vector<std::string> cloud_reason;  ///< "" or why the cloud fit is NaN
  /// Usable cells left out of every fit (FragilityCells::excluded), per combination and per
  /// [combination][stripe]; empty when no cell is marked for exclusion (no such rule).
  std::vector<std::int64_t> n_excluded, stripe_excluded;
};

/// Which combinations of a limit state are fitted here, when the ranks of a sweep share the
/// fits: combination c is (its point fit, cloud fit and bootstrap) when
/// (first_job + c) % ranks == rank. The others keep only their counts per stripe (and of
/// excluded cells) until the rank that fitted them hands them over.
struct FitShare {
  int rank = 0;               ///< this rank
  int ranks = 1;              ///< ranks sharing the work
  std::size_t first_job = 0;  ///< jobs of the limit states before this one
  /// Whether combination `combo` is fitted on this rank.
  bool Mine(std::size_t combo) const {
    return (first_job + combo) % static_cast<std::size_t>(ranks) == static_cast<std::size_t>(rank);
  }
};

/// Fits one limit state over the cells of `grid`: for every combination of the axes other than
/// `record` and `stripe_axis`, FitLognormalMle over its usable cells (one trial each, so
/// stripes and clouds alike), FitCloud over D / C when given (else `no_cloud` as the reason),
/// and a percentile bootstrap that resamples the records with replacement (no bootstrap
/// without a record axis). Deterministic: the generator is seeded per combination. A cell
/// marked in `cells.excluded` enters no fit, count or stripe; it is counted in n_excluded.
/// `share`: only the combinations it names are fitted (every one by default); the bits of a
/// fit do not depend on the share.
/// @pre every span of `cells` has grid.CellCount() entries (demand_over_capacity, excluded:
/// or none)
FragilityTable FitFragilityOverCells(const CellGrid& grid, const std::string& stripe_axis,
                                     const FragilityCells& cells, const std::string& no_cloud,
                                     int bootstrap_resamples = kBootstrapResamples,
                                     std::uint64_t bootstrap_seed = kBootstrapSeed,
                                     const FitShare& share = {});

}  // namespace skewbridge::spectra
