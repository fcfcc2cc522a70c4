// The deck's record loop defers the root searches of the coordinates' maxima and of its corners'
// travel and resolves them when it leaves (ResolveDeferredMaxima, ResolveDeferredTravel): its
// maxima and their times against the
// general flight loop, which scans every step in order while an observer sees the run (the bits
// of max_abs_q, time_of_max_s, max_travel_m and the rest of the result), over drawn records,
// scales, directions, lengths and gaps; and the resolution alone against the in-order fold it
// stands for on drawn sequences of ends and roots (one per step, or four corners per step), with
// ties and with the bounds it rests on broken (the in-order replay).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "records/excitations.h"
#include "records/incidence.h"
#include "solver/dynamics/coordinate_maxima.h"
#include "solver/dynamics/simulate.h"
#include "tests/dynamics/benchmark_cases.h"
#include "tests/dynamics/run_bits.h"

namespace skewbridge::dynamics::deferred_maxima_test {
namespace {

using testing::PassThrough;

TEST(DeferredMaxima, TheDeckLoopsMaximaAreTheInOrderScans) {
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> scale(0.2, 3.0), angle(0.0, 90.0), end(4.0, 30.0);
  const model::Model free_model = bench::PilotBridge(false, 0.0);
  const model::Model gap_model = bench::PilotBridge(true, bench::kPilotStressGap_m);
  SimulationWorkspace ws_free(free_model), ws_free_general(free_model);
  SimulationWorkspace ws_gap(gap_model), ws_gap_general(gap_model);
  for (int draw = 0; draw < 24; ++draw) {
    const bool gaps = draw % 4 == 3;
    const model::Model& model = gaps ? gap_model : free_model;
    const unsigned seed = rng();
    const double factor = scale(rng), angle_deg = draw % 2 == 0 ? 0.0 : angle(rng);
    const double end_s = end(rng), output_s = draw % 6 == 5 ? 0.1 : 0.0;
    SCOPED_TRACE("draw " + std::to_string(draw) + ", seed " + std::to_string(seed) + ", scale " +
                 std::to_string(factor) + ", angle " + std::to_string(angle_deg) + " deg, end " +
                 std::to_string(end_s) + " s");
    records::GroundMotion motion;
    motion.dt_s = 0.01;
    motion.acc_mps2 = bench::RecordLikeSignal(seed);
    const Eigen::Vector2d direction =
        angle_deg == 0.0 ? Eigen::Vector2d::UnitX() : records::DirectionAt(angle_deg);
    const records::SampledExcitation excitation =
        records::ScaledExcitation(motion, factor, direction);
    model::RunControl control;
    control.end_time_s = end_s;
    control.energy_ledger = false;  // the record flight's condition
    control.output_interval_s = output_s;
    const RunResult deck = Simulate(model, excitation, control, gaps ? ws_gap : ws_free);
    PassThrough seen;
    const RunResult general = Simulate(model, excitation, control,
                                       gaps ? ws_gap_general : ws_free_general, {}, {}, &seen);
    testing::ExpectSameRunBits(deck, general);
    EXPECT_GT(deck.free_steps, 100);
  }
}

// One drawn root of a step: whether the rate changes sign, the cheap bound, the peak bound and
// the value at the root.
struct DrawnRoot {
  bool sign_change = false;
  double bound = 0.0, peak_bound = 0.0, root = 0.0;
};

// One drawn step of a sequence for the resolution: its end |q_i| and its velocity root (|q_i|
// there).
struct DrawnStep {
  double end = 0.0;
  DrawnRoot r;
};

// The in-order fold of ScanCoordinateMaxima over the steps (step k from k to k + 1 s, its root at
// k + 0.5 s): each end, then, where the velocity changes sign, the cheap bound is above the
// maximum and the peak bound does not stay below it, the root.
std::pair<double, double> InOrder(const std::vector<DrawnStep>& steps, double max0, double time0) {
  double m = max0, time = time0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const DrawnStep& s = steps[k];
    if (s.end > m) {
      m = s.end;
      time = static_cast<double>(k + 1);
    }
    if (s.r.sign_change && s.r.bound > m && !(s.r.peak_bound < m)) {
      if (s.r.root > m) {
        m = s.r.root;
        time = static_cast<double>(k) + 0.5;
      }
    }
  }
  return {m, time};
}

// A value from a small pool (ties between ends, roots and bounds) or drawn.
double Value(std::mt19937_64& rng) {
  static constexpr double kPool[] = {0.0, 1.0, 2.0, 3.0, 4.0};
  std::uniform_int_distribution<int> pick(0, 9);
  const int k = pick(rng);
  if (k < 5) return kPool[k];
  return std::uniform_real_distribution<double>(0.0, 5.0)(rng);
}

// A root of the given sign change whose bounds hold, unless break_cheap draws the cheap bound
// below the root now and then; either bound may be the larger.
DrawnRoot DrawRoot(std::mt19937_64& rng, bool sign_change, bool break_cheap) {
  std::uniform_int_distribution<int> coin(0, 3);
  DrawnRoot r;
  r.sign_change = sign_change;
  r.root = Value(rng);
  r.bound = r.root + (coin(rng) == 0 ? 0.0 : Value(rng));
  r.peak_bound = r.root + (coin(rng) == 0 ? 0.0 : 0.5 * Value(rng));
  r.bound = std::max(r.bound, r.peak_bound - Value(rng));
  if (break_cheap && coin(rng) == 0) r.bound = std::max(0.0, r.root - Value(rng));
  return r;
}

// A root whose peak bound is broken, drawn only where the root lies above every other candidate
// of the sequence (the draws' values are at most 5), so that a skip on it never hides a raise.
void BreakPeak(std::mt19937_64& rng, DrawnRoot& r) {
  r.sign_change = true;
  r.root = 10.0;
  r.bound = 11.0;
  r.peak_bound = 0.5 * Value(rng) + 5.0;  // below the root, above every other candidate
}

TEST(DeferredMaxima, TheResolutionIsTheInOrderFold) {
  std::mt19937_64 rng(455);
  std::uniform_int_distribution<int> length(0, 40), coin(0, 3), rare(0, 30);
  long replays = 0, searches = 0, spared = 0;
  for (int draw = 0; draw < 200000; ++draw) {
    // Bounds hold unless drawn broken: the cheap bound (rarely) and, where the root is searched,
    // the peak bound (rarely); a broken peak bound is drawn only where the root then lies above
    // the sequence's every other candidate, so that a skip on it never hides a raise.
    const bool break_cheap = rare(rng) == 0, break_peak = rare(rng) == 0;
    std::vector<DrawnStep> steps(static_cast<std::size_t>(length(rng)));
    for (DrawnStep& s : steps) {
      s.end = Value(rng);
      const bool sign_change = coin(rng) != 0;
      s.r = DrawRoot(rng, sign_change, break_cheap);
    }
    if (break_peak && !steps.empty()) {
      BreakPeak(rng, steps[static_cast<std::size_t>(rng() % steps.size())].r);
    }
    const double max0 = Value(rng) * 0.5, time0 = -1.0;
    const auto [want, want_time] = InOrder(steps, max0, time0);
    // The record loop: each end raised, a sign change whose cheap bound is above the maximum
    // deferred with the end fold after it.
    std::vector<DeferredPeakStep> deferred;
    std::vector<int> source;  // the drawn step of each deferred one
    double m = max0, time = time0;
    for (std::size_t k = 0; k < steps.size(); ++k) {
      const DrawnStep& s = steps[k];
      if (s.end > m) {
        m = s.end;
        time = static_cast<double>(k + 1);
      }
      if (s.r.sign_change && s.r.bound > m) {
        DeferredPeakStep d;
        d.t0_s = static_cast<double>(k);
        d.t1_s = static_cast<double>(k + 1);
        d.bound[1] = s.r.bound;
        d.end_max[1] = m;
        d.end_time_s[1] = time;
        d.coordinates = 1 << 1;
        deferred.push_back(d);
        source.push_back(static_cast<int>(k));
      }
    }
    DeferredScratch scratch;
    const auto search = [&](int j) {
      ++searches;
      const std::size_t k = static_cast<std::size_t>(source[static_cast<std::size_t>(j)]);
      return std::pair<double, double>(steps[k].r.root, static_cast<double>(k) + 0.5);
    };
    const auto below = [&](int j, double best) {
      return steps[static_cast<std::size_t>(source[static_cast<std::size_t>(j)])].r.peak_bound <
             best;
    };
    const long before = searches;
    const bool replayed = ResolveDeferredMaxima(1, deferred, scratch, m, time, search, below);
    replays += replayed ? 1 : 0;
    if (!replayed) spared += static_cast<long>(deferred.size()) - (searches - before);
    ASSERT_EQ(m, want) << "draw " << draw;
    ASSERT_EQ(time, want_time) << "draw " << draw;
  }
  // Both ways were taken, and the resolution spared searches.
  EXPECT_GT(replays, 1000);
  EXPECT_GT(spared, 100000);
}

// One drawn step for the travel's resolution: its end travel and each corner's rate root (the
// travel bound as its peak bound, the travel there).
struct DrawnCorners {
  double end = 0.0;
  DrawnRoot corner[4];
};

// CornerTravelTracker::Scan's in-order fold over the steps: each step's end, then its corners in
// order, each searched where its rate changes sign, its cheap bound is above the maximum and its
// travel bound does not stay below it.
double InOrderTravel(const std::vector<DrawnCorners>& steps, double max0) {
  double m = max0;
  for (const DrawnCorners& s : steps) {
    m = std::max(m, s.end);
    for (int c = 0; c < 4; ++c) {
      const DrawnRoot& r = s.corner[c];
      if (r.sign_change && r.bound > m && !(r.peak_bound < m)) m = std::max(m, r.root);
    }
  }
  return m;
}

TEST(DeferredMaxima, TheTravelsResolutionIsTheInOrderFold) {
  std::mt19937_64 rng(2011);
  std::uniform_int_distribution<int> length(0, 30), coin(0, 3), rare(0, 30);
  long replays = 0, searches = 0, spared = 0;
  for (int draw = 0; draw < 100000; ++draw) {
    // As for the coordinates: the cheap bound broken now and then, and a travel bound broken
    // only where its root lies above every other candidate.
    const bool break_cheap = rare(rng) == 0, break_peak = rare(rng) == 0;
    std::vector<DrawnCorners> steps(static_cast<std::size_t>(length(rng)));
    for (DrawnCorners& s : steps) {
      s.end = Value(rng);
      for (DrawnRoot& r : s.corner) {
        const bool sign_change = coin(rng) == 0;
        r = DrawRoot(rng, sign_change, break_cheap);
      }
    }
    if (break_peak && !steps.empty()) {
      DrawnCorners& s = steps[static_cast<std::size_t>(rng() % steps.size())];
      BreakPeak(rng, s.corner[rng() % 4]);
    }
    const double max0 = Value(rng) * 0.5;
    const double want = InOrderTravel(steps, max0);
    // The record loop (CornerTravelTracker::ScanEnd): each end raised, the corners whose cheap
    // bound is above that maximum deferred with it.
    std::vector<DeferredPeakStep> deferred;
    std::vector<int> source;
    double m = max0;
    long candidates = 0;
    for (std::size_t k = 0; k < steps.size(); ++k) {
      const DrawnCorners& s = steps[k];
      m = std::max(m, s.end);
      DeferredPeakStep d;
      d.t0_s = static_cast<double>(k);
      d.t1_s = static_cast<double>(k + 1);
      d.end_travel_m = m;
      for (int c = 0; c < 4; ++c) {
        if (s.corner[c].sign_change && s.corner[c].bound > m) {
          d.corner_bound[c] = s.corner[c].bound;
          d.corners |= 1 << c;
          ++candidates;
        }
      }
      if (d.corners != 0 || coin(rng) == 0) {  // steps kept for their coordinates too
        deferred.push_back(d);
        source.push_back(static_cast<int>(k));
      }
    }
    DeferredScratch scratch;
    const auto of = [&](int j) -> const DrawnCorners& {
      return steps[static_cast<std::size_t>(source[static_cast<std::size_t>(j)])];
    };
    const auto search = [&](int j, int c) {
      ++searches;
      return of(j).corner[c].root;
    };
    const auto below = [&](int j, int c, double best) { return of(j).corner[c].peak_bound < best; };
    const long before = searches;
    const bool replayed = ResolveDeferredTravel(deferred, scratch, m, search, below);
    replays += replayed ? 1 : 0;
    if (!replayed) spared += candidates - (searches - before);
    ASSERT_EQ(m, want) << "draw " << draw;
  }
  EXPECT_GT(replays, 500);
  EXPECT_GT(spared, 100000);
}

}  // namespace
}  // namespace skewbridge::dynamics::deferred_maxima_test
