#pragma once
/// @file
/// The robustness grid of the event-driven integrator: the corners of the subsystem's parameter
/// space where pounding is most intense (closed and small joints, plastic to elastic impacts,
/// friction up to 0.6, stiff to soft substructures) [docs/theory.md §6]. Shared by the test (a
/// seeded sample, with time-stepping as the second method) and the benchmark program (the whole
/// grid).

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/builders.h"
#include "spectra/point.h"

namespace skewbridge::robustness {

/// The axes of the grid (every combination is one cell).
struct GridAxes {
  std::vector<double> Pi_delta = {0.0, 0.01, 0.05, 0.2, 1.0};
  std::vector<double> eps_N = {0.0, 0.5, 1.0};
  std::vector<double> mu = {0.0, 0.1, 0.3, 0.6};
  std::vector<double> skew_deg = {5.0, 20.0, 45.0, 75.0};
  std::vector<double> eta0 = {0.5, 0.9, 1.5, 4.0};
  std::vector<double> W0_over_w0 = {0.5, 1.0, 2.0};
  std::vector<double> w0_over_wg = {0.1, 0.3, 1.0, 3.0, 10.0};
  std::vector<records::PulseShape> pulse = {records::PulseShape::kCosine,
                                            records::PulseShape::kSine};

  /// Number of cells (the product of the axis lengths).
  std::int64_t size() const {
    return static_cast<std::int64_t>(Pi_delta.size() * eps_N.size() * mu.size() * skew_deg.size() *
                                     eta0.size() * W0_over_w0.size() * w0_over_wg.size() *
                                     pulse.size());
  }

  /// The point of cell `index` in [0, size()), the last axis varying fastest.
  spectra::PointParameters Cell(std::int64_t index) const {
    spectra::PointParameters p;
    p.family = spectra::Family::kSubsystem;
    auto take = [&index](const auto& axis) {
      const auto n = static_cast<std::int64_t>(axis.size());
      const auto i = static_cast<std::size_t>(index % n);
      index /= n;
      return axis[i];
    };
    p.pulse = take(pulse);
    p.w0_over_wg = take(w0_over_wg);
    p.W0_over_w0 = take(W0_over_w0);
    p.eta0 = take(eta0);
    p.skew_deg = take(skew_deg);
    p.mu = take(mu);
    p.eps_N = take(eps_N);
    p.Pi_delta = take(Pi_delta);
    // A closed joint cannot set the deck length through delta/L: every cell uses L = 250 L_e.
    p.L_over_Le = 250.0;
    p.xi = 0.05;
    return p;
  }
};

/// `count` distinct cell indices drawn with a seeded generator (same seed, same cells).
inline std::vector<std::int64_t> SampleCells(const GridAxes& grid, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::int64_t> cells;
  const auto n = static_cast<std::uint64_t>(grid.size());
  while (static_cast<int>(cells.size()) < count) {
    const auto c = static_cast<std::int64_t>(rng() % n);
    bool seen = false;
    for (std::int64_t d : cells) {
      seen = seen || d == c;
    }
    if (!seen) {
      cells.push_back(c);
    }
  }
  return cells;
}

/// One-line description of a point (for messages and the benchmark's list of worst cells).
inline std::string Describe(const spectra::PointParameters& p) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "Pi_delta=%g eps_N=%g mu=%g a=%g eta0=%g W0/w0=%g w0/wg=%g pulse=%s", p.Pi_delta,
                p.eps_N, p.mu, p.skew_deg, p.eta0.value_or(0.0), p.W0_over_w0, p.w0_over_wg,
                p.pulse == records::PulseShape::kCosine ? "cosine" : "sine");
  return buf;
}

/// Evaluates one point under its pulse by `method` (the sweep's own path).
inline spectra::PointResult Evaluate(spectra::PointParameters p, spectra::Method method,
                                     double time_step_over_Tg = 1e-5) {
  p.method = method;
  p.time_step_over_Tg = time_step_over_Tg;
  const spectra::ExcitationScales scales = spectra::PulseScales(p);
  const spectra::DimensionalPoint point = spectra::ToDimensional(p, scales);
  const records::PulseExcitation pulse(p.pulse, scales.a_g_mps2, scales.w_g_radps);
  return spectra::EvaluatePoint(point, pulse);
}

/// The whole run of a point with the event-driven integrator (event log included), with the
/// controls of spectra::EvaluatePoint, its events decided by `policy`.
inline dynamics::RunResult RunEventDriven(const spectra::PointParameters& p,
                                          long max_steps = 10'000'000,
                                          const dynamics::EventPolicy& policy = {}) {
  const spectra::ExcitationScales scales = spectra::PulseScales(p);
  const spectra::DimensionalPoint point = spectra::ToDimensional(p, scales);
  const records::PulseExcitation pulse(p.pulse, scales.a_g_mps2, scales.w_g_radps);
  const model::Model model = model::BuildDeckModel(point.deck, "point");
  const model::Modes modes = model::ComputeModes(model.M(), model.K());
  const double w_min = modes.omega_radps.minCoeff();
  model::RunControl control;
  control.absolute_tolerance = 1e-11 * point.persistency_m;
  control.max_steps = max_steps;
  control.energy_ledger = false;
  control.end_time_s = pulse.Duration() + 2.0 * std::max(2.0 * std::numbers::pi / scales.w_g_radps,
                                                         2.0 * std::numbers::pi / w_min);
  dynamics::SimulationWorkspace workspace(model);
  return dynamics::Simulate(model, pulse, control, workspace, {}, policy);
}

}  // namespace skewbridge::robustness
