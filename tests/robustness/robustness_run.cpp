// Runs the robustness grid (tests/robustness/robustness_grid.h), or a seeded sample of it, with
// the event-driven integrator and reports the status of every cell, the cost distribution (CPU
// time per cell: median, maximum, total) and the worst cells. With --compare it also runs
// Moreau-Jean at h = 1e-5 of the excitation period on the sample and reports the worst
// disagreement of the maxima (docs/validation.md, docs/performance.md). With --repeat R the set
// is run R times and each cell's cheapest run kept: a cell's cost without the interruptions of a
// shared machine, which otherwise decide which single run is the slowest. With --dump-events FILE
// the whole event-driven run of every cell of the set (status, counts, maxima, residuals and the
// event log, every number as a C99 hexadecimal float) is written to FILE first: two dumps are the
// same file exactly when the runs gave the same bits.
//
//   robustness_run [--sample N --seed S] [--compare] [--list K] [--repeat R]
//                  [--dump-events FILE]

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <numeric>
#include <string>
#include <vector>

#include "tests/robustness/robustness_grid.h"

using namespace skewbridge;

namespace {

struct CellOutcome {
  std::int64_t index = 0;
  spectra::PointResult ed;
  double seconds = 0.0;
  double worst_rel = 0.0;  // against time-stepping (with --compare)
  spectra::PointResult ts;
};

// CPU time of this process (s): robust to other load on the machine, unlike wall time.
double CpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Relative disagreement of two maxima, with an absolute floor of 1e-6 (normalised units: L_e).
double Disagreement(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-4); }

// Writes every number of one cell's run `r` to `out` as hexadecimal floats (exact bits).
void DumpRun(std::FILE* out, std::int64_t cell, const dynamics::RunResult& r) {
  std::fprintf(out, "cell %lld %s t_end %a impacts %ld plastic %ld detach %ld stick %ld slip %ld",
               static_cast<long long>(cell), dynamics::ToString(r.status), r.end_time_s, r.impacts,
               r.plastic_closures, r.detachments, r.stick_transitions, r.slip_transitions);
  std::fprintf(out, " free %ld rk %ld rejected %ld min_sep %a\n", r.free_steps, r.rk_steps,
               r.rk_rejected, r.min_impact_separation_s);
  std::fprintf(out, "  message %s\n", r.message.c_str());
  for (Eigen::Index i = 0; i < r.max_abs_q.size(); ++i) {
    std::fprintf(out, "  dof %ld max %a at %a end %a %a\n", static_cast<long>(i), r.max_abs_q[i],
                 r.time_of_max_s[i], r.q_end[i], r.u_end[i]);
  }
  for (const dynamics::EventRecord& e : r.events) {
    std::fprintf(out, "  %a %s c%d %a %a %a %a %a\n", e.t_s, dynamics::ToString(e.kind), e.contact,
                 e.gamma_N_before_mps, e.gamma_N_after_mps, e.impulse_N_Ns, e.impulse_T_Ns,
                 e.kinetic_loss_J);
  }
}

}  // namespace

int main(int argc, char** argv) {
  int sample = 0, list = 10, repeat = 1;
  long long one_cell = -1;
  long max_steps = 10'000'000;
  double ts_step = 1e-5;
  std::uint64_t seed = 12;
  bool compare = false;
  const char* dump_path = nullptr;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sample") && i + 1 < argc) {
      sample = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (!std::strcmp(argv[i], "--cell") && i + 1 < argc) {
      one_cell = std::atoll(argv[++i]);
    } else if (!std::strcmp(argv[i], "--ts-step") && i + 1 < argc) {
      ts_step = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--max-steps") && i + 1 < argc) {
      max_steps = std::atol(argv[++i]);
    } else if (!std::strcmp(argv[i], "--dump-events") && i + 1 < argc) {
      dump_path = argv[++i];
    } else if (!std::strcmp(argv[i], "--compare")) {
      compare = true;
    } else if (!std::strcmp(argv[i], "--list") && i + 1 < argc) {
      list = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) {
      repeat = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: robustness_run [--sample N --seed S] [--compare] [--list K] "
                   "[--repeat R] [--dump-events FILE]\n");
      return 2;
    }
  }
  if (repeat < 1) {
    std::fprintf(stderr, "robustness_run: --repeat must be at least 1\n");
    return 2;
  }
  const robustness::GridAxes grid;
  if (one_cell >= 0) {
    // The event log of one cell (the last `list` events), for diagnosis.
    const dynamics::RunResult r = robustness::RunEventDriven(grid.Cell(one_cell), max_steps);
    if (compare) {
      const spectra::PointParameters p = grid.Cell(one_cell);
      const spectra::PointResult ed = robustness::Evaluate(p, spectra::Method::kEventDriven);
      const spectra::PointResult ts =
          robustness::Evaluate(p, spectra::Method::kTimeStepping, ts_step);
      std::printf(
          "event-driven x %.9e y %.9e theta %.9e; time-stepping (h = %g T_g, %s) x %.9e "
          "y %.9e theta %.9e\n",
          ed.x_norm, ed.y_norm, ed.theta_norm, ts_step, dynamics::ToString(ts.status), ts.x_norm,
          ts.y_norm, ts.theta_norm);
    }
    std::printf("%s: %s %s, t_end %.9g, impacts %ld plastic %ld detach %ld stick %ld slip %ld\n",
                robustness::Describe(grid.Cell(one_cell)).c_str(), dynamics::ToString(r.status),
                r.message.c_str(), r.end_time_s, r.impacts, r.plastic_closures, r.detachments,
                r.stick_transitions, r.slip_transitions);
    const std::size_t n = r.events.size();
    for (std::size_t i = n > static_cast<std::size_t>(list) ? n - list : 0; i < n; ++i) {
      const dynamics::EventRecord& e = r.events[i];
      std::printf("%.12f %-16s c%d vA=%.3e vE=%.3e LN=%.3e LT=%.3e\n", e.t_s,
                  dynamics::ToString(e.kind), e.contact, e.gamma_N_before_mps, e.gamma_N_after_mps,
                  e.impulse_N_Ns, e.impulse_T_Ns);
    }
    return r.status == dynamics::RunStatus::kOk ? 0 : 1;
  }
  std::vector<std::int64_t> cells;
  if (sample > 0) {
    cells = robustness::SampleCells(grid, sample, seed);
  } else {
    cells.resize(static_cast<std::size_t>(grid.size()));
    std::iota(cells.begin(), cells.end(), 0);
  }
  if (dump_path != nullptr) {
    std::FILE* dump = std::fopen(dump_path, "w");
    if (dump == nullptr) {
      std::fprintf(stderr, "robustness_run: cannot write %s\n", dump_path);
      return 2;
    }
    for (std::int64_t c : cells) {
      DumpRun(dump, c, robustness::RunEventDriven(grid.Cell(c)));
    }
    if (std::fclose(dump) != 0) {
      std::fprintf(stderr, "robustness_run: cannot write %s\n", dump_path);
      return 2;
    }
  }
  std::vector<CellOutcome> out;
  out.reserve(cells.size());
  int failed = 0;
  for (std::int64_t c : cells) {
    const spectra::PointParameters p = grid.Cell(c);
    CellOutcome o;
    o.index = c;
    const double t0 = CpuSeconds();
    o.ed = robustness::Evaluate(p, spectra::Method::kEventDriven);
    o.seconds = CpuSeconds() - t0;
    if (o.ed.status != dynamics::RunStatus::kOk) {
      ++failed;
      std::printf("FAIL cell %lld (%s): %s\n", static_cast<long long>(c),
                  robustness::Describe(p).c_str(), o.ed.message.c_str());
    }
    if (compare) {
      const spectra::PointResult ts =
          robustness::Evaluate(p, spectra::Method::kTimeStepping, ts_step);
      o.ts = ts;
      o.worst_rel =
          std::max({Disagreement(o.ed.x_norm, ts.x_norm), Disagreement(o.ed.y_norm, ts.y_norm),
                    Disagreement(o.ed.theta_norm, ts.theta_norm)});
    }
    out.push_back(o);
  }
  // Further passes over the whole set (not back to back per cell: an interruption of a few
  // milliseconds would then slow every run of the same cell).
  for (int r = 1; r < repeat; ++r) {
    for (CellOutcome& o : out) {
      const spectra::PointParameters p = grid.Cell(o.index);
      const double t0 = CpuSeconds();
      const spectra::PointResult again = robustness::Evaluate(p, spectra::Method::kEventDriven);
      o.seconds = std::min(o.seconds, CpuSeconds() - t0);
      if (again.status != o.ed.status || again.x_norm != o.ed.x_norm) {
        std::fprintf(stderr, "robustness_run: cell %lld gave another result when run again\n",
                     static_cast<long long>(o.index));
        return 1;
      }
    }
  }
  std::vector<double> secs;
  for (const CellOutcome& o : out) {
    secs.push_back(o.seconds);
  }
  std::vector<double> sorted = secs;
  std::sort(sorted.begin(), sorted.end());
  const double total = std::accumulate(secs.begin(), secs.end(), 0.0);
  const double median = sorted[sorted.size() / 2];
  std::printf(
      "cells %zu, failed %d, total %.3f s, median %.1f us, max %.1f us (%.1fx median)%s\n",
      out.size(), failed, total, 1e6 * median, 1e6 * sorted.back(), sorted.back() / median,
      repeat > 1 ? (" (each cell's cheapest of " + std::to_string(repeat) + " runs)").c_str() : "");
  const auto above =
      std::count_if(secs.begin(), secs.end(), [&](double x) { return x > 50.0 * median; });
  std::printf("cells above 50x the median: %ld\n", static_cast<long>(above));
  std::sort(out.begin(), out.end(),
            [](const CellOutcome& a, const CellOutcome& b) { return a.seconds > b.seconds; });
  std::printf("slowest cells:\n");
  for (int i = 0; i < list && i < static_cast<int>(out.size()); ++i) {
    std::printf("  %8.1f us  steps %6ld events %5ld  %s\n", 1e6 * out[i].seconds, out[i].ed.steps,
                out[i].ed.events, robustness::Describe(grid.Cell(out[i].index)).c_str());
  }
  if (compare) {
    std::sort(out.begin(), out.end(),
              [](const CellOutcome& a, const CellOutcome& b) { return a.worst_rel > b.worst_rel; });
    std::printf("largest disagreement with time-stepping (h = 1e-5 T_g):\n");
    for (int i = 0; i < list && i < static_cast<int>(out.size()); ++i) {
      const CellOutcome& w = out[i];
      std::printf("  %.3e  cell %lld %s\n     x %.6e / %.6e  y %.6e / %.6e  theta %.6e / %.6e\n",
                  w.worst_rel, static_cast<long long>(w.index),
                  robustness::Describe(grid.Cell(w.index)).c_str(), w.ed.x_norm, w.ts.x_norm,
                  w.ed.y_norm, w.ts.y_norm, w.ed.theta_norm, w.ts.theta_norm);
    }
  }
  return failed == 0 ? 0 : 1;
}
