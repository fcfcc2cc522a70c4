#pragma once
/// @file
/// The LCP w = M z + q, w >= 0, z >= 0, w^T z = 0 solved by enumerating its complementary
/// bases [Cottle, Pang and Stone 1992, §1.1]: for every subset alpha of the indices, z_alpha
/// solves M_aa z_a = -q_a (least squares for a singular M_aa), z = 0 elsewhere, and the first
/// subset whose z and w pass lcp::CheckSolution is returned. 2^n small solves: a second method
/// for small problems, used where Lemke's algorithm ends on a secondary ray, which for a
/// degenerate problem (two identical rows: the tangents of two corners on one face) does not
/// prove that no solution exists. When the enumeration finds none either, none exists (up to
/// the tolerance): that is the proof behind a Painleve status.

#include <Eigen/Core>

#include "solver/lcp/lemke.h"

namespace skewbridge::lcp {

/// Largest n enumerated (2^n bases).
inline constexpr int kMaxEnumerationSize = 14;

/// Solves by enumeration; `solution.status` is kSolved (z, w filled, the first subset in
/// increasing bit order that passes CheckSolution(M, q, z, tolerance)), kSecondaryRay when no
/// subset does (no solution), or kInvalidInput (n > kMaxEnumerationSize, sizes, non-finite).
/// Allocates (a fallback path, not the hot loop).
LcpStatus SolveByEnumeration(const Eigen::Ref<const Eigen::MatrixXd>& M,
                             const Eigen::Ref<const Eigen::VectorXd>& q, LcpSolution& solution,
                             double tolerance = 1e-9);

}  // namespace skewbridge::lcp
