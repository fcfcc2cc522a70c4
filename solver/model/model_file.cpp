#include "solver/model/model_file.h"

#include <toml++/toml.h>

#include <fstream>
#include <sstream>

#include "solver/common/error.h"
#include "solver/common/file_kind.h"
#include "solver/model/model_file_tables.h"

namespace skewbridge::model {

using detail::AbutmentParameters;
using detail::CheckRunLength;
using detail::Fail;
using detail::ReadAbutments;
using detail::ReadDeck;
using detail::ReadExcitation;
using detail::ReadMultiDeck;
using detail::ReadRun;
using detail::ReadSubstructure;
using detail::Section;
using detail::Where;

namespace {

// A sweep specification or a record-set manifest given where a model file belongs is named
// as what it is, not by its first table foreign to a model file.
void RejectOtherKindOfFile(const toml::table& root, std::string_view source) {
  if (root.contains("deck") || root.contains("substructure")) {
    return;
  }
  if (const toml::node* sweep = root.get("sweep"); sweep != nullptr && sweep->is_table()) {
    throw InputError::AtLine(
        source, 0,
        "this is a sweep specification ([sweep] table), not a model file (docs/model-format.md); "
        "`skewbridge sweep SPEC --out FILE.h5` takes it");
  }
  if (const toml::node* record = root.get("record"); record != nullptr && record->is_array()) {
    throw InputError::AtLine(
        source, 0,
        "this is a record-set manifest ([[record]] tables), not a model file "
        "(docs/model-format.md); `skewbridge records info` and a sweep's [records] set take it");
  }
}

// The compliant abutments against what the rest of the file says: the event-driven method (the
// only integrator of compliant springs) and a law of each wall that its deck's geometry gives
// (`walls`: the deck of each wall of c.walls, +x then -x).
void CheckCompliant(const toml::table& root, const CompliantAbutments& c,
                    const std::vector<DeckGeometry>& walls, const RunControl& run,
                    std::string_view source) {
  const toml::node* abutments = root.get("abutments");
  if (run.method != Method::kEventDriven) {
    const toml::node* method = root.at_path("run.method").node();
    Fail(Where{source, method != nullptr ? detail::LineOf(*method) : 0}, "run.method",
         c.Mixed() && !c.joints.empty()
             ? "a row with compliant joints (abutments.law, joint[i].law) runs "
               "with the event-driven method only (allowed: \"event-driven\")"
         : c.Mixed() ? "a law per abutment (abutments.law, one wall compliant) runs with the "
                       "event-driven method only (allowed: \"event-driven\")"
                     : "the compliant abutments (abutments.law = \"compliant\") run with "
                       "the event-driven method only (allowed: \"event-driven\")");
  }
  const toml::node* backfill = root.at_path("abutments.backfill").node();
  for (std::size_t w = 0; w < c.walls.size(); ++w) {
    if (c.walls[w].law == JointLaw::kImpact) continue;  // a law per abutment's rigid wall
    // The wall's own table [abutments.backfill."+x"], or the one of every wall.
    const std::string_view name = WallName(w);
    const toml::node* own =
        backfill != nullptr && backfill->is_table() ? backfill->as_table()->get(name) : nullptr;
    const toml::node* table = own != nullptr ? own : backfill;
    const long line = table != nullptr       ? detail::LineOf(*table)
                      : abutments != nullptr ? detail::LineOf(*abutments)
                                             : 0;
    const std::string field =
        own != nullptr ? "abutments.backfill.\"" + std::string(name) + "\"" : "abutments.backfill";
    (void)WallBackfill(c.walls[w].backfill, walls[w],
                       std::string(source) + ":" + std::to_string(line) + ": " + field);
  }
}

// A [[deck]] file's compliant joints: the abutments' walls on the first and the last deck, and
// each joint's backfill on the narrower deck's end (the one whose corners carry the springs).
void CheckCompliantDecks(const toml::table& root, const CompliantAbutments& c,
                         const MultiDeckSpec& decks, const RunControl& run,
                         std::string_view source) {
  // The +x wall on the last deck's end, the -x wall on deck 0's.
  CheckCompliant(root, c, {decks.decks.back().geometry, decks.decks.front().geometry}, run, source);
  const toml::array* joints =
      root.get("joint") != nullptr ? root.get("joint")->as_array() : nullptr;
  for (std::size_t i = 0; i < c.joints.size(); ++i) {
    if (c.joints[i].law == JointLaw::kImpact || c.joints[i].spring_dashpot) continue;
    const DeckGeometry& left = decks.decks[i].geometry;
    const DeckGeometry& right = decks.decks[i + 1].geometry;
    const toml::node* table = joints != nullptr ? joints->get(i) : nullptr;
    const toml::node* backfill =
        table != nullptr && table->is_table() ? table->as_table()->get("backfill") : nullptr;
    const long line = backfill != nullptr ? detail::LineOf(*backfill) : 0;
    (void)WallBackfill(c.joints[i].backfill, left.width_m <= right.width_m ? left : right,
                       std::string(source) + ":" + std::to_string(line) + ": joint[" +
                           std::to_string(i) + "].backfill");
  }
}

ModelFile Parse(const toml::table& root, std::string_view source,
                const std::filesystem::path& base_dir, const std::filesystem::path& path) {
  RejectOtherKindOfFile(root, source);
  Section top(root, "", source);
  DeckSpec deck;
  ExcitationSpec excitation;
  RunControl run;
  const bool multi_deck = root.get("deck") != nullptr && root.get("deck")->is_array();
  top.Expect(multi_deck ? "sections [[deck]], [[joint]], abutments, [[support]], excitation, run"
                        : "sections deck, substructure, abutments, excitation, run");
  const auto required = [&](std::string_view name) -> const toml::table& {
    const toml::table* t = top.Table(name);
    if (t == nullptr) {
      top.RejectUndeclared();  // a misspelt section is named as such
      Fail(Where{source, 0}, name, "missing required section [" + std::string(name) + "]");
    }
    return *t;
  };
  if (const toml::node* deck_node = root.get("deck");
      deck_node != nullptr && deck_node->is_array()) {
    std::optional<CompliantAbutments> compliant;
    MultiDeckSpec decks = ReadMultiDeck(top, source, compliant);
    {
      Section s(required("excitation"), "excitation", source);
      ReadExcitation(s, base_dir, excitation);
    }
    if (const toml::table* t = top.Table("run")) {
      Section s(*t, "run", source);
      ReadRun(s, run);
    }
    top.Finish("sections [[deck]], [[joint]], abutments, [[support]], excitation, run");
    CheckRunLength(excitation, run, source);
    Model model = BuildMultiDeckModel(decks, std::string(source));
    if (compliant) CheckCompliantDecks(root, *compliant, decks, run, source);
    return ModelFile{path, deck, std::move(model), excitation, run, std::move(decks), compliant};
  }
  {
    Section s(required("deck"), "deck", source);
    ReadDeck(s, deck);
  }
  {
    Section s(required("substructure"), "substructure", source);
    ReadSubstructure(s, deck);
  }
  std::optional<CompliantAbutments> compliant;
  {
    Section s(required("abutments"), "abutments", source);
    const AbutmentParameters a = ReadAbutments(s, false);
    compliant = a.compliant;
    deck.abutments = a.set;
    deck.gap_plus_m = a.gap_plus_m;
    deck.gap_minus_m = a.gap_minus_m;
    deck.restitution = a.restitution;
    deck.friction = a.friction;
    deck.overrides = a.overrides;
  }
  {
    Section s(required("excitation"), "excitation", source);
    ReadExcitation(s, base_dir, excitation);
  }
  if (const toml::table* t = top.Table("run")) {
    Section s(*t, "run", source);
    ReadRun(s, run);
  }
  top.Finish("sections deck, substructure, abutments, excitation, run");
  CheckRunLength(excitation, run, source);
  Model model = BuildDeckModel(deck, std::string(source));
  if (compliant) {
    CheckCompliant(root, *compliant, {deck.geometry, deck.geometry}, run, source);
  }
  return ModelFile{path, deck, std::move(model), excitation, run, std::nullopt, compliant};
}

}  // namespace

ModelFile ParseModelString(std::string_view text, std::string_view source_name,
                           const std::filesystem::path& base_dir) {
  if (HasHdf5Signature(text)) {
    throw InputError::AtLine(source_name, 0,
                             "this is an HDF5 file (a sweep cube or a run file), not a model file "
                             "(TOML, docs/model-format.md); `skewbridge inspect` summarises a "
                             "cube");
  }
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    // A record or signal file given as the model reads as bad TOML on its first line.
    const bool toml_name = std::filesystem::path(source_name).extension() == ".toml";
    throw InputError::AtLine(
        source_name, static_cast<long>(e.source().begin.line),
        std::string("syntax error: ")
            .append(e.description())
            .append(toml_name ? "" : " (a model file is TOML, docs/model-format.md)"));
  }
  return Parse(root, source_name, base_dir, {});
}

ModelFile ParseModelFile(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::ifstream in(path);
  if (!in) {
    throw InputError::AtLine(source, 0, "cannot open the model file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  ModelFile file = ParseModelString(text.str(), source, path.parent_path());
  file.path = path;
  return file;
}

std::vector<DeckAsWritten> DecksAsWritten(const std::filesystem::path& path) {
  toml::table root;
  try {
    root = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    throw InputError::AtLine(path.string(), static_cast<long>(e.source().begin.line),
                             std::string("syntax error: ").append(e.description()));
  }
  std::vector<const toml::table*> decks;
  if (const toml::array* list = root["deck"].as_array()) {
    for (const toml::node& item : *list) decks.push_back(item.as_table());
  } else {
    decks.push_back(root["deck"].as_table());
  }
  std::vector<DeckAsWritten> out;
  for (const toml::table* deck : decks) {
    DeckAsWritten d;
    if (deck != nullptr) {
      d.eta0 = (*deck)["eta0"].value<double>();
      const toml::node* inertia = deck->get("I_m");
      d.inertia_given = inertia != nullptr && inertia->is_number();
    }
    out.push_back(d);
  }
  return out;
}

}  // namespace skewbridge::model
