#include <cmath>

#include "solver/model/model_file_tables.h"

namespace skewbridge::model::detail {
namespace {

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

}  // namespace

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

}  // namespace skewbridge::model::detail
