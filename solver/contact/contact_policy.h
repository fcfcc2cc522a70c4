#pragma once
/// @file
/// The thresholds of the contact layer's two complementarity problems (the impact problem and
/// the contact problem) in one place [docs/theory.md §3.15, the table of §3.16]. Each member
/// says its unit, the scale it is relative to and why it has its value. The event-driven
/// integrator holds one as EventPolicy::contact and hands it to its problems at the start of a
/// run (ImpactProblem::SetPolicy, ContactProblem::SetPolicy); run files and cubes store it with
/// the rest of the event policy. Its Describe (solver/common/schema.h) is the one list of its
/// members: the stored entries, their ranges and the documentation table come from it.

#include "solver/common/schema.h"
#include "solver/lcp/enumeration.h"

namespace skewbridge::contact {

/// The contact layer's thresholds (defaults: the values every result so far used).
struct ContactPolicy {
  /// A slip acceleration (a_R, a_L) or separating acceleration (d gamma_N/dt) of the contact
  /// problem's solution at most tie_tolerance times the scale of its row is zero: the contact
  /// keeps its mode (1; the scale is the largest sum of the magnitudes of the terms summed into
  /// an entry of b, |w_N|^T |M^-1 h| + |what_N|, in m/s^2). Those terms cancel in a balanced
  /// state (two identical decks at a closed joint have b = 0 up to their rounding, about 1e-16
  /// of the terms), so the band must be relative to the terms, not to b; 1e-9 is seven decades
  /// above that rounding and two below the integrator's a_detach (EventPolicy::force_tolerance,
  /// 1e-7 of v_ref omega_ref), so that a tie here is a tie there.
  double tie_tolerance = 1e-9;
  /// The compliance added to the normal rows of a contact problem that neither Lemke's
  /// algorithm nor the enumeration solved, d gamma_N/dt = -c lambda_N (1; c relative to the
  /// largest normal diagonal entry of W_N^T M^-1 W_Q, in m/s^2 per N). A deck clamped between
  /// two closed faces has dependent normal rows and no regular complementary basis; 1e-9 makes
  /// the normal block regular and picks the solution without squeeze while moving the forces by
  /// that relative amount, far below any resolved response.
  double contact_compliance = 1e-9;
  /// The same compliance for the impact problem, gamma_N,E + eps gamma_N,A = -c Lambda_N (1; c
  /// relative to the largest normal diagonal entry of W_N^T M^-1 (W_N - W_T mu), in m/s per N s).
  double impact_compliance = 1e-9;
  /// A problem of at most this many unknowns that Lemke's algorithm left on a ray is decided by
  /// the enumeration of its complementary bases (count, at most lcp::kMaxEnumerationSize): a
  /// ray proves nothing for a degenerate problem (two corners of one face with identical
  /// tangent rows). 14 unknowns are 2^14 bases at most, a few milliseconds; the contact problem
  /// of a single deck between two abutments has at most 12, its impact problem 12.
  int enumeration_unknowns = lcp::kMaxEnumerationSize;

  /// The members as stored (schema.h): name, unit, the scale each multiplies, what is allowed.
  template <typename Archive>
  void Describe(Archive* a) {
    using schema::Interval;
    a->Visit(SB_NVP(tie_tolerance),
             {"1", "largest sum of the magnitudes of the terms of b", Interval::AtLeast(0.0)});
    a->Visit(SB_NVP(contact_compliance),
             {"1", "largest normal diagonal entry", Interval::AtLeast(0.0)});
    a->Visit(SB_NVP(impact_compliance),
             {"1", "largest normal diagonal entry", Interval::AtLeast(0.0)});
    a->Visit(SB_NVP(enumeration_unknowns),
             {"1", "", Interval::Closed(0.0, lcp::kMaxEnumerationSize)});
  }
};

/// Aborts (SB_DEMAND) unless every member of `policy` is within its description's range (the
/// tolerances finite and >= 0, 0 <= enumeration_unknowns <= lcp::kMaxEnumerationSize): the
/// integrator validates the policy it is given (dynamics::ValidatePolicy), so a policy outside
/// here is a bug.
void CheckContactPolicy(const ContactPolicy& policy);

/// Whether every member of `a` has the bytes of the same member of `b` (the padding between
/// them aside): two such policies get the same verdict from CheckContactPolicy, so a problem
/// that holds a checked policy need not check one with its bytes again.
bool SameBytes(const ContactPolicy& a, const ContactPolicy& b);

}  // namespace skewbridge::contact
