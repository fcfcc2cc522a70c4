#pragma once
/// @file
/// The joint law of a model file's abutments ([abutments] law, docs/model-format.md): the rigid
/// impact law lives in the Model's contacts; the compliant law is described here, beside the
/// Model, as the file gives it: per wall the backfill behind its backwall in one of three forms,
/// the number of springs along it and the abutment's exterior shear keys, and the walls' friction
/// [docs/compliant.md §1, §2, §4]. solver/dynamics turns it into springs (abutment_springs.h).
/// SI: N, m.

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "solver/joint/backfill.h"
#include "solver/joint/shear_key.h"
#include "solver/model/deck.h"

namespace skewbridge::model {

/// The law of the deck-abutment joints of a model file.
enum class JointLaw {
  kImpact,     ///< rigid unilateral contacts with restitution and friction (the Model's contacts)
  kCompliant,  ///< springs with the hyperbolic backfill law normal to the backwall
};

/// How [abutments.backfill] gives the backfill law of one wall.
enum class BackfillForm {
  kHyperbolicGap,  ///< OpenSees HyperbolicGap constants, per wall or per metre of wall
  kShamsabadi,     ///< K50, F_ult and y_max (or the wall's height H, y_max = 0.05 H)
  kCaltrans,       ///< Caltrans SDC 2.0 from the backwall's width and height
};

/// The backfill of one compliant wall (or deck-deck joint) of a model file, as written.
struct BackfillSpec {
  BackfillForm form = BackfillForm::kHyperbolicGap;
  /// kHyperbolicGap: the constants are per metre of wall (N/m/m, N/m), multiplied by the wall's
  /// length corner to corner, W / cos a; else per wall (N/m, N).
  bool per_metre = false;
  double k_max = 0.0;          ///< kHyperbolicGap: K_max (N/m, or N/m per m)
  double k_ur = 0.0;           ///< kHyperbolicGap: K_ur (N/m, or N/m per m)
  double r_f = 0.0;            ///< kHyperbolicGap: failure ratio R_f, in (0, 1]
  double f_ult = 0.0;          ///< kHyperbolicGap, kShamsabadi: F_ult (N, or N per m)
  double k50_Npm = 0.0;        ///< kShamsabadi: secant stiffness at F_ult / 2 (N/m)
  double y_max_m = 0.0;        ///< kShamsabadi, kCaltrans: deformation at capacity (m)
  double width_m = 0.0;        ///< kCaltrans: backwall width w (m)
  double height_m = 0.0;       ///< kCaltrans: backwall height h (m)
  bool skew_reduction = true;  ///< kCaltrans: R_sk = exp(-a / 45 deg), else R_sk = 1
};

/// The exterior shear keys of one abutment ([abutments.shear_keys] for every abutment, or
/// [abutments.shear_keys."+x"] for one): two, one beside each side of the deck, each with this
/// backbone [docs/compliant.md §2].
struct ShearKeysSpec {
  /// Each key's backbone; gap_m is the transverse gap between the deck's side and the key.
  joint::ShearKey key;
  /// The key's concrete and steel when V_n is theirs (key.v_n_N = V_c + V_s, Megally et al.
  /// 2001); empty when the file gives V_n.
  std::optional<joint::ShearKeyDetails> details;
};

/// One deck-deck joint of a [[deck]] model file with compliant parts ([[joint]] law =
/// "compliant"): `springs` springs from corner to corner of the narrower deck's end, on the
/// relative displacement of the two decks' facing edges normal to the skewed joint, each with an
/// n-th of the joint's law: the hyperbolic backfill-type law or a linear spring-dashpot
/// [docs/compliant.md §6]. Or, in a row with rigid and compliant parts, a rigid joint (law
/// kImpact): its corners keep the Model's contacts with their eps_N and mu, and the rest is unused.
struct CompliantJoint {
  JointLaw law = JointLaw::kCompliant;  ///< kImpact: the joint keeps its rigid contacts
  bool spring_dashpot = false;          ///< true: k_Npm and c_Nspm; false: `backfill`
  BackfillSpec backfill;  ///< the joint's hyperbolic law, as a wall's (per metre: of the joint)
  double k_Npm = 0.0;     ///< spring-dashpot: the joint's stiffness (N/m), > 0
  double c_Nspm = 0.0;    ///< spring-dashpot: the joint's dashpot (N s/m), >= 0
  int springs = 5;        ///< springs along the joint, >= 2
};

/// The compliant law of one abutment ([abutments] law = "compliant"): the backfill behind its
/// backwall, the springs along the wall and its exterior shear keys. The file gives it for both
/// walls at once ([abutments.backfill], [abutments.shear_keys], `springs` a number) or per wall
/// ([abutments.backfill."+x"], a `springs` table, ...); either way each wall holds its own.
struct CompliantWall {
  /// The wall's law: kCompliant, or kImpact for the rigid wall of a per-abutment law ([abutments]
  /// law = { "+x" = "impact", "-x" = "compliant" }): its corners keep the Model's rigid contacts
  /// and it has no springs or keys (backfill, springs, shear_keys and stick_stiffness_Npm unused;
  /// `friction` is its corners' mu).
  JointLaw law = JointLaw::kCompliant;
  BackfillSpec backfill;                    ///< the wall's backfill law
  int springs = 5;                          ///< springs along the wall from corner to corner, >= 2
  std::optional<ShearKeysSpec> shear_keys;  ///< the abutment's two exterior keys; none when empty
  /// Coulomb friction coefficient on the wall, >= 0, on its springs' normal forces; 0: none.
  double friction = 0.0;
  /// The wall's stick stiffness along it (N/m), shared by its springs; 0: the wall's K_max.
  double stick_stiffness_Npm = 0.0;
};

/// The compliant joints of a model file ([abutments] law = "compliant", a law per abutment with
/// one wall compliant, or a [[deck]] row with some joint or abutment compliant): per wall its law
/// (`springs` springs from corner to corner, each with an n-th of the wall's backfill, optionally
/// the abutment's two exterior shear keys, the wall's friction and stick stiffness) and, for a
/// [[deck]] file, each deck-deck joint's law.
struct CompliantAbutments {
  /// The law of each wall: [0] the +x wall, [1] the -x wall (with set = "both"; absent with
  /// set = "+x"). One [abutments.backfill] or [abutments.shear_keys] table, or one `mu` or
  /// `stick_stiffness_Npm` number, fills every wall.
  std::vector<CompliantWall> walls;
  /// A [[deck]] file: joint i between decks i and i + 1, each with its law; empty for a single
  /// deck.
  std::vector<CompliantJoint> joints;

  /// Gives every wall the friction coefficient `mu` (>= 0), as `mu = ...` for both walls in the
  /// file would (a sweep's mu); each wall keeps its stick stiffness.
  void SetWallFriction(double mu) {
    for (CompliantWall& w : walls) w.friction = mu;
  }

  /// Whether one wall or deck-deck joint keeps the impact law (a law per abutment, or a row with
  /// rigid and compliant joints): the run is SimulateMixed's.
  bool Mixed() const {
    for (const CompliantWall& w : walls) {
      if (w.law == JointLaw::kImpact) return true;
    }
    for (const CompliantJoint& j : joints) {
      if (j.law == JointLaw::kImpact) return true;
    }
    return false;
  }

  /// Whether any abutment has shear keys.
  bool HasShearKeys() const {
    for (const CompliantWall& w : walls) {
      if (w.shear_keys) return true;
    }
    return false;
  }
};

/// The name of wall `index` of CompliantAbutments::walls: "+x" (0) or "-x" (1).
constexpr std::string_view WallName(std::size_t index) { return index == 0 ? "+x" : "-x"; }

/// The length of a wall of `deck` from corner to corner along its skewed end line, W / cos a (m).
double WallLength_m(const DeckGeometry& deck);

/// The backfill law of one wall of `deck` (its length and skew angle) from `spec`, gap 0 (the
/// joint's gap is the Model's, on the contacts' faces).
/// @throws InputError naming `source` when the constants give no softening hyperbola.
joint::HyperbolicGap WallBackfill(const BackfillSpec& spec, const DeckGeometry& deck,
                                  std::string_view source);

}  // namespace skewbridge::model
