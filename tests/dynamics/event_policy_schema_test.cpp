// The event policy's one description (EventPolicy::Describe, ContactPolicy::Describe; schema.h):
// it visits every member of both structs, names each once in the stored order with its value,
// refuses a value outside each member's range with one line naming that member (every member
// tried, at and beyond its bounds), and docs/theory.md §3.16 lists exactly its members with
// their defaults, units, scales and ranges; the same for the time-stepping scheme's policy
// (TimeSteppingPolicy::Describe) and its table in §3.16.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "solver/common/error.h"
#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/time_stepping_policy.h"

namespace skewbridge::dynamics::event_policy_schema_test {
namespace {

using schema::Entry;
using schema::Interval;

TEST(EventPolicySchema, DescriptionsVisitEveryMember) {
  EXPECT_EQ(schema::MemberCount<EventPolicy>(), 41u);  // 40 numbers and rules, `contact`
  EXPECT_EQ(schema::MemberCount<contact::ContactPolicy>(), 4u);
  EXPECT_TRUE(schema::DescribesEveryMember<EventPolicy>());
  EXPECT_TRUE(schema::DescribesEveryMember<contact::ContactPolicy>());
}

TEST(EventPolicySchema, EntriesNameEveryMemberOnceWithItsValue) {
  EventPolicy p;
  p.zeno_ratio = 0.5;
  p.touch_probes = 7;
  p.jam = false;
  p.finite_check_steps = 64;
  p.contact.tie_tolerance = 2.5e-10;
  p.contact.enumeration_unknowns = 9;
  const std::vector<Entry> entries = schema::Entries(p);
  ASSERT_EQ(entries.size(), 44u);  // 40 members, the contact policy's 4
  std::set<std::string> names;
  std::map<std::string, const Entry*> by_name;
  for (const Entry& e : entries) {
    EXPECT_TRUE(names.insert(e.name).second) << e.name << " listed twice";
    EXPECT_FALSE(e.unit.empty()) << e.name;
    by_name[e.name] = &e;
  }
  EXPECT_EQ(entries.front().name, "velocity_tolerance");
  EXPECT_EQ(entries.back().name, "contact.enumeration_unknowns");
  struct Expect {
    const char* name;
    double value;
    schema::Kind kind;
    const char* relative_to;
  };
  for (const Expect& x : std::vector<Expect>{
           {"zeno_ratio", 0.5, schema::Kind::kReal, "previous approach speed"},
           {"touch_probes", 7.0, schema::Kind::kCount, ""},
           {"jam", 0.0, schema::Kind::kRule, ""},
           {"cone_sign", 1.0, schema::Kind::kRule, ""},
           {"finite_check_steps", 64.0, schema::Kind::kCount, ""},
           {"velocity_tolerance", 1e-10, schema::Kind::kReal, "v_ref"},
           {"gap_rounding_ulps", 64.0, schema::Kind::kReal, "L"},
           {"contact.tie_tolerance", 2.5e-10, schema::Kind::kReal,
            "largest sum of the magnitudes of the terms of b"},
           {"contact.enumeration_unknowns", 9.0, schema::Kind::kCount, ""},
       }) {
    ASSERT_EQ(by_name.count(x.name), 1u) << x.name;
    const Entry& e = *by_name[x.name];
    EXPECT_EQ(e.value, x.value) << x.name;
    EXPECT_EQ(e.kind, x.kind) << x.name;
    EXPECT_EQ(e.relative_to, x.relative_to) << x.name;
  }
}

// A value of `e`'s kind just outside its range (below, then above), if the range has that side.
std::vector<double> OutsideValues(const Entry& e) {
  const Interval& r = e.allowed;
  std::vector<double> out;
  if (r.power_of_two) return {0.0, 3.0, 24.0, -4.0};
  const bool count = e.kind == schema::Kind::kCount;
  if (std::isfinite(r.lower)) {
    out.push_back(r.lower_open ? r.lower
                               : (count ? r.lower - 1.0 : std::nextafter(r.lower, -1e300)));
  }
  if (std::isfinite(r.upper)) {
    out.push_back(r.upper_open ? r.upper
                               : (count ? r.upper + 1.0 : std::nextafter(r.upper, 1e300)));
  }
  if (!count) out.push_back(std::numeric_limits<double>::quiet_NaN());
  return out;
}

// The policy with the member `name` set to `value` through the description.
template <typename Policy>
Policy With(const std::string& name, double value) {
  Policy p;
  schema::Assign(&p, [&](const std::string& n) -> std::optional<double> {
    if (n == name) return value;
    return std::nullopt;
  });
  return p;
}

// Every number member of `Policy` just outside its range is refused in the line "`what`: NAME:
// must be ALLOWED (got VALUE)", its closed bounds are accepted; returns the refusals.
template <typename Policy>
int ExpectEveryMemberOutsideItsRangeRefused(const std::string& what) {
  int refused = 0;
  for (const Entry& e : schema::Entries(Policy{})) {
    if (e.kind == schema::Kind::kRule) continue;  // a bool has no value outside
    for (const double bad : OutsideValues(e)) {
      const Policy p = With<Policy>(e.name, bad);
      try {
        ValidatePolicy(p);
        ADD_FAILURE() << e.name << " = " << bad << " accepted (allowed: " << e.allowed.Text()
                      << ")";
      } catch (const InputError& error) {
        const std::string expected = what + ": " + e.name + ": must be " + e.allowed.Text() +
                                     " (got " + schema::FormatNumber(bad) + ")";
        EXPECT_EQ(std::string(error.what()), expected);
        ++refused;
      }
    }
    // The closed bounds themselves are allowed.
    if (std::isfinite(e.allowed.lower) && !e.allowed.lower_open) {
      EXPECT_NO_THROW(ValidatePolicy(With<Policy>(e.name, e.allowed.lower))) << e.name;
    }
    if (std::isfinite(e.allowed.upper) && !e.allowed.upper_open) {
      EXPECT_NO_THROW(ValidatePolicy(With<Policy>(e.name, e.allowed.upper))) << e.name;
    }
  }
  EXPECT_NO_THROW(ValidatePolicy(Policy{}));
  return refused;
}

TEST(EventPolicySchema, SameMembersComparesTheMembersNotThePadding) {
  // Two default policies in storage whose padding differs (all ones against all zeros) have the
  // same members; a change of any one described member's bits (set through the description, so
  // a member SameMembers leaves out fails here) or of a zero's sign makes them differ.
  alignas(EventPolicy) unsigned char ones[sizeof(EventPolicy)], zeros[sizeof(EventPolicy)];
  std::memset(ones, 0xff, sizeof ones);
  std::memset(zeros, 0x00, sizeof zeros);
  const EventPolicy* a = new (ones) EventPolicy;  // default-initialised: the padding is left
  const EventPolicy* b = new (zeros) EventPolicy;
  ASSERT_NE(std::memcmp(a, b, sizeof(EventPolicy)), 0);  // the padding differs
  EXPECT_TRUE(SameMembers(*a, *b));
  EXPECT_TRUE(SameMembers(*b, *a));
  int changed = 0;
  for (const Entry& e : schema::Entries(EventPolicy{})) {
    const double other = e.kind == schema::Kind::kRule    ? 1.0 - e.value
                         : e.kind == schema::Kind::kCount ? e.value + 1.0
                         : e.value == 0.0                 ? 1.0
                                                          : 2.0 * e.value;
    const EventPolicy c = With<EventPolicy>(e.name, other);
    EXPECT_FALSE(SameMembers(*a, c)) << e.name;
    EXPECT_FALSE(SameMembers(c, *a)) << e.name;
    ++changed;
  }
  EXPECT_EQ(changed, 40 + 4);  // every number and rule, the contact policy's four
  EXPECT_FALSE(SameMembers(With<EventPolicy>("gap_rounding_ulps", 0.0),
                           With<EventPolicy>("gap_rounding_ulps", -0.0)));
}

TEST(EventPolicySchema, EveryMemberOutsideItsRangeIsRefusedByName) {
  // Every number member has at least one side and NaN or a count.
  EXPECT_GE(ExpectEveryMemberOutsideItsRangeRefused<EventPolicy>("event policy"), 2 * 30);
}

TEST(TimeSteppingPolicySchema, DescribesEveryMemberAndRefusesEachOutsideItsRange) {
  EXPECT_EQ(schema::MemberCount<TimeSteppingPolicy>(), 8u);
  EXPECT_TRUE(schema::DescribesEveryMember<TimeSteppingPolicy>());
  const std::vector<Entry> entries = schema::Entries(TimeSteppingPolicy{});
  ASSERT_EQ(entries.size(), 8u);
  std::set<std::string> names;
  for (const Entry& e : entries) {
    EXPECT_TRUE(names.insert(e.name).second) << e.name << " listed twice";
    EXPECT_EQ(e.kind, schema::Kind::kReal) << e.name;
  }
  EXPECT_EQ(entries.front().name, "velocity_tolerance");
  EXPECT_EQ(entries.front().value, 1e-9);
  EXPECT_EQ(entries.front().relative_to, "v_ref");
  // Each of the 8 members has a finite bound and NaN outside.
  EXPECT_GE(ExpectEveryMemberOutsideItsRangeRefused<TimeSteppingPolicy>("time-stepping policy"),
            2 * 8);
}

// The cells of a Markdown table row, trimmed, with escaped bars kept as written:
// "| a | b \| c |" -> {"a", "b \| c"}.
std::vector<std::string> Cells(const std::string& row) {
  std::vector<std::string> cells;
  std::string cell;
  bool open = false;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (row[i] == '|' && (i == 0 || row[i - 1] != '\\')) {
      if (open) {
        const std::size_t first = cell.find_first_not_of(' ');
        const std::size_t last = cell.find_last_not_of(' ');
        cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
      }
      open = true;
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  return cells;
}

// The rows of the first table of docs/theory.md §3.16 after the line that starts with `marker`
// (the section's heading for the event policy), after the table's header and separator lines.
std::vector<std::string> TheoryTableAfter(const std::string& marker) {
  const std::string path = std::string(SKEWBRIDGE_TEST_DATA_DIR) + "/../../docs/theory.md";
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  std::vector<std::string> rows;
  bool in_section = false, after_marker = false, in_table = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("### ", 0) == 0) in_section = line.rfind("### 3.16 ", 0) == 0;
    if (!in_section) continue;
    if (line.rfind(marker, 0) == 0) after_marker = true;
    if (!after_marker) continue;
    if (line.rfind("|", 0) == 0) {
      in_table = true;
      rows.push_back(line);
    } else if (in_table) {
      break;
    }
  }
  EXPECT_GE(rows.size(), 2u) << "no table after \"" << marker << "\" in §3.16 of " << path;
  if (rows.size() >= 2) rows.erase(rows.begin(), rows.begin() + 2);
  return rows;
}

// The table's rows list exactly the described members of `policy`, with the described columns,
// each with a reason.
template <typename Policy>
void ExpectTableListsExactlyTheDescribedMembers(const std::vector<std::string>& rows,
                                                const Policy& policy) {
  const std::vector<std::string> expected = schema::MarkdownRows(policy);
  std::string generated;
  for (const std::string& row : expected) generated += row.substr(0, row.size() - 1) + " why |\n";
  ASSERT_EQ(rows.size(), expected.size())
      << "docs/theory.md §3.16 has " << rows.size() << " rows for " << expected.size()
      << " members; the described columns are\n"
      << generated;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::vector<std::string> doc = Cells(rows[i]);
    const std::vector<std::string> want = Cells(expected[i]);
    ASSERT_EQ(doc.size(), want.size() + 1) << rows[i];
    for (std::size_t c = 0; c < want.size(); ++c) {
      EXPECT_EQ(doc[c], want[c]) << "row " << i + 1 << " of §3.16: " << rows[i]
                                 << "\nthe description gives: " << expected[i];
    }
    EXPECT_FALSE(doc.back().empty()) << "row " << i + 1 << " gives no reason: " << rows[i];
  }
}

TEST(EventPolicySchema, TheoryTableListsExactlyTheDescribedMembers) {
  ExpectTableListsExactlyTheDescribedMembers(TheoryTableAfter("### 3.16 "), EventPolicy{});
}

TEST(TimeSteppingPolicySchema, TheoryTableListsExactlyTheDescribedMembers) {
  ExpectTableListsExactlyTheDescribedMembers(
      TheoryTableAfter("#### The time-stepping scheme's thresholds"), TimeSteppingPolicy{});
}

}  // namespace
}  // namespace skewbridge::dynamics::event_policy_schema_test
