#include "solver/lcp/lemke.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "solver/lcp/lcp_check.h"

namespace skewbridge::lcp {
namespace {

/// The exponent e of the smallest power of two 2^e >= max_abs (0 for 0): dividing by 2^e is
/// exact, so the scaled problem has the same solution bits up to the exponent.
int ExponentAtLeast(double max_abs) {
  if (max_abs == 0.0) return 0;
  const auto bits = std::bit_cast<std::uint64_t>(max_abs);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased != 0 && biased != 0x7ff) {
    // A normal number 1.f 2^(biased - 1023): frexp's exponent is biased - 1022, its mantissa
    // 0.5 exactly when f = 0 (read from the bits: no library call per solve).
    const bool power_of_two = (bits & ((std::uint64_t{1} << 52) - 1)) == 0;
    return power_of_two ? biased - 1023 : biased - 1022;
  }
  int exponent = 0;
  const double mantissa = std::frexp(max_abs, &exponent);  // max_abs = mantissa 2^exponent
  return mantissa == 0.5 ? exponent - 1 : exponent;
}

/// 2^exponent, exactly std::ldexp(1.0, exponent): built from its bits when it is a normal double.
double TwoToThe(int exponent) {
  if (exponent >= std::numeric_limits<double>::min_exponent - 1 &&
      exponent <= std::numeric_limits<double>::max_exponent - 1) {
    return std::bit_cast<double>(static_cast<std::uint64_t>(exponent + 1023) << 52);
  }
  return std::ldexp(1.0, exponent);
}

/// "M(2, 3)" style position for messages.
std::string Position(const char* name, Eigen::Index i, Eigen::Index j) {
  return std::string(name) + "(" + std::to_string(i) + ", " + std::to_string(j) + ")";
}

/// Empty when (M, q) is a well-formed problem; otherwise the problem in one line.
std::string ValidationMessage(const Eigen::Ref<const Eigen::MatrixXd>& M,
                              const Eigen::Ref<const Eigen::VectorXd>& q) {
  if (M.rows() != M.cols()) {
    return "M must be square (got " + std::to_string(M.rows()) + " x " + std::to_string(M.cols()) +
           ")";
  }
  if (q.size() != M.rows()) {
    return "q must have M's size " + std::to_string(M.rows()) + " (got " +
           std::to_string(q.size()) + ")";
  }
  if (M.rows() == 0) return "empty problem (n = 0)";
  for (Eigen::Index j = 0; j < M.cols(); ++j) {
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      if (!std::isfinite(M(i, j))) return Position("M", i, j) + " is not finite";
    }
  }
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    if (!std::isfinite(q(i))) return "q(" + std::to_string(i) + ") is not finite";
  }
  return {};
}

/// The largest magnitude of the `rows` x `cols` entries at `a` (column-major, columns `ld`
/// apart) into `max_abs`, and whether every entry is finite, in one pass: an entry's magnitude
/// is at most the largest double exactly when it is finite. When all are, max_abs is the value
/// cwiseAbs().maxCoeff() gives (the maximum of magnitudes is exact in any order).
bool MaxAbsOfFinite(const double* a, Eigen::Index rows, Eigen::Index cols, Eigen::Index ld,
                    double& max_abs) {
  constexpr double kLargest = std::numeric_limits<double>::max();
  double largest = 0.0;
  bool finite = true;
  for (Eigen::Index j = 0; j < cols; ++j) {
    const double* col = a + j * ld;
    for (Eigen::Index i = 0; i < rows; ++i) {
      const double m = std::abs(col[i]);
      finite = finite & (m <= kLargest);
      largest = m > largest ? m : largest;
    }
  }
  max_abs = largest;
  return finite;
}

/// True when (M, q) is a well-formed problem (the check of ValidationMessage without building a
/// string, for the solve of every impact and contact problem), with the largest magnitudes of
/// the entries of M and q (in their units) into `max_abs_M` and `max_abs_q` when it is.
bool WellFormed(const Eigen::Ref<const Eigen::MatrixXd>& M,
                const Eigen::Ref<const Eigen::VectorXd>& q, double& max_abs_M, double& max_abs_q) {
  if (!(M.rows() == M.cols() && q.size() == M.rows() && M.rows() != 0)) return false;
  const bool m_finite = MaxAbsOfFinite(M.data(), M.rows(), M.cols(), M.outerStride(), max_abs_M);
  return m_finite && MaxAbsOfFinite(q.data(), q.size(), 1, q.size(), max_abs_q);
}

/// x 2^exponent: a product by the exact power of two when that power is a normal double (the
/// same correctly rounded result as std::ldexp, without the library call), else std::ldexp.
class PowerOfTwo {
 public:
  explicit PowerOfTwo(int exponent)
      : exponent_(exponent),
        factor_(exponent >= std::numeric_limits<double>::min_exponent - 1 &&
                        exponent <= std::numeric_limits<double>::max_exponent - 1
                    ? TwoToThe(exponent)
                    : 0.0) {}
  double operator()(double x) const {
    return factor_ != 0.0 ? x * factor_ : std::ldexp(x, exponent_);
  }

 private:
  int exponent_;
  double factor_;  // 2^exponent, or 0 when it is not a normal double
};

void ResizeIfNeeded(Eigen::VectorXd& v, Eigen::Index n) {
  if (v.size() != n) v.resize(n);
}

}  // namespace

const char* ToString(LcpStatus status) {
  switch (status) {
    case LcpStatus::kSolved:
      return "solved";
    case LcpStatus::kSecondaryRay:
      return "secondary-ray";
    case LcpStatus::kPivotLimit:
      return "pivot-limit";
    case LcpStatus::kInvalidInput:
      return "invalid-input";
    case LcpStatus::kInaccurate:
      return "inaccurate";
  }
  return "unknown";
}

LemkeSolver::LemkeSolver(LemkeOptions options) : options_(options) {}

void LemkeSolver::Reserve(Eigen::Index n) {
  if (n <= capacity_) return;
  capacity_ = n;
  inverse_basis_.resize(n, n);
  basic_values_.resize(n);
  column_.resize(n);
  residual_.resize(n);
  basis_.resize(n);
  ties_.resize(n);
  row_size_.resize(n);
  tie_size_.resize(n);
}

void LemkeSolver::Pivot(Eigen::Index n, Eigen::Index r) {
  // One Gauss-Jordan step on [B^-1 | x_B] with the entering column d: row r is divided by d_r,
  // then d_i times the new row r is taken from every other row. Column-major loops keep the
  // inner loop contiguous.
  const Eigen::Index ld = capacity_;
  double* binv = inverse_basis_.data();
  double* d = column_.data();
  double* x = basic_values_.data();
  const double inv_pivot = 1.0 / d[r];
  const double d_r = d[r];
  d[r] = 0.0;  // so the row update below leaves row r alone; restored after
  for (Eigen::Index j = 0; j < n; ++j) {
    double* col = binv + j * ld;
    const double b_rj = col[r] * inv_pivot;
    if (b_rj != 0.0) {
      for (Eigen::Index i = 0; i < n; ++i) col[i] -= d[i] * b_rj;
    }
    col[r] = b_rj;
  }
  const double x_r = x[r] * inv_pivot;
  for (Eigen::Index i = 0; i < n; ++i) x[i] -= d[i] * x_r;
  x[r] = x_r;
  d[r] = d_r;

  // Growth bound of each row: the largest magnitude combined into it so far. Rounding in a row
  // is of order eps times this bound, even after cancellation has made the row itself small.
  double* growth = row_size_.data();
  growth[r] *= std::abs(inv_pivot);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (i == r) continue;
    growth[i] = std::max(growth[i], std::abs(d[i]) * growth[r]);
  }
}

Eigen::Index LemkeSolver::LexicographicRatioTest(Eigen::Index n, Eigen::Index z0_row,
                                                 double column_size) {
  // Rounding in x_i = (B^-1 q')_i and d_i = (B^-1 a_e)_i is of order eps g_i, with g_i the
  // growth bound of row i (see Pivot), which reaches 1/(smallest pivot) when M mixes scales
  // (impulse rows of order 1/m next to friction rows of order 1). Every comparison below is
  // therefore relative to g_i: d_i counts as positive when d_i > tol g_i |a_e|, and two ratios
  // tie when they differ by less than the sum of their rounding bounds
  // tie_tol g_i (1 + |ratio_i| |a_e|) / d_i (max|q'| = 1 after scaling).
  const double tol = options_.relative_tolerance;
  const Eigen::Index ld = capacity_;
  const double* binv = inverse_basis_.data();
  const double* d = column_.data();
  const double* x = basic_values_.data();
  const double* growth = row_size_.data();
  double* size = tie_size_.data();
  int* ties = ties_.data();

  Eigen::Index num_candidates = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (d[i] > tol * growth[i] * column_size) {
      size[num_candidates] = growth[i];
      ties[num_candidates++] = static_cast<int>(i);
    }
  }
  if (num_candidates == 0) return -1;

  // Minimum ratio and its rounding bound, then every candidate within the two bounds.
  const double tie_tol = options_.tie_tolerance;
  auto ratio_error = [&](Eigen::Index k, double value) {
    return tie_tol * size[k] * (1.0 + std::abs(value) * column_size) / d[ties[k]];
  };
  Eigen::Index best = 0;
  for (Eigen::Index k = 1; k < num_candidates; ++k) {
    if (x[ties[k]] / d[ties[k]] < x[ties[best]] / d[ties[best]]) best = k;
  }
  const double min_ratio = x[ties[best]] / d[ties[best]];
  const double min_error = ratio_error(best, min_ratio);
  Eigen::Index num_ties = 0;
  for (Eigen::Index k = 0; k < num_candidates; ++k) {
    const double ratio = x[ties[k]] / d[ties[k]];
    if (ratio - min_ratio <= min_error + ratio_error(k, ratio)) {
      size[num_ties] = size[k];
      ties[num_ties++] = ties[k];
    }
  }
  // When z0 can leave it does: the basis that remains is complementary, so the solve ends.
  for (Eigen::Index k = 0; k < num_ties; ++k) {
    if (ties[k] == z0_row) return z0_row;
  }
  // Ties broken by the lexicographic minimum of rows (x_B, B^-1)_i / d_i: rows of B^-1 are
  // linearly independent, so exactly one row survives in exact arithmetic, and the basic
  // solution of the lexicographically perturbed problem q + (eps, eps^2, ...) stays
  // non-degenerate; that is what rules out cycling [Cottle, Pang and Stone 1992, §4.9].
  for (Eigen::Index j = 0; j < n && num_ties > 1; ++j) {
    const double* col = binv + j * ld;
    Eigen::Index lex_best = 0;
    for (Eigen::Index k = 1; k < num_ties; ++k) {
      if (col[ties[k]] / d[ties[k]] < col[ties[lex_best]] / d[ties[lex_best]]) lex_best = k;
    }
    const double min_entry = col[ties[lex_best]] / d[ties[lex_best]];
    const double min_entry_error = ratio_error(lex_best, min_entry);
    Eigen::Index kept = 0;
    for (Eigen::Index k = 0; k < num_ties; ++k) {
      const double entry = col[ties[k]] / d[ties[k]];
      if (entry - min_entry <= min_entry_error + ratio_error(k, entry)) {
        size[kept] = size[k];
        ties[kept++] = ties[k];
      }
    }
    num_ties = kept;
  }
  return ties[0];
}

LcpStatus LemkeSolver::Solve(const Eigen::Ref<const Eigen::MatrixXd>& M,
                             const Eigen::Ref<const Eigen::VectorXd>& q, LcpSolution& solution) {
  solution.pivots = 0;
  solution.complementarity = 0.0;
  solution.worst_violation = 0.0;
  solution.message.clear();
  double max_abs_M = 0.0, max_abs_q = 0.0;
  if (!WellFormed(M, q, max_abs_M, max_abs_q)) {
    solution.status = LcpStatus::kInvalidInput;
    solution.message = ValidationMessage(M, q);
    return solution.status;
  }
  const Eigen::Index n = M.rows();
  ResizeIfNeeded(solution.z, n);
  ResizeIfNeeded(solution.w, n);
  solution.z.setZero();

  const double tol = options_.relative_tolerance;
  // Exact power-of-two scaling: with M' = M / s_M and q' = q / s_q, the LCP (M', q') has the
  // solution z' = z s_M / s_q, w' = w / s_q, and every entry of M', q' lies in [-1, 1]. Scaling
  // by powers of two changes no mantissa, so the pivots follow the same path for any units.
  // q is scaled by ldexp rather than by 1 / s_q, which overflows when q is subnormal (a q of
  // rounding residue only, as for a deck at rest).
  const double inv_s_m = TwoToThe(-ExponentAtLeast(max_abs_M));
  const int q_exponent = ExponentAtLeast(max_abs_q);
  const PowerOfTwo to_scaled(-q_exponent), from_scaled(q_exponent);
  // Entries of q' within twice the pivot tolerance of zero are zero to the solver. The first
  // pivot's tie test (tolerance tol (1 + |min q'|)) cannot tell them from 0: a tiny negative
  // q'_i tied with a zero entry could be passed over there, stay basic and negative, and end
  // the path on a false secondary ray (q = (8e-17, -2e-35, 0) of a contact problem did). With
  // the margin 2 tol every surviving negative entry is below every zero entry's tie band. The
  // answer for the snapped q' solves the given problem within 2 tol max|q|.
  const double snap = 2.0 * tol;
  auto scaled_q = [&](Eigen::Index i) {
    const double value = to_scaled(q(i));
    return std::abs(value) <= snap ? 0.0 : value;
  };
  bool z_zero_solves = true;
  for (Eigen::Index i = 0; i < n && z_zero_solves; ++i) z_zero_solves = scaled_q(i) >= 0.0;
  if (z_zero_solves) {
    solution.w = q;
    const double min_q = q.minCoeff();
    if (min_q < 0.0) {  // only snapped entries are negative
      solution.complementarity = -min_q;
      solution.worst_violation = CheckSolutionOfFinite(M, q, solution.z, max_abs_M, max_abs_q,
                                                       options_.acceptance_tolerance)
                                     .worst_violation;
    }
    solution.status = LcpStatus::kSolved;
    return solution.status;
  }

  Reserve(n);
  const Eigen::Index ld = capacity_;
  const Eigen::Index z0 = 2 * n;  // variable numbering: w_i = i, z_i = n + i, z0 = 2n
  const double* m_data = M.data();
  const Eigen::Index m_ld = M.outerStride();

  double* binv = inverse_basis_.data();
  double* x = basic_values_.data();
  double* d = column_.data();
  int* basis = basis_.data();
  std::fill_n(binv, (n - 1) * ld + n, 0.0);  // B^-1 = I: its n columns of stride ld
  for (Eigen::Index j = 0; j < n; ++j) {
    binv[j * ld + j] = 1.0;
    x[j] = scaled_q(j);
    basis[j] = static_cast<int>(j);
    row_size_(j) = 1.0;  // [I | q'] has entries of size <= 1
  }

  // First pivot: z0 enters with column -e and replaces the most negative q_i, which makes every
  // basic value non-negative. Ties go to the largest index: with B^-1 = I that is the
  // lexicographic rule (row r - row i starts with +1 at min(i, r) only when r > i).
  Eigen::Index r = 0;
  {
    double min_x = x[0];
    for (Eigen::Index i = 1; i < n; ++i) min_x = std::min(min_x, x[i]);
    const double tie_tol = tol * (1.0 + std::abs(min_x));
    for (Eigen::Index i = 0; i < n; ++i) {
      if (x[i] <= min_x + tie_tol) r = i;
    }
  }
  for (Eigen::Index i = 0; i < n; ++i) d[i] = -1.0;
  Pivot(n, r);
  basis[r] = static_cast<int>(z0);
  const Eigen::Index z0_row = r;  // z0 keeps its row until it leaves
  Eigen::Index entering = n + r;  // w_r left, so z_r enters
  solution.pivots = 1;

  const int max_pivots = options_.max_pivots_per_unknown * static_cast<int>(n + 1);
  LcpStatus status = LcpStatus::kSolved;
  while (true) {
    if (solution.pivots >= max_pivots) {
      status = LcpStatus::kPivotLimit;
      break;
    }
    // Entering column d = B^-1 a_e with a_e the column of (I, -M', -e) for the variable.
    double column_size = 1.0;  // max |a_e|
    if (entering < n) {
      const double* col = binv + entering * ld;
      for (Eigen::Index i = 0; i < n; ++i) d[i] = col[i];
    } else {
      const Eigen::Index j = entering - n;
      const double* m_col = m_data + j * m_ld;
      for (Eigen::Index i = 0; i < n; ++i) d[i] = 0.0;
      column_size = 0.0;
      for (Eigen::Index k = 0; k < n; ++k) {
        const double c = -m_col[k] * inv_s_m;
        if (c == 0.0) continue;
        column_size = std::max(column_size, std::abs(c));
        const double* binv_col = binv + k * ld;
        for (Eigen::Index i = 0; i < n; ++i) d[i] += c * binv_col[i];
      }
    }
    r = LexicographicRatioTest(n, z0_row, column_size);
    if (r < 0) {
      status = LcpStatus::kSecondaryRay;
      break;
    }
    const Eigen::Index leaving = basis[r];
    Pivot(n, r);
    basis[r] = static_cast<int>(entering);
    ++solution.pivots;
    if (leaving == z0) break;  // complementary basis: solved
    entering = leaving < n ? leaving + n : leaving - n;
  }

  if (status == LcpStatus::kSecondaryRay) {
    solution.message = "secondary ray: the entering column has no positive entry";
  } else if (status == LcpStatus::kPivotLimit) {
    solution.message = "pivot limit of " + std::to_string(max_pivots) + " reached";
  }
  if (status != LcpStatus::kSolved) {
    solution.w = q;  // z = 0
    solution.status = status;
    return status;
  }

  // One step of iterative refinement on B x_B = q' with the original columns removes most of
  // the rounding the pivots accumulated: x_B += B^-1 (q' - B x_B).
  double* res = residual_.data();
  for (Eigen::Index i = 0; i < n; ++i) res[i] = to_scaled(q(i));
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index var = basis[k];
    if (var < n) {
      res[var] -= x[k];
    } else {  // z_j has column -M'_j (z0 has left the basis)
      const double* m_col = m_data + (var - n) * m_ld;
      const double x_scaled = x[k] * inv_s_m;
      for (Eigen::Index i = 0; i < n; ++i) res[i] += m_col[i] * x_scaled;
    }
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    const double* col = binv + j * ld;
    const double r_j = res[j];
    if (r_j == 0.0) continue;
    for (Eigen::Index i = 0; i < n; ++i) x[i] += col[i] * r_j;
  }

  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index var = basis[k];
    if (var >= n) solution.z(var - n) = from_scaled(std::max(0.0, x[k]) * inv_s_m);
  }
  solution.w.noalias() = M * solution.z;
  solution.w += q;
  solution.complementarity = solution.z.cwiseMin(solution.w).cwiseAbs().maxCoeff();
  // (M, q) passed WellFormed and were measured above: the check need not read them again.
  const LcpCheck check =
      CheckSolutionOfFinite(M, q, solution.z, max_abs_M, max_abs_q, options_.acceptance_tolerance);
  solution.worst_violation = check.worst_violation;
  if (!check.is_solution) {
    status = LcpStatus::kInaccurate;
    solution.message = fmt::format("terminal basis inaccurate: worst violation {:g} exceeds {:g}",
                                   check.worst_violation, options_.acceptance_tolerance);
  }
  solution.status = status;
  return status;
}

void LemkeSolver::Prepare(Eigen::Index max_n, std::vector<LcpSolution>& solutions) {
  solutions.resize(static_cast<std::size_t>(max_n + 1));
  for (std::size_t n = 0; n < solutions.size(); ++n) {
    solutions[n].z.setZero(static_cast<Eigen::Index>(n));
    solutions[n].w.setZero(static_cast<Eigen::Index>(n));
    solutions[n].message.reserve(128);
  }
  // The pivoting's buffers for the largest size: the first solve that pivots, inside a run's
  // time loop, then allocates nothing either.
  Reserve(max_n);
}

}  // namespace skewbridge::lcp
