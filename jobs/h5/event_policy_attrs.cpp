#include "jobs/h5/event_policy_attrs.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace skewbridge::jobs::h5 {

void WritePolicy(hid_t parent, const std::string& group_name,
                 const std::vector<schema::Entry>& entries) {
  Id group = CreateGroup(parent, group_name);
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

const char* PolicyGroup(model::Method method) {
  return method == model::Method::kTimeStepping ? "time_stepping_policy" : "event_policy";
}

void WriteMethodPolicies(hid_t parent, const std::vector<model::Method>& methods,
                         const dynamics::RunPolicies& policies) {
  for (const model::Method method : {model::Method::kEventDriven, model::Method::kTimeStepping}) {
    if (std::find(methods.begin(), methods.end(), method) != methods.end()) {
      WritePolicy(parent, PolicyGroup(method), spectra::PolicyEntries(method, policies));
    }
  }
}

}  // namespace skewbridge::jobs::h5
