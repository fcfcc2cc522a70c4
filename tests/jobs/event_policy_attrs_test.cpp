// The event policy as HDF5 attributes (jobs/h5/event_policy_attrs.h): a policy that differs from
// the defaults in every kind of member, the contact layer's thresholds included, is written to a
// file and read back member by member with its unit and scale.

#include "jobs/h5/event_policy_attrs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/time_stepping_policy.h"

namespace skewbridge::jobs::h5::event_policy_attrs_test {
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
    WritePolicy(file.get(), "event_policy", entries);
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

// Each method's policy in its own group, written once whatever the repeats: a run file of one
// method carries that method's thresholds only, a cube of both carries both.
TEST(EventPolicyAttrs, EachMethodStoresItsOwnPolicy) {
  const std::string path = ::testing::TempDir() + "method_policies_test.h5";
  const auto groups = [&](const std::vector<model::Method>& methods) {
    {
      Id file = CreateFile(path);
      WriteMethodPolicies(file.get(), methods, {});
    }
    Id file = OpenFile(path, false);
    std::vector<std::string> out;
    for (const char* name : {"event_policy", "time_stepping_policy"}) {
      if (Exists(file.get(), name)) out.push_back(name);
    }
    return out;
  };
  using V = std::vector<std::string>;
  EXPECT_EQ(groups({model::Method::kEventDriven}), V{"event_policy"});
  EXPECT_EQ(groups({model::Method::kTimeStepping}), V{"time_stepping_policy"});
  EXPECT_EQ(groups({model::Method::kTimeStepping, model::Method::kEventDriven,
                    model::Method::kTimeStepping}),
            (V{"event_policy", "time_stepping_policy"}));
  {
    Id file = OpenFile(path, false);
    Id group = OpenGroup(file.get(), "time_stepping_policy");
    const std::vector<schema::Entry> entries = schema::Entries(dynamics::TimeSteppingPolicy{});
    std::vector<std::string> names;
    for (const schema::Entry& e : entries) names.push_back(e.name);
    EXPECT_EQ(GetStringListAttr(group.get(), "keys"), names);
    EXPECT_EQ(GetDoubleAttr(group.get(), "velocity_tolerance"), 1e-9);
    EXPECT_EQ(GetDoubleAttr(group.get(), "normal_compliance"), 1e-9);
    EXPECT_EQ(GetDoubleAttr(group.get(), "active_set_lookahead"), 0.5);
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace skewbridge::jobs::h5::event_policy_attrs_test
