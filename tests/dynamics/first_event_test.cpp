/// The first event of a step as the integrator's two steps locate it (solver/dynamics/
/// event_location.h) [docs/theory.md §3.12]: FirstClosedEvent on analytic event functions of
/// closed contacts against their closed-form first roots, and SimultaneousContacts on linear gaps
/// against the contacts that close within the simultaneity tolerance.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "solver/dynamics/event_location.h"

namespace skewbridge::dynamics::first_event_test {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Event functions of three contacts over a step [t0, t1] = [1, 1.01] s as functions of time,
// two per contact (detachment, then stick-slip), the values at the step's ends taken from them.
struct Case {
  std::vector<ContactMode> modes;                // per contact
  std::vector<std::function<double(double)>> f;  // 2 per contact
  double expected;                               // the first event time (s), or +inf
  int fires;                                     // the function that fires first (-1: none)
  const char* why;
};

double Line(double t, double root, double slope) { return slope * (t - root); }

TEST(ClosedEvent, FindsTheFirstEventOfTheClosedContacts) {
  const double t0 = 1.0, t1 = 1.01;
  const auto positive = [](double) { return 1.0; };
  using M = ContactMode;
  const std::vector<Case> cases = {
      {{M::kSlidePositive, M::kOpen, M::kStick},
       {[](double t) { return Line(t, 1.004, -50.0); }, positive, positive, positive, positive,
        positive},
       1.004,
       0,
       "a normal force falling through zero: detachment at its root"},
      {{M::kSlidePositive, M::kOpen, M::kStick},
       {[](double t) { return Line(t, 1.009, -50.0); }, positive, positive, positive, positive,
        [](double t) { return 1e-4 - 2.0 * (t - 1.0) * (t - 1.0); }},
       1.0 + std::sqrt(0.5e-4),
       5,
       "a friction reaching the cone (quadratic) before the detachment"},
      {{M::kSlidePositive, M::kOpen, M::kStick},
       {positive, positive, [](double t) { return Line(t, 1.002, -1.0); }, positive, positive,
        positive},
       kInf,
       -1,
       "an open contact's functions are not looked at"},
      {{M::kSlidePositive, M::kOpen, M::kStick},
       {positive, [](double t) { return Line(t, 1.008, -3.0); }, positive, positive,
        [](double) { return -1e-3; }, positive},
       t0,
       4,
       "a function already negative at the step's start fires there"},
      {{M::kSlidePositive, M::kOpen, M::kStick},
       {[](double t) { return (t - 1.005) * (t - 1.005) - 1e-5; }, positive, positive, positive,
        positive, positive},
       kInf,
       -1,
       "a function that dips below zero and recovers inside the step: only a sign change between "
       "the ends is searched"},
      {{M::kStick, M::kOpen, M::kStick},
       {positive, positive, positive, positive, [](double t) { return Line(t, 1.003, -2.0); },
        [](double t) { return Line(t, 1.001, -2.0); }},
       1.001,
       5,
       "the earliest of two crossings of one contact"},
  };
  const EventPolicy policy;
  const double bracket = EventTimeBracket(t1, policy);
  for (const Case& k : cases) {
    SCOPED_TRACE(k.why);
    ContactModes modes(static_cast<int>(k.modes.size()));
    for (std::size_t c = 0; c < k.modes.size(); ++c) {
      modes.Set(static_cast<int>(c), k.modes[c]);
    }
    Eigen::VectorXd f0(k.f.size()), f1(k.f.size());
    for (std::size_t e = 0; e < k.f.size(); ++e) {
      f0[static_cast<Eigen::Index>(e)] = k.f[e](t0);
      f1[static_cast<Eigen::Index>(e)] = k.f[e](t1);
    }
    int evaluations = 0;
    const auto value_at = [&](double t, int e) {
      ++evaluations;
      return k.f[static_cast<std::size_t>(e)](t);
    };
    const double t = FirstClosedEvent(t0, t1, f0, f1, modes, value_at, policy);
    if (k.fires < 0) {
      EXPECT_EQ(t, kInf);
      EXPECT_EQ(evaluations, 0) << "nothing to search";
      continue;
    }
    EXPECT_NEAR(t, k.expected, bracket);
    // On the side where the event has happened: the function is not positive there.
    EXPECT_LE(k.f[static_cast<std::size_t>(k.fires)](t), 0.0);
  }
}

// The bracket is the policy's: a coarse event_time_tolerance gives a time within it, still on
// the side where the event has happened.
TEST(ClosedEvent, LocatesToThePolicysBracket) {
  const double t0 = 0.0, t1 = 0.02, root = 0.0123;
  ContactModes modes(1);
  modes.Set(0, ContactMode::kFrictionless);
  const auto f = [&](double t) { return 1.0 - t / root; };
  Eigen::VectorXd f0(2), f1(2);
  f0 << f(t0), 1.0;
  f1 << f(t1), 1.0;
  for (const double tolerance : {1e-13, 1e-9, 1e-5}) {
    EventPolicy policy;
    policy.event_time_tolerance = tolerance;
    const double t = FirstClosedEvent(
        t0, t1, f0, f1, modes, [&](double s, int e) { return e == 0 ? f(s) : 1.0; }, policy);
    EXPECT_NEAR(t, root, EventTimeBracket(t1, policy)) << "tolerance " << tolerance;
    EXPECT_LE(f(t), 0.0) << "tolerance " << tolerance;
  }
}

// --- Nearly simultaneous impacts [§3, §3.12] ---------------------------------------------------

// The contacts that strike with the first impact at t_e: open contacts approaching their faces
// at v, g_c(t) = v (r_c - t), closing at r_c. Those whose gap is within gap_tol at
// t_e + simultaneity (or at the step's end, if that comes first) join it; a closed contact
// does not (it takes part in any decision as closed).
TEST(Simultaneity, GroupsTheContactsClosedWithinTheToleranceOfTheFirst) {
  const double v = 0.1, t_e = 1.0, tol = 1e-9, step_end = 1.0 + 1e-6;
  const double gap_tol = 1e-12;  // m: gap_tol / v = 1e-11 s
  struct Row {
    std::vector<double> roots;       // r_c (s)
    std::vector<ContactMode> modes;  // per contact
    double t_end;                    // the step's end
    std::vector<int> expected;       // the contacts grouped
    const char* why;
  };
  using M = ContactMode;
  const Row rows[] = {
      {{t_e, t_e + 0.5e-9, t_e + 2e-9, t_e + 1e-3},
       {M::kOpen, M::kOpen, M::kOpen, M::kOpen},
       step_end,
       {0, 1},
       "the first and one 0.5 ns later; not 2 ns or 1 ms later"},
      {{t_e + 1e-9 + 0.5e-11, t_e, t_e + 1e-9 + 2e-11},
       {M::kOpen, M::kOpen, M::kOpen},
       step_end,
       {0, 1},
       "within the touch band at t_e + tol (0.5 gap_tol away) joins; 2 gap_tol away does not"},
      {{t_e, t_e + 0.5e-9, t_e},
       {M::kOpen, M::kOpen, M::kStick},
       step_end,
       {0, 1},
       "a closed contact at its face is not listed"},
      {{t_e, t_e + 0.5e-9, t_e + 0.2e-9},
       {M::kOpen, M::kOpen, M::kOpen},
       t_e + 0.3e-9,
       {0, 2},
       "the step ends 0.3 ns after the first impact: the gaps there decide"},
  };
  for (const Row& r : rows) {
    ContactModes modes(static_cast<int>(r.modes.size()));
    for (std::size_t c = 0; c < r.modes.size(); ++c) {
      modes.Set(static_cast<int>(c), r.modes[c]);
    }
    // "Positions" are the time itself here: the gaps are functions of t alone.
    Eigen::VectorXd q(1);
    const auto positions_at = [&](double t) {
      q[0] = t;
      return q;
    };
    const auto gap_of = [&](int c, const Eigen::VectorXd& at) {
      return v * (r.roots[static_cast<std::size_t>(c)] - at[0]);
    };
    std::vector<int> forced = {7};  // appended to
    SimultaneousContacts(t_e, r.t_end, tol, gap_tol, modes, positions_at, gap_of, forced);
    std::vector<int> expected = {7};
    expected.insert(expected.end(), r.expected.begin(), r.expected.end());
    EXPECT_EQ(forced, expected) << r.why;
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::first_event_test
