// The event policy as HDF5 attributes (jobs/h5/event_policy_attrs.h): a policy that differs from
// the defaults in every kind of member, the contact layer's thresholds included, is written to a
// file and read back member by member with its unit and scale.

#include "jobs/h5/event_policy_attrs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "solver/dynamics/event_policy.h"

namespace skewbridge::jobs::h5 {
namespace {

TEST(EventPolicyAttrs, EveryMemberRoundTripsThroughAFileWithItsUnitAndScale) {
  dynamics::EventPolicy policy;
  policy.velocity_tolerance = 3e-11;
  policy.touch_probes = 12;
  policy.jam = false;
  policy.contact.tie_tolerance = 2.5e-10;
  policy.contact.contact_compliance = 1e-7;
  policy.contact.impact_compliance = 4e-8;
  policy.contact.enumeration_unknowns = 9;
  const std::vector<schema::Entry> entries = schema::Entries(policy);

  const std::string path = ::testing::TempDir() + "event_policy_attrs_test.h5";
  {
    Id file = CreateFile(path);
    WriteEventPolicy(file.get(), entries);
  }
  {
    Id file = OpenFile(path, false);
    Id group = OpenGroup(file.get(), "event_policy");
    const std::vector<std::string> keys = GetStringListAttr(group.get(), "keys");
    const std::vector<std::string> units = GetStringListAttr(group.get(), "units");
    const std::vector<std::string> relative_to = GetStringListAttr(group.get(), "relative_to");
    ASSERT_EQ(keys.size(), entries.size());
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const schema::Entry& e = entries[i];
      EXPECT_EQ(keys[i], e.name);
      EXPECT_EQ(units[i], e.unit) << e.name;
      EXPECT_EQ(relative_to[i], e.relative_to) << e.name;
      if (e.integral()) {
        EXPECT_EQ(static_cast<double>(GetIntAttr(group.get(), e.name)), e.value) << e.name;
      } else {
        EXPECT_EQ(GetDoubleAttr(group.get(), e.name), e.value) << e.name;
      }
    }
    EXPECT_EQ(GetDoubleAttr(group.get(), "velocity_tolerance"), 3e-11);
    EXPECT_EQ(GetIntAttr(group.get(), "jam"), 0);
    EXPECT_EQ(GetDoubleAttr(group.get(), "contact.tie_tolerance"), 2.5e-10);
    EXPECT_EQ(GetDoubleAttr(group.get(), "contact.contact_compliance"), 1e-7);
    EXPECT_EQ(GetDoubleAttr(group.get(), "contact.impact_compliance"), 4e-8);
    EXPECT_EQ(GetIntAttr(group.get(), "contact.enumeration_unknowns"), 9);
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace skewbridge::jobs::h5
