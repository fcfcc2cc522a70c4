#include "solver/model/model_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <numbers>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "solver/common/error.h"
#include "solver/common/file_kind.h"
#include "solver/common/nearest.h"
#include "solver/common/units.h"
#include "solver/model/checks.h"

namespace skewbridge::model {

using detail::CheckFinite;
using detail::CheckNonNegative;
using detail::CheckPositive;
using detail::CheckRange;
using detail::Fail;
using detail::Where;

std::optional<double> ExcitationSpec::Duration() const {
  if (kind == Kind::kPulse) {
    return 2.0 * std::numbers::pi / omega_radps;
  }
  if (file.empty() && dt_s && !values.empty()) {
    return *dt_s * static_cast<double>(values.size() - 1);
  }
  return std::nullopt;
}

void ExcitationSpec::CheckPga(double pga_mps2, std::string_view source, long line,
                              std::string_view field) const {
  const double as_given_mps2 = scale != 0.0 ? pga_mps2 / std::abs(scale) : 0.0;
  if (!(as_given_mps2 > max_pga_g * kStandardGravity_mps2)) {
    return;
  }
  std::ostringstream text;
  text.precision(4);
  text << "PGA " << as_given_mps2 << " m/s^2 (" << as_given_mps2 / kStandardGravity_mps2
       << " g) in the units " << UnitsName(units) << " is above max_pga_g = " << max_pga_g
       << " g, beyond any recorded ground motion; allowed: the true excitation.units ("
       << AllowedUnitsText() << "), or a larger excitation.max_pga_g (inf: no bound) if the "
       << "motion means it";
  Fail(Where{source, line}, field, text.str());
}

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

long LineOf(const toml::node& node) { return static_cast<long>(node.source().begin.line); }

std::string Join(std::initializer_list<std::string_view> names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) {
      out += ", ";
    }
    out += n;
  }
  return out;
}

// The key names of an "allowed" text such as `kind, w0, W0 (with kind = "uncoupled")` or
// `sections [[deck]], excitation`: the words between commas, without brackets and quotes.
std::vector<std::string> AllowedNames(std::string_view allowed) {
  if (const std::size_t paren = allowed.find(" ("); paren != std::string_view::npos) {
    allowed = allowed.substr(0, paren);
  }
  if (allowed.rfind("sections ", 0) == 0) {
    allowed.remove_prefix(9);
  }
  std::vector<std::string> names;
  std::string name;
  for (const char c : std::string(allowed) + ",") {
    if (c == ',') {
      if (!name.empty()) names.push_back(name);
      name.clear();
    } else if (c != ' ' && c != '[' && c != ']' && c != '"') {
      name += c;
    }
  }
  return names;
}

// One TOML table being read: remembers which keys were used so that any other key is reported
// as unknown, with the key path and line, the allowed keys and the nearest of them.
class Section {
 public:
  Section(const toml::table& table, std::string path, std::string_view source)
      : table_(table), path_(std::move(path)), source_(source) {}

  // The TOML key path; keys that are not bare TOML keys ("+x") are quoted.
  std::string Field(std::string_view key) const {
    bool bare = !key.empty();
    for (char c : key) {
      bare = bare && (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_');
    }
    std::string path = path_;
    if (!path.empty()) {
      path += '.';
    }
    if (!bare) {
      path += '"';
    }
    path += key;
    if (!bare) {
      path += '"';
    }
    return path;
  }
  Where At(std::string_view key) const {
    const toml::node* node = table_.get(key);
    return Where{source_, node != nullptr ? LineOf(*node) : TableLine()};
  }
  long TableLine() const { return LineOf(table_); }
  bool Has(std::string_view key) const { return table_.contains(key); }
  const toml::node* Get(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  // Declares the keys this table may hold (as Finish will): a required key found missing is
  // then reported as a misspelling when the table holds an unknown key, which it most often
  // is. `elsewhere` names other forms of the table and their keys (`kind = "principal"`,
  // `w1, w2, w_theta`), for a key that is allowed only there.
  void Expect(std::string_view allowed,
              std::vector<std::pair<std::string, std::string>> elsewhere = {}) {
    allowed_ = allowed;
    elsewhere_ = std::move(elsewhere);
  }

  // Fails on a key outside the keys declared by Expect (nothing when none were declared).
  void RejectUndeclared() const {
    if (!allowed_.empty()) {
      const std::vector<std::string> names = AllowedNames(allowed_);
      RejectUnknown([&](std::string_view k) {
        return std::find(names.begin(), names.end(), k) == names.end();
      });
    }
  }

  [[noreturn]] void Missing(std::string_view key, std::string_view what) const {
    RejectUndeclared();
    Fail(Where{source_, TableLine()}, Field(key),
         std::string("missing required key (").append(what).append(")"));
  }

  std::optional<double> Number(std::string_view key) {
    const toml::node* node = Get(key);
    if (node == nullptr) {
      return std::nullopt;
    }
    if (!node->is_number()) {
      Fail(At(key), Field(key), "must be a number");
    }
    const double value =
        node->is_integer() ? static_cast<double>(*node->value<int64_t>()) : *node->value<double>();
    CheckFinite(value, Field(key), At(key));
    return value;
  }

  double RequiredNumber(std::string_view key, std::string_view what) {
    const std::optional<double> value = Number(key);
    if (!value) {
      Missing(key, what);
    }
    return *value;
  }

  std::optional<std::string> String(std::string_view key,
                                    std::initializer_list<std::string_view> allowed) {
    const toml::node* node = Get(key);
    if (node == nullptr) {
      return std::nullopt;
    }
    const std::string allowed_text = Join(allowed);
    if (!node->is_string()) {
      Fail(At(key), Field(key), "must be a string (allowed: " + allowed_text + ")");
    }
    std::string value = *node->value<std::string>();
    if (allowed.size() > 0) {
      bool ok = false;
      for (std::string_view a : allowed) {
        ok = ok || value == a;
      }
      if (!ok) {
        Fail(At(key), Field(key), "must be one of " + allowed_text + " (got \"" + value + "\")");
      }
    }
    return value;
  }

  // A sub-table, or nullopt.
  const toml::table* Table(std::string_view key) {
    const toml::node* node = Get(key);
    if (node == nullptr) {
      return nullptr;
    }
    if (!node->is_table()) {
      Fail(At(key), Field(key), "must be a table");
    }
    return node->as_table();
  }

  // Every key not read is unknown.
  void Finish(std::string_view allowed) {
    allowed_ = allowed;
    RejectUnknown([&](std::string_view k) { return used_.count(std::string(k)) == 0; });
  }

  // A key read only to be rejected in this context.
  void Reject(std::string_view key, std::string_view why) {
    if (Has(key)) {
      Fail(At(key), Field(key), why);
    }
  }

  std::string_view source() const { return source_; }

 private:
  // Fails on the first key (by line) for which `unknown` holds, naming the allowed keys, the
  // nearest of them, or the form of the table that takes the key.
  template <class Predicate>
  void RejectUnknown(Predicate unknown) const {
    const toml::node* first = nullptr;
    std::string first_key;
    for (auto&& [key, node] : table_) {
      if (unknown(key.str()) && (first == nullptr || LineOf(node) < LineOf(*first))) {
        first = &node;
        first_key = key.str();
      }
    }
    if (first == nullptr) {
      return;
    }
    const bool sections = allowed_.rfind("sections ", 0) == 0;  // the file's top level
    std::string problem = sections ? "unknown section (allowed: " + allowed_.substr(9) + ")"
                                   : "unknown key (allowed: " + allowed_ + ")";
    for (const auto& [form, keys] : elsewhere_) {
      const std::vector<std::string> names = AllowedNames(keys);
      if (std::find(names.begin(), names.end(), first_key) != names.end()) {
        Fail(Where{source_, LineOf(*first)}, Field(first_key),
             problem + "; it is a key of " + form);
      }
    }
    Fail(Where{source_, LineOf(*first)}, Field(first_key),
         problem + DidYouMean(first_key, AllowedNames(allowed_)));
  }

  const toml::table& table_;
  std::string path_;
  std::string_view source_;
  std::set<std::string> used_;
  std::string allowed_;  // the allowed keys as Finish names them, once known
  std::vector<std::pair<std::string, std::string>> elsewhere_;
};

Eigen::Matrix3d Matrix3(Section& s, std::string_view key) {
  const toml::node* node = s.Get(key);
  const std::string problem = "must be a 3 x 3 array of numbers, row by row";
  if (node == nullptr || !node->is_array() || node->as_array()->size() != 3) {
    Fail(s.At(key), s.Field(key), problem);
  }
  Eigen::Matrix3d A;
  const toml::array& rows = *node->as_array();
  for (std::size_t i = 0; i < 3; ++i) {
    if (!rows[i].is_array() || rows[i].as_array()->size() != 3) {
      Fail(s.At(key), s.Field(key), problem);
    }
    const toml::array& row = *rows[i].as_array();
    for (std::size_t j = 0; j < 3; ++j) {
      if (!row[j].is_number()) {
        Fail(s.At(key), s.Field(key), problem);
      }
      A(static_cast<int>(i), static_cast<int>(j)) =
          row[j].is_integer() ? static_cast<double>(*row[j].value<int64_t>())
                              : *row[j].value<double>();
    }
  }
  if (!A.allFinite()) {
    Fail(s.At(key), s.Field(key), "must contain finite numbers only (got NaN or Inf)");
  }
  return A;
}

// The tables of a TOML array of tables ([[name]]), each with its line.
std::vector<const toml::table*> ArrayOfTables(Section& top, std::string_view name) {
  std::vector<const toml::table*> tables;
  const toml::node* node = top.Get(name);
  if (node == nullptr) {
    return tables;
  }
  const toml::array* array = node->as_array();
  if (array == nullptr) {
    Fail(top.At(name), top.Field(name), "must be an array of tables [[" + std::string(name) + "]]");
  }
  for (const toml::node& entry : *array) {
    if (!entry.is_table()) {
      Fail(Where{top.source(), LineOf(entry)}, top.Field(name),
           "must be an array of tables [[" + std::string(name) + "]]");
    }
    tables.push_back(entry.as_table());
  }
  return tables;
}

std::string Indexed(std::string_view name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

void ReadDeck(Section& s, DeckSpec& spec) {
  s.Expect("m, I_m, L, W, eta0, skew_deg");
  const double m = s.RequiredNumber("m", "deck mass, kg");
  CheckPositive(m, s.Field("m"), s.At("m"));
  spec.mass_kg = m;
  const double L = s.RequiredNumber("L", "deck length, m");
  CheckPositive(L, s.Field("L"), s.At("L"));
  const double skew_deg = s.RequiredNumber("skew_deg", "skew angle, deg");
  CheckRange(skew_deg, 0.0, 90.0, true, s.Field("skew_deg"), s.At("skew_deg"), "deg");
  spec.geometry.length_m = L;
  spec.geometry.skew_rad = skew_deg * kDegToRad;
  const std::optional<double> W = s.Number("W");
  const std::optional<double> eta0 = s.Number("eta0");
  if (W && eta0) {
    Fail(s.At("eta0"), s.Field("eta0"), "give either W or eta0, not both");
  }
  if (W) {
    CheckPositive(*W, s.Field("W"), s.At("W"));
    spec.geometry.width_m = *W;
  } else if (eta0) {
    CheckPositive(*eta0, s.Field("eta0"), s.At("eta0"));
    if (!(skew_deg > 0.0)) {
      Fail(s.At("eta0"), s.Field("eta0"),
           "needs skew_deg in (0, 90) deg (W is then L sin 2a / (2 eta0))");
    }
    spec.geometry.width_m = WidthFromEta0(*eta0, spec.geometry.skew_rad, L);
  } else {
    s.Missing("W", "deck width, m, or eta0");
  }
  if (s.Has("I_m")) {
    const toml::node* node = s.Get("I_m");
    if (node->is_string()) {
      s.String("I_m", {"uniform"});
      spec.inertia_kgm2.reset();
    } else {
      const double I_m = s.RequiredNumber("I_m", "");
      CheckPositive(I_m, s.Field("I_m"), s.At("I_m"));
      spec.inertia_kgm2 = I_m;
    }
  }
  s.Finish("m, I_m, L, W, eta0, skew_deg");
}

// A plan spring's keys: k_strong_Npm and k_weak_Npm with strong_axis_deg, or k_Npm for the
// same stiffness along every axis.
PlanSpring ReadPlanSpring(Section& s, bool positive) {
  PlanSpring k;
  const auto check = [&](double value, std::string_view key) {
    if (positive) {
      CheckPositive(value, s.Field(key), s.At(key));
    } else {
      CheckNonNegative(value, s.Field(key), s.At(key));
    }
  };
  if (const std::optional<double> k_all = s.Number("k_Npm")) {
    s.Reject("k_strong_Npm", "give either k_Npm or k_strong_Npm and k_weak_Npm, not both");
    s.Reject("k_weak_Npm", "give either k_Npm or k_strong_Npm and k_weak_Npm, not both");
    s.Reject("strong_axis_deg", "has no meaning with k_Npm (the same stiffness on every axis)");
    check(*k_all, "k_Npm");
    k.k_strong_Npm = *k_all;
    k.k_weak_Npm = *k_all;
    return k;
  }
  k.k_strong_Npm = s.RequiredNumber("k_strong_Npm", "N/m along the strong axis, or k_Npm");
  check(k.k_strong_Npm, "k_strong_Npm");
  k.k_weak_Npm = s.RequiredNumber("k_weak_Npm", "N/m along the weak axis, or k_Npm");
  check(k.k_weak_Npm, "k_weak_Npm");
  k.strong_axis_rad = s.Number("strong_axis_deg").value_or(0.0) * kDegToRad;
  return k;
}

// kind = "elements": [[substructure.pier]] (position, stiffness > 0) and
// [[substructure.bearing]] (on pier i, or on the ground without `pier`; stiffness >= 0).
void ReadElements(Section& s, DeckSpec& spec) {
  spec.piers.clear();
  spec.bearings.clear();
  const std::vector<const toml::table*> piers = ArrayOfTables(s, "pier");
  for (std::size_t i = 0; i < piers.size(); ++i) {
    Section p(*piers[i], Indexed(s.Field("pier"), i), s.source());
    p.Expect("x_m, y_m, k_Npm, k_strong_Npm, k_weak_Npm, strong_axis_deg");
    PierSpec pier;
    pier.position_m = {p.RequiredNumber("x_m", "pier axis x in the deck frame, m"),
                       p.RequiredNumber("y_m", "pier axis y in the deck frame, m")};
    pier.spring = ReadPlanSpring(p, true);
    p.Finish("x_m, y_m, k_Npm, k_strong_Npm, k_weak_Npm, strong_axis_deg");
    spec.piers.push_back(pier);
  }
  const std::vector<const toml::table*> bearings = ArrayOfTables(s, "bearing");
  if (bearings.empty()) {
    Fail(Where{s.source(), s.TableLine()}, s.Field("bearing"),
         "at least one [[substructure.bearing]] is required with kind = \"elements\"");
  }
  std::vector<bool> carries(piers.size(), false);
  for (std::size_t i = 0; i < bearings.size(); ++i) {
    Section b(*bearings[i], Indexed(s.Field("bearing"), i), s.source());
    b.Expect("pier, x_m, y_m, k_Npm, k_strong_Npm, k_weak_Npm, strong_axis_deg");
    BearingSpec bearing;
    if (const std::optional<double> pier = b.Number("pier")) {
      if (!(*pier >= 0.0) || *pier != std::floor(*pier) ||
          *pier >= static_cast<double>(piers.size())) {
        Fail(b.At("pier"), b.Field("pier"),
             "must be a pier index, a whole number in [0, " + std::to_string(piers.size()) +
                 ") (got " + detail::Show(*pier) + "); omit it for a bearing on the ground");
      }
      bearing.pier = static_cast<int>(*pier);
      carries[static_cast<std::size_t>(bearing.pier)] = true;
    }
    // On a pier the bearing sits on its axis unless placed; on the ground it must be placed.
    if (bearing.pier >= 0 && !b.Has("x_m") && !b.Has("y_m")) {
      bearing.position_m = spec.piers[static_cast<std::size_t>(bearing.pier)].position_m;
    } else {
      const char* what = bearing.pier >= 0 ? "bearing x in the deck frame, m"
                                           : "bearing x in the deck frame, m (a bearing on the "
                                             "ground has no pier to take it from)";
      bearing.position_m = {b.RequiredNumber("x_m", what),
                            b.RequiredNumber("y_m", "bearing y in the deck frame, m")};
    }
    bearing.spring = ReadPlanSpring(b, false);
    b.Finish("pier, x_m, y_m, k_Npm, k_strong_Npm, k_weak_Npm, strong_axis_deg");
    spec.bearings.push_back(bearing);
  }
  for (std::size_t i = 0; i < piers.size(); ++i) {
    if (!carries[i]) {
      Fail(Where{s.source(), LineOf(*piers[i])}, Indexed(s.Field("pier"), i),
           "no bearing sits on it (give a [[substructure.bearing]] with pier = " +
               std::to_string(i) + ", or remove the pier)");
    }
  }
}

// The keys of [substructure] for each kind.
constexpr std::array<std::pair<std::string_view, std::string_view>, 4> kSubstructureKeys{{
    {"uncoupled", "kind, w0, w0x, w0y, W0, xi, C (with kind = \"uncoupled\")"},
    {"principal", "kind, w1, w2, w_theta, axis_deg, e_x, e_y, xi, C (with kind = \"principal\")"},
    {"elements", "kind, bearing, pier, xi, C (with kind = \"elements\")"},
    {"matrix", "kind, K, xi, C (with kind = \"matrix\")"},
}};

// Declares the keys of `kind` among `forms` (kind, keys), the other kinds as where a key
// foreign to this one belongs.
template <std::size_t N>
void ExpectForm(Section& s, std::string_view kind,
                const std::array<std::pair<std::string_view, std::string_view>, N>& forms) {
  std::string_view keys;
  std::vector<std::pair<std::string, std::string>> elsewhere;
  for (const auto& [k, text] : forms) {
    if (k == kind) {
      keys = text;
    } else {
      elsewhere.emplace_back("kind = \"" + std::string(k) + "\"", std::string(text));
    }
  }
  s.Expect(keys, std::move(elsewhere));
}

void ReadSubstructure(Section& s, DeckSpec& spec) {
  const std::string kind =
      s.String("kind", {"uncoupled", "principal", "matrix", "elements"}).value_or("uncoupled");
  ExpectForm(s, kind, kSubstructureKeys);
  if (kind == "uncoupled") {
    spec.stiffness = DeckSpec::StiffnessKind::kUncoupled;
    const std::optional<double> w0 = s.Number("w0");
    if (w0) {
      s.Reject("w0x", "give either w0 or w0x and w0y, not both");
      s.Reject("w0y", "give either w0 or w0x and w0y, not both");
      CheckNonNegative(*w0, s.Field("w0"), s.At("w0"));
      spec.w0x_radps = *w0;
      spec.w0y_radps = *w0;
    } else {
      spec.w0x_radps = s.RequiredNumber("w0x", "rad/s, or w0 for both x and y");
      CheckNonNegative(spec.w0x_radps, s.Field("w0x"), s.At("w0x"));
      spec.w0y_radps = s.RequiredNumber("w0y", "rad/s, or w0 for both x and y");
      CheckNonNegative(spec.w0y_radps, s.Field("w0y"), s.At("w0y"));
    }
    spec.W0_radps = s.RequiredNumber("W0", "torsional frequency, rad/s");
    CheckNonNegative(spec.W0_radps, s.Field("W0"), s.At("W0"));
  } else if (kind == "principal") {
    spec.stiffness = DeckSpec::StiffnessKind::kPrincipal;
    spec.w1_radps = s.RequiredNumber("w1", "rad/s along principal axis 1");
    CheckNonNegative(spec.w1_radps, s.Field("w1"), s.At("w1"));
    spec.w2_radps = s.RequiredNumber("w2", "rad/s along principal axis 2");
    CheckNonNegative(spec.w2_radps, s.Field("w2"), s.At("w2"));
    spec.w_theta_radps =
        s.RequiredNumber("w_theta", "torsional rad/s about the centre of rigidity");
    CheckNonNegative(spec.w_theta_radps, s.Field("w_theta"), s.At("w_theta"));
    spec.axis_rad = s.Number("axis_deg").value_or(0.0) * kDegToRad;
    spec.centre_of_rigidity_m = {s.Number("e_x").value_or(0.0), s.Number("e_y").value_or(0.0)};
  } else if (kind == "elements") {
    spec.stiffness = DeckSpec::StiffnessKind::kElements;
    ReadElements(s, spec);
  } else {
    spec.stiffness = DeckSpec::StiffnessKind::kMatrix;
    if (!s.Has("K")) {
      s.Missing("K", "3 x 3 stiffness matrix");
    }
    spec.K = Matrix3(s, "K");
  }
  if (s.Has("C")) {
    s.Reject("xi", "give either xi or C, not both");
    spec.C = Matrix3(s, "C");
  } else {
    spec.C.reset();
    spec.xi = s.Number("xi").value_or(0.05);
    CheckRange(spec.xi, 0.0, 1.0, true, s.Field("xi"), s.At("xi"));
  }
  for (const auto& [k, keys] : kSubstructureKeys) {
    if (k == kind) {
      s.Finish(keys);
    }
  }
}

// What an [abutments] section says, in either form of the file.
struct AbutmentParameters {
  AbutmentSet set = AbutmentSet::kBoth;
  double gap_plus_m = 0.0;
  double gap_minus_m = 0.0;
  double restitution = 0.5;
  double friction = 0.0;
  std::vector<ContactOverride> overrides;
};

// The one [abutments] reader. A single deck names its set ("+x" or "both") and may override
// contacts P1..P4; a row of [[deck]] tables always has both abutments (set may say "both") and
// no per-contact table (its contacts are named by deck and corner).
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

// The largest ground acceleration accepted [m/s^2] (about 1e5 g: beyond any ground motion, a
// unit error; far enough from overflow that responses stay finite).
constexpr double kMaxAcceleration_mps2 = 1e6;
// The largest factor on a sampled excitation's values.
constexpr double kMaxScale = 1e6;

// The keys of [excitation] for each kind.
constexpr std::array<std::pair<std::string_view, std::string_view>, 2> kExcitationKeys{{
    {"pulse", "kind, shape, a_g, a_g_g, w_g, T_g, direction, angle_deg (with kind = \"pulse\")"},
    {"sampled",
     "kind, file, values, dt_s, units, scale, max_pga_g, direction, angle_deg (with kind = "
     "\"sampled\")"},
}};

void ReadExcitation(Section& s, const std::filesystem::path& base_dir, ExcitationSpec& spec) {
  s.Expect(
      "kind, shape, a_g, a_g_g, w_g, T_g, file, values, dt_s, units, scale, max_pga_g, "
      "direction, angle_deg");
  const std::optional<std::string> kind = s.String("kind", {"pulse", "sampled"});
  if (!kind) {
    s.Missing("kind", "\"pulse\" or \"sampled\"");
  }
  ExpectForm(s, *kind, kExcitationKeys);
  // Direction: "x", "y" or an angle from x (CCW, deg).
  if (s.Has("direction")) {
    s.Reject("angle_deg", "give either direction or angle_deg, not both");
    const std::string d = *s.String("direction", {"x", "y"});
    spec.direction = d == "x" ? Eigen::Vector2d::UnitX() : Eigen::Vector2d::UnitY();
  } else if (const std::optional<double> angle = s.Number("angle_deg")) {
    spec.direction = {std::cos(*angle * kDegToRad), std::sin(*angle * kDegToRad)};
  }
  if (*kind == "pulse") {
    spec.kind = ExcitationSpec::Kind::kPulse;
    const std::optional<std::string> shape = s.String("shape", {"cosine", "sine"});
    if (!shape) {
      s.Missing("shape", "\"cosine\" or \"sine\"");
    }
    spec.shape = *shape == "cosine" ? ExcitationSpec::PulseShape::kCosine
                                    : ExcitationSpec::PulseShape::kSine;
    if (s.Has("a_g")) {
      s.Reject("a_g_g", "give either a_g (m/s^2) or a_g_g (g), not both");
      spec.amplitude_mps2 = *s.Number("a_g");
    } else if (s.Has("a_g_g")) {
      spec.amplitude_mps2 = *s.Number("a_g_g") * kStandardGravity_mps2;
    } else {
      s.Missing("a_g", "pulse amplitude in m/s^2, or a_g_g in g");
    }
    // In m/s^2 after the conversion from g, which can overflow (a_g_g = 1e308).
    const std::string amplitude_key = s.Has("a_g") ? "a_g" : "a_g_g";
    if (!(std::abs(spec.amplitude_mps2) <= kMaxAcceleration_mps2)) {
      Fail(s.At(amplitude_key), s.Field(amplitude_key),
           "the amplitude is " + detail::Show(spec.amplitude_mps2) +
               " m/s^2; allowed: finite, at most 1e6 m/s^2 (about 1e5 g) in magnitude");
    }
    if (s.Has("w_g")) {
      s.Reject("T_g", "give either w_g (rad/s) or T_g (s), not both");
      spec.omega_radps = *s.Number("w_g");
      CheckPositive(spec.omega_radps, s.Field("w_g"), s.At("w_g"));
    } else if (s.Has("T_g")) {
      const double T_g = *s.Number("T_g");
      CheckPositive(T_g, s.Field("T_g"), s.At("T_g"));
      spec.omega_radps = 2.0 * std::numbers::pi / T_g;
    } else {
      s.Missing("w_g", "pulse frequency in rad/s, or T_g in s");
    }
    s.Finish(kExcitationKeys[0].second);
    return;
  }
  spec.kind = ExcitationSpec::Kind::kSampled;
  // The units vocabulary of every reader of accelerations (solver/common/units.h).
  AccelerationUnits units = AccelerationUnits::kMetresPerSecond2;
  if (const std::optional<std::string> name = s.String("units", {})) {
    const std::optional<AccelerationUnits> parsed = ParseAccelerationUnits(*name);
    if (!parsed) {
      Fail(s.At("units"), s.Field("units"),
           "unknown units \"" + *name + "\" (allowed: " + std::string(AllowedUnitsText()) + ")");
    }
    units = *parsed;
  }
  const double scale = s.Number("scale").value_or(1.0);
  if (!(std::abs(scale) <= kMaxScale)) {
    Fail(s.At("scale"), s.Field("scale"),
         "must be finite and at most 1e6 in magnitude (got " + detail::Show(scale) + ")");
  }
  spec.units = units;
  spec.scale = scale;
  spec.to_mps2 = ToMetresPerSecond2(units) * scale;
  if (const toml::node* bound = s.Get("max_pga_g")) {
    // A number > 0 in g, or inf: the user means the amplitudes as they are.
    const std::optional<double> value =
        bound->is_integer() ? std::optional<double>(static_cast<double>(*bound->value<int64_t>()))
                            : bound->value<double>();
    if (!value || !(*value > 0.0)) {
      Fail(s.At("max_pga_g"), s.Field("max_pga_g"),
           "must be a number > 0 (g), or inf for no bound");
    }
    spec.max_pga_g = *value;
  }
  if (const std::optional<double> dt = s.Number("dt_s")) {
    CheckPositive(*dt, s.Field("dt_s"), s.At("dt_s"));
    spec.dt_s = dt;
  }
  if (s.Has("file")) {
    s.Reject("values", "give either file or values, not both");
    const std::string file = *s.String("file", {});
    if (file.empty()) {
      Fail(s.At("file"), s.Field("file"), "must name a file");
    }
    const std::filesystem::path p(file);
    spec.file = p.is_absolute() ? p : base_dir / p;
  } else if (s.Has("values")) {
    const toml::node* node = s.Get("values");
    const toml::array* values = node->as_array();
    if (values == nullptr || values->empty()) {
      Fail(s.At("values"), s.Field("values"), "must be a non-empty array of numbers");
    }
    spec.values.clear();
    for (const toml::node& v : *values) {
      if (!v.is_number()) {
        Fail(Where{s.source(), LineOf(v)}, s.Field("values"),
             "must be a non-empty array of numbers");
      }
      const double a =
          v.is_integer() ? static_cast<double>(*v.value<int64_t>()) : *v.value<double>();
      CheckFinite(a, s.Field("values"), Where{s.source(), LineOf(v)});
      spec.values.push_back(a * spec.to_mps2);
    }
    if (!spec.dt_s) {
      s.Missing("dt_s", "sample interval in s, required with values");
    }
    double pga_mps2 = 0.0;
    for (double a : spec.values) pga_mps2 = std::max(pga_mps2, std::abs(a));
    spec.CheckPga(pga_mps2, s.source(), s.At("values").line, s.Field("values"));
  } else {
    s.Missing("file", "a two-column (time, acceleration) file, or inline values with dt_s");
  }
  s.Finish(kExcitationKeys[1].second);
}

void ReadRun(Section& s, RunControl& run) {
  if (const std::optional<double> v = s.Number("end_time_s")) {
    CheckPositive(*v, s.Field("end_time_s"), s.At("end_time_s"));
    run.end_time_s = v;
  }
  run.tail_s = s.Number("tail_s").value_or(run.tail_s);
  CheckNonNegative(run.tail_s, s.Field("tail_s"), s.At("tail_s"));
  run.output_interval_s = s.Number("output_interval_s").value_or(run.output_interval_s);
  CheckNonNegative(run.output_interval_s, s.Field("output_interval_s"), s.At("output_interval_s"));
  run.relative_tolerance = s.Number("rel_tol").value_or(run.relative_tolerance);
  CheckRange(run.relative_tolerance, 1e-15, 1e-2, false, s.Field("rel_tol"), s.At("rel_tol"));
  run.absolute_tolerance = s.Number("abs_tol").value_or(run.absolute_tolerance);
  CheckPositive(run.absolute_tolerance, s.Field("abs_tol"), s.At("abs_tol"));
  run.accumulation_threshold =
      s.Number("accumulation_threshold").value_or(run.accumulation_threshold);
  CheckRange(run.accumulation_threshold, 0.0, 1.0, true, s.Field("accumulation_threshold"),
             s.At("accumulation_threshold"));
  run.simultaneity_tolerance_s =
      s.Number("simultaneity_tol_s").value_or(run.simultaneity_tolerance_s);
  CheckNonNegative(run.simultaneity_tolerance_s, s.Field("simultaneity_tol_s"),
                   s.At("simultaneity_tol_s"));
  run.method = s.String("method", {"event-driven", "time-stepping"}).value_or(run.method);
  run.linear_algebra =
      s.String("linear_algebra", {"auto", "dense", "sparse"}).value_or(run.linear_algebra);
  run.time_step_s = s.Number("time_step_s").value_or(run.time_step_s);
  CheckPositive(run.time_step_s, s.Field("time_step_s"), s.At("time_step_s"));
  if (const std::optional<double> v = s.Number("max_steps")) {
    if (!(*v >= 1.0) || *v != std::floor(*v) || *v > 1e15) {
      Fail(s.At("max_steps"), s.Field("max_steps"),
           "must be a whole number >= 1 (got " + detail::Show(*v) + ")");
    }
    run.max_steps = static_cast<long>(*v);
  }
  s.Finish(
      "end_time_s, tail_s, output_interval_s, rel_tol, abs_tol, accumulation_threshold, "
      "simultaneity_tol_s, method, time_step_s, max_steps, linear_algebra");
}

// The longest run accepted [s]: event times keep a resolution of 1.2e-10 s up to here (one ulp
// of 1e6), below the default simultaneity tolerance of 1e-9 s; beyond, a run length is a unit
// error or an overflow (a pulse period of 1e308 s).
constexpr double kMaxEndTime_s = 1e6;
// The most history samples a run may store (3 DOFs, positions and velocities: 0.5 GB).
constexpr double kMaxHistorySamples = 1e7;

// Counts what a run asks for whose excitation's duration is known when the file is parsed
// (a pulse, inline values, or an end time given); a file's samples are counted when read.
void CheckRunLength(const ExcitationSpec& excitation, const RunControl& run,
                    std::string_view source) {
  const std::optional<double> duration = excitation.Duration();
  if (!run.end_time_s && !duration) {
    return;
  }
  const std::size_t samples = excitation.file.empty() ? excitation.values.size() : 0;
  CheckRunSize(run, duration.value_or(0.0), samples, source, "excitation");
}

// A deck index: a whole number in [0, n_decks).
int DeckIndex(Section& s, std::string_view key, double value, std::size_t n_decks) {
  if (!(value >= 0.0) || value != std::floor(value) || value >= static_cast<double>(n_decks)) {
    Fail(s.At(key), s.Field(key),
         "must be a deck index, a whole number in [0, " + std::to_string(n_decks) + ") (got " +
             detail::Show(value) + ")");
  }
  return static_cast<int>(value);
}

void ReadSupport(Section& s, std::size_t n_decks, SupportSpec& support) {
  s.Expect("deck, between, k_x, k_y, k_theta, c_x, c_y, c_theta, xi");
  if (s.Has("between")) {
    s.Reject("deck", "give either deck (to the ground) or between = [i, j] (a link), not both");
    const toml::node* node = s.Get("between");
    const toml::array* pair = node->as_array();
    if (pair == nullptr || pair->size() != 2 || !(*pair)[0].is_number() ||
        !(*pair)[1].is_number()) {
      Fail(s.At("between"), s.Field("between"), "must be two deck indices [i, j]");
    }
    const auto value = [](const toml::node& v) {
      return v.is_integer() ? static_cast<double>(*v.value<int64_t>()) : *v.value<double>();
    };
    support.deck = DeckIndex(s, "between", value((*pair)[0]), n_decks);
    support.other = DeckIndex(s, "between", value((*pair)[1]), n_decks);
    if (support.deck == support.other) {
      Fail(s.At("between"), s.Field("between"), "must name two different decks");
    }
  } else {
    support.deck = DeckIndex(s, "deck", s.RequiredNumber("deck", "deck index from 0"), n_decks);
    support.other = kGround;
  }
  const char* keys[] = {"k_x", "k_y", "k_theta"};
  const char* damping_keys[] = {"c_x", "c_y", "c_theta"};
  bool any_damping = false;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int d = 0; d < 3; ++d) {
    support.stiffness(d) = s.Number(keys[d]).value_or(0.0);
    CheckNonNegative(support.stiffness(d), s.Field(keys[d]), s.At(keys[d]));
    if (const std::optional<double> v = s.Number(damping_keys[d])) {
      CheckNonNegative(*v, s.Field(damping_keys[d]), s.At(damping_keys[d]));
      c(d) = *v;
      any_damping = true;
    }
  }
  if (any_damping) {
    s.Reject("xi", "give either xi or c_x, c_y, c_theta, not both");
    support.damping = c;
  } else if (support.other != kGround) {
    s.Reject("xi", "a link between decks takes c_x, c_y, c_theta (xi is for ground supports)");
    support.damping = c;
  } else {
    support.xi = s.Number("xi").value_or(0.05);
    CheckRange(support.xi, 0.0, 1.0, true, s.Field("xi"), s.At("xi"));
  }
  s.Finish("deck, between, k_x, k_y, k_theta, c_x, c_y, c_theta, xi");
}

// The most decks of a [[deck]] file: 600 DOFs, 402 contacts. The integrators hold dense
// matrices of (2 x DOFs)^2 entries (a dozen of 11.5 MB here); 1000 decks already take half a
// minute to set up and 3000 do not fit in memory. A bridge of more spans is several models.
constexpr std::size_t kMaxDecks = 200;

// The [[deck]] form: decks in a row along x, joints between consecutive decks, supports.
MultiDeckSpec ReadMultiDeck(Section& top, std::string_view source) {
  MultiDeckSpec spec;
  const std::vector<const toml::table*> decks = ArrayOfTables(top, "deck");
  if (decks.empty()) {
    Fail(Where{source, top.TableLine()}, "deck", "at least one [[deck]] table is required");
  }
  if (decks.size() > kMaxDecks) {
    Fail(Where{source, LineOf(*decks[kMaxDecks])}, "deck",
         std::to_string(decks.size()) + " [[deck]] tables (" + std::to_string(3 * decks.size()) +
             " DOFs); allowed: at most " + std::to_string(kMaxDecks) + " decks (" +
             std::to_string(3 * kMaxDecks) + " DOFs, " + std::to_string(2 * kMaxDecks + 2) +
             " contacts)");
  }
  for (std::size_t i = 0; i < decks.size(); ++i) {
    Section s(*decks[i], Indexed("deck", i), source);
    DeckSpec d;
    ReadDeck(s, d);
    Body b;
    b.mass_kg = d.mass_kg;
    b.geometry = d.geometry;
    b.inertia_kgm2 = d.inertia_kgm2 ? *d.inertia_kgm2 : UniformDeckInertia(d.mass_kg, d.geometry);
    spec.decks.push_back(b);
  }
  const std::vector<const toml::table*> joints = ArrayOfTables(top, "joint");
  if (joints.size() + 1 != decks.size()) {
    const long line = joints.empty() ? 0 : LineOf(*joints.back());
    Fail(Where{source, line}, "joint",
         "needs " + std::to_string(decks.size() - 1) + " [[joint]] tables for " +
             std::to_string(decks.size()) +
             " [[deck]] tables, one after each deck but the last (got " +
             std::to_string(joints.size()) + ")");
  }
  for (std::size_t i = 0; i < joints.size(); ++i) {
    Section s(*joints[i], Indexed("joint", i), source);
    s.Expect("gap_m, eps_N, mu");
    JointSpec j;
    j.gap_m = s.RequiredNumber("gap_m", "joint gap along x, m");
    CheckNonNegative(j.gap_m, s.Field("gap_m"), s.At("gap_m"));
    j.restitution = s.Number("eps_N").value_or(0.5);
    CheckRange(j.restitution, 0.0, 1.0, false, s.Field("eps_N"), s.At("eps_N"));
    j.friction = s.Number("mu").value_or(0.0);
    CheckNonNegative(j.friction, s.Field("mu"), s.At("mu"));
    if (spec.decks[i].geometry.skew_rad != spec.decks[i + 1].geometry.skew_rad) {
      Fail(s.At("gap_m"), s.Field("gap_m"),
           "decks " + std::to_string(i) + " and " + std::to_string(i + 1) +
               " must have the same skew_deg (their end faces are parallel)");
    }
    s.Finish("gap_m, eps_N, mu");
    spec.joints.push_back(j);
  }
  const toml::table* abutments = top.Table("abutments");
  if (abutments == nullptr) {
    Fail(Where{source, 0}, "abutments", "missing required section [abutments]");
  }
  {
    Section s(*abutments, "abutments", source);
    const AbutmentParameters a = ReadAbutments(s, true);
    spec.gap_plus_m = a.gap_plus_m;
    spec.gap_minus_m = a.gap_minus_m;
    spec.restitution = a.restitution;
    spec.friction = a.friction;
  }
  const std::vector<const toml::table*> supports = ArrayOfTables(top, "support");
  for (std::size_t i = 0; i < supports.size(); ++i) {
    Section s(*supports[i], Indexed("support", i), source);
    SupportSpec support;
    ReadSupport(s, decks.size(), support);
    spec.supports.push_back(support);
  }
  top.Reject("substructure", "not used with [[deck]] tables: give [[support]] tables instead");
  return spec;
}

// A sweep specification or a record-set manifest given where a model file belongs is named
// as what it is, not by its first table foreign to a model file.
void RejectOtherKindOfFile(const toml::table& root, std::string_view source) {
  if (root.contains("deck") || root.contains("substructure")) {
    return;
  }
  if (const toml::node* sweep = root.get("sweep"); sweep != nullptr && sweep->is_table()) {
    throw InputError::AtLine(
        source, 0,
        "this is a sweep specification ([sweep] table), not a model file (docs/model-format.md); "
        "`skewbridge sweep SPEC --out FILE.h5` takes it");
  }
  if (const toml::node* record = root.get("record"); record != nullptr && record->is_array()) {
    throw InputError::AtLine(
        source, 0,
        "this is a record-set manifest ([[record]] tables), not a model file "
        "(docs/model-format.md); `skewbridge records info` and a sweep's [records] set take it");
  }
}

ModelFile Parse(const toml::table& root, std::string_view source,
                const std::filesystem::path& base_dir, const std::filesystem::path& path) {
  RejectOtherKindOfFile(root, source);
  Section top(root, "", source);
  DeckSpec deck;
  ExcitationSpec excitation;
  RunControl run;
  const bool multi_deck = root.get("deck") != nullptr && root.get("deck")->is_array();
  top.Expect(multi_deck ? "sections [[deck]], [[joint]], abutments, [[support]], excitation, run"
                        : "sections deck, substructure, abutments, excitation, run");
  const auto required = [&](std::string_view name) -> const toml::table& {
    const toml::table* t = top.Table(name);
    if (t == nullptr) {
      top.RejectUndeclared();  // a misspelt section is named as such
      Fail(Where{source, 0}, name, "missing required section [" + std::string(name) + "]");
    }
    return *t;
  };
  if (const toml::node* deck_node = root.get("deck");
      deck_node != nullptr && deck_node->is_array()) {
    MultiDeckSpec decks = ReadMultiDeck(top, source);
    {
      Section s(required("excitation"), "excitation", source);
      ReadExcitation(s, base_dir, excitation);
    }
    if (const toml::table* t = top.Table("run")) {
      Section s(*t, "run", source);
      ReadRun(s, run);
    }
    top.Finish("sections [[deck]], [[joint]], abutments, [[support]], excitation, run");
    CheckRunLength(excitation, run, source);
    Model model = BuildMultiDeckModel(decks, std::string(source));
    return ModelFile{path, deck, std::move(model), excitation, run, std::move(decks)};
  }
  {
    Section s(required("deck"), "deck", source);
    ReadDeck(s, deck);
  }
  {
    Section s(required("substructure"), "substructure", source);
    ReadSubstructure(s, deck);
  }
  {
    Section s(required("abutments"), "abutments", source);
    const AbutmentParameters a = ReadAbutments(s, false);
    deck.abutments = a.set;
    deck.gap_plus_m = a.gap_plus_m;
    deck.gap_minus_m = a.gap_minus_m;
    deck.restitution = a.restitution;
    deck.friction = a.friction;
    deck.overrides = a.overrides;
  }
  {
    Section s(required("excitation"), "excitation", source);
    ReadExcitation(s, base_dir, excitation);
  }
  if (const toml::table* t = top.Table("run")) {
    Section s(*t, "run", source);
    ReadRun(s, run);
  }
  top.Finish("sections deck, substructure, abutments, excitation, run");
  CheckRunLength(excitation, run, source);
  Model model = BuildDeckModel(deck, std::string(source));
  return ModelFile{path, deck, std::move(model), excitation, run, std::nullopt};
}

}  // namespace

void CheckRunSize(const RunControl& run, double excitation_duration_s,
                  std::size_t excitation_samples, std::string_view source,
                  std::string_view excitation_field) {
  const Where where{source, 0};
  const double t_end = run.EndTime(excitation_duration_s);
  const std::string field = run.end_time_s ? "run.end_time_s" : std::string(excitation_field);
  if (!std::isfinite(t_end) || !(t_end <= kMaxEndTime_s)) {
    Fail(where, field,
         "the run would end at t = " + detail::Show(t_end) +
             " s (the excitation's duration plus run.tail_s, or run.end_time_s); allowed: a "
             "finite end time up to 1e6 s");
  }
  if (run.output_interval_s > 0.0) {
    const double samples = t_end / run.output_interval_s;
    if (!(samples <= kMaxHistorySamples)) {
      Fail(where, "run.output_interval_s",
           "the run of " + detail::Show(t_end) + " s would store " + detail::Show(samples) +
               " history samples; allowed at most 1e7 (a larger interval, or 0 for none)");
    }
  }
  if (run.method == "time-stepping") {
    const double steps = t_end / run.time_step_s;
    if (!(steps <= static_cast<double>(run.max_steps))) {
      Fail(where, "run.time_step_s",
           "the run of " + detail::Show(t_end) + " s would take " + detail::Show(steps) +
               " steps, more than run.max_steps = " + std::to_string(run.max_steps));
    }
  } else if (excitation_samples > 1 &&
             static_cast<double>(excitation_samples - 1) > static_cast<double>(run.max_steps)) {
    // Each sample is a kink of the ground motion, so each interval is one step at least.
    Fail(where, std::string(excitation_field),
         "its " + std::to_string(excitation_samples) +
             " samples take one step each at least, more than run.max_steps = " +
             std::to_string(run.max_steps));
  }
}

ModelFile ParseModelString(std::string_view text, std::string_view source_name,
                           const std::filesystem::path& base_dir) {
  if (HasHdf5Signature(text)) {
    throw InputError::AtLine(source_name, 0,
                             "this is an HDF5 file (a sweep cube or a run file), not a model file "
                             "(TOML, docs/model-format.md); `skewbridge inspect` summarises a "
                             "cube");
  }
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    // A record or signal file given as the model reads as bad TOML on its first line.
    const bool toml_name = std::filesystem::path(source_name).extension() == ".toml";
    throw InputError::AtLine(
        source_name, static_cast<long>(e.source().begin.line),
        std::string("syntax error: ")
            .append(e.description())
            .append(toml_name ? "" : " (a model file is TOML, docs/model-format.md)"));
  }
  return Parse(root, source_name, base_dir, {});
}

ModelFile ParseModelFile(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::ifstream in(path);
  if (!in) {
    throw InputError::AtLine(source, 0, "cannot open the model file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  ModelFile file = ParseModelString(text.str(), source, path.parent_path());
  file.path = path;
  return file;
}

std::vector<DeckAsWritten> DecksAsWritten(const std::filesystem::path& path) {
  toml::table root;
  try {
    root = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    throw InputError::AtLine(path.string(), static_cast<long>(e.source().begin.line),
                             std::string("syntax error: ").append(e.description()));
  }
  std::vector<const toml::table*> decks;
  if (const toml::array* list = root["deck"].as_array()) {
    for (const toml::node& item : *list) decks.push_back(item.as_table());
  } else {
    decks.push_back(root["deck"].as_table());
  }
  std::vector<DeckAsWritten> out;
  for (const toml::table* deck : decks) {
    DeckAsWritten d;
    if (deck != nullptr) {
      d.eta0 = (*deck)["eta0"].value<double>();
      const toml::node* inertia = deck->get("I_m");
      d.inertia_given = inertia != nullptr && inertia->is_number();
    }
    out.push_back(d);
  }
  return out;
}

}  // namespace skewbridge::model
