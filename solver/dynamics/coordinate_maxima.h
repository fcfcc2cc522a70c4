#pragma once
/// @file
/// The running maxima of |q_i| over a run, raised step by step at the exactness of the step's
/// solution: each step's end, and the root of u_i inside a step where u_i changes sign and the
/// peak could pass the running maximum (a cheap hull first, then the peaks' bound of a full modal
/// free step, docs/theory.md §3.20, and a Brent search on the dense output only where both fail).

#include <Eigen/Core>
#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "solver/dynamics/peak_bound.h"
#include "solver/dynamics/root_finding.h"

namespace skewbridge::dynamics {

/// Raises max_abs_q (and time_of_max_s, s) of the n coordinates over the step [t0, t1] with ends
/// (q0, u0), (q1, u1); component_at(t, i) is entry i of (q, u) at t on the step's dense output
/// (the velocity root needs one entry, not the whole state), time_tolerance_s the root search's.
template <class ComponentAt>
inline void ScanCoordinateMaxima(int n, double t0, const Eigen::Map<const Eigen::VectorXd>& q0,
                                 const Eigen::Map<const Eigen::VectorXd>& u0, double t1,
                                 const Eigen::Map<const Eigen::VectorXd>& q1,
                                 const Eigen::Map<const Eigen::VectorXd>& u1,
                                 double time_tolerance_s, ComponentAt&& component_at,
                                 FreeStepPeaks& peaks, Eigen::VectorXd& max_abs_q,
                                 Eigen::VectorXd& time_of_max_s) {
  for (int i = 0; i < n; ++i) {
    if (std::abs(q1[i]) > max_abs_q[i]) {
      max_abs_q[i] = std::abs(q1[i]);
      time_of_max_s[i] = t1;
    }
    if (u0[i] * u1[i] < 0.0) {
      const double bound = std::max(std::abs(q0[i]), std::abs(q1[i])) +
                           0.5 * (t1 - t0) * std::max(std::abs(u0[i]), std::abs(u1[i]));
      if (bound > max_abs_q[i] &&
          !peaks.PeakBelow(i, q0[i], u0[i], q1[i], u1[i], t1 - t0, max_abs_q[i])) {
        const auto velocity = [&](double t) { return component_at(t, n + i); };
        const RootResult peak = FindRootBrent(velocity, t0, t1, u0[i], u1[i], time_tolerance_s);
        const double q_peak = std::abs(component_at(peak.x, i));
        if (q_peak > max_abs_q[i]) {
          max_abs_q[i] = q_peak;
          time_of_max_s[i] = peak.x;
        }
      }
    }
  }
}

/// ScanCoordinateMaxima's work that needs no dense output, over plain arrays: raises
/// max_abs_q[i] (and time_of_max_s[i]) to |q1[i]| at the step's end t1, and returns whether some
/// u_i changes sign inside the step [t1 - h_s, t1] with the cheap hull's peak above the running
/// maximum: only then would ScanCoordinateMaxima ask the peaks' bound or search (the same tests
/// in the same order, so a step for which this returns false leaves the maxima as that scan
/// would).
inline bool RaiseMaximaAtEnd(int n, const double* q0, const double* u0, double t1, const double* q1,
                             const double* u1, double h_s, double* max_abs_q,
                             double* time_of_max_s) {
  bool search = false;
  for (int i = 0; i < n; ++i) {
    if (std::abs(q1[i]) > max_abs_q[i]) {
      max_abs_q[i] = std::abs(q1[i]);
      time_of_max_s[i] = t1;
    }
    if (u0[i] * u1[i] < 0.0) {
      const double bound = std::max(std::abs(q0[i]), std::abs(q1[i])) +
                           0.5 * h_s * std::max(std::abs(u0[i]), std::abs(u1[i]));
      search = search || bound > max_abs_q[i];
    }
  }
  return search;
}

/// A coordinate's (q_i, u_i) side by side in two lanes: each operation on it is the IEEE operation
/// on each lane.
using CoordinateLanes = double __attribute__((vector_size(16)));

/// RaiseMaximaAtEnd of three coordinates held as lanes, x0[i] = (q_i, u_i) at the step's start
/// and x1[i] at its end t1 (h_s the step's length), per coordinate: every coordinate's two
/// tests, max_abs_q[i] < |q1_i| and u0_i u1_i < +0 (RaiseMaximaAtEnd's comparisons with their
/// operands swapped, the same outcome), side by side first; when none holds nothing is raised
/// and 0 is returned. Else RaiseMaximaAtEnd's operations on the lanes in its order: the same
/// maxima, and bit i of the result set when u_i changes sign inside the step and the cheap
/// hull's peak bound[i] (written then only) is above max_abs_q[i] after the end's raise, the
/// coordinates for which RaiseMaximaAtEnd would search (bound[i] 0 otherwise; bound is left
/// unwritten when no end rises and no velocity changes sign).
inline int RaiseMaximaAtEnd3Each(const CoordinateLanes x0[3], const CoordinateLanes x1[3],
                                 double t1, double h_s, double max_abs_q[3],
                                 double time_of_max_s[3], double bound[3]) {
  using Bits2 = long long __attribute__((vector_size(16)));
  const auto magnitude = [](CoordinateLanes v) {
    return std::bit_cast<CoordinateLanes>(std::bit_cast<Bits2>(v) &
                                          Bits2{0x7fffffffffffffffLL, 0x7fffffffffffffffLL});
  };
  const Bits2 q_magnitude = {0x7fffffffffffffffLL, 0};
#if defined(__SSE2__)
  // The comparisons' masks ORed as doubles (cmpltpd, orpd) and their signs gathered (movmskpd):
  // the same outcome as the generic form below without turning each mask into a bool lane.
  __m128d any = _mm_setzero_pd();
  for (int i = 0; i < 3; ++i) {
    const CoordinateLanes end =
        std::bit_cast<CoordinateLanes>(std::bit_cast<Bits2>(x1[i]) & q_magnitude);
    const CoordinateLanes product = x0[i] * x1[i];
    const CoordinateLanes reference = {max_abs_q[i], product[1]};
    any = _mm_or_pd(any, _mm_cmplt_pd(reference, end));
  }
  const bool none = _mm_movemask_pd(any) == 0;
#else
  Bits2 any = {0, 0};
  for (int i = 0; i < 3; ++i) {
    const CoordinateLanes end =
        std::bit_cast<CoordinateLanes>(std::bit_cast<Bits2>(x1[i]) & q_magnitude);
    const CoordinateLanes product = x0[i] * x1[i];
    const CoordinateLanes reference = {max_abs_q[i], product[1]};
    any |= reference < end;
  }
  const bool none = (any[0] | any[1]) == 0;
#endif
  if (none) {
    return 0;
  }
  int search = 0;
  for (int i = 0; i < 3; ++i) {
    const CoordinateLanes a0 = magnitude(x0[i]), a1 = magnitude(x1[i]);
    if (a1[0] > max_abs_q[i]) {
      max_abs_q[i] = a1[0];
      time_of_max_s[i] = t1;
    }
    bound[i] = 0.0;
    if (x0[i][1] * x1[i][1] < 0.0) {
      const CoordinateLanes larger = a0 < a1 ? a1 : a0;
      const double b = larger[0] + 0.5 * h_s * larger[1];
      if (b > max_abs_q[i]) {
        bound[i] = b;
        search |= 1 << i;
      }
    }
  }
  return search;
}

/// A full free step of a deck whose root searches are deferred (DeckRecordSteps): what
/// rebuilding its dense output and its peak bound needs, per coordinate what the in-order scan
/// of its velocity root would compare with, and the same for the deck's corners.
struct DeferredPeakStep {
  double t0_s = 0.0, t1_s = 0.0;           ///< the step's ends (s)
  double h_s = 0.0;                        ///< the plan's nominal step (s; the peak bound's length)
  CoordinateLanes x0[3] = {}, x1[3] = {};  ///< (q_i, u_i) at t0_s and at t1_s
  CoordinateLanes gx = {}, gy = {};        ///< the generator's (a, slope) of x and of y
  double bound[3] = {};                    ///< the cheap hull's peak of each deferred coordinate
  /// The running maximum of |q_i| and its time right after the step's end was raised, with
  /// only the ends of the steps since the last resolution raising it: the in-order scan's
  /// maximum before the root less the roots deferred before it.
  double end_max[3] = {}, end_time_s[3] = {};
  int coordinates = 0;  ///< bit i: coordinate i's root deferred
  /// The deck's running maximum of the corners' travel (m) right after the step's end was
  /// raised, the ends since the last resolution alone raising it (as end_max).
  double end_travel_m = 0.0;
  double corner_bound[4] = {};  ///< Scan's cheap peak of each deferred corner (m)
  int corners = 0;              ///< bit k: corner k's rate root deferred
};

/// One deferred root search of a running maximum, as ResolveDeferredRoots takes it: its cheap
/// bound, the running maximum and its time right after its step's end was raised (the ends since
/// the last resolution alone), its place in the in-order sequence (its step's end time, s: after
/// that end and after the roots of the same step listed before it) and the caller's key.
struct DeferredRoot {
  double bound = 0.0;
  double end_max = 0.0, end_time_s = 0.0;
  double place_s = 0.0;
  int key = 0;
};

/// Scratch of a resolution: the roots in their in-order sequence, the order they are visited in.
struct DeferredScratch {
  std::vector<DeferredRoot> roots;
  std::vector<int> order;
};

/// The deferred steps of a run's record loop and a resolution's scratch (storage reused from
/// run to run).
struct DeferredPeaks {
  std::vector<DeferredPeakStep> steps;
  DeferredScratch scratch;
};

/// The deferred roots scratch.roots (in their in-order sequence) folded into a running maximum
/// (max, time_s, which hold the fold of every step's end), the same bits as the in-order scan
/// [docs/theory.md §3.20]. search(key) returns (the value at the root, the root's time) (a Brent
/// search on the step's dense output, a value independent of the running maximum); below(key,
/// best) is the peak bound of the root's step against best. The in-order fold takes each end,
/// then each searched root, a larger value replacing the maximum: its result is the largest
/// candidate, the first in that sequence among equals. The roots are visited by their cheap
/// bound from the largest; one whose peak bound stays below the maximum so far is not searched
/// (it cannot reach the in-order result), the others are searched and folded by (value, place in
/// the sequence). Where a searched value exceeds its cheap bound or its peak bound, the roots are
/// taken again in order from each one's end fold (end_max) and the roots found so far (the
/// in-order scan itself). Returns whether that replay ran.
template <class Search, class Below>
bool ResolveDeferredRoots(DeferredScratch& scratch, double& max, double& time_s, Search&& search,
                          Below&& below) {
  const std::vector<DeferredRoot>& roots = scratch.roots;
  std::vector<int>& order = scratch.order;
  if (roots.empty()) {
    return false;
  }
  order.resize(roots.size());
  for (std::size_t j = 0; j < roots.size(); ++j) order[j] = static_cast<int>(j);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return roots[static_cast<std::size_t>(a)].bound > roots[static_cast<std::size_t>(b)].bound;
  });
  // The fold so far and its place in the sequence: an end at time T is (T, before the roots of
  // its step); the root of the step ending at t1 is (t1, after its end). Every root deferred
  // comes after any candidate older than the steps (time at most their start).
  double best = max, best_time = time_s, best_place = time_s;
  bool exact = true;
  for (const int j : order) {
    const DeferredRoot& r = roots[static_cast<std::size_t>(j)];
    if (below(r.key, best)) {
      continue;  // the root's peak stays below a candidate of the in-order set
    }
    const auto [value, time] = search(r.key);
    if (!(value <= r.bound) || below(r.key, value)) {
      exact = false;  // a bound the argument rests on failed by rounding
      break;
    }
    if (value > best || (value == best && r.place_s < best_place)) {
      best = value;
      best_time = time;
      best_place = r.place_s;
    }
  }
  if (exact) {
    max = best;
    time_s = best_time;
    return false;
  }
  // The in-order scan: before a root the maximum is the better of its end fold and the roots
  // raised so far (found: root_place the place of the last).
  bool found = false;
  double root = 0.0, root_time = 0.0, root_place = 0.0;
  for (const DeferredRoot& r : roots) {
    double m = r.end_max;
    if (found && (root > m || (root == m && root_place < r.end_time_s))) m = root;
    if (r.bound > m && !below(r.key, m)) {
      const auto [value, time] = search(r.key);
      if (value > m) {
        found = true;
        root = value;
        root_time = time;
        root_place = r.place_s;
      }
    }
  }
  if (found && (root > max || (root == max && root_place < time_s))) {
    max = root;
    time_s = root_time;
  }
  return true;
}

/// Coordinate i's velocity roots of the deferred `steps` folded into its running maximum
/// (max_abs_q, time_of_max_s, which hold the fold of every step's end): ResolveDeferredRoots
/// with the key k of steps[k]; search(k) returns (|q_i| at the root, the root's time) of
/// steps[k], below(k, best) is FreeStepPeaks::PeakBelow of steps[k] against best. Returns
/// whether the in-order replay ran.
template <class Search, class Below>
bool ResolveDeferredMaxima(int i, const std::vector<DeferredPeakStep>& steps,
                           DeferredScratch& scratch, double& max_abs_q, double& time_of_max_s,
                           Search&& search, Below&& below) {
  const int bit = 1 << i;
  scratch.roots.clear();
  for (int k = 0; k < static_cast<int>(steps.size()); ++k) {
    const DeferredPeakStep& s = steps[static_cast<std::size_t>(k)];
    if ((s.coordinates & bit) != 0) {
      scratch.roots.push_back({s.bound[i], s.end_max[i], s.end_time_s[i], s.t1_s, k});
    }
  }
  return ResolveDeferredRoots(scratch, max_abs_q, time_of_max_s, search, below);
}

/// The deck's corner roots of the deferred `steps` folded into its running maximum of the
/// travel (max_travel_m, the fold of every step's end; the travel has no time, so equal values
/// are one): ResolveDeferredRoots over the corners of each step in Scan's order (corner 0 to 3
/// after the step's ends); search(k, c) returns the travel (m) at the root of corner c's rate in
/// steps[k], below(k, c, best) whether Scan's travel bound of that corner stays below best.
/// Returns whether the in-order replay ran.
template <class Search, class Below>
bool ResolveDeferredTravel(const std::vector<DeferredPeakStep>& steps, DeferredScratch& scratch,
                           double& max_travel_m, Search&& search, Below&& below) {
  scratch.roots.clear();
  for (int k = 0; k < static_cast<int>(steps.size()); ++k) {
    const DeferredPeakStep& s = steps[static_cast<std::size_t>(k)];
    for (int c = 0; c < 4; ++c) {
      if ((s.corners & (1 << c)) != 0) {
        scratch.roots.push_back({s.corner_bound[c], s.end_travel_m, 0.0, s.t1_s, 4 * k + c});
      }
    }
  }
  double time_s = 0.0;  // the travel's maximum has none: every place ties with it
  return ResolveDeferredRoots(
      scratch, max_travel_m, time_s,
      [&](int key) { return std::pair<double, double>(search(key / 4, key % 4), 0.0); },
      [&](int key, double best) { return below(key / 4, key % 4, best); });
}

}  // namespace skewbridge::dynamics
