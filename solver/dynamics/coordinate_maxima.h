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
/// and x1[i] at its end t1 (h_s the step's length): every coordinate's two tests,
/// max_abs_q[i] < |q1_i| and u0_i u1_i < +0 (RaiseMaximaAtEnd's comparisons with their operands
/// swapped, the same outcome), side by side first; when none holds nothing is raised and there
/// is nothing to search. Else RaiseMaximaAtEnd's operations on the lanes in its order, so the
/// same maxima and the same answer.
inline bool RaiseMaximaAtEnd3(const CoordinateLanes x0[3], const CoordinateLanes x1[3], double t1,
                              double h_s, double max_abs_q[3], double time_of_max_s[3]) {
  using Bits2 = long long __attribute__((vector_size(16)));
  const auto magnitude = [](CoordinateLanes v) {
    return std::bit_cast<CoordinateLanes>(std::bit_cast<Bits2>(v) &
                                          Bits2{0x7fffffffffffffffLL, 0x7fffffffffffffffLL});
  };
  // (max_abs_q[i], u0_i u1_i) < (|q1_i|, +0), lane by lane.
  const Bits2 q_magnitude = {0x7fffffffffffffffLL, 0};
  Bits2 any = {0, 0};
  for (int i = 0; i < 3; ++i) {
    const CoordinateLanes end =
        std::bit_cast<CoordinateLanes>(std::bit_cast<Bits2>(x1[i]) & q_magnitude);
    const CoordinateLanes product = x0[i] * x1[i];
    const CoordinateLanes reference = {max_abs_q[i], product[1]};
    any |= reference < end;
  }
  // No lane's comparison held: no lane's sign bit is set (one movmskpd where SSE2 has it;
  // elsewhere the lanes' OR).
#if defined(__SSE2__)
  const bool none = __builtin_ia32_movmskpd(std::bit_cast<CoordinateLanes>(any)) == 0;
#else
  const bool none = (any[0] | any[1]) == 0;
#endif
  if (none) {
    return false;
  }
  bool search = false;
  for (int i = 0; i < 3; ++i) {
    const CoordinateLanes a0 = magnitude(x0[i]), a1 = magnitude(x1[i]);
    if (a1[0] > max_abs_q[i]) {
      max_abs_q[i] = a1[0];
      time_of_max_s[i] = t1;
    }
    if (x0[i][1] * x1[i][1] < 0.0) {
      // (max(|q0|, |q1|), max(|u0|, |u1|)) as std::max takes them.
      const CoordinateLanes larger = a0 < a1 ? a1 : a0;
      const double bound = larger[0] + 0.5 * h_s * larger[1];
      search = search || bound > max_abs_q[i];
    }
  }
  return search;
}

}  // namespace skewbridge::dynamics
