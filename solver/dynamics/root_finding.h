#pragma once
/// @file
/// Bracketed scalar root finding for event location on dense output [docs/theory.md §3, events]:
/// Brent's method (inverse quadratic interpolation, secant and bisection), which keeps the
/// bracket and converges superlinearly on smooth functions [Brent 1973, ch. 4].

#include <algorithm>
#include <cmath>
#include <utility>

namespace skewbridge::dynamics {

/// Outcome of a bracketed root search.
struct RootResult {
  double x = 0.0;         ///< the root estimate (inside the final bracket)
  double fx = 0.0;        ///< f(x)
  double lower = 0.0;     ///< final bracket [lower, upper] with a sign change (or a zero)
  double upper = 0.0;     ///< final bracket end
  int evaluations = 0;    ///< calls of f
  bool bracketed = true;  ///< false when f(a) f(b) > 0 on entry (then x = a)
};

/// Brent's method for f(x) = 0 on [a, b] given fa = f(a), fb = f(b) with fa fb <= 0.
/// Stops when the bracket is shorter than 2 x_tolerance (absolute, > 0) or f(x) = 0.
/// One change to Brent's rules: once a minimal step (x_tolerance-sized, taken where the
/// interpolation puts the root within it) lands on the same side, f is flat at that resolution
/// (rounding noise near the root, or a multiple root), and the rest of the search bisects. Brent
/// would alternate such a step with a bisection, two evaluations per halving of the bracket.
/// @pre a < b; f is continuous on [a, b].
template <class Function>
RootResult FindRootBrent(Function&& f, double a, double b, double fa, double fb, double x_tolerance,
                         int max_iterations = 200) {
  RootResult result;
  if (fa * fb > 0.0) {
    result.x = a;
    result.fx = fa;
    result.lower = a;
    result.upper = b;
    result.bracketed = false;
    return result;
  }
  if (fa == 0.0 || fb == 0.0) {
    result.x = fa == 0.0 ? a : b;
    result.fx = 0.0;
    result.lower = result.upper = result.x;
    return result;
  }
  double c = b, fc = fb, d = b - a, e = d;
  bool flat = false;  // a minimal step stayed on its side: bisect from now on
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    if ((fb > 0.0) == (fc > 0.0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tolerance = 2.0 * 1.1102230246251565e-16 * std::abs(b) + 0.5 * x_tolerance;
    const double middle = 0.5 * (c - b);
    if (std::abs(middle) <= tolerance || fb == 0.0) {
      break;
    }
    if (!flat && std::abs(e) >= tolerance && std::abs(fa) > std::abs(fb)) {
      // Inverse quadratic interpolation (secant when only two distinct points).
      const double s = fb / fa;
      double p, q;
      if (a == c) {
        p = 2.0 * middle * s;
        q = 1.0 - s;
      } else {
        const double qq = fa / fc, r = fb / fc;
        p = s * (2.0 * middle * qq * (qq - r) - (b - a) * (r - 1.0));
        q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) {
        q = -q;
      }
      p = std::abs(p);
      if (2.0 * p < std::min(3.0 * middle * q - std::abs(tolerance * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = middle;
        e = d;
      }
    } else {
      d = middle;
      e = d;
    }
    a = b;
    fa = fb;
    const bool minimal = !(std::abs(d) > tolerance);
    b += minimal ? (middle > 0.0 ? tolerance : -tolerance) : d;
    fb = f(b);
    ++result.evaluations;
    flat = flat || (minimal && (fb > 0.0) == (fa > 0.0) && fb != 0.0);
  }
  result.x = b;
  result.fx = fb;
  result.lower = std::min(b, c);
  result.upper = std::max(b, c);
  return result;
}

}  // namespace skewbridge::dynamics
