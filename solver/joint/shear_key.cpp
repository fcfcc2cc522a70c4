#include "solver/joint/shear_key.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "solver/common/error.h"

namespace skewbridge::joint {
namespace {

void Require(bool ok, std::string_view source, std::string_view field, std::string_view allowed,
             double value) {
  if (!ok) {
    throw InputError::AtField(source, field, fmt::format("must be {} (got {})", allowed, value));
  }
}

}  // namespace

void ValidateShearKey(const ShearKey& key, std::string_view source) {
  Require(std::isfinite(key.gap_m) && key.gap_m >= 0.0, source, "gap_m", ">= 0", key.gap_m);
  Require(std::isfinite(key.v_n_N) && key.v_n_N > 0.0, source, "v_n_N", "> 0", key.v_n_N);
  Require(std::isfinite(key.d3_m) && key.d3_m > 0.0, source, "d3_m", "> 0", key.d3_m);
  Require(std::isfinite(key.dd_m) && key.dd_m > key.d3_m, source, "dd_m", "> d3_m", key.dd_m);
  Require(std::isfinite(key.v_res_N) && key.v_res_N >= 0.0 && key.v_res_N <= key.v_n_N, source,
          "v_res_N", "in [0, v_n_N]", key.v_res_N);
  Require(std::isfinite(key.d_res_m) && key.d_res_m >= key.d3_m && key.d_res_m <= key.dd_m, source,
          "d_res_m", "in [d3_m, dd_m]", key.d_res_m);
  Require(key.v_res_N == 0.0 || key.d_res_m < key.dd_m, source, "d_res_m",
          "< dd_m when v_res_N > 0", key.d_res_m);
}

double ShearKeyBackbone_N(const ShearKey& key, double d_m) {
  if (d_m <= 0.0 || d_m >= key.dd_m) return 0.0;
  if (d_m <= key.d3_m) return key.v_n_N * d_m / key.d3_m;
  if (d_m <= key.d_res_m) {
    return key.v_n_N + (key.v_res_N - key.v_n_N) * (d_m - key.d3_m) / (key.d_res_m - key.d3_m);
  }
  return key.v_res_N * (key.dd_m - d_m) / (key.dd_m - key.d_res_m);
}

bool ShearKeyBroken(const ShearKey& key, const ShearKeyState& state) {
  return state.d_max_m >= key.dd_m;
}

double ShearKeyForce_N(const ShearKey& key, const ShearKeyState& state, double u_m) {
  if (ShearKeyBroken(key, state)) return 0.0;
  const double d = u_m - key.gap_m;
  if (d >= state.d_max_m) return ShearKeyBackbone_N(key, d);
  const double k0 = key.v_n_N / key.d3_m;
  return std::max(0.0, ShearKeyBackbone_N(key, state.d_max_m) - k0 * (state.d_max_m - d));
}

ShearKeyState ShearKeyCommit(const ShearKey& key, const ShearKeyState& state, double u_m) {
  return ShearKeyState{std::max(state.d_max_m, u_m - key.gap_m)};
}

double ShearKeyConcrete_N(const ShearKeyDetails& key) {
  constexpr double kMPa = 1e6;
  return 0.2 * std::sqrt(key.f_c_Pa / kMPa) * kMPa * key.stem_width_m * key.stem_height_m;
}

double ShearKeySteel_N(const ShearKeyDetails& key) {
  const double h = key.stem_height_m, d = key.key_length_m, s = key.side_spacing_m;
  const double s_v = key.side_spacing_v_m > 0.0 ? key.side_spacing_v_m : s;
  const double moment = key.tie1_N * h + key.tie2_N * d +
                        key.side_faces_h * key.side_bar_h_N * h * h / (2.0 * s) +
                        key.side_faces_v * key.side_bar_v_N * d * d / (2.0 * s_v);
  return moment / (h + key.load_height_m);
}

double ShearKeyCapacity_N(const ShearKeyDetails& key, std::string_view source) {
  Require(std::isfinite(key.f_c_Pa) && key.f_c_Pa > 0.0, source, "f_c_Pa", "> 0", key.f_c_Pa);
  Require(key.stem_width_m > 0.0, source, "stem_width_m", "> 0", key.stem_width_m);
  Require(key.stem_height_m > 0.0, source, "stem_height_m", "> 0", key.stem_height_m);
  Require(key.key_length_m > 0.0, source, "key_length_m", "> 0", key.key_length_m);
  Require(key.load_height_m >= 0.0, source, "load_height_m", ">= 0", key.load_height_m);
  Require(key.side_spacing_m > 0.0, source, "side_spacing_m", "> 0", key.side_spacing_m);
  Require(key.side_spacing_v_m >= 0.0, source, "side_spacing_v_m", ">= 0 (0: side_spacing_m)",
          key.side_spacing_v_m);
  Require(
      key.tie1_N >= 0.0 && key.tie2_N >= 0.0 && key.side_bar_h_N >= 0.0 && key.side_bar_v_N >= 0.0,
      source, "tie forces", ">= 0",
      std::min({key.tie1_N, key.tie2_N, key.side_bar_h_N, key.side_bar_v_N}));
  Require(key.side_faces_h >= 0 && key.side_faces_v >= 0, source, "side_faces", ">= 0",
          std::min(key.side_faces_h, key.side_faces_v));
  return ShearKeyConcrete_N(key) + ShearKeySteel_N(key);
}

}  // namespace skewbridge::joint
