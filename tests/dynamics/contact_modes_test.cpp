/// ContactModes (solver/dynamics/contact_modes.h): the closed set follows every change of a
/// mode, checked against a recount from the modes; the mode helpers against their tables.

#include "solver/dynamics/contact_modes.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace skewbridge::dynamics::contact_modes_test {
namespace {

constexpr ContactMode kAll[] = {ContactMode::kOpen, ContactMode::kStick,
                                ContactMode::kSlidePositive, ContactMode::kSlideNegative,
                                ContactMode::kFrictionless};

TEST(ContactModes, ClosedSetFollowsEveryChange) {
  constexpr int n = 7;
  ContactModes modes(n);
  EXPECT_FALSE(modes.any_closed());
  std::vector<ContactMode> mirror(n, ContactMode::kOpen);
  std::mt19937 rng(25);
  std::uniform_int_distribution<int> contact(0, n - 1), kind(0, 4);
  for (int step = 0; step < 2000; ++step) {
    const int c = contact(rng);
    const ContactMode m = kAll[kind(rng)];
    modes.Set(c, m);
    mirror[static_cast<std::size_t>(c)] = m;
    std::vector<int> ids;
    bool stick = false;
    for (int i = 0; i < n; ++i) {
      ASSERT_EQ(modes[i], mirror[static_cast<std::size_t>(i)]);
      if (mirror[static_cast<std::size_t>(i)] != ContactMode::kOpen) {
        ids.push_back(i);
      }
      stick = stick || mirror[static_cast<std::size_t>(i)] == ContactMode::kStick;
    }
    ASSERT_EQ(modes.closed_ids(), ids) << "step " << step;
    ASSERT_EQ(modes.closed_count(), static_cast<int>(ids.size()));
    ASSERT_EQ(modes.any_closed(), !ids.empty());
    ASSERT_EQ(modes.any_stick(), stick);
  }
}

TEST(ContactModes, HelpersMatchTheirTables) {
  struct Row {
    ContactMode mode;
    bool closed, sliding;
    int slip_sign;
    ContactState history;
  };
  const Row rows[] = {
      {ContactMode::kOpen, false, false, 0, ContactState::kOpen},
      {ContactMode::kStick, true, false, 0, ContactState::kStick},
      {ContactMode::kSlidePositive, true, true, 1, ContactState::kSlidePositive},
      {ContactMode::kSlideNegative, true, true, -1, ContactState::kSlideNegative},
      {ContactMode::kFrictionless, true, false, 0, ContactState::kSlidePositive},
  };
  for (const Row& r : rows) {
    EXPECT_EQ(IsClosed(r.mode), r.closed);
    EXPECT_EQ(IsSliding(r.mode), r.sliding);
    EXPECT_EQ(SlipSign(r.mode), r.slip_sign);
    EXPECT_EQ(HistoryState(r.mode), r.history);
  }
  EXPECT_EQ(SlideOrStick(1), ContactMode::kSlidePositive);
  EXPECT_EQ(SlideOrStick(-1), ContactMode::kSlideNegative);
  EXPECT_EQ(SlideOrStick(0), ContactMode::kStick);
}

}  // namespace
}  // namespace skewbridge::dynamics::contact_modes_test
