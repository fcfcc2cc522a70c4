#include "jobs/h5/event_policy_attrs.h"

#include <cstdint>
#include <string>
#include <vector>

namespace skewbridge::jobs::h5 {

void WriteEventPolicy(hid_t parent, const std::vector<schema::Entry>& entries) {
  Id group = CreateGroup(parent, "event_policy");
  std::vector<std::string> keys, units, relative_to;
  for (const schema::Entry& e : entries) {
    if (e.integral()) {
      SetAttr(group.get(), e.name, static_cast<std::int64_t>(e.value));
    } else {
      SetAttr(group.get(), e.name, e.value);
    }
    keys.push_back(e.name);
    units.push_back(e.unit);
    relative_to.push_back(e.relative_to);
  }
  SetAttr(group.get(), "keys", keys);
  SetAttr(group.get(), "units", units);
  SetAttr(group.get(), "relative_to", relative_to);
}

}  // namespace skewbridge::jobs::h5
