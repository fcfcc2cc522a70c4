#include <array>
#include <limits>

#include "jobs/sweep_spec.h"

namespace skewbridge::jobs {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The one table of parameter names. The spectra mapping extends it here (and in
// docs/sweep-format.md); the order is the canonical axis order of every cube.
// clang-format off
constexpr std::array<ParameterInfo, 26> kParameters{{
  {"record", "record", "", "ground-motion record, by its label in the [records] set",
   ParameterKind::kLabel, 0, true, 0, true, false, ""},
  {"pulse", "pulse", "", "one cycle of a_g cos(w_g t) or a_g sin(w_g t) [docs/theory.md §5]",
   ParameterKind::kLabel, 0, true, 0, true, false, "cosine|sine"},
  {"incidence_deg", "incidence", "deg", "incidence angle: H1 (or the one component) along alpha from the bridge's x axis, H2 at alpha + 90 deg",
   ParameterKind::kNumber, -360, true, 360, true, false, ""},
  {"spans", "spans", "1", "number of deck spans", ParameterKind::kNumber, 1, true, 64, true,
   true, ""},
  {"a_g_g", "a_g", "g", "pulse amplitude a_g (cancels out of the dimensionless responses)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"w_g", "w_g", "rad/s", "pulse frequency w_g (family model-file; or T_g)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"T_g", "T_g", "s", "pulse period T_g = 2 pi / w_g (family model-file; or w_g)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"scale", "scale", "1", "factor on the excitation's accelerations (family model-file)",
   ParameterKind::kNumber, 0, false, 1e6, true, false, ""},
  {"im_g", "IM", "g", "intensity the records are scaled to: Sa, AvgSa, PGA, RotD50, RotD100, GM or AvgSa_RotD50 in g ([records] scale_to)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"im_mps", "IM_v", "m/s", "intensity the records are scaled to: PGV in m/s ([records] scale_to)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"a_deg", "a", "deg", "skew angle a", ParameterKind::kNumber, 0, true, 90, false, false, ""},
  {"eta0", "eta0", "1", "skew ratio eta0 = sin 2a / (2 W/L)", ParameterKind::kNumber, 0, false,
   kInf, false, false, ""},
  {"W_over_L", "W/L", "1", "deck width over length", ParameterKind::kNumber, 0, false, kInf,
   false, false, ""},
  {"delta_over_L", "delta/L", "1", "joint gap over deck length", ParameterKind::kNumber, 0,
   true, kInf, false, false, ""},
  {"L_over_Le", "L/L_e", "1", "deck length over the persistency a_g / w_g^2 (when delta/L is not given)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"W0_over_w0", "W0/w0", "1", "torsional over translational frequency of the substructure",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"xi", "xi", "1", "modal damping ratio", ParameterKind::kNumber, 0, true, 1, false, false,
   ""},
  {"eps_N", "eps_N", "1", "normal coefficient of restitution", ParameterKind::kNumber, 0, true,
   1, true, false, ""},
  {"mu", "mu", "1", "Coulomb friction coefficient", ParameterKind::kNumber, 0, true, kInf,
   false, false, ""},
  {"Pi_delta", "Pi_delta", "1", "gap over persistency: delta w_g^2 / a_g",
   ParameterKind::kNumber, 0, true, kInf, false, false, ""},
  {"gap_m", "delta", "m", "every gap, abutments and joints, along x (family model-file; or Pi_delta)",
   ParameterKind::kNumber, 0, true, kInf, false, false, ""},
  {"k_factor", "k_factor", "1", "factor on the substructure stiffness K (family model-file)",
   ParameterKind::kNumber, 0, false, 1e6, true, false, ""},
  {"seat_over_L", "seat/L", "1", "support seat width over span length (unseating margins)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"seat_m", "seat", "m", "support seat width, the same for every deck (unseating margins; or seat_over_L)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"w0_over_wg", "w0/w_g", "1", "substructure over excitation frequency w0 / w_g",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"method", "method", "", "integrator: event-driven, or Moreau-Jean time-stepping with h = 1e-4 of the excitation period",
   ParameterKind::kLabel, 0, true, 0, true, false, "event-driven|time-stepping"},
}};
// clang-format on

constexpr std::array<std::string_view, 4> kFamilies{"subsystem", "pilot-bridge", "model-file",
                                                    "multi-span"};

}  // namespace

std::span<const ParameterInfo> KnownParameters() { return kParameters; }

const ParameterInfo* FindParameter(std::string_view name) {
  for (const ParameterInfo& p : kParameters) {
    if (p.key == name || p.symbol == name) {
      return &p;
    }
  }
  return nullptr;
}

std::span<const std::string_view> KnownFamilies() { return kFamilies; }

}  // namespace skewbridge::jobs
