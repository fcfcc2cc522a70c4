#include <cmath>

#include "solver/model/model_file_tables.h"

namespace skewbridge::model::detail {

AbutmentParameters ReadAbutments(Section& s, bool multi_deck) {
  AbutmentParameters a;
  s.Expect(multi_deck ? "set, gap_m, eps_N, mu (with [[deck]] tables)"
                      : "set, gap_m, eps_N, mu, contacts");
  const std::optional<std::string> set =
      multi_deck ? s.String("set", {"both"}) : s.String("set", {"+x", "both"});
  if (!set && !multi_deck) {
    s.Missing("set", "\"+x\" or \"both\"");
  }
  a.set = set.value_or("both") == "both" ? AbutmentSet::kBoth : AbutmentSet::kPlusX;
  if (!s.Has("gap_m")) {
    s.Missing("gap_m", "joint gap along x, m, or a table { \"+x\" = ..., \"-x\" = ... }");
  }
  if (const toml::node* gap_node = s.Get("gap_m"); gap_node->is_table()) {
    Section g(*gap_node->as_table(), s.Field("gap_m"), s.source());
    g.Expect(a.set == AbutmentSet::kBoth ? "\"+x\", \"-x\"" : "\"+x\" (with set = \"+x\")");
    a.gap_plus_m = g.RequiredNumber("+x", "gap of the +x abutment, m");
    CheckNonNegative(a.gap_plus_m, g.Field("+x"), g.At("+x"));
    if (a.set == AbutmentSet::kBoth) {
      a.gap_minus_m = g.RequiredNumber("-x", "gap of the -x abutment, m");
      CheckNonNegative(a.gap_minus_m, g.Field("-x"), g.At("-x"));
      g.Finish("\"+x\", \"-x\"");
    } else {
      g.Finish("\"+x\" (with set = \"+x\")");
    }
  } else {
    const double gap = s.RequiredNumber("gap_m", "");
    CheckNonNegative(gap, s.Field("gap_m"), s.At("gap_m"));
    a.gap_plus_m = gap;
    a.gap_minus_m = gap;
  }
  a.restitution = s.Number("eps_N").value_or(0.5);
  CheckRange(a.restitution, 0.0, 1.0, false, s.Field("eps_N"), s.At("eps_N"));
  a.friction = s.Number("mu").value_or(0.0);
  CheckNonNegative(a.friction, s.Field("mu"), s.At("mu"));
  if (multi_deck) {
    s.Finish("set, gap_m, eps_N, mu (with [[deck]] tables)");
    return a;
  }
  if (const toml::table* contacts = s.Table("contacts")) {
    Section cs(*contacts, s.Field("contacts"), s.source());
    const bool both = a.set == AbutmentSet::kBoth;
    for (std::string_view name : {"P1", "P2", "P3", "P4"}) {
      if (!both && (name == "P3" || name == "P4")) {
        continue;
      }
      if (const toml::table* t = cs.Table(name)) {
        Section c(*t, cs.Field(name), s.source());
        ContactOverride o;
        o.name = std::string(name);
        o.restitution = c.Number("eps_N");
        if (o.restitution) {
          CheckRange(*o.restitution, 0.0, 1.0, false, c.Field("eps_N"), c.At("eps_N"));
        }
        o.friction = c.Number("mu");
        if (o.friction) {
          CheckNonNegative(*o.friction, c.Field("mu"), c.At("mu"));
        }
        c.Finish("eps_N, mu");
        a.overrides.push_back(o);
      }
    }
    cs.Finish(both ? "P1, P2, P3, P4" : "P1, P2 (with set = \"+x\")");
  }
  s.Finish("set, gap_m, eps_N, mu, contacts");
  return a;
}

}  // namespace skewbridge::model::detail
