// Nearest names for error messages: the edit distance against hand-counted textbook pairs, and
// the hints the command-line and file errors give for typical slips.
#include "solver/common/nearest.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace skewbridge::nearest_test {
namespace {

TEST(EditDistance, TextbookPairs) {
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);  // k->s, e->i, +g
  EXPECT_EQ(EditDistance("flaw", "lawn"), 2u);       // -f, +n
  EXPECT_EQ(EditDistance("", "abc"), 3u);
  EXPECT_EQ(EditDistance("abc", ""), 3u);
  EXPECT_EQ(EditDistance("sweep", "sweep"), 0u);
  EXPECT_EQ(EditDistance("swep", "sweep"), 1u);
  EXPECT_EQ(EditDistance("W0", "w0"), 0u);    // case-insensitive
  EXPECT_EQ(EditDistance("cvs", "csv"), 1u);  // one swap of neighbours
  EXPECT_EQ(EditDistance("ca", "abc"), 3u);   // optimal string alignment: no edit of a swap
  EXPECT_EQ(EditDistance("abcd", "badc"), 2u);
}

TEST(EditDistance, IsSymmetric) {
  const std::vector<std::string> words = {"", "a", "skew", "skew_deg", "a_deg", "w_theta", "W0"};
  for (const std::string& a : words) {
    for (const std::string& b : words) {
      EXPECT_EQ(EditDistance(a, b), EditDistance(b, a)) << a << " / " << b;
    }
  }
}

TEST(SlipDistance, AUnitOrExtensionLeftOffIsOneSlip) {
  EXPECT_EQ(SlipDistance("skew", "skew_deg"), 1u);
  EXPECT_EQ(SlipDistance("RSN1_NORTHR", "RSN1_NORTHR.AT2"), 1u);
  EXPECT_EQ(SlipDistance("skew_angle", "skew"), 1u);
}

TEST(NearestNames, ModelKeys) {
  const std::vector<std::string> deck = {"m", "I_m", "L", "W", "eta0", "skew_deg"};
  EXPECT_EQ(DidYouMean("skew", deck), "; did you mean `skew_deg`?");
  EXPECT_EQ(DidYouMean("skew_dg", deck), "; did you mean `skew_deg`?");
  EXPECT_EQ(DidYouMean("stiffness", deck), "");  // nothing plausible: no hint
}

TEST(NearestNames, SubCommands) {
  const std::vector<std::string> commands = {"version", "run",     "modes",
                                             "sweep",   "inspect", "records"};
  EXPECT_EQ(DidYouMean("swep", commands), "; did you mean `sweep`?");
  EXPECT_EQ(DidYouMean("record", commands), "; did you mean `records`?");
  EXPECT_EQ(DidYouMean("mode", commands), "; did you mean `modes`?");
  EXPECT_EQ(DidYouMean("xyz", commands), "");
}

TEST(NearestNames, NearestFirstAtMostCount) {
  const std::vector<std::string> labels = {"RSN6_IMPVALL.I_I-ELC180.AT2", "RSN15_KERN_TAF021.AT2",
                                           "RSN6_IMPVALL.I_I-ELC270.AT2",
                                           "RSN125_FRIULI.A_A-TMZ000.AT2"};
  const std::vector<std::string> nearest =
      NearestNames("RSN6_IMPVALL.I_I-ELC180", labels, 2, false);
  ASSERT_EQ(nearest.size(), 2u);
  EXPECT_EQ(nearest[0], "RSN6_IMPVALL.I_I-ELC180.AT2");
  EXPECT_EQ(nearest[1], "RSN6_IMPVALL.I_I-ELC270.AT2");
  EXPECT_EQ(NearestNames("x", labels, 0, false).size(), 0u);
  EXPECT_EQ(NearestNames("x", labels, 10, false).size(), labels.size());
}

}  // namespace
}  // namespace skewbridge::nearest_test
