// The description of stored structs (solver/common/schema.h) on a small nested struct written for
// the test: the entries in the order of Describe with their units, scales and kinds; the ranges
// at, inside and outside each kind of bound; one message naming the member; reading stored
// entries back; the documentation rows; and the count of members a description must visit.

#include "solver/common/schema.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "solver/common/error.h"

namespace skewbridge::schema::schema_test {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Spring {
  double stiffness_npm = 2e6;
  int probes = 3;

  template <typename Archive>
  void Describe(Archive* a) {
    a->Visit(SB_NVP(stiffness_npm), {"N/m", "", Interval::Above(0.0)});
    a->Visit(SB_NVP(probes), {"1", "", Interval::Closed(0.0, 5.0)});
  }
};

struct Settings {
  double tolerance = 1e-9;
  long check_steps = 8;
  bool rule = true;
  Spring spring;

  template <typename Archive>
  void Describe(Archive* a) {
    a->Visit(SB_NVP(tolerance), {"1", "max(1 s, |t|)", Interval::ClosedOpen(0.0, 1.0)});
    a->Visit(SB_NVP(check_steps), {"1", "", Interval::PowerOfTwo()});
    a->Visit(SB_NVP(rule));
    a->Visit(SB_NVP(spring));
  }
};

// A struct whose description forgets a member.
struct Forgetful {
  double kept = 1.0;
  double forgotten = 2.0;

  template <typename Archive>
  void Describe(Archive* a) {
    a->Visit(SB_NVP(kept), {"1", "", Interval::Finite()});
  }
};

TEST(Schema, EntriesFollowTheDescriptionWithFullNamesUnitsScalesAndKinds) {
  Settings s;
  s.tolerance = 3e-10;
  s.check_steps = 32;
  s.rule = false;
  s.spring.stiffness_npm = 5.5e7;
  s.spring.probes = 4;
  const std::vector<Entry> e = Entries(s);
  ASSERT_EQ(e.size(), 5u);
  const std::vector<std::string> names = {"tolerance", "check_steps", "rule",
                                          "spring.stiffness_npm", "spring.probes"};
  const std::vector<double> values = {3e-10, 32.0, 0.0, 5.5e7, 4.0};
  const std::vector<Kind> kinds = {Kind::kReal, Kind::kCount, Kind::kRule, Kind::kReal,
                                   Kind::kCount};
  const std::vector<std::string> units = {"1", "1", "1", "N/m", "1"};
  const std::vector<std::string> scales = {"max(1 s, |t|)", "", "", "", ""};
  for (std::size_t i = 0; i < e.size(); ++i) {
    EXPECT_EQ(e[i].name, names[i]);
    EXPECT_EQ(e[i].value, values[i]) << names[i];
    EXPECT_EQ(e[i].kind, kinds[i]) << names[i];
    EXPECT_EQ(e[i].integral(), kinds[i] != Kind::kReal) << names[i];
    EXPECT_EQ(e[i].unit, units[i]) << names[i];
    EXPECT_EQ(e[i].relative_to, scales[i]) << names[i];
  }
  const Record r = ToRecord("settings", s);
  EXPECT_EQ(r.name, "settings");
  EXPECT_EQ(r.entries.size(), 5u);
}

TEST(Schema, IntervalsAdmitTheirBoundsOnlyWhenClosedAndNeverNanOrInfinity) {
  struct Row {
    Interval interval;
    double x;
    bool admitted;
  };
  const double just_above_1 = std::nextafter(1.0, 2.0);
  const double just_below_1 = std::nextafter(1.0, 0.0);
  const double just_above_0 = std::nextafter(0.0, 1.0);
  const std::vector<Row> rows = {
      {Interval::AtLeast(1.0), 1.0, true},
      {Interval::AtLeast(1.0), just_below_1, false},
      {Interval::AtLeast(1.0), 1e300, true},
      {Interval::AtLeast(1.0), kInf, false},
      {Interval::Above(0.0), 0.0, false},
      {Interval::Above(0.0), just_above_0, true},
      {Interval::Above(0.0), -1.0, false},
      {Interval::Closed(0.0, 5.0), 0.0, true},
      {Interval::Closed(0.0, 5.0), 5.0, true},
      {Interval::Closed(0.0, 5.0), std::nextafter(5.0, 6.0), false},
      {Interval::Open(0.0, 1.0), 0.0, false},
      {Interval::Open(0.0, 1.0), 1.0, false},
      {Interval::Open(0.0, 1.0), just_below_1, true},
      {Interval::ClosedOpen(0.0, 1.0), 0.0, true},
      {Interval::ClosedOpen(0.0, 1.0), 1.0, false},
      {Interval::ClosedOpen(0.0, 1.0), just_above_1, false},
      {Interval::Finite(), -1e308, true},
      {Interval::Finite(), -kInf, false},
      {Interval::Finite(), kNaN, false},
      {Interval::PowerOfTwo(), 1.0, true},
      {Interval::PowerOfTwo(), 2.0, true},
      {Interval::PowerOfTwo(), 1024.0, true},
      {Interval::PowerOfTwo(), 0.0, false},
      {Interval::PowerOfTwo(), 0.5, false},
      {Interval::PowerOfTwo(), 3.0, false},
      {Interval::PowerOfTwo(), 10.0, false},
      {Interval::PowerOfTwo(), -2.0, false},
      {Interval::PowerOfTwo(), kNaN, false},
  };
  for (const Row& row : rows) {
    EXPECT_EQ(row.interval.Admits(row.x), row.admitted) << row.interval.Text() << " x = " << row.x;
  }
}

TEST(Schema, IntervalsSayWhatTheyAllow) {
  EXPECT_EQ(Interval::AtLeast(1.0).Text(), "at least 1");
  EXPECT_EQ(Interval::Above(0.0).Text(), "greater than 0");
  EXPECT_EQ(Interval::Closed(0.0, 14.0).Text(), "in [0, 14]");
  EXPECT_EQ(Interval::Open(0.0, 1.0).Text(), "in (0, 1)");
  EXPECT_EQ(Interval::ClosedOpen(0.0, 1.0).Text(), "in [0, 1)");
  EXPECT_EQ(Interval::Finite().Text(), "finite");
  EXPECT_EQ(Interval::PowerOfTwo().Text(), "a power of two (1, 2, 4, ...)");
  Interval at_most;
  at_most.upper = 2.5;
  EXPECT_EQ(at_most.Text(), "at most 2.5");
}

TEST(Schema, ValidationNamesTheFirstMemberOutsideItsRangeInOneLine) {
  struct Row {
    void (*set)(Settings&);
    std::string message;
  };
  const std::vector<Row> rows = {
      {[](Settings& s) { s.tolerance = -1e-3; },
       "settings.toml: tolerance: must be in [0, 1) (got -0.001)"},
      {[](Settings& s) { s.tolerance = kNaN; },
       "settings.toml: tolerance: must be in [0, 1) (got nan)"},
      {[](Settings& s) { s.check_steps = 12; },
       "settings.toml: check_steps: must be a power of two (1, 2, 4, ...) (got 12)"},
      {[](Settings& s) { s.spring.stiffness_npm = 0.0; },
       "settings.toml: spring.stiffness_npm: must be greater than 0 (got 0)"},
      {[](Settings& s) { s.spring.probes = 6; },
       "settings.toml: spring.probes: must be in [0, 5] (got 6)"},
      // Two members outside: the first in the description is named.
      {[](Settings& s) {
         s.spring.probes = -1;
         s.check_steps = 0;
       },
       "settings.toml: check_steps: must be a power of two (1, 2, 4, ...) (got 0)"},
  };
  for (const Row& row : rows) {
    Settings s;
    row.set(s);
    try {
      Validate(s, "settings.toml");
      ADD_FAILURE() << "accepted: " << row.message;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), row.message);
    }
  }
  EXPECT_NO_THROW(Validate(Settings{}, "settings.toml"));
  EXPECT_EQ(FirstViolation(Settings{}), std::nullopt);
}

TEST(Schema, StoredEntriesReadBackIntoTheStructMemberByMember) {
  Settings written;
  written.tolerance = 0.25;
  written.check_steps = 64;
  written.rule = false;
  written.spring.stiffness_npm = 7.0;
  written.spring.probes = 1;
  std::map<std::string, double> stored;
  for (const Entry& e : Entries(written)) stored[e.name] = e.value;

  Settings read;
  const std::vector<std::string> missing =
      Assign(&read, [&](const std::string& name) -> std::optional<double> {
        const auto it = stored.find(name);
        if (it == stored.end()) return std::nullopt;
        return it->second;
      });
  EXPECT_TRUE(missing.empty());
  EXPECT_EQ(read.tolerance, 0.25);
  EXPECT_EQ(read.check_steps, 64);
  EXPECT_FALSE(read.rule);
  EXPECT_EQ(read.spring.stiffness_npm, 7.0);
  EXPECT_EQ(read.spring.probes, 1);

  // A file without two of the members: those keep their values and are named.
  stored.erase("rule");
  stored.erase("spring.probes");
  Settings partial;
  const std::vector<std::string> lacking =
      Assign(&partial, [&](const std::string& name) -> std::optional<double> {
        const auto it = stored.find(name);
        if (it == stored.end()) return std::nullopt;
        return it->second;
      });
  EXPECT_EQ(lacking, (std::vector<std::string>{"rule", "spring.probes"}));
  EXPECT_TRUE(partial.rule);
  EXPECT_EQ(partial.spring.probes, 3);
  EXPECT_EQ(partial.tolerance, 0.25);
}

TEST(Schema, MarkdownRowsGiveNameDefaultUnitScaleAndRange) {
  const std::vector<std::string> rows = MarkdownRows(Settings{});
  const std::vector<std::string> expected = {
      "| `tolerance` | 1e-9 | 1 | max(1 s, \\|t\\|) | in [0, 1) |",
      "| `check_steps` | 8 | 1 |  | a power of two (1, 2, 4, ...) |",
      "| `rule` | on | 1 |  | on or off |",
      "| `spring.stiffness_npm` | 2e6 | N/m |  | greater than 0 |",
      "| `spring.probes` | 3 | 1 |  | in [0, 5] |",
  };
  EXPECT_EQ(rows, expected);
}

TEST(Schema, NumbersAreWrittenWithTheFewestDigitsThatReadBack) {
  EXPECT_EQ(FormatNumber(64.0), "64");
  EXPECT_EQ(FormatNumber(-2.0), "-2");
  EXPECT_EQ(FormatNumber(0.0), "0");
  EXPECT_EQ(FormatNumber(1e-10), "1e-10");
  EXPECT_EQ(FormatNumber(1.5e-8), "1.5e-8");
  EXPECT_EQ(FormatNumber(1e10), "1e10");
  EXPECT_EQ(FormatNumber(2e6), "2e6");
  EXPECT_EQ(FormatNumber(0.9), "0.9");
  EXPECT_EQ(FormatNumber(-0.001), "-0.001");
  EXPECT_EQ(FormatNumber(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(FormatNumber(kNaN), "nan");
  EXPECT_EQ(FormatNumber(-kInf), "-inf");
}

TEST(Schema, MemberCountFindsADescriptionThatForgetsAMember) {
  EXPECT_EQ(MemberCount<Spring>(), 2u);
  EXPECT_EQ(MemberCount<Settings>(), 4u);
  EXPECT_EQ(MemberCount<Forgetful>(), 2u);
  EXPECT_TRUE(DescribesEveryMember<Spring>());
  EXPECT_TRUE(DescribesEveryMember<Settings>());
  EXPECT_FALSE(DescribesEveryMember<Forgetful>());
}

}  // namespace
}  // namespace skewbridge::schema::schema_test
