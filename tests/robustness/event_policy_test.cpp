/// The event policy (solver/dynamics/event_policy.h): the event-cascade status it bounds, and
/// rules that can be switched off one at a time on cells of the robustness grid
/// (tests/robustness/robustness_grid.h) [docs/theory.md §3].

#include <gtest/gtest.h>

#include <string>

#include "solver/dynamics/event_policy.h"
#include "tests/robustness/robustness_grid.h"

namespace skewbridge::event_policy_test {
namespace {

// The closed-joint cells of the grid that bounce (eps_N = 0.5, w0/w_g = 10).
std::vector<std::int64_t> BouncingCells(const robustness::GridAxes& grid) {
  std::vector<std::int64_t> cells;
  for (std::int64_t c = 0; c < grid.size() && cells.size() < 40; ++c) {
    const spectra::PointParameters p = grid.Cell(c);
    if (p.Pi_delta == 0.0 && p.eps_N == 0.5 && p.w0_over_wg == 10.0 && p.mu == 0.3) {
      cells.push_back(c);
    }
  }
  return cells;
}

TEST(EventPolicy, EventCascadeHasItsOwnStatus) {
  // With no second decision allowed at one instant, a run whose decision needs a second pass
  // at some instant (an event found at the start of the next step) ends there as an event
  // cascade, never as a spent step budget; the same cell with the default policy ends ok.
  const robustness::GridAxes grid;
  dynamics::EventPolicy strict;
  strict.max_events_at_one_instant = 0;
  int cascades = 0;
  for (std::int64_t c : BouncingCells(grid)) {
    const dynamics::RunResult r = robustness::RunEventDriven(grid.Cell(c), 10'000'000, strict);
    EXPECT_NE(r.status, dynamics::RunStatus::kStepLimit) << r.message;
    if (r.status == dynamics::RunStatus::kEventCascade) {
      ++cascades;
      EXPECT_NE(r.message.find("event cascade"), std::string::npos) << r.message;
      EXPECT_STREQ(dynamics::ToString(r.status), "event-cascade");
      EXPECT_EQ(robustness::RunEventDriven(grid.Cell(c)).status, dynamics::RunStatus::kOk);
    }
  }
  EXPECT_GT(cascades, 0);
}

TEST(EventPolicy, ZenoExtrapolationRemovesImpactsOfABouncingCorner) {
  // A corner bouncing at eps_N = 0.5 on a closed joint: the Zeno rule replaces the tail of each
  // geometric sequence of impacts by closing the contact (and the bounce-at-once rule its
  // first rebound), so without them every such cell takes more impacts.
  const robustness::GridAxes grid;
  dynamics::EventPolicy no_zeno;
  no_zeno.zeno_extrapolation = false;
  no_zeno.bounce_at_once = false;
  for (std::int64_t c : BouncingCells(grid)) {
    const dynamics::RunResult a = robustness::RunEventDriven(grid.Cell(c));
    const dynamics::RunResult b = robustness::RunEventDriven(grid.Cell(c), 10'000'000, no_zeno);
    ASSERT_EQ(a.status, dynamics::RunStatus::kOk) << a.message;
    ASSERT_EQ(b.status, dynamics::RunStatus::kOk) << b.message;
    EXPECT_GT(b.impacts, a.impacts) << "cell " << c;
  }
}

}  // namespace
}  // namespace skewbridge::event_policy_test
