#include <algorithm>
#include <cmath>

#include "solver/model/model_file_tables.h"

namespace skewbridge::model::detail {
namespace {

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

// The keys of a [[joint]] under each law.
constexpr std::string_view kImpactJointKeys = "gap_m, eps_N, mu, law";
constexpr std::string_view kCompliantJointKeys = "gap_m, law, springs, backfill, spring_dashpot";

// [[joint]] law = "compliant": the springs along the joint and their law, a backfill table or a
// linear spring-dashpot table [docs/compliant.md §6].
// `taken`: the law is the abutments' (the joint gives none), which the missing table's message
// says.
CompliantJoint ReadCompliantJoint(Section& s, bool taken) {
  CompliantJoint j;
  if (const std::optional<double> n = s.Number("springs")) {
    if (*n != std::floor(*n) || *n < 2.0 || *n > 1000.0) {
      Fail(s.At("springs"), s.Field("springs"),
           "must be a whole number of springs along the joint from 2 to 1000 (got " + Show(*n) +
               ")");
    }
    j.springs = static_cast<int>(*n);
  }
  const toml::table* backfill = s.Table("backfill");
  const toml::table* dashpot = s.Table("spring_dashpot");
  if (backfill != nullptr && dashpot != nullptr) {
    Fail(s.At("spring_dashpot"), s.Field("spring_dashpot"),
         "give the joint's law once: a table backfill or a table spring_dashpot, not both");
  }
  if (backfill == nullptr && dashpot == nullptr) {
    s.Missing("backfill",
              std::string(taken ? "the joint's law, compliant as [abutments] law is: a table "
                                  "[joint.backfill] or [joint.spring_dashpot] with k_Npm and "
                                  "c_Nspm, or law = \"impact\" for a rigid joint"
                                : "the joint's law with law = \"compliant\": a table "
                                  "[joint.backfill] or [joint.spring_dashpot] with k_Npm and "
                                  "c_Nspm"));
  }
  if (backfill != nullptr) {
    Section b(*backfill, s.Field("backfill"), s.source());
    j.backfill = ReadBackfillTable(b);
    return j;
  }
  Section d(*dashpot, s.Field("spring_dashpot"), s.source());
  d.Expect("k_Npm, c_Nspm");
  j.spring_dashpot = true;
  j.k_Npm = d.RequiredNumber("k_Npm", "the joint's stiffness, N/m, shared by its springs");
  CheckPositive(j.k_Npm, d.Field("k_Npm"), d.At("k_Npm"));
  j.c_Nspm = d.Number("c_Nspm").value_or(0.0);
  CheckNonNegative(j.c_Nspm, d.Field("c_Nspm"), d.At("c_Nspm"));
  d.Finish("k_Npm, c_Nspm");
  return j;
}

// The most decks of a [[deck]] file: 600 DOFs, 402 contacts. The integrators hold dense
// matrices of (2 x DOFs)^2 entries (a dozen of 11.5 MB here); 1000 decks already take half a
// minute to set up and 3000 do not fit in memory. A bridge of more spans is several models.
constexpr std::size_t kMaxDecks = 200;

}  // namespace

MultiDeckSpec ReadMultiDeck(Section& top, std::string_view source,
                            std::optional<CompliantAbutments>& compliant) {
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
  // A joint without `law` takes the abutments' one law ("impact" when [abutments] gives none): a
  // file whose abutments are compliant has compliant joints unless a joint says "impact". With a
  // law per abutment, one of each, every joint names its own (none: the abutments' law, if any, is
  // refused in its own place).
  std::optional<std::string> default_law = "impact";
  if (const toml::node* a = top.Get("abutments"); a != nullptr && a->is_table()) {
    const toml::node* law = a->as_table()->get("law");
    const auto value = [](const toml::node* n) {
      return n != nullptr && n->is_string() ? *n->value<std::string>() : std::string("impact");
    };
    if (law != nullptr && law->is_table()) {
      const std::string plus = value(law->as_table()->get("+x"));
      const std::string minus = value(law->as_table()->get("-x"));
      default_law = plus == minus ? std::optional<std::string>(plus) : std::nullopt;
    } else {
      default_law = value(law);
    }
  }
  // Each joint's law: its compliant law, or law kImpact.
  std::vector<CompliantJoint> laws;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    Section s(*joints[i], Indexed("joint", i), source);
    const std::optional<std::string> given = s.String("law", {"impact", "compliant"});
    if (!given && !default_law) {
      s.Missing("law",
                "the abutments have a law per abutment, one of each: give each joint its law, "
                "\"impact\" or \"compliant\"");
    }
    const bool compliant = given.value_or(*default_law) == "compliant";
    s.Expect(compliant ? kCompliantJointKeys : kImpactJointKeys,
             {{compliant ? "law = \"impact\"" : "law = \"compliant\"",
               compliant ? "eps_N, mu" : "springs, backfill, spring_dashpot"}});
    JointSpec j;
    j.gap_m = s.RequiredNumber("gap_m", "joint gap along x, m");
    CheckNonNegative(j.gap_m, s.Field("gap_m"), s.At("gap_m"));
    if (compliant) {
      laws.push_back(ReadCompliantJoint(s, !given));
    } else {
      j.restitution = s.Number("eps_N").value_or(0.5);
      CheckRange(j.restitution, 0.0, 1.0, false, s.Field("eps_N"), s.At("eps_N"));
      j.friction = s.Number("mu").value_or(0.0);
      CheckNonNegative(j.friction, s.Field("mu"), s.At("mu"));
      laws.emplace_back().law = JointLaw::kImpact;
    }
    if (spec.decks[i].geometry.skew_rad != spec.decks[i + 1].geometry.skew_rad) {
      Fail(s.At("gap_m"), s.Field("gap_m"),
           "decks " + std::to_string(i) + " and " + std::to_string(i + 1) +
               " must have the same skew_deg (their end faces are parallel)");
    }
    s.Finish(compliant ? kCompliantJointKeys : kImpactJointKeys);
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
    compliant = a.compliant;
    // Rigid abutments beside a compliant joint: both walls keep their corners' contacts (eps_N
    // and mu the abutments').
    const bool compliant_joint = std::any_of(laws.begin(), laws.end(), [](const CompliantJoint& j) {
      return j.law == JointLaw::kCompliant;
    });
    if (!compliant && compliant_joint) {
      compliant.emplace();
      compliant->walls.resize(2);
      for (CompliantWall& w : compliant->walls) {
        w.law = JointLaw::kImpact;
        w.friction = a.friction;
      }
    }
    if (compliant) compliant->joints = laws;
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

}  // namespace skewbridge::model::detail
