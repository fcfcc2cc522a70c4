#pragma once
/// @file
/// The backbone of an exterior shear key of a seat abutment [Megally, Silva and Seible 2001,
/// SSRP-2001/23; docs/compliant.md §2]: a compression-only resistance to the deck's transverse
/// motion beyond a gap that rises linearly to the capacity V_n at D3, softens linearly to a
/// residual V_res at D_res and to zero at DD, unloads and reloads elastically with the initial
/// stiffness V_n / D3, and never recovers once broken (DD reached). Pure functions of the
/// constants and an explicit state; SI inside (N, m).
///
/// Sign convention: u_m is the deck's transverse displacement towards the key (m, positive closes
/// its gap, from rest); d = u - gap is the deformation beyond the gap; the force is what the key
/// pushes back with (N, >= 0). The two keys of an abutment are two of these, facing each other.

#include <string_view>

namespace skewbridge::joint {

/// The constants of one shear key's backbone.
struct ShearKey {
  double gap_m = 0.0;    ///< transverse gap before the key is touched, >= 0
  double v_n_N = 0.0;    ///< capacity V_n, > 0
  double d3_m = 0.0;     ///< deformation beyond the gap at the capacity, > 0
  double v_res_N = 0.0;  ///< residual force reached at d_res, in [0, V_n]
  double d_res_m = 0.0;  ///< deformation at the end of the softening, in [D3, DD]
  double dd_m = 0.0;     ///< deformation at which the key has broken (zero force), > D3
};

/// The memory of one key: the largest deformation beyond the gap reached so far (m, >= 0).
struct ShearKeyState {
  double d_max_m = 0.0;  ///< largest d = u - gap reached; the key is broken once it reaches DD
};

/// Checks the constants; throws InputError naming `source` and the field outside its range
/// (gap >= 0; V_n, D3 > 0; 0 <= V_res <= V_n; D3 <= D_res <= DD; DD > D3; D_res < DD when
/// V_res > 0, all finite).
/// @throws InputError
void ValidateShearKey(const ShearKey& key, std::string_view source);

/// The backbone V(d) (N): V_n d / D3 on (0, D3]; linear from V_n to V_res on (D3, D_res];
/// linear from V_res to 0 on (D_res, DD); 0 for d <= 0 and d >= DD.
double ShearKeyBackbone_N(const ShearKey& key, double d_m);

/// Whether the key has broken: d_max >= DD. A broken key carries nothing ever again.
bool ShearKeyBroken(const ShearKey& key, const ShearKeyState& state);

/// The force at the transverse displacement u with the memory `state` (N, >= 0): the backbone for
/// d >= d_max; below it the elastic line through (d_max, V(d_max)) of slope V_n / D3, cut at 0.
double ShearKeyForce_N(const ShearKey& key, const ShearKeyState& state, double u_m);

/// The memory after a step that ended at u: d_max grows to u - gap and never shrinks.
ShearKeyState ShearKeyCommit(const ShearKey& key, const ShearKeyState& state, double u_m);

/// What a key is made of, for its capacity after Megally et al. [2001] (V_n = V_c + V_s).
struct ShearKeyDetails {
  double f_c_Pa = 0.0;          ///< concrete compressive strength f'c
  double stem_width_m = 0.0;    ///< b: width (thickness) of the abutment stem wall
  double stem_height_m = 0.0;   ///< h: height of the stem wall under the key
  double key_length_m = 0.0;    ///< d: length of the key's base along the stem (vertical ties)
  double load_height_m = 0.0;   ///< a: height of the deck's load above the top of the stem wall
  double tie1_N = 0.0;          ///< T1 = A_s1 f_y: first row of horizontal ties
  double tie2_N = 0.0;          ///< T2 = A_s2 f_y: first row of vertical ties
  double side_bar_h_N = 0.0;    ///< T_h = A_h f_y: one horizontal side bar
  double side_bar_v_N = 0.0;    ///< T_v = A_v f_y: one vertical side bar
  int side_faces_h = 2;         ///< n_h: faces carrying horizontal side bars
  int side_faces_v = 2;         ///< n_v: faces carrying vertical side bars
  double side_spacing_m = 0.0;  ///< s: spacing of the side bars (the horizontal ones), > 0
  /// s_v: spacing of the vertical side bars when it differs from s (m); 0: s
  double side_spacing_v_m = 0.0;
};

/// The concrete's share V_c = 0.2 sqrt(f'c / 1 MPa) MPa x b h (N), the SI form of Megally's
/// 2.4 sqrt(f'c [psi]) b h [lb] [Megally et al. 2001].
double ShearKeyConcrete_N(const ShearKeyDetails& key);

/// The steel's share from the moment balance of the failure wedge about its toe
/// [Megally et al. 2001, strut-and-tie model]:
///   V_s = [T1 h + T2 d + n_h T_h h^2 / (2 s) + n_v T_v d^2 / (2 s_v)] / (h + a)   (N),
/// s_v = s unless side_spacing_v_m is given.
double ShearKeySteel_N(const ShearKeyDetails& key);

/// V_n = V_c + V_s (N).
/// @throws InputError naming `source` when a dimension or strength is not positive.
double ShearKeyCapacity_N(const ShearKeyDetails& key, std::string_view source);

}  // namespace skewbridge::joint
