#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "jobs/sweep_parser.h"
#include "solver/common/nearest.h"
#include "spectra/event_policy.h"

namespace skewbridge::jobs {

namespace {

// Sets the members of `policy` that `table` names, each checked against the policy's own
// description (schema.h): `table_name` is the TOML table ("event_policy"), `what` the policy as
// the messages name it, `error` makes the parser's one-line InputError.
template <typename Policy>
void ReadPolicy(const toml::table& table, const std::string& table_name, const std::string& what,
                Policy* policy,
                const std::function<InputError(const toml::source_region&, const std::string&,
                                               const std::string&)>& error) {
  const std::vector<schema::Entry> members = schema::Entries(*policy);
  std::vector<std::string> names;
  for (const schema::Entry& e : members) names.push_back(e.name);
  // A nested member is a dotted key (contact.tie_tolerance = 1e-9) or a table
  // [event_policy.contact]; both reach here as a sub-table.
  const std::function<void(const toml::table&, const std::string&)> read =
      [&](const toml::table& t, const std::string& prefix) {
        for (auto&& [key, node] : t) {
          const std::string name = prefix + std::string(key.str());
          const std::string field = table_name + "." + name;
          if (const toml::table* nested = node.as_table()) {
            read(*nested, name + ".");
            continue;
          }
          const auto it = std::find_if(members.begin(), members.end(),
                                       [&](const schema::Entry& e) { return e.name == name; });
          if (it == members.end()) {
            throw error(key.source(), field,
                        "not a member of the " + what + " (docs/theory.md §3.16, its table)" +
                            DidYouMean(name, names));
          }
          std::optional<double> value;
          switch (it->kind) {
            case schema::Kind::kRule:
              if (const std::optional<bool> on = node.template value_exact<bool>())
                value = *on ? 1.0 : 0.0;
              if (!value) throw error(node.source(), field, "must be true or false (a rule)");
              break;
            case schema::Kind::kCount:
              // Within int's range, so that the member (an int or unsigned) holds it.
              if (const std::optional<std::int64_t> n = node.template value_exact<std::int64_t>();
                  n && *n >= 0 && *n <= std::numeric_limits<std::int32_t>::max()) {
                value = static_cast<double>(*n);
              }
              if (!value) {
                throw error(node.source(), field, "must be an integer, " + it->allowed.Text());
              }
              break;
            case schema::Kind::kReal:
              value = node.template value<double>();  // an integer reads as a real
              if (!value) {
                throw error(node.source(), field, "must be a number, " + it->allowed.Text());
              }
              break;
          }
          if (!it->allowed.Admits(*value)) {
            throw error(
                node.source(), field,
                "must be " + it->allowed.Text() + " (got " + schema::FormatNumber(*value) + ")");
          }
          spectra::SetPolicyMember(policy, name, *value);
        }
      };
  read(table, "");
}

}  // namespace

void SpecParser::ParseEventPolicy(const toml::table& table, SweepSpec& spec) const {
  ReadPolicy(table, "event_policy", "event policy", &spec.policies.event,
             [this](const toml::source_region& where, const std::string& field,
                    const std::string& message) { return Error(where, field, message); });
}

void SpecParser::ParseTimeSteppingPolicy(const toml::table& table, SweepSpec& spec) const {
  ReadPolicy(table, "time_stepping_policy", "time-stepping policy", &spec.policies.time_stepping,
             [this](const toml::source_region& where, const std::string& field,
                    const std::string& message) { return Error(where, field, message); });
}

}  // namespace skewbridge::jobs
