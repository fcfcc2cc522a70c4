#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "solver/model/model_file_tables.h"

namespace skewbridge::model::detail {
namespace {

// The keys of [abutments] with each law, and of [abutments.backfill] in each of its forms.
constexpr std::string_view kImpactKeys = "set, gap_m, law, eps_N, mu, contacts";
constexpr std::string_view kCompliantKeys =
    "set, gap_m, law, springs, backfill, mu, stick_stiffness_Npm, shear_keys";
// With a law per abutment, one wall of each law: the rigid wall's keys and the compliant wall's
// (a [[deck]] file's abutments have no per-corner tables).
constexpr std::string_view kMixedKeys =
    "set, gap_m, law, eps_N, mu, contacts, springs, backfill, stick_stiffness_Npm, shear_keys";
constexpr std::string_view kMixedDeckKeys =
    "set, gap_m, law, eps_N, mu, springs, backfill, stick_stiffness_Npm, shear_keys (with [[deck]] "
    "tables)";
constexpr std::string_view kShearKeyKeys = "gap_m, v_n_N, details, d3_m, v_res_N, d_res_m, dd_m";
constexpr std::string_view kShearKeyDetailKeys =
    "f_c_MPa, stem_width_m, stem_height_m, key_length_m, load_height_m, tie1_N, tie2_N, "
    "side_bar_h_N, side_bar_v_N, side_faces_h, side_faces_v, side_spacing_m, side_spacing_v_m";
constexpr std::array<std::pair<std::string_view, std::string_view>, 3> kBackfillForms = {{
    {"hyperbolic-gap",
     "form, k_max_Npm, k_ur_Npm, r_f, f_ult_N, k_max_Npm_per_m, k_ur_Npm_per_m, f_ult_N_per_m"},
    {"shamsabadi", "form, k50_Npm, f_ult_N, height_m, y_max_m"},
    {"caltrans", "form, width_m, width_ft, height_m, height_ft, skew_reduction, y_max_m"},
}};

// A positive length given in metres (`metres`) or feet (`feet`), exactly one of them; in m.
double LengthMOrFt(Section& b, std::string_view metres, std::string_view feet,
                   std::string_view what) {
  const std::optional<double> m = b.Number(metres);
  const std::optional<double> ft = b.Number(feet);
  if (m && ft) {
    Fail(b.At(feet), b.Field(feet),
         "give " + std::string(metres) + " or " + std::string(feet) + ", not both");
  }
  if (!m && !ft) {
    b.Missing(metres, std::string(what) + ", m (or " + std::string(feet) + " in ft)");
  }
  const std::string_view key = m ? metres : feet;
  CheckPositive(m ? *m : *ft, b.Field(key), b.At(key));
  return m ? *m : *ft * 0.3048;
}

// A positive number that is required.
double Positive(Section& b, std::string_view key, std::string_view what) {
  const double value = b.RequiredNumber(key, what);
  CheckPositive(value, b.Field(key), b.At(key));
  return value;
}

// [abutments.backfill]: the law of each wall in one of its three forms [docs/compliant.md §1].
BackfillSpec ReadBackfill(Section& b) {
  BackfillSpec f;
  const std::optional<std::string> form =
      b.String("form", {"hyperbolic-gap", "shamsabadi", "caltrans"});
  if (!form) {
    b.Missing("form", "\"hyperbolic-gap\", \"shamsabadi\" or \"caltrans\"");
  }
  // The keys of this form; a key of another form is named with the form that takes it.
  std::string_view keys;
  std::vector<std::pair<std::string, std::string>> elsewhere;
  for (const auto& [name, names] : kBackfillForms) {
    if (name == *form) {
      keys = names;
    } else {
      elsewhere.emplace_back("form = \"" + std::string(name) + "\"", std::string(names));
    }
  }
  b.Expect(keys, std::move(elsewhere));
  b.Reject("gap_m",
           "the joint's gap is abutments.gap_m (along x), the same for both laws; remove it here");
  if (*form == "hyperbolic-gap") {
    f.form = BackfillForm::kHyperbolicGap;
    f.per_metre = b.Has("k_max_Npm_per_m") || b.Has("f_ult_N_per_m");
    const std::string_view k_max = f.per_metre ? "k_max_Npm_per_m" : "k_max_Npm";
    const std::string_view k_ur = f.per_metre ? "k_ur_Npm_per_m" : "k_ur_Npm";
    const std::string_view f_ult = f.per_metre ? "f_ult_N_per_m" : "f_ult_N";
    // The other kind's keys are refused by name: a law is per wall or per metre, not both.
    for (std::string_view other :
         f.per_metre ? std::array<std::string_view, 3>{"k_max_Npm", "k_ur_Npm", "f_ult_N"}
                     : std::array<std::string_view, 3>{"k_max_Npm_per_m", "k_ur_Npm_per_m",
                                                       "f_ult_N_per_m"}) {
      b.Reject(other,
               "give the constants per wall (k_max_Npm, k_ur_Npm, f_ult_N) or per metre of wall "
               "(k_max_Npm_per_m, k_ur_Npm_per_m, f_ult_N_per_m), not both");
    }
    f.k_max = Positive(b, k_max,
                       f.per_metre ? "initial stiffness per metre of wall, N/m per m"
                                   : "initial stiffness of the wall, N/m");
    f.k_ur = b.Number(k_ur).value_or(f.k_max);
    CheckPositive(f.k_ur, b.Field(k_ur), b.At(k_ur));
    f.r_f = b.RequiredNumber("r_f", "failure ratio, in (0, 1]");
    CheckRange(f.r_f, 0.0, 1.0, false, b.Field("r_f"), b.At("r_f"));
    if (f.r_f == 0.0) {
      Fail(b.At("r_f"), b.Field("r_f"), "must be in (0, 1] (got 0)");
    }
    f.f_ult = Positive(b, f_ult,
                       f.per_metre ? "ultimate passive force per metre of wall, N/m"
                                   : "ultimate passive force of the wall, N");
  } else if (*form == "shamsabadi") {
    f.form = BackfillForm::kShamsabadi;
    f.k50_Npm = Positive(b, "k50_Npm", "secant stiffness of the wall at F_ult / 2, N/m");
    f.f_ult = Positive(b, "f_ult_N", "ultimate passive force of the wall, N");
    if (b.Has("y_max_m")) {
      b.Reject("height_m", "give height_m (y_max = 0.05 H) or y_max_m, not both");
      f.y_max_m = Positive(b, "y_max_m", "");
    } else {
      f.y_max_m = joint::ShamsabadiYMax_m(
          Positive(b, "height_m", "backwall height H, m (y_max = 0.05 H), or y_max_m"));
    }
    if (!(f.k50_Npm * f.y_max_m > f.f_ult)) {
      Fail(b.At("k50_Npm"), b.Field("k50_Npm"),
           "K50 y_max must exceed F_ult for a softening hyperbola (K50 y_max = " +
               Show(f.k50_Npm * f.y_max_m) + " N, f_ult_N = " + Show(f.f_ult) + " N)");
    }
  } else {
    f.form = BackfillForm::kCaltrans;
    f.width_m = LengthMOrFt(b, "width_m", "width_ft", "backwall width w");
    f.height_m = LengthMOrFt(b, "height_m", "height_ft", "backwall height h");
    f.skew_reduction = b.String("skew_reduction", {"exp", "none"}).value_or("exp") == "exp";
    f.y_max_m = joint::ShamsabadiYMax_m(f.height_m);
    if (b.Has("y_max_m")) f.y_max_m = Positive(b, "y_max_m", "");
  }
  b.Finish(keys);
  return f;
}

// A number >= 0 that is optional (`fallback` when absent).
double NonNegative(Section& b, std::string_view key, double fallback) {
  const double value = b.Number(key).value_or(fallback);
  CheckNonNegative(value, b.Field(key), b.At(key));
  return value;
}

// [abutments.shear_keys.details]: the key's concrete and steel, whose V_c + V_s is its capacity
// [Megally et al. 2001; docs/compliant.md §2].
joint::ShearKeyDetails ReadShearKeyDetails(Section& d) {
  d.Expect(kShearKeyDetailKeys);
  joint::ShearKeyDetails k;
  k.f_c_Pa = 1e6 * Positive(d, "f_c_MPa", "concrete compressive strength f'c, MPa");
  k.stem_width_m = Positive(d, "stem_width_m", "width b of the abutment stem wall, m");
  k.stem_height_m = Positive(d, "stem_height_m", "height h of the stem wall under the key, m");
  k.key_length_m = Positive(d, "key_length_m", "length d of the key's base along the stem, m");
  k.load_height_m = NonNegative(d, "load_height_m", 0.0);
  k.tie1_N = NonNegative(d, "tie1_N", 0.0);
  k.tie2_N = NonNegative(d, "tie2_N", 0.0);
  k.side_bar_h_N = NonNegative(d, "side_bar_h_N", 0.0);
  k.side_bar_v_N = NonNegative(d, "side_bar_v_N", 0.0);
  for (std::string_view faces : {"side_faces_h", "side_faces_v"}) {
    const double n = d.Number(faces).value_or(2.0);
    if (n != std::floor(n) || n < 0.0 || n > 2.0) {
      Fail(d.At(faces), d.Field(faces), "must be 0, 1 or 2 faces (got " + Show(n) + ")");
    }
    (faces == "side_faces_h" ? k.side_faces_h : k.side_faces_v) = static_cast<int>(n);
  }
  // The spacing matters only with side bars; without them any positive value gives V_s alike.
  k.side_spacing_m = k.side_bar_h_N > 0.0 || k.side_bar_v_N > 0.0
                         ? Positive(d, "side_spacing_m", "spacing s of the side bars, m")
                         : d.Number("side_spacing_m").value_or(1.0);
  CheckPositive(k.side_spacing_m, d.Field("side_spacing_m"), d.At("side_spacing_m"));
  if (d.Has("side_spacing_v_m")) {
    k.side_spacing_v_m = Positive(d, "side_spacing_v_m", "");
  }
  d.Finish(kShearKeyDetailKeys);
  return k;
}

// [abutments.shear_keys]: the backbone of each exterior key, its capacity given (v_n_N) or from
// its concrete and steel ([abutments.shear_keys.details]) [docs/compliant.md §2].
ShearKeysSpec ReadShearKeys(Section& k) {
  k.Expect(kShearKeyKeys);
  ShearKeysSpec spec;
  joint::ShearKey& key = spec.key;
  key.gap_m = k.RequiredNumber("gap_m", "transverse gap between the deck's side and the key, m");
  CheckNonNegative(key.gap_m, k.Field("gap_m"), k.At("gap_m"));
  const toml::table* details = k.Table("details");
  if (details != nullptr) {
    k.Reject("v_n_N", "give the capacity v_n_N or the key's concrete and steel [" +
                          k.Field("details") + "] (V_n = V_c + V_s), not both");
    Section d(*details, k.Field("details"), k.source());
    spec.details = ReadShearKeyDetails(d);
    key.v_n_N = joint::ShearKeyCapacity_N(
        *spec.details,
        std::string(k.source()) + ":" + std::to_string(d.TableLine()) + ": " + d.path());
  } else {
    key.v_n_N = Positive(k, "v_n_N",
                         "the key's capacity V_n, N, or its concrete and steel in a table [" +
                             k.Field("details") + "]");
  }
  key.d3_m = Positive(k, "d3_m", "deformation beyond the gap at the capacity, m");
  key.dd_m = Positive(k, "dd_m", "deformation beyond the gap at which the key has broken, m");
  if (!(key.dd_m > key.d3_m)) {
    Fail(k.At("dd_m"), k.Field("dd_m"),
         "must be > d3_m = " + Show(key.d3_m) + " m (got " + Show(key.dd_m) + ")");
  }
  key.v_res_N = NonNegative(k, "v_res_N", 0.0);
  if (key.v_res_N > key.v_n_N) {
    Fail(k.At("v_res_N"), k.Field("v_res_N"),
         "must be in [0, V_n = " + Show(key.v_n_N) + " N] (got " + Show(key.v_res_N) + ")");
  }
  if (key.v_res_N > 0.0) {
    key.d_res_m = k.RequiredNumber("d_res_m", "deformation at the end of the softening, m");
    if (!(key.d_res_m >= key.d3_m && key.d_res_m < key.dd_m)) {
      Fail(k.At("d_res_m"), k.Field("d_res_m"),
           "must be in [d3_m, dd_m) = [" + Show(key.d3_m) + ", " + Show(key.dd_m) +
               ") m with v_res_N > 0 (got " + Show(key.d_res_m) + ")");
    }
  } else {
    // No residual: the backbone falls from V_n at D3 straight to zero at DD.
    k.Reject("d_res_m",
             "belongs to a residual force v_res_N > 0 (without it the key falls "
             "from V_n at d3_m straight to zero at dd_m)");
    key.d_res_m = key.dd_m;
  }
  // Every range is checked above with its line; the backbone's own check stays the last word.
  joint::ValidateShearKey(
      key, std::string(k.source()) + ":" + std::to_string(k.TableLine()) + ": " + k.path());
  k.Finish(kShearKeyKeys);
  return spec;
}

// A wall "-x" in a per-wall table `t` when the set has the +x wall only (`walls` = 1).
void RejectMinusX(const Section& t, std::size_t walls) {
  if (walls == 1 && t.Has("-x")) {
    Fail(t.At("-x"), t.Field("-x"), "no -x wall with set = \"+x\" (allowed: \"+x\")");
  }
}

// The rigid wall `impact` (a law per abutment; none: every wall compliant) named in a per-wall
// table `t` of a key that only a compliant wall takes.
void RejectImpactWall(const Section& t, std::optional<std::size_t> impact) {
  if (!impact) return;
  const std::string_view name = WallName(*impact), other = WallName(1 - *impact);
  if (t.Has(name)) {
    Fail(t.At(name), t.Field(name),
         "the " + std::string(name) + " abutment's law is \"impact\" (rigid contacts, no " +
             "springs or keys); allowed: \"" + std::string(other) + "\"");
  }
}

// A key of [abutments] given for every wall at once or per wall, as a table { "+x" = ...,
// "-x" = ... } ([abutments.backfill."+x"]): whether `s` gives `key` per wall. A per-wall table
// holds the walls' names only (a key for both walls beside them is refused), and only the walls
// of the set (`walls`: 1 with set = "+x", 2 with "both").
bool PerWall(Section& s, std::string_view key, std::size_t walls) {
  const toml::node* node = s.Get(key);
  if (node == nullptr || !node->is_table()) return false;
  const toml::table& table = *node->as_table();
  if (!table.contains("+x") && !table.contains("-x")) return false;
  // The first key (by line) that is not a wall's name: a key of one table for both walls.
  const toml::node* shared = nullptr;
  std::string shared_key;
  for (auto&& [name, value] : table) {
    if (name.str() != "+x" && name.str() != "-x" &&
        (shared == nullptr || LineOf(value) < LineOf(*shared))) {
      shared = &value;
      shared_key = name.str();
    }
  }
  const Section t(table, s.Field(key), s.source());
  if (shared != nullptr) {
    Fail(Where{s.source(), LineOf(*shared)}, t.Field(shared_key),
         "a key for both walls beside the per-wall table [" +
             t.Field(table.contains("+x") ? "+x" : "-x") +
             "]: give one table for both walls or one per wall, not both");
  }
  RejectMinusX(t, walls);
  return true;
}

// The tables that give `key` for each wall ([abutments.backfill] or [abutments.shear_keys]).
struct WallTables {
  bool per_wall = false;  ///< one table per wall; else one table for every wall, or none
  /// Per wall its own table (per_wall), or tables[0] the one for every wall; empty: none.
  std::vector<std::optional<Section>> tables;
};

// The tables of `key`: one for every wall, or per wall (PerWall). A wall without a table of its
// own has none; with `required` it is refused as a missing key, `what` naming it. The rigid wall
// `impact` of a law per abutment takes none (its table is refused).
WallTables ReadWallTables(Section& s, std::string_view key, std::size_t walls, bool required,
                          std::string_view what, std::optional<std::size_t> impact) {
  WallTables out;
  out.tables.resize(walls);
  out.per_wall = PerWall(s, key, walls);
  const toml::table* table = s.Table(key);
  if (table == nullptr) return out;
  if (!out.per_wall) {
    out.tables.front().emplace(*table, s.Field(key), s.source());
    return out;
  }
  Section t(*table, s.Field(key), s.source());
  RejectImpactWall(t, impact);
  for (std::size_t w = 0; w < walls; ++w) {
    if (w == impact) continue;
    const std::string_view name = WallName(w);
    if (const toml::table* own = t.Table(name)) {
      out.tables[w].emplace(*own, t.Field(name), s.source());
    } else if (required) {
      t.Missing(name, "the " + std::string(name) + " wall's " + std::string(what) + ": a table [" +
                          t.Field(name) + "]");
    }
  }
  return out;
}

// One wall's number of a key given for every wall or per wall: its value (empty when the file
// gives none), where it is written and its key path.
struct WallNumber {
  std::optional<double> value;
  Where at;
  std::string field;
};

// `key`: one number for every wall, or a table { "+x" = ..., "-x" = ... } with a number for the
// walls of the set (`walls`: 1 with set = "+x", 2 with "both"), each wall's required unless
// `what` is null. Per wall its number; empty when the file gives none for it. `what(name)` says
// what the wall `name` misses in a table without it. `per_wall`, when given, is set to whether
// the file gives a table. The rigid wall `impact` of a law per abutment, when given, takes none.
template <class What>
std::vector<WallNumber> WallNumbers(Section& s, std::string_view key, std::size_t walls, What what,
                                    bool* per_wall = nullptr,
                                    std::optional<std::size_t> impact = std::nullopt) {
  const toml::node* node = s.Get(key);
  if (per_wall != nullptr) *per_wall = node != nullptr && node->is_table();
  if (node == nullptr || !node->is_table()) {
    const std::optional<double> value = s.Number(key);
    return std::vector<WallNumber>(walls, WallNumber{value, s.At(key), s.Field(key)});
  }
  Section g(*node->as_table(), s.Field(key), s.source());
  const std::string_view allowed = impact       ? (*impact == 0 ? "\"-x\"" : "\"+x\"")
                                   : walls == 2 ? "\"+x\", \"-x\""
                                                : "\"+x\" (with set = \"+x\")";
  g.Expect(allowed);
  RejectMinusX(g, walls);
  RejectImpactWall(g, impact);
  std::vector<WallNumber> out;
  for (std::size_t w = 0; w < walls; ++w) {
    const std::string_view name = WallName(w);
    if (w == impact) {
      out.push_back({std::nullopt, g.At(name), g.Field(name)});
      continue;
    }
    if constexpr (!std::is_same_v<What, std::nullptr_t>) {
      if (!g.Has(name)) g.Missing(name, what(name));
    }
    out.push_back({g.Number(name), g.At(name), g.Field(name)});
  }
  g.Finish(allowed);
  return out;
}

// `springs`: one number for every wall or a table { "+x" = ..., "-x" = ... }; 5 when absent.
std::vector<int> WallSpringCounts(Section& s, std::size_t walls,
                                  std::optional<std::size_t> impact) {
  std::vector<int> out;
  const auto what = [](std::string_view name) {
    return "springs along the " + std::string(name) + " wall, 2 to 1000";
  };
  for (const WallNumber& n : WallNumbers(s, "springs", walls, what, nullptr, impact)) {
    if (!n.value) {
      out.push_back(5);
      continue;
    }
    if (*n.value != std::floor(*n.value) || *n.value < 2.0 || *n.value > 1000.0) {
      Fail(
          n.at, n.field,
          "must be a whole number of springs per wall from 2 to 1000 (got " + Show(*n.value) + ")");
    }
    out.push_back(static_cast<int>(*n.value));
  }
  return out;
}

// `mu` and `stick_stiffness_Npm`: each wall's Coulomb friction and stick stiffness along it, one
// number for every wall or one per wall (mu for both walls; a stick stiffness for either, the
// other taking its K_max); a stick stiffness belongs to a wall with friction (one for every wall:
// to at least one wall with friction) [docs/compliant.md §4, Wall friction]. With a law per
// abutment (`impact`, the rigid wall) mu is each wall's, the rigid wall's its corners'; the stick
// stiffness is the compliant wall's only.
void ReadWallFriction(Section& s, std::vector<CompliantWall>& walls,
                      std::optional<std::size_t> impact) {
  const std::vector<WallNumber> mu = WallNumbers(s, "mu", walls.size(), [](std::string_view name) {
    return "the Coulomb friction coefficient of the " + std::string(name) + " wall, >= 0";
  });
  bool any = false;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    walls[w].friction = mu[w].value.value_or(0.0);
    CheckNonNegative(walls[w].friction, mu[w].field, mu[w].at);
    any = any || (walls[w].friction > 0.0 && w != impact);
  }
  // A wall left out of a per-wall table takes its K_max, as a file without the key.
  bool per_wall = false;
  const std::vector<WallNumber> k_t =
      WallNumbers(s, "stick_stiffness_Npm", walls.size(), nullptr, &per_wall, impact);
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (!k_t[w].value) continue;
    const double k = *k_t[w].value;
    if (!(k > 0.0 && std::isfinite(k))) {
      Fail(k_t[w].at, k_t[w].field,
           "must be a stiffness > 0 N/m (the wall's, shared by its springs; omit it for the "
           "wall's K_max) (got " +
               Show(k) + ")");
    }
    if (per_wall && !(walls[w].friction > 0.0)) {
      Fail(k_t[w].at, k_t[w].field,
           "belongs to a wall with friction (the " + std::string(WallName(w)) +
               " wall's mu is 0; give it mu > 0 or omit its stick stiffness)");
    }
    if (!any) {
      Fail(k_t[w].at, k_t[w].field,
           impact ? "belongs to a compliant wall with friction (the " +
                        std::string(WallName(1 - *impact)) + " wall's mu is 0)"
                  : std::string("belongs to a wall with friction (mu > 0)"));
    }
    walls[w].stick_stiffness_Npm = k;
  }
}

// law = "compliant": per wall its friction, its springs, its backfill and its abutment's shear
// keys. `walls`: 1 with set = "+x", 2 with "both". `impact`: with a law per abutment, the wall that
// keeps the impact law (its friction read, nothing else; eps_N and contacts are then the caller's).
CompliantAbutments ReadCompliant(Section& s, std::size_t walls,
                                 std::optional<std::size_t> impact = std::nullopt) {
  if (!impact) {
    for (std::string_view key : {"eps_N", "contacts"}) {
      s.Reject(key,
               "belongs to law = \"impact\" (the compliant springs have no restitution or "
               "contacts)");
    }
  }
  CompliantAbutments c;
  c.walls.resize(walls);
  if (impact) c.walls[*impact].law = JointLaw::kImpact;
  ReadWallFriction(s, c.walls, impact);
  const std::vector<int> springs = WallSpringCounts(s, walls, impact);
  for (std::size_t w = 0; w < walls; ++w) c.walls[w].springs = springs[w];
  if (!s.Has("backfill")) {
    s.Missing("backfill",
              impact ? "the backfill of the compliant " + std::string(WallName(1 - *impact)) +
                           " wall: a table [abutments.backfill]"
                     : std::string("the backfill of each wall with law = \"compliant\": a table "
                                   "[abutments.backfill], or one per wall "
                                   "[abutments.backfill.\"+x\"]"));
  }
  // One table fills every compliant wall alike; per-wall tables each their own wall.
  WallTables backfill = ReadWallTables(s, "backfill", walls, true, "backfill", impact);
  WallTables keys = ReadWallTables(s, "shear_keys", walls, false, "shear keys", impact);
  if (!backfill.per_wall) {
    const BackfillSpec law = ReadBackfill(*backfill.tables.front());
    for (CompliantWall& w : c.walls) {
      if (w.law == JointLaw::kCompliant) w.backfill = law;
    }
  }
  if (!keys.per_wall && keys.tables.front()) {
    const ShearKeysSpec both = ReadShearKeys(*keys.tables.front());
    for (CompliantWall& w : c.walls) {
      if (w.law == JointLaw::kCompliant) w.shear_keys = both;
    }
  }
  for (std::size_t w = 0; w < walls; ++w) {
    if (w == impact) continue;
    if (backfill.per_wall) c.walls[w].backfill = ReadBackfill(*backfill.tables[w]);
    if (keys.per_wall && keys.tables[w]) c.walls[w].shear_keys = ReadShearKeys(*keys.tables[w]);
  }
  return c;
}

// [abutments.contacts]: per corner its eps_N and mu. With a law per abutment (`impact`, the rigid
// wall) only that wall's corners have contacts (+x: P1, P2; -x: P3, P4).
void ReadContactOverrides(Section& s, AbutmentParameters& a, std::optional<std::size_t> impact) {
  const toml::table* contacts = s.Table("contacts");
  if (contacts == nullptr) return;
  Section cs(*contacts, s.Field("contacts"), s.source());
  const bool both = a.set == AbutmentSet::kBoth;
  const std::string_view allowed = impact ? (*impact == 0 ? "P1, P2" : "P3, P4")
                                   : both ? "P1, P2, P3, P4"
                                          : "P1, P2 (with set = \"+x\")";
  for (std::string_view name : {"P1", "P2", "P3", "P4"}) {
    const bool plus_x = name == "P1" || name == "P2";
    if (!both && !plus_x) {
      continue;
    }
    if (impact && plus_x != (*impact == 0)) {
      if (cs.Has(name)) {
        Fail(cs.At(name), cs.Field(name),
             std::string(name) + " is a corner of the " + (plus_x ? "+x" : "-x") +
                 " wall, whose law is \"compliant\" (springs, no rigid contact); allowed: " +
                 std::string(allowed));
      }
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
  cs.Finish(allowed);
}

// `law`: one for both abutments ("impact", the default, or "compliant"), or, with set = "both"
// (a [[deck]] file's always), one per abutment, a table { "+x" = ..., "-x" = ... } naming both.
// Per wall (+x, then -x) its law.
std::array<JointLaw, 2> ReadLaws(Section& s, AbutmentSet set) {
  const toml::node* node = s.Get("law");
  if (node == nullptr || !node->is_table()) {
    const JointLaw law = s.String("law", {"impact", "compliant"}).value_or("impact") == "compliant"
                             ? JointLaw::kCompliant
                             : JointLaw::kImpact;
    return {law, law};
  }
  if (set != AbutmentSet::kBoth) {
    Fail(s.At("law"), s.Field("law"),
         "a law per abutment needs set = \"both\"; with set = \"+x\" give one law (allowed: "
         "\"impact\", \"compliant\")");
  }
  Section t(*node->as_table(), s.Field("law"), s.source());
  t.Expect("\"+x\", \"-x\"");
  std::array<JointLaw, 2> out{};
  for (std::size_t w = 0; w < 2; ++w) {
    const std::string name(WallName(w));
    if (!t.Has(name)) {
      t.Missing(name, "the law of the " + name + " abutment: \"impact\" or \"compliant\"");
    }
    out[w] = *t.String(name, {"impact", "compliant"}) == "compliant" ? JointLaw::kCompliant
                                                                     : JointLaw::kImpact;
  }
  t.Finish("\"+x\", \"-x\"");
  return out;
}

}  // namespace

BackfillSpec ReadBackfillTable(Section& b) { return ReadBackfill(b); }

AbutmentParameters ReadAbutments(Section& s, bool multi_deck) {
  AbutmentParameters a;
  s.Expect(multi_deck ? "set, gap_m, law, eps_N, mu (with [[deck]] tables)" : kImpactKeys,
           {{"law = \"compliant\"", "springs, backfill, stick_stiffness_Npm, shear_keys"}});
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
  const std::array<JointLaw, 2> laws = ReadLaws(s, a.set);
  if (laws[0] != laws[1]) {
    // A law per abutment, one wall of each: the rigid wall keeps its corners' contacts with eps_N,
    // mu and (a single deck) their per-contact tables; the compliant wall's keys are read as
    // law = "compliant" reads them; mu is both walls' (one number, or per wall).
    const std::size_t impact = laws[0] == JointLaw::kImpact ? 0 : 1;
    const std::string_view keys = multi_deck ? kMixedDeckKeys : kMixedKeys;
    s.Expect(keys);
    a.compliant = ReadCompliant(s, 2, impact);
    a.restitution = s.Number("eps_N").value_or(0.5);
    CheckRange(a.restitution, 0.0, 1.0, false, s.Field("eps_N"), s.At("eps_N"));
    a.friction = a.compliant->walls[impact].friction;
    if (!multi_deck) ReadContactOverrides(s, a, impact);
    s.Finish(keys);
    return a;
  }
  const bool compliant = laws[0] == JointLaw::kCompliant;
  if (compliant) {
    s.Expect(kCompliantKeys, {{"law = \"impact\"", "eps_N, contacts"}});
    a.compliant = ReadCompliant(s, a.set == AbutmentSet::kBoth ? 2 : 1);
    s.Finish(kCompliantKeys);
    return a;
  }
  for (std::string_view key : {"springs", "backfill", "stick_stiffness_Npm", "shear_keys"}) {
    s.Reject(key, "belongs to law = \"compliant\" (the law here is \"impact\")");
  }
  a.restitution = s.Number("eps_N").value_or(0.5);
  CheckRange(a.restitution, 0.0, 1.0, false, s.Field("eps_N"), s.At("eps_N"));
  if (const toml::node* mu = s.Get("mu"); mu != nullptr && mu->is_table()) {
    Fail(s.At("mu"), s.Field("mu"),
         multi_deck ? "a friction per wall belongs to law = \"compliant\"; with law = \"impact\" "
                      "give one number"
                    : "a friction per wall belongs to law = \"compliant\"; with law = \"impact\" "
                      "give one number, or one per corner in [abutments.contacts.P1] (mu)");
  }
  a.friction = s.Number("mu").value_or(0.0);
  CheckNonNegative(a.friction, s.Field("mu"), s.At("mu"));
  if (multi_deck) {
    s.Finish("set, gap_m, law, eps_N, mu (with [[deck]] tables)");
    return a;
  }
  ReadContactOverrides(s, a, std::nullopt);
  s.Finish(kImpactKeys);
  return a;
}

}  // namespace skewbridge::model::detail
