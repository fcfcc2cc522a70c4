// Plausibility warnings (solver/model/plausibility.h): each limit warned of just beyond it and
// not just inside, with the field, the value and the likely unit slip named; a model file as
// a user slips (gap in mm typed as m, tonnes typed as kg, kN/m typed as N/m) and as written.
#include "solver/model/plausibility.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "solver/model/model_file.h"

namespace skewbridge::model {
namespace {

using ::testing::HasSubstr;

TEST(Plausibility, AGapOrSeatBeyondATenthOfTheSpan) {
  EXPECT_FALSE(WidthWarning("abutments.gap_m", "gap", 3.5, 35.0));  // exactly a tenth
  const std::optional<std::string> w = WidthWarning("abutments.gap_m", "gap", 50.0, 35.0);
  ASSERT_TRUE(w);
  EXPECT_EQ(*w,
            "abutments.gap_m: a gap of 50 m is more than a tenth of the 35 m span: a width in "
            "millimetres typed as metres?");
  EXPECT_THAT(*WidthWarning("seat_m", "seat", 3.6, 35.0), HasSubstr("a seat of 3.6 m"));
}

TEST(Plausibility, ADeckLighterThanATonnePerMetre) {
  EXPECT_FALSE(MassWarning("deck.m", 35e3, 35.0));  // 1 t/m
  EXPECT_EQ(*MassWarning("deck.m", 700.0, 35.0),
            "deck.m: 700 kg is 20 kg per metre of the 35 m span, below 1 t/m (road decks weigh "
            "10-30 t/m): a mass in tonnes typed as kg?");
}

TEST(Plausibility, AFundamentalPeriodOutsideTwoHundredthsToTenSeconds) {
  EXPECT_FALSE(PeriodWarning("T1", 0.02));
  EXPECT_FALSE(PeriodWarning("T1", 10.0));
  EXPECT_EQ(*PeriodWarning("T1", 0.019),
            "T1 is 0.019 s, below 0.02 s: a mass in tonnes typed as kg?");
  EXPECT_EQ(*PeriodWarning("T1", 31.0),
            "T1 is 31 s, above 10 s: a stiffness in kN/m or MN/m typed as N/m?");
  EXPECT_THAT(*PeriodWarning("T1", std::numeric_limits<double>::infinity()),
              HasSubstr("T1 is infinite (a direction without stiffness"));
}

TEST(Plausibility, IntensitiesAboveFiveG) {
  EXPECT_FALSE(IntensityWarning("axes.im_g", 5.0));
  EXPECT_EQ(*IntensityWarning("axes.im_g", 40.0),
            "axes.im_g: up to 40 g, above 5 g (beyond the strongest recorded motions): "
            "accelerations in m/s^2 or cm/s^2 typed as g?");
}

// A 35 m x 12 m deck at 35 deg on bearings of 30 MN/m in all along x and y: with m = 700 t,
// w = sqrt(3e7 / 7e5) = 6.55 rad/s, T = 0.96 s, as the bridge of the study the issue describes.
// The torsional stiffness is k rho^2 (rho^2 = (35^2 + 12^2 / cos^2 35) / 12 = 120 m^2).
std::string Bridge(const std::string& m, double k, const std::string& gap) {
  return "[deck]\nm = " + m +
         "\nI_m = \"uniform\"\nL = 35.0\nW = 12.0\nskew_deg = 35.0\n"
         "[substructure]\nkind = \"matrix\"\nK = [[" +
         std::to_string(k) + ", 0, 0], [0, " + std::to_string(k) + ", 0], [0, 0, " +
         std::to_string(120.0 * k) +
         "]]\nxi = 0.05\n"
         "[abutments]\nset = \"both\"\ngap_m = " +
         gap + "\n[excitation]\nkind = \"pulse\"\nshape = \"cosine\"\na_g_g = 0.5\nT_g = 0.5\n";
}

TEST(Plausibility, AModelFileAsWrittenHasNone) {
  const ModelFile file = ParseModelString(Bridge("700e3", 3e7, "0.05"), "bridge.toml");
  EXPECT_NEAR(FundamentalPeriod(file.model), 2.0 * std::numbers::pi / std::sqrt(3e7 / 7e5), 0.02);
  EXPECT_TRUE(PlausibilityWarnings(file).empty());
}

TEST(Plausibility, AModelFileWithUnitSlipsNamesEach) {
  // The gap in mm typed as m; the mass in tonnes typed as kg (T1 = 0.03 s: no period warning).
  const ModelFile slips = ParseModelString(Bridge("700", 3e7, "50"), "bridge.toml");
  const std::vector<std::string> w = PlausibilityWarnings(slips);
  ASSERT_EQ(w.size(), 2u) << ::testing::PrintToString(w);
  EXPECT_THAT(w[0], HasSubstr("bridge.toml: deck.m: 700 kg is 20 kg per metre"));
  EXPECT_THAT(w[1], HasSubstr("bridge.toml: abutments.gap_m: a gap of 50 m"));
  // The stiffness in kN/m typed as N/m: T1 = 0.96 sqrt(1000) = 30 s.
  const std::vector<std::string> soft =
      PlausibilityWarnings(ParseModelString(Bridge("700e3", 3e4, "0.05"), "bridge.toml"));
  ASSERT_EQ(soft.size(), 1u) << ::testing::PrintToString(soft);
  EXPECT_THAT(soft[0], HasSubstr("the fundamental period T1 of the model is 30.4 s, above 10 s"));
}

}  // namespace
}  // namespace skewbridge::model
