// The shear-key backbone against its corner points, elastic unloading and breaking; its capacity
// against Megally's formula in US units and a bar-by-bar moment balance of the failure wedge.
#include "solver/joint/shear_key.h"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/common/error.h"

namespace skewbridge::joint {
namespace {

ShearKey TestKey() {
  ShearKey key;
  key.gap_m = 0.02;
  key.v_n_N = 2.0e6;
  key.d3_m = 0.01;
  key.v_res_N = 0.5e6;
  key.d_res_m = 0.05;
  key.dd_m = 0.10;
  return key;
}

TEST(ShearKeyBackbone, PassesItsCornerPointsAndIsLinearBetween) {
  const ShearKey key = TestKey();
  ASSERT_NO_THROW(ValidateShearKey(key, "m.toml"));
  EXPECT_EQ(ShearKeyBackbone_N(key, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(ShearKeyBackbone_N(key, key.d3_m), key.v_n_N);
  EXPECT_DOUBLE_EQ(ShearKeyBackbone_N(key, key.d_res_m), key.v_res_N);
  EXPECT_EQ(ShearKeyBackbone_N(key, key.dd_m), 0.0);
  EXPECT_DOUBLE_EQ(ShearKeyBackbone_N(key, 0.5 * key.d3_m), 0.5 * key.v_n_N);
  EXPECT_DOUBLE_EQ(ShearKeyBackbone_N(key, 0.5 * (key.d3_m + key.d_res_m)),
                   0.5 * (key.v_n_N + key.v_res_N));
  EXPECT_DOUBLE_EQ(ShearKeyBackbone_N(key, 0.5 * (key.d_res_m + key.dd_m)), 0.5 * key.v_res_N);
  EXPECT_EQ(ShearKeyBackbone_N(key, 2.0 * key.dd_m), 0.0);
}

TEST(ShearKeyBackbone, UnloadsElasticallyAndKeepsThePermanentSetOnceSoftened) {
  const ShearKey key = TestKey();
  const double k0 = key.v_n_N / key.d3_m;
  ShearKeyState state;
  // Below D3 the key is elastic: it unloads along its loading line, back to zero at the gap.
  state = ShearKeyCommit(key, state, key.gap_m + 0.6 * key.d3_m);
  EXPECT_NEAR(ShearKeyForce_N(key, state, key.gap_m + 0.3 * key.d3_m), 0.3 * k0 * key.d3_m, 1e-6);
  EXPECT_NEAR(ShearKeyForce_N(key, state, key.gap_m), 0.0, 1e-6);
  // Past D3, on the softening branch at d = 0.03 (V = 1.25 MN): unloading with k0 reaches zero
  // at 0.03 - 1.25e6 / 2e8 = 23.75 mm; reloading retraces it and rejoins the backbone.
  const double d_peak = 0.03;
  state = ShearKeyCommit(key, state, key.gap_m + d_peak);
  const double v_peak = ShearKeyBackbone_N(key, d_peak);
  EXPECT_DOUBLE_EQ(v_peak, 1.25e6);
  const double set = d_peak - v_peak / k0;
  EXPECT_NEAR(set, 0.02375, 1e-12);
  EXPECT_EQ(ShearKeyForce_N(key, state, key.gap_m + 0.99 * set), 0.0);
  EXPECT_NEAR(ShearKeyForce_N(key, state, key.gap_m + 0.5 * (set + d_peak)), 0.5 * v_peak, 1e-6);
  // A smaller excursion commits nothing new; the capacity left is V(d_max) < V_n.
  EXPECT_NEAR(ShearKeyCommit(key, state, key.gap_m + 0.025).d_max_m, d_peak, 1e-15);
  EXPECT_LT(ShearKeyForce_N(key, state, key.gap_m + 0.035), v_peak);
  EXPECT_FALSE(ShearKeyBroken(key, state));
}

TEST(ShearKeyBackbone, NeverRecoversOnceBroken) {
  const ShearKey key = TestKey();
  ShearKeyState state;
  state = ShearKeyCommit(key, state, key.gap_m + 0.5 * (key.d_res_m + key.dd_m));
  EXPECT_FALSE(ShearKeyBroken(key, state));
  EXPECT_GT(ShearKeyForce_N(key, state, key.gap_m + 0.08), 0.0);  // on the residual branch
  state = ShearKeyCommit(key, state, key.gap_m + key.dd_m);
  EXPECT_TRUE(ShearKeyBroken(key, state));
  for (const double d : {-0.01, 0.0, 0.005, key.d3_m, 0.04, key.dd_m, 0.2}) {
    EXPECT_EQ(ShearKeyForce_N(key, state, key.gap_m + d), 0.0) << "d = " << d;
  }
}

TEST(ShearKeyBackbone, RefusesAnInconsistentBackbone) {
  ShearKey key = TestKey();
  key.dd_m = key.d3_m;
  EXPECT_THROW(ValidateShearKey(key, "m.toml"), InputError);
  key = TestKey();
  key.v_res_N = 3.0e6;
  EXPECT_THROW(ValidateShearKey(key, "m.toml"), InputError);
  key = TestKey();
  key.d_res_m = 0.005;
  EXPECT_THROW(ValidateShearKey(key, "m.toml"), InputError);
  key = TestKey();
  key.d_res_m = key.dd_m;  // a residual must fall to zero over some length
  EXPECT_THROW(ValidateShearKey(key, "m.toml"), InputError);
}

TEST(ShearKeyCapacity, ConcreteShareMatchesMegallysFormulaInUsUnits) {
  // V_c = 2.4 sqrt(f'c [psi]) b h [in] lb; 5000 psi, b = 4 ft, h = 6 ft.
  const double psi = 6894.757293168, inch = 0.0254, lb = 4.4482216152605;
  ShearKeyDetails key;
  key.f_c_Pa = 5000.0 * psi;
  key.stem_width_m = 48.0 * inch;
  key.stem_height_m = 72.0 * inch;
  const double vc_lb = 2.4 * std::sqrt(5000.0) * 48.0 * 72.0;
  // 0.2 sqrt(MPa) MPa is 2.4 sqrt(psi) psi rounded (0.1993): agreement to 0.4 %.
  EXPECT_NEAR(ShearKeyConcrete_N(key) / (vc_lb * lb), 1.0, 0.004);
}

TEST(ShearKeyCapacity, SteelShareIsTheMomentBalanceOfTheWedgeBarByBar) {
  ShearKeyDetails key;
  key.f_c_Pa = 30e6;
  key.stem_width_m = 1.2;
  key.stem_height_m = 1.8;
  key.key_length_m = 1.2;
  key.load_height_m = 0.3;
  key.tie1_N = 400e3;
  key.tie2_N = 300e3;
  key.side_bar_h_N = 120e3;
  key.side_bar_v_N = 90e3;
  key.side_faces_h = 2;
  key.side_faces_v = 2;
  key.side_spacing_m = 0.3;
  // Moments about the toe of the wedge: the first ties at lever arms h and d, side bars at the
  // mid-points of their spacings ((i - 1/2) s, i = 1..h/s), the load at h + a.
  double moment = key.tie1_N * key.stem_height_m + key.tie2_N * key.key_length_m;
  const int n_h = static_cast<int>(std::lround(key.stem_height_m / key.side_spacing_m));
  const int n_v = static_cast<int>(std::lround(key.key_length_m / key.side_spacing_m));
  for (int i = 1; i <= n_h; ++i) moment += 2 * key.side_bar_h_N * (i - 0.5) * key.side_spacing_m;
  for (int i = 1; i <= n_v; ++i) moment += 2 * key.side_bar_v_N * (i - 0.5) * key.side_spacing_m;
  const double vs = moment / (key.stem_height_m + key.load_height_m);
  EXPECT_NEAR(ShearKeySteel_N(key), vs, 1e-9 * vs);
  EXPECT_NEAR(ShearKeyCapacity_N(key, "m.toml"), ShearKeyConcrete_N(key) + vs, 1e-9 * vs);
  key.side_spacing_m = 0.0;
  EXPECT_THROW(ShearKeyCapacity_N(key, "m.toml"), InputError);
}

}  // namespace
}  // namespace skewbridge::joint
