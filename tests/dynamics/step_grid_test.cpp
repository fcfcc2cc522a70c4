/// Step reuse and snapping (solver/dynamics/step_grid.h) [docs/theory.md §3.14], each rule with
/// its band on and off, against grid points and step lengths worked by hand.

#include "solver/dynamics/step_grid.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace skewbridge::dynamics::step_grid_test {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

ExcitationPiece Piece(double t_begin, double t_end, double omega = 0.0) {
  ExcitationPiece p;
  p.t_begin = t_begin;
  p.t_end = t_end;
  p.omega = omega;
  return p;
}

TEST(StepGrid, FreeStepIsAFractionOfTheShortestPeriodCutEvenlyOverThePiece) {
  const EventPolicy policy;
  const double omega = 2.0 * std::numbers::pi * 10.0;  // 10 Hz: h_max = 1 / 200 s
  struct Row {
    ExcitationPiece piece;
    double omega_max;
    double expected;
    const char* why;
  };
  const Row rows[] = {
      {Piece(0.0, kInf), omega, 0.005, "an unbounded piece: h_max"},
      {Piece(1.0, 1.0195), omega, 0.0195 / 4.0, "a piece of 3.9 h_max: four equal steps"},
      {Piece(1.0, 1.021), omega, 0.021 / 5.0, "a piece of 4.2 h_max: five equal steps"},
      {Piece(0.0, kInf, 2.0 * omega), omega, 0.0025, "the excitation's frequency is higher"},
      {Piece(0.0, kInf), 0.0, 2.0 * std::numbers::pi / 1e-3 / 20.0, "a free body: the floor"},
  };
  for (const Row& r : rows) {
    EXPECT_NEAR(FreeStepSize(r.piece, r.omega_max, policy), r.expected, 1e-13 * r.expected)
        << r.why;
  }
}

// The pieces of a record sampled at dt = 0.01 s, [i dt, (i + 1) dt] as the record computes them,
// differ in length by rounding, and so do their nominal steps. Reuse keeps one step for all of
// them (the first), bit for bit; without the band (step_reuse_band = 0) the step changes with
// the pieces.
TEST(StepGrid, StepReuseKeepsOneStepOverASampledRecord) {
  // 7 Hz: h_max = 1/140 s, so each piece of about dt takes two steps of about dt / 2.
  const double dt = 0.01, omega_max = 2.0 * std::numbers::pi * 7.0;
  EventPolicy policy, no_reuse;
  no_reuse.step_reuse_band = 0.0;
  std::set<double> nominal, reused, unreused;
  double h_last = 0.0, h_last_off = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const ExcitationPiece p = Piece(i * dt, (i + 1) * dt);
    const double h = FreeStepSize(p, omega_max, policy);
    nominal.insert(h);
    const FreeStepPlan plan = PlanFreeStep(p.t_begin, p.t_begin, p.t_end, h, h_last, policy);
    const FreeStepPlan off = PlanFreeStep(p.t_begin, p.t_begin, p.t_end, h, h_last_off, no_reuse);
    h_last = plan.h_s;
    h_last_off = off.h_s;
    reused.insert(plan.h_s);
    unreused.insert(off.h_s);
    // Two steps of h per piece; the first ends at the grid point begin + h.
    EXPECT_EQ(plan.t_next_s, p.t_begin + plan.h_s) << "piece " << i;
    EXPECT_TRUE(plan.full) << "piece " << i;
  }
  ASSERT_GT(nominal.size(), 1u) << "the pieces' own steps must differ by rounding";
  for (double h : nominal) {
    ASSERT_NEAR(h, dt / 2.0, 1e-15);
  }
  EXPECT_EQ(reused.size(), 1u);
  EXPECT_EQ(*reused.begin(), FreeStepSize(Piece(0.0, dt), omega_max, policy));
  EXPECT_EQ(unreused.size(), nominal.size());
}

// Where a step from t ends on the grid begin + k h of a piece [begin, stop), h = 2^-10 s (its
// grid points exact in binary, so the rows test the bands, not the rounding of the grid).
TEST(StepGrid, StepsEndOnTheGridWithoutSliverSteps) {
  const double begin = 2.0, h = 1.0 / 1024.0;
  const EventPolicy policy;  // step_snap_band 1e-9
  EventPolicy no_snap;
  no_snap.step_snap_band = 0.0;
  struct Row {
    double t;           // the step's start
    double stop;        // the piece's (or run's) end
    double t_next;      // where the step ends
    bool full;          // a whole h
    double t_next_off;  // where it ends without the band
    const char* why;
  };
  const double k3 = begin + 3.0 * h, k4 = begin + 4.0 * h;
  const Row rows[] = {
      {k3, 1.0e9, k4, true, k4, "on a grid point: one whole step"},
      {begin + 2.5 * h, 1.0e9, k3, false, k3, "after an event between grid points: to the next"},
      {k3 - 1e-12 * h, 1.0e9, k4, true, k3,
       "1e-12 h below a grid point counts as on it (else a sliver of 1e-12 h)"},
      {k3 - 1e-6 * h, 1.0e9, k3, false, k3, "1e-6 h below: a short step to the grid point"},
      {k3, k4 + 1e-10 * h, k4 + 1e-10 * h, true, k4,
       "a stop 1e-10 h beyond a grid point: the step goes to the stop (else a sliver after it)"},
      {k3, k4 - 0.25 * h, k4 - 0.25 * h, false, k4 - 0.25 * h, "the stop inside the step"},
  };
  for (const Row& r : rows) {
    const FreeStepPlan plan = PlanFreeStep(r.t, begin, r.stop, h, h, policy);
    EXPECT_EQ(plan.h_s, h) << r.why;
    EXPECT_NEAR(plan.t_next_s, r.t_next, 1e-15) << r.why;
    EXPECT_EQ(plan.full, r.full) << r.why;
    EXPECT_NEAR(PlanFreeStep(r.t, begin, r.stop, h, h, no_snap).t_next_s, r.t_next_off, 1e-15)
        << r.why << " (band off)";
  }
}

// The bits of a double, so that +0 and -0 (and NaN payloads) count as different.
std::uint64_t Bits(double x) { return std::bit_cast<std::uint64_t>(x); }

TEST(StepGrid, RampPlannerIsPlanFreeStepAtAPiecesStartOverDrawnSteps) {
  std::mt19937_64 rng(20261130);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Bands as ValidatePolicy takes them (0 to 1), the defaults, and 0 and 1 themselves.
  const double bands[] = {0.0, 1e-12, 1e-9, 1e-6, 0.3, 1.0};
  for (int draw = 0; draw < 20000; ++draw) {
    EventPolicy policy;
    policy.step_snap_band = bands[rng() % 6];
    policy.step_reuse_band = bands[rng() % 6];
    // A record's ramp [begin, end] of about dt, a nominal step near it, a last step within a
    // few relative ulps to a few percent of it, and a stop at the ramp's end or the run's.
    const double dt = std::ldexp(1.0 + unit(rng), -7 - static_cast<int>(rng() % 4));
    const double begin = static_cast<double>(rng() % 100000) * dt;
    const double end = begin + dt * (1.0 + (unit(rng) - 0.5) * std::ldexp(1.0, -40));
    const double h = (rng() % 3 == 0) ? end - begin : (end - begin) / (1.0 + rng() % 3);
    const double spread = std::ldexp(1.0, -50 + static_cast<int>(rng() % 46));
    const double h_last = (rng() % 4 == 0) ? h : h * (1.0 + (unit(rng) - 0.5) * spread);
    const double stop = (rng() % 4 == 0) ? begin + unit(rng) * 2.0 * dt : end;
    RampStepPlanner planner(policy);
    const double length = planner.Reset(h, h_last);
    // The reuse rule's length, then the same plan for the step after (its last step `length`).
    for (const double last : {h_last, length}) {
      const FreeStepPlan expected = PlanFreeStep(begin, begin, stop, h, last, policy);
      const FreeStepPlan plan = planner.At(begin, begin, stop);
      ASSERT_EQ(Bits(plan.h_s), Bits(expected.h_s)) << draw;
      ASSERT_EQ(Bits(plan.t_next_s), Bits(expected.t_next_s)) << draw;
      ASSERT_EQ(plan.full, expected.full) << draw;
    }
  }
}

// A pulse's and a free vibration's steps: from a time on or off the grid, steps along a piece
// (its start far from or near 0, so that the quotient's rounding varies), each planned by
// PlanFreeStepExpecting with the expectation a loop gives it (the last k plus one, or NaN
// first) and with wrong ones (one off either way, -0, NaN): the plan is PlanFreeStep's, bit for
// bit, and the k handed back is the floor's.
TEST(StepGrid, ExpectingPlanIsPlanFreeStepWhateverTheExpectation) {
  std::mt19937_64 rng(20261201);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double bands[] = {0.0, 1e-12, 1e-9, 1e-6, 0.3, 1.0};
  long right = 0, steps = 0;
  for (int draw = 0; draw < 2000; ++draw) {
    EventPolicy policy;
    policy.step_snap_band = bands[rng() % 6];
    policy.step_reuse_band = bands[rng() % 6];
    const double h = std::ldexp(1.0 + unit(rng), -6 - static_cast<int>(rng() % 8));
    const double begin = (rng() % 2 == 0) ? unit(rng) * h : unit(rng) * 1e3;
    const double stop = (rng() % 3 == 0) ? kInf : begin + h * (5.0 + unit(rng) * 200.0);
    // The first step from a point inside a grid interval (after an impact) or on the start.
    double t = (rng() % 2 == 0) ? begin : begin + unit(rng) * 3.0 * h;
    double h_last = h * (1.0 + (unit(rng) - 0.5) * 1e-9);
    double k_last = std::numeric_limits<double>::quiet_NaN();
    for (int step = 0; step < 60 && t < stop; ++step) {
      const FreeStepPlan expected = PlanFreeStep(t, begin, stop, h, h_last, policy);
      const double guesses[] = {k_last + 1.0, k_last, k_last + 2.0, -0.0,
                                std::numeric_limits<double>::quiet_NaN()};
      double k_floor = 0.0;
      for (const double guess : guesses) {
        double k = -1.0;
        const FreeStepPlan plan =
            PlanFreeStepExpecting(t, begin, stop, h, h_last, policy, guess, k);
        ASSERT_EQ(Bits(plan.h_s), Bits(expected.h_s)) << draw << " " << step;
        ASSERT_EQ(Bits(plan.t_next_s), Bits(expected.t_next_s)) << draw << " " << step;
        ASSERT_EQ(plan.full, expected.full) << draw << " " << step;
        // The floor of the quotient, as PlanFreeStep takes it (at the piece's start that of the
        // band alone).
        const double quotient =
            t == begin ? policy.step_snap_band : (t - begin) / plan.h_s + policy.step_snap_band;
        ASSERT_EQ(k, std::floor(quotient)) << draw << " " << step;
        k_floor = k;
      }
      if (policy.step_snap_band == EventPolicy{}.step_snap_band && step > 0) {
        right += k_floor == k_last + 1.0 ? 1 : 0;
        ++steps;
      }
      k_last = k_floor;
      h_last = expected.h_s;
      t = expected.t_next_s;
    }
  }
  // With the default snap band the loop's expectation holds on every step after the first (the
  // quotient's rounding, a few ulps of (t - begin) / h, stays far inside the band).
  EXPECT_GT(steps, 10000);
  EXPECT_EQ(right, steps);
}

TEST(StepGrid, ConstrainedStepIsCutAtTheStopWithoutSliverSteps) {
  const EventPolicy policy;
  EventPolicy no_snap;
  no_snap.step_snap_band = 0.0;
  const double t = 1.0, h = 1e-4;
  struct Row {
    double stop;
    bool to_stop, to_stop_off;  // the step ends at the stop (else it is the proposed h)
    const char* why;
  };
  const Row rows[] = {
      {t + 1.0, false, false, "far from the stop: the proposed step"},
      {t + 0.5 * h, true, true, "the stop inside the step: cut there"},
      {t + h * (1.0 + 1e-10), true, false,
       "the stop 1e-10 h beyond the step: stretched to it (else a sliver after it)"},
      {t + h * (1.0 + 1e-6), false, false, "the stop 1e-6 h beyond: the proposed step"},
  };
  for (const Row& r : rows) {
    EXPECT_EQ(ConstrainedStepLength(t, r.stop, h, policy), r.to_stop ? r.stop - t : h) << r.why;
    EXPECT_EQ(ConstrainedStepLength(t, r.stop, h, no_snap), r.to_stop_off ? r.stop - t : h)
        << r.why << " (band off)";
  }
}

// Pieces [k, k + 1) for k = 0, 1, 2 and the rest from 3, each PieceAt counted. A piece whose
// number is in `promised` (3: the rest) is PieceHolds' and the same at every time inside it; any
// other carries the time it was asked at in its slope, so a cursor that kept one where it was
// not promised would hand back another time's bits.
class CountedPieces final : public Excitation {
 public:
  explicit CountedPieces(std::set<long> promised) : promised_(std::move(promised)) {}
  ExcitationPiece PieceAt(double t) const override {
    ++calls;
    const long k = t >= 3.0 ? 3 : static_cast<long>(std::floor(t));
    ExcitationPiece p;
    p.t_begin = static_cast<double>(k);
    p.t_end = k == 3 ? kInf : static_cast<double>(k + 1);
    p.a_begin = Eigen::Vector2d(1.0 + static_cast<double>(k), 0.0);
    p.omega = k == 1 ? 2.5 : 0.0;
    if (promised_.count(k) == 0) p.slope = Eigen::Vector2d(t, -t);
    return p;
  }
  bool PieceHolds(const ExcitationPiece& piece) const override {
    return promised_.count(static_cast<long>(piece.t_begin)) != 0;
  }
  double Duration() const override { return 3.0; }
  mutable int calls = 0;

 private:
  std::set<long> promised_;
};

void ExpectSamePiece(const ExcitationPiece& a, const ExcitationPiece& b, double t) {
  EXPECT_EQ(Bits(a.t_begin), Bits(b.t_begin)) << t;
  EXPECT_EQ(Bits(a.t_end), Bits(b.t_end)) << t;
  EXPECT_EQ(Bits(a.omega), Bits(b.omega)) << t;
  EXPECT_EQ(a.index, b.index) << t;
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(Bits(a.a_begin[i]), Bits(b.a_begin[i])) << t;
    EXPECT_EQ(Bits(a.slope[i]), Bits(b.slope[i])) << t;
    EXPECT_EQ(Bits(a.cos_amplitude[i]), Bits(b.cos_amplitude[i])) << t;
    EXPECT_EQ(Bits(a.sin_amplitude[i]), Bits(b.sin_amplitude[i])) << t;
  }
}

TEST(PieceCursor, KeepsOnlyAPromisedPieceWhileTheTimeIsInsideIt) {
  // Steps of 0.1 from 0 past the rest, a step back into piece 0 and one that lands on piece 2's
  // end: every piece the cursor gives is PieceAt's at that time, and PieceAt is asked once per
  // promised piece entered, at every step elsewhere.
  std::vector<double> times;
  for (int i = 0; i < 60; ++i) times.push_back(0.1 * i);
  times.push_back(0.5);   // back inside piece 0 (promised or not: asked again)
  times.push_back(2.95);  // inside piece 2, then its end exactly (NextPiece)
  times.push_back(3.0);
  times.push_back(1e300);
  for (const std::set<long>& promised :
       {std::set<long>{}, std::set<long>{3}, std::set<long>{0, 2, 3}, std::set<long>{1}}) {
    const CountedPieces excitation(promised), reference(promised);
    for (const bool view : {false, true}) {
      PieceCursor cursor;
      excitation.calls = 0;
      int expected_calls = 0;
      const ExcitationPiece* kept = nullptr;
      double kept_begin = 0.0, kept_end = kInf;  // the cursor's first piece ends at +inf
      for (const double t : times) {
        const ExcitationPiece& piece =
            view ? cursor.At(excitation, SampleView{}, t) : cursor.At(excitation, t);
        ExpectSamePiece(piece, reference.PieceAt(t), t);
        const long k = t >= 3.0 ? 3 : static_cast<long>(std::floor(t));
        const bool inside = kept != nullptr && t >= kept_begin && t < kept_end;
        if (!inside) {
          // A step that starts a piece where the last one ended asks too (NextPiece is
          // PieceAt here), without the promise.
          ++expected_calls;
          kept = promised.count(k) != 0 && !(t == kept_end) ? &piece : nullptr;
          kept_begin = static_cast<double>(k);
          kept_end = k == 3 ? kInf : static_cast<double>(k + 1);
        }
      }
      EXPECT_EQ(excitation.calls, expected_calls) << promised.size() << " promised, view " << view;
    }
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::step_grid_test
