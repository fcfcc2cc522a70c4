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
#include <vector>

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
  Bits2 any = {0, 0};
  for (int i = 0; i < 3; ++i) {
    const CoordinateLanes end =
        std::bit_cast<CoordinateLanes>(std::bit_cast<Bits2>(x1[i]) & q_magnitude);
    const CoordinateLanes product = x0[i] * x1[i];
    const CoordinateLanes reference = {max_abs_q[i], product[1]};
    any |= reference < end;
  }
#if defined(__SSE2__)
  const bool none = __builtin_ia32_movmskpd(std::bit_cast<CoordinateLanes>(any)) == 0;
#else
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

/// A full free step of a deck whose velocity-root searches are deferred (DeckRecordSteps): what
/// rebuilding its dense output and its peak bound needs, and per coordinate what the in-order
/// scan of its root would compare with.
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
};

/// The deferred steps of a run's record loop and the order their roots are visited in (storage
/// reused from run to run).
struct DeferredPeaks {
  std::vector<DeferredPeakStep> steps;
  std::vector<int> order;
};

/// Coordinate i's velocity roots of the deferred `steps` folded into its running maximum
/// (max_abs_q, time_of_max_s, which hold the fold of every step's end), the same bits as
/// ScanCoordinateMaxima taking the steps in order [docs/theory.md §3.20]. search(k) returns
/// (|q_i| at the root, the root's time) of steps[k] (FindRootBrent on its dense output, a value
/// independent of the running maximum); below(k, best) is FreeStepPeaks::PeakBelow of steps[k]
/// against best. The in-order fold takes each end, then each searched root, a larger value
/// replacing the maximum: its result is the largest candidate, the first in that sequence among
/// equals. The roots are visited by their cheap bound from the largest; one whose peak bound
/// stays below the maximum so far is not searched (it cannot reach the in-order result), the
/// others are searched and folded by (value, place in the sequence). Where a searched value
/// exceeds its cheap bound or its peak bound, the steps are taken again in order from each
/// step's end fold (end_max) and the roots found so far (the in-order scan itself). Returns
/// whether that replay ran. `order` is scratch.
template <class Search, class Below>
bool ResolveDeferredMaxima(int i, const std::vector<DeferredPeakStep>& steps,
                           std::vector<int>& order, double& max_abs_q, double& time_of_max_s,
                           Search&& search, Below&& below) {
  const int bit = 1 << i;
  order.clear();
  for (int k = 0; k < static_cast<int>(steps.size()); ++k) {
    if ((steps[static_cast<std::size_t>(k)].coordinates & bit) != 0) order.push_back(k);
  }
  if (order.empty()) {
    return false;
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return steps[static_cast<std::size_t>(a)].bound[i] >
           steps[static_cast<std::size_t>(b)].bound[i];
  });
  // The fold so far and its place in the sequence: an end at time T is (T, before the roots of
  // its step); the root of the step ending at t1 is (t1, after its end). Every root deferred
  // comes after any candidate older than the steps (time at most their start).
  double best = max_abs_q, best_time = time_of_max_s, best_place = time_of_max_s;
  bool exact = true;
  for (const int k : order) {
    const DeferredPeakStep& s = steps[static_cast<std::size_t>(k)];
    if (below(k, best)) {
      continue;  // the root's peak stays below a candidate of the in-order set
    }
    const auto [value, time] = search(k);
    if (!(value <= s.bound[i]) || below(k, value)) {
      exact = false;  // a bound the argument rests on failed by rounding
      break;
    }
    if (value > best || (value == best && s.t1_s < best_place)) {
      best = value;
      best_time = time;
      best_place = s.t1_s;
    }
  }
  if (exact) {
    max_abs_q = best;
    time_of_max_s = best_time;
    return false;
  }
  // The in-order scan: before step k's root the maximum is the better of its end fold and the
  // roots raised so far (found: root_place the place of the last).
  bool found = false;
  double root = 0.0, root_time = 0.0, root_place = 0.0;
  for (int k = 0; k < static_cast<int>(steps.size()); ++k) {
    const DeferredPeakStep& s = steps[static_cast<std::size_t>(k)];
    if ((s.coordinates & bit) == 0) continue;
    double m = s.end_max[i];
    if (found && (root > m || (root == m && root_place < s.end_time_s[i]))) m = root;
    if (s.bound[i] > m && !below(k, m)) {
      const auto [value, time] = search(k);
      if (value > m) {
        found = true;
        root = value;
        root_time = time;
        root_place = s.t1_s;
      }
    }
  }
  if (found && (root > max_abs_q || (root == max_abs_q && root_place < time_of_max_s))) {
    max_abs_q = root;
    time_of_max_s = root_time;
  }
  return true;
}

}  // namespace skewbridge::dynamics
