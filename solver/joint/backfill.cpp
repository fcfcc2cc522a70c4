#include "solver/joint/backfill.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "solver/common/error.h"

namespace skewbridge::joint {
namespace {

// 1 kip = 4448.2216152605 N and 1 in = 0.0254 m, 1 ft = 0.3048 m (exact definitions).
constexpr double kKip_N = 4448.2216152605;
constexpr double kInch_m = 0.0254;
constexpr double kFoot_m = 0.3048;

void RequirePositive(double value, std::string_view source, std::string_view field) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InputError::AtField(source, field, fmt::format("must be > 0 (got {})", value));
  }
}

}  // namespace

void ValidateHyperbolicGap(const HyperbolicGap& law, std::string_view source) {
  RequirePositive(law.k_max_N_per_m, source, "k_max_N_per_m");
  RequirePositive(law.k_ur_N_per_m, source, "k_ur_N_per_m");
  RequirePositive(law.f_ult_N, source, "f_ult_N");
  if (!(std::isfinite(law.r_f) && law.r_f > 0.0 && law.r_f <= 1.0)) {
    throw InputError::AtField(source, "r_f", fmt::format("must be in (0, 1] (got {})", law.r_f));
  }
  if (!(std::isfinite(law.gap_m) && law.gap_m >= 0.0)) {
    throw InputError::AtField(source, "gap_m", fmt::format("must be >= 0 (got {})", law.gap_m));
  }
}

double EnvelopeForce_N(const HyperbolicGap& law, double d_m) {
  if (d_m <= 0.0) return 0.0;
  return d_m / (1.0 / law.k_max_N_per_m + law.r_f * d_m / law.f_ult_N);
}

double EnvelopeTangent_N_per_m(const HyperbolicGap& law, double d_m) {
  if (d_m <= 0.0) return 0.0;
  const double flexibility = 1.0 / law.k_max_N_per_m + law.r_f * d_m / law.f_ult_N;
  return (1.0 / law.k_max_N_per_m) / (flexibility * flexibility);
}

double PermanentSet_m(const HyperbolicGap& law, const BackfillState& state) {
  return std::max(0.0, state.d_max_m - EnvelopeForce_N(law, state.d_max_m) / law.k_ur_N_per_m);
}

BackfillBranch BackfillBranchAt(const HyperbolicGap& law, const BackfillState& state, double u_m) {
  const double d = u_m - law.gap_m;
  if (d >= state.d_max_m && d > 0.0) return BackfillBranch::kEnvelope;
  if (d > PermanentSet_m(law, state) && d < state.d_max_m) return BackfillBranch::kLine;
  return BackfillBranch::kOpen;
}

double BackfillForce_N(const HyperbolicGap& law, const BackfillState& state, double u_m) {
  const double d = u_m - law.gap_m;
  if (d >= state.d_max_m) return EnvelopeForce_N(law, d);
  // Below the peak: the straight line through (d_max, F(d_max)) of slope K_ur, cut at zero (the
  // backfill pulls on nothing). Written from the peak so that the line meets the envelope there.
  const double line = EnvelopeForce_N(law, state.d_max_m) - law.k_ur_N_per_m * (state.d_max_m - d);
  return std::max(0.0, line);
}

double BackfillTangent_N_per_m(const HyperbolicGap& law, const BackfillState& state, double u_m) {
  switch (BackfillBranchAt(law, state, u_m)) {
    case BackfillBranch::kEnvelope:
      return EnvelopeTangent_N_per_m(law, u_m - law.gap_m);
    case BackfillBranch::kLine:
      return law.k_ur_N_per_m;
    case BackfillBranch::kOpen:
      break;
  }
  return 0.0;
}

BackfillState BackfillCommit(const HyperbolicGap& law, const BackfillState& state, double u_m) {
  return BackfillState{std::max(state.d_max_m, u_m - law.gap_m)};
}

HyperbolicGap FromShamsabadi(double k50_N_per_m, double f_ult_N, double y_max_m, double gap_m,
                             std::string_view source) {
  RequirePositive(k50_N_per_m, source, "k50_N_per_m");
  RequirePositive(f_ult_N, source, "f_ult_N");
  RequirePositive(y_max_m, source, "y_max_m");
  // F = y / (a + b y) through (F_ult / (2 K50), F_ult / 2) and (y_max, F_ult):
  //   a = y_max / (2 K50 y_max - F_ult), b = 2 (K50 y_max - F_ult) / (F_ult (2 K50 y_max - F_ult)).
  const double twice = 2.0 * k50_N_per_m * y_max_m;
  if (!(k50_N_per_m * y_max_m > f_ult_N)) {
    throw InputError::AtField(
        source, "k50_N_per_m",
        fmt::format("K50 y_max must exceed F_ult for a softening hyperbola (K50 y_max = {} N, "
                    "F_ult = {} N)",
                    k50_N_per_m * y_max_m, f_ult_N));
  }
  HyperbolicGap law;
  law.k_max_N_per_m = (twice - f_ult_N) / y_max_m;
  law.r_f = 1.0 - f_ult_N / (twice - f_ult_N);
  law.f_ult_N = f_ult_N;
  law.k_ur_N_per_m = law.k_max_N_per_m;
  law.gap_m = gap_m;
  ValidateHyperbolicGap(law, source);
  return law;
}

HyperbolicGap FromInitialStiffness(double k_max_N_per_m, double f_ult_N, double y_max_m,
                                   double gap_m, std::string_view source) {
  RequirePositive(k_max_N_per_m, source, "k_max_N_per_m");
  RequirePositive(f_ult_N, source, "f_ult_N");
  RequirePositive(y_max_m, source, "y_max_m");
  if (!(k_max_N_per_m * y_max_m > f_ult_N)) {
    throw InputError::AtField(
        source, "k_max_N_per_m",
        fmt::format("K_max y_max must exceed F_ult for a softening hyperbola (K_max y_max = {} N, "
                    "F_ult = {} N)",
                    k_max_N_per_m * y_max_m, f_ult_N));
  }
  HyperbolicGap law;
  law.k_max_N_per_m = k_max_N_per_m;
  // F(y_max) = F_ult: y_max / (1 / K_max + R_f y_max / F_ult) = F_ult.
  law.r_f = 1.0 - f_ult_N / (k_max_N_per_m * y_max_m);
  law.f_ult_N = f_ult_N;
  law.k_ur_N_per_m = k_max_N_per_m;
  law.gap_m = gap_m;
  ValidateHyperbolicGap(law, source);
  return law;
}

double ShamsabadiYMax_m(double backwall_height_m) { return 0.05 * backwall_height_m; }

double CaltransSkewFactor(double skew_rad) {
  return std::exp(-std::abs(skew_rad) / (std::numbers::pi / 4.0));
}

CaltransAbutment CaltransSdc2(double backwall_width_m, double backwall_height_m, double r_sk) {
  SB_DEMAND(backwall_width_m > 0.0 && backwall_height_m > 0.0, "backwall w and h must be > 0");
  SB_DEMAND(r_sk > 0.0 && r_sk <= 1.0, "the skew reduction must be in (0, 1]");
  const double w_ft = backwall_width_m / kFoot_m;
  const double h_ft = backwall_height_m / kFoot_m;
  CaltransAbutment out;
  out.k_initial_N_per_m = w_ft * (5.5 * h_ft + 20.0) * r_sk * kKip_N / kInch_m;
  out.p_bw_N = w_ft * 5.5 * std::pow(h_ft, 2.5) / (1.0 + 2.37 * h_ft) * r_sk * kKip_N;
  return out;
}

}  // namespace skewbridge::joint
