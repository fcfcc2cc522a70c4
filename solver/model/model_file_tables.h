#pragma once
/// @file
/// The readers of a model file's tables (docs/model-format.md), private to solver/model: each
/// reads one table through a `Section` (model_file_section.h), checks every value and fails
/// with an InputError naming the key path and line. model_file.cpp reads the document with them.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "solver/model/model_file.h"
#include "solver/model/model_file_section.h"

namespace skewbridge::model::detail {

// [deck] and [substructure] (model_file_deck.cpp).

/// [deck]: mass, inertia, length, width (or eta0) and skew angle.
void ReadDeck(Section& s, DeckSpec& spec);
/// [substructure]: the substructure's stiffness and damping in one of its four forms (uncoupled,
/// principal, elements, matrix).
void ReadSubstructure(Section& s, DeckSpec& spec);

// [abutments] (model_file_abutments.cpp).

/// What an [abutments] section says, in either form of the file.
struct AbutmentParameters {
  AbutmentSet set = AbutmentSet::kBoth;
  double gap_plus_m = 0.0;
  double gap_minus_m = 0.0;
  double restitution = 0.5;
  double friction = 0.0;
  std::vector<ContactOverride> overrides;
  /// law = "compliant": the springs that replace the contacts (then restitution, friction and
  /// overrides are unused); empty for law = "impact".
  std::optional<CompliantAbutments> compliant;
};

/// The one [abutments] reader. A single deck names its set ("+x" or "both") and may override
/// contacts P1..P4; a row of [[deck]] tables always has both abutments (set may say "both") and
/// no per-contact table (its contacts are named by deck and corner). law = "compliant" reads
/// [abutments.backfill] and `springs` instead of eps_N, mu and the contacts (ReadCompliant).
AbutmentParameters ReadAbutments(Section& s, bool multi_deck);

/// A backfill table ([abutments.backfill] or a joint's [joint.backfill]) in one of its three
/// forms [docs/compliant.md §1].
BackfillSpec ReadBackfillTable(Section& b);

// [[deck]], [[joint]] and [[support]] (model_file_multi_deck.cpp).

/// The [[deck]] form: decks in a row along x, joints between consecutive decks, supports.
/// `compliant` takes the law of each abutment and of each joint when one of them is compliant
/// ([abutments] law, [[joint]] law; a joint without one takes the abutments' one law); empty when
/// every one is rigid.
MultiDeckSpec ReadMultiDeck(Section& top, std::string_view source,
                            std::optional<CompliantAbutments>& compliant);

// [excitation] and [run] (model_file_excitation.cpp).

/// [excitation]: a pulse or a sampled motion (a file or inline values), with its direction.
void ReadExcitation(Section& s, const std::filesystem::path& base_dir, ExcitationSpec& spec);
/// [run]: the integrator's run control.
void ReadRun(Section& s, RunControl& run);
/// Counts what a run asks for whose excitation's duration is known when the file is parsed
/// (a pulse, inline values, or an end time given); a file's samples are counted when read.
void CheckRunLength(const ExcitationSpec& excitation, const RunControl& run,
                    std::string_view source);

}  // namespace skewbridge::model::detail
