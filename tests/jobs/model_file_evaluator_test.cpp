// The model-file sweep family: every new key valid and invalid (a one-line InputError naming
// the file and the key), record = "*" and the implied record axis, and the cell's model against
// its definition (the deck re-derived from eta0, the stiffness factor, gaps of Pi_delta L_e).
// tests/jobs/model_file_sweep_test.sh runs such sweeps against `skewbridge run`.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>

#include "jobs/sweep_spec.h"
#include "records/measures.h"
#include "records/synthetic.h"
#include "solver/common/error.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/deck.h"
#include "solver/model/multispan.h"
#include "spectra/model_file_evaluator.h"

namespace skewbridge::jobs::model_file_evaluator_test {
namespace {

using spectra::CellOutcome;
using spectra::kStatusOk;
using spectra::ModelFileCell;
using spectra::ModelFileEvaluator;
using spectra::SweepRecord;

using ::testing::HasSubstr;

constexpr double kG = 9.80665;

// The text of the one-deck model of the model-file sweep tests.
std::string DeckText() {
  const std::filesystem::path path =
      std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / "models" / "one-deck-pulse.toml";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A folder holding the model file, a folder set of two plain records and its manifest.
std::filesystem::path Folder() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = std::filesystem::path(::testing::TempDir()) / "model-file";
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d / "recs");
    std::ofstream(d / "deck.toml") << DeckText();
    std::string with_c = DeckText();
    with_c.replace(with_c.find("xi = 0.05"), 9, "C = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]");
    std::ofstream(d / "deck-c.toml") << with_c;
    std::string sampled = DeckText();
    sampled.replace(sampled.find("kind = \"pulse\""),
                    sampled.size() - sampled.find("kind = \"pulse\""),
                    "kind = \"sampled\"\nfile = \"recs/b.txt\"\ndt_s = 0.01\n");
    std::ofstream(d / "deck-file.toml") << sampled;
    for (const char* name : {"b.txt", "a.txt"}) {
      std::ofstream out(d / "recs" / name);
      for (int k = 0; k < 200; ++k) out << std::sin(0.1 * k) * (name[0] == 'a' ? 2.0 : 3.0) << "\n";
    }
    std::ofstream(d / "set.toml") << "folder = \"recs\"\npattern = \"*.txt\"\nunits = \"m/s^2\"\n"
                                     "dt = 0.01\n";
    return d;
  }();
  return dir;
}

SweepSpec Spec(const std::string& body, const std::string& model = "deck.toml",
               const std::string& family = "model-file") {
  const std::string head = "[sweep]\nname = \"m\"\nfamily = \"" + family + "\"\n" +
                           (family == "model-file" ? "model = \"" + model + "\"\n" : "");
  return ParseSweepSpec(head + body, "spec.toml", Folder());
}

// The message of the spec parser's InputError for this body (the evaluator not built), or
// "no error".
std::string SpecErrorOf(const std::string& body) {
  try {
    Spec(body);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
    return what;
  }
  return "no error";
}

std::string ErrorOf(const std::string& body, const std::string& model = "deck.toml",
                    const std::string& family = "model-file") {
  try {
    ModelFileEvaluator evaluator(Spec(body, model, family));
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
    return what;
  }
  return "no error";
}

TEST(ModelFileSpec, NewKeysTakeTheirRanges) {
  const SweepSpec spec = Spec(
      "[axes]\nw_g = [5.0, 10.0]\nscale = [0.5, 2]\ngap_m = [0, 0.01]\nk_factor = [0.5, 1, 4]\n");
  EXPECT_EQ(spec.CellCount(), 24u);
  EXPECT_NO_THROW(Spec("[axes]\nT_g = [0.3, 0.6]\n"));
  EXPECT_THAT(SpecErrorOf("[axes]\nw_g = [0.0]\n"),
              HasSubstr("spec.toml:6: axes.w_g: must be a number > 0"));
  EXPECT_THAT(SpecErrorOf("[axes]\nT_g = [-1]\n"),
              HasSubstr("spec.toml:6: axes.T_g: must be a number > 0"));
  EXPECT_THAT(SpecErrorOf("[axes]\nscale = [0]\n"),
              HasSubstr("spec.toml:6: axes.scale: must be a number > 0"));
  EXPECT_THAT(SpecErrorOf("[axes]\nscale = [2e6]\n"),
              HasSubstr("axes.scale: must be a number > 0 and <= 1000000 (got 2000000)"));
  EXPECT_THAT(SpecErrorOf("[axes]\ngap_m = [-0.01]\n"),
              HasSubstr("spec.toml:6: axes.gap_m: must be a number >= 0"));
  EXPECT_THAT(SpecErrorOf("[axes]\nk_factor = [0]\n"),
              HasSubstr("spec.toml:6: axes.k_factor: must be a number > 0"));
  EXPECT_THAT(SpecErrorOf("[axes]\nk_factor = [\"x\"]\n"),
              HasSubstr("axes.k_factor: must be a number"));
  EXPECT_THAT(SpecErrorOf("[axes]\nw_g = [5.0]\n[fixed]\nT_g = 0.5\n"),
              HasSubstr("spec.toml: T_g: give w_g or T_g, not both"));
  EXPECT_THAT(SpecErrorOf("[axes]\ngap_m = [0.01]\n[fixed]\nPi_delta = 1\n"),
              HasSubstr("spec.toml: gap_m: give gap_m or Pi_delta, not both"));
  // The model-file keys mean nothing to the other families.
  for (const char* key : {"w_g", "T_g", "scale", "gap_m", "k_factor"}) {
    try {
      Spec(std::string("[axes]\n") + key + " = [1.0]\n", "", "subsystem");
      ADD_FAILURE() << key;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(std::string("spec.toml: ") + key +
                                      ": only a parameter of family \"model-file\""));
    }
  }
}

// The model file's bytes are part of the identity: --resume refuses a changed model.
TEST(ModelFileSpec, HashFollowsTheModelFileContent) {
  std::ofstream(Folder() / "copy.toml") << DeckText();
  const std::string before = Spec("[axes]\nmu = [0.1]\n", "copy.toml").Hash();
  EXPECT_EQ(Spec("[axes]\nmu = [0.1]\n", "copy.toml").Hash(), before);
  std::ofstream(Folder() / "copy.toml") << DeckText() << "# edited\n";
  EXPECT_NE(Spec("[axes]\nmu = [0.1]\n", "copy.toml").Hash(), before);
}

TEST(ModelFileSpec, RecordStarTakesEveryRecordOfTheSetInSetOrder) {
  const SweepSpec star = Spec("[records]\nset = \"set.toml\"\n[axes]\nrecord = \"*\"\n");
  ASSERT_NE(star.FindAxis("record"), nullptr);
  EXPECT_EQ(star.FindAxis("record")->labels, (std::vector<std::string>{"a.txt", "b.txt"}));
  // Omitted, the record key means the same; and the spec is the one that lists the labels.
  const SweepSpec omitted = Spec("[records]\nset = \"set.toml\"\n[axes]\nscale = [1.0]\n");
  ASSERT_NE(omitted.FindAxis("record"), nullptr);
  EXPECT_EQ(omitted.FindAxis("record")->labels, star.FindAxis("record")->labels);
  const SweepSpec listed =
      Spec("[records]\nset = \"set.toml\"\n[axes]\nrecord = [\"a.txt\", \"b.txt\"]\n");
  EXPECT_EQ(star.Hash(), listed.Hash());
  // A synthetic suite: its labels, as records synth names them.
  const SweepSpec synth =
      Spec("[records]\nsynthetic = {count = 3, seed = 5}\n[axes]\nrecord = \"*\"\n");
  records::SynthOptions options;
  options.count = 3;
  options.seed = 5;
  EXPECT_EQ(synth.FindAxis("record")->labels,
            (std::vector<std::string>{records::SyntheticLabel(options, 0),
                                      records::SyntheticLabel(options, 1),
                                      records::SyntheticLabel(options, 2)}));
  EXPECT_EQ(synth.FindAxis("record")->labels[2], "synth-5-002");
  // A pulse key keeps [records] from implying a record axis (and pulse with record is refused).
  EXPECT_EQ(Spec("[records]\nset = \"set.toml\"\n[axes]\npulse = [\"sine\"]\n").FindAxis("record"),
            nullptr);
}

TEST(ModelFileSpec, RecordStarErrorsNameTheKey) {
  EXPECT_THAT(SpecErrorOf("[axes]\nrecord = \"*\"\n"),
              HasSubstr("spec.toml:6: axes.record: \"*\" (every record) needs [records] set"));
  EXPECT_THAT(SpecErrorOf("[records]\nset = \"set.toml\"\n[axes]\nrecord = \"a.txt\"\n"),
              HasSubstr("spec.toml:8: axes.record: must be a list of record labels or \"*\""));
  EXPECT_THAT(SpecErrorOf("[records]\nset = \"set.toml\"\n[axes]\nrecord = [\"*\", \"a.txt\"]\n"),
              HasSubstr("spec.toml:8: axes.record: \"*\" stands alone"));
  EXPECT_THAT(
      SpecErrorOf(
          "[records]\nset = \"set.toml\"\n[axes]\nscale = [1.0]\n[fixed]\nrecord = \"*\"\n"),
      HasSubstr("spec.toml:10: fixed.record: a fixed record is one label"));
  // A folder set whose pattern matches nothing: the manifest's line and key.
  std::ofstream(Folder() / "none.toml") << "folder = \"recs\"\npattern = \"*.AT2\"\n";
  EXPECT_THAT(SpecErrorOf("[records]\nset = \"none.toml\"\n[axes]\nrecord = \"*\"\n"),
              HasSubstr("none.toml:2: pattern: no file of"));
}

// [records] folder and pattern: the set of a folder without a manifest, the same records as a
// manifest of that folder (and the same cube identity whichever spelling of the axis).
TEST(RecordsFolder, TakesTheFilesOfTheFolderLikeAManifest) {
  const SweepSpec folder = Spec(
      "[records]\nfolder = \"recs\"\npattern = \"*.txt\"\nunits = \"m/s^2\"\ndt = 0.01\n"
      "[axes]\nscale = [1.0]\n");
  ASSERT_NE(folder.FindAxis("record"), nullptr);
  EXPECT_EQ(folder.FindAxis("record")->labels, (std::vector<std::string>{"a.txt", "b.txt"}));
  const ModelFileEvaluator by_folder(folder);
  const ModelFileEvaluator by_manifest(
      Spec("[records]\nset = \"set.toml\"\n[axes]\nscale = [1.0]\n"));
  ASSERT_NE(by_folder.Records(), nullptr);
  ASSERT_EQ(by_folder.Records()->size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const SweepRecord& a = (*by_folder.Records())[i];
    const SweepRecord& b = (*by_manifest.Records())[i];
    EXPECT_EQ(a.label, b.label);
    EXPECT_EQ(a.file, b.file);
    EXPECT_EQ(a.file, "recs/" + a.label);
    EXPECT_EQ(a.motion.acc_mps2, b.motion.acc_mps2);
    EXPECT_EQ(a.measures.persistency_m, b.measures.persistency_m);
  }
  EXPECT_NE(folder.Hash(), Spec("[records]\nfolder = \"recs\"\npattern = \"a*\"\nunits = "
                                "\"m/s^2\"\ndt = 0.01\n[axes]\nscale = [1.0]\n")
                               .Hash());
}

TEST(RecordsFolder, ErrorsNameTheSpecLineAndKey) {
  const std::string axes = "[axes]\nscale = [1.0]\n";
  EXPECT_THAT(SpecErrorOf("[records]\nfolder = \"nope\"\npattern = \"*\"\n" + axes),
              HasSubstr("spec.toml:6: records.folder: not a folder"));
  EXPECT_THAT(SpecErrorOf("[records]\nfolder = \"recs\"\npattern = \"*.AT2\"\n" + axes),
              HasSubstr("spec.toml:7: records.pattern: no file of"));
  EXPECT_THAT(SpecErrorOf("[records]\nfolder = \"recs\"\npattern = \"[a\"\n" + axes),
              HasSubstr("spec.toml:7: records.pattern: '[a' has an unclosed '['"));
  EXPECT_THAT(SpecErrorOf("[records]\nfolder = \"recs\"\n" + axes),
              HasSubstr("spec.toml:6: records.pattern: is required with folder"));
  EXPECT_THAT(SpecErrorOf("[records]\npattern = \"*\"\n" + axes),
              HasSubstr("spec.toml: records.folder: missing"));
  EXPECT_THAT(SpecErrorOf("[records]\nfolder = \"recs\"\npattern = \"*\"\nunits = \"ft\"\n" + axes),
              HasSubstr("spec.toml:8: records.units: must be one of g, m/s^2, cm/s^2"));
  EXPECT_THAT(SpecErrorOf("[records]\nfolder = \"recs\"\npattern = \"*\"\ndt = 0\n" + axes),
              HasSubstr("spec.toml:8: records.dt: must be a number > 0"));
  EXPECT_THAT(
      SpecErrorOf("[records]\nset = \"set.toml\"\nfolder = \"recs\"\npattern = \"*\"\n" + axes),
      HasSubstr("spec.toml: records: give set"));
  EXPECT_THAT(SpecErrorOf("[records]\nset = \"set.toml\"\nunits = \"g\"\n" + axes),
              HasSubstr("spec.toml:7: records.units: unknown key"));
}

TEST(ModelFileEvaluator, RefusesKeysAndCombinationsNamingFileAndKey) {
  for (const char* key : {"w0_over_wg", "W0_over_w0", "L_over_Le", "W_over_L", "delta_over_L"}) {
    EXPECT_THAT(
        ErrorOf(std::string("[axes]\n") + key + " = [1.0]\n"),
        HasSubstr(std::string("spec.toml: ") + key + ": not a parameter of family 'model-file'"));
  }
  EXPECT_THAT(ErrorOf("[axes]\nspans = [1]\n"),
              HasSubstr("spec.toml: spans: not a parameter of family 'model-file'"));
  EXPECT_THAT(
      ErrorOf("[records]\nset = \"set.toml\"\n[axes]\nrecord = \"*\"\n[fixed]\na_g_g = 0.3\n"),
      HasSubstr("spec.toml: a_g_g: not a parameter of a record-driven sweep"));
  EXPECT_THAT(ErrorOf("[records]\nset = \"set.toml\"\n[axes]\nrecord = \"*\"\n[fixed]\nw_g = 3\n"),
              HasSubstr("spec.toml: w_g: not a parameter of a record-driven sweep"));
  EXPECT_THAT(ErrorOf("[axes]\nxi = [0.02]\n", "deck-c.toml"),
              HasSubstr("spec.toml: xi: the model file gives substructure.C"));
  EXPECT_THAT(ErrorOf("[axes]\na_deg = [0, 30]\n"),
              HasSubstr("spec.toml: a_deg: needs a skew angle > 0"));
  EXPECT_THAT(ErrorOf("[axes]\na_g_g = [0.1]\n", "deck-file.toml"),
              HasSubstr("spec.toml: w_g: missing: the model file's excitation is sampled"));
  // The same sweep with a record is accepted once the file's excitation is replaced.
  EXPECT_EQ(ErrorOf("[records]\nset = \"set.toml\"\n[axes]\nrecord = \"*\"\n", "deck-file.toml"),
            "no error");
}

// The value of the response `name` in `out` (the evaluator's Responses() give the order).
double ValueOf(const ModelFileEvaluator& evaluator, const CellOutcome& out,
               const std::string& name) {
  const std::vector<spectra::ResponseInfo> names = evaluator.Responses();
  EXPECT_EQ(names.size(), out.responses.size());
  for (std::size_t k = 0; k < names.size() && k < out.responses.size(); ++k) {
    if (names[k].name == name) return out.responses[k];
  }
  ADD_FAILURE() << "no response " << name;
  return 0.0;
}

// Inline samples without a mean period (all zero) have no L_e: Pi_delta is refused, naming it;
// other keys run with NaN scales.
TEST(ModelFileEvaluator, SamplesWithoutMeanPeriodRefuseOnlyPiDelta) {
  std::string still = DeckText();
  still.replace(still.find("kind = \"pulse\""), still.size() - still.find("kind = \"pulse\""),
                "kind = \"sampled\"\nvalues = [0.0, 0.0, 0.0, 0.0]\ndt_s = 0.01\n");
  std::ofstream(Folder() / "still.toml") << still;
  EXPECT_THAT(ErrorOf("[axes]\nPi_delta = [1.0]\n", "still.toml"),
              HasSubstr("spec.toml: Pi_delta: needs L_e of the model file's samples"));
  const ModelFileEvaluator evaluator(Spec("[axes]\nmu = [0.1]\n", "still.toml"));
  const std::vector<std::size_t> cell{0};
  const CellOutcome out = evaluator.Evaluate(cell);
  EXPECT_EQ(out.status, kStatusOk);
  EXPECT_EQ(ValueOf(evaluator, out, "x_m_d0"), 0.0);              // the ground does not move
  EXPECT_TRUE(std::isnan(ValueOf(evaluator, out, "x_norm_d0")));  // x_m / L_e, L_e undefined
}

// Every response of a cell of the three-span bridge, named, against a run of the cell's model
// by the integrator itself and the definitions of docs/sweep-format.md: each deck's maxima,
// residuals, normalised values (rho = sqrt(I / m)), margins and travels, the bridge's largest
// theta_norm, the counts and the scales. A value read from the wrong place fails here.
TEST(ModelFileEvaluator, EveryResponseByNameIsWhatTheCellsOwnRunGives) {
  const std::string model = (std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / ".." / ".." /
                             "docs" / "examples" / "three-span.toml")
                                .string();
  const ModelFileEvaluator evaluator(
      Spec("[axes]\nPi_delta = [0.5, 3.0]\n[fixed]\nseat_over_L = 0.01\n"
           "[limit_states]\nrotation = {above_rad = 0.01}\n",
           model));
  const std::vector<spectra::ResponseInfo> names = evaluator.Responses();
  ASSERT_EQ(names.size(), 3u * 15u + 7u);
  for (std::size_t cell = 0; cell < 2; ++cell) {
    const std::vector<std::size_t> index{cell};
    const CellOutcome out = evaluator.Evaluate(index);
    ASSERT_EQ(out.status, kStatusOk) << out.status_text;
    ASSERT_EQ(out.responses.size(), names.size());
    const ModelFileCell c = evaluator.MakeCell(index, true);
    dynamics::SimulationWorkspace workspace(*c.model);
    const dynamics::RunResult run =
        dynamics::Simulate(*c.model, *c.excitation, c.control, workspace);
    ASSERT_EQ(run.status, dynamics::RunStatus::kOk);
    const double L_e = c.persistency_m;
    double theta_norm_max = 0.0;
    for (int d = 0; d < 3; ++d) {
      SCOPED_TRACE("cell " + std::to_string(cell) + ", deck " + std::to_string(d));
      const model::Body& deck = c.model->body(d);
      const Eigen::Vector3d q_max = run.max_abs_q.segment<3>(3 * d);
      const Eigen::Vector3d q_end = run.q_end.segment<3>(3 * d);
      const double rho = std::sqrt(deck.inertia_kgm2 / deck.mass_kg);
      const std::string s = "_d" + std::to_string(d);
      const auto at = [&](const std::string& stem) { return ValueOf(evaluator, out, stem + s); };
      EXPECT_EQ(at("x_m"), q_max(0));
      EXPECT_EQ(at("y_m"), q_max(1));
      EXPECT_EQ(at("theta_m"), q_max(2));
      EXPECT_EQ(at("x_end"), q_end(0));
      EXPECT_EQ(at("y_end"), q_end(1));
      EXPECT_EQ(at("theta_end"), q_end(2));
      EXPECT_DOUBLE_EQ(at("x_norm"), q_max(0) / L_e);
      EXPECT_DOUBLE_EQ(at("y_norm"), q_max(1) / L_e);
      EXPECT_DOUBLE_EQ(at("theta_norm"), q_max(2) * rho / L_e);
      EXPECT_DOUBLE_EQ(at("theta_end_norm"), q_end(2) * rho / L_e);
      const double seat_m = 0.01 * deck.geometry.length_m;
      const double travel_m = run.max_travel_m(d);
      EXPECT_DOUBLE_EQ(at("margin_m"), seat_m - travel_m);
      EXPECT_DOUBLE_EQ(at("margin_norm"), (seat_m - travel_m) / L_e);
      EXPECT_EQ(at("travel_m"), travel_m);
      EXPECT_EQ(at("travel_end_m"), model::CornerTravelAt(deck.geometry, q_end));
      EXPECT_EQ(at("travel_bound_m"), model::CornerTravelBound(deck.geometry, q_max));
      theta_norm_max = std::max(theta_norm_max, q_max(2) * rho / L_e);
    }
    EXPECT_DOUBLE_EQ(ValueOf(evaluator, out, "theta_norm_max"), theta_norm_max);
    EXPECT_EQ(ValueOf(evaluator, out, "impacts"), static_cast<double>(run.impacts));
    EXPECT_EQ(ValueOf(evaluator, out, "min_impact_separation"), run.min_impact_separation_s);
    EXPECT_EQ(ValueOf(evaluator, out, "a_g"), c.a_g_mps2);
    EXPECT_EQ(ValueOf(evaluator, out, "w_g"), c.w_g_radps);
    EXPECT_EQ(ValueOf(evaluator, out, "L_e"), L_e);
    EXPECT_DOUBLE_EQ(ValueOf(evaluator, out, "delta"), (cell == 0 ? 0.5 : 3.0) * L_e);
    if (cell == 0) {
      EXPECT_GT(run.impacts, 0);  // the small gap closes: not a linear run only
    }
  }
}

// Cells that differ only in the seat width share one dynamic run: evaluated in cube order
// (each run serves the seat widths after it), every response of every cell has the bits of the
// cell evaluated on its own (an order in which no two cells in a row share a run), for a
// three-deck and a one-deck model file; the margins differ between the seat widths.
TEST(ModelFileEvaluator, CellsOfOneRunAndSeveralSeatsAreTheCellsOwn) {
  const std::string three_span = (std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / ".." / ".." /
                                  "docs" / "examples" / "three-span.toml")
                                     .string();
  for (const std::string& model : {three_span, std::string("deck.toml")}) {
    SCOPED_TRACE(model);
    const std::string body = "[axes]\nPi_delta = [0.5, 3.0]\nseat_over_L = [0.001, 0.01, 0.02]\n" +
                             std::string(model == three_span ? "" : "[fixed]\npulse = \"sine\"\n") +
                             "[limit_states]\nunseating = true\nrotation = {above_rad = 0.01}\n";
    const ModelFileEvaluator shared(Spec(body, model));
    const ModelFileEvaluator alone(Spec(body, model));
    const std::vector<spectra::ResponseInfo> names = shared.Responses();
    std::size_t margin = names.size();
    for (std::size_t r = 0; r < names.size(); ++r) {
      if (names[r].name == "margin_m_d0") margin = r;
    }
    ASSERT_LT(margin, names.size());
    std::vector<CellOutcome> in_order;
    for (std::size_t cell = 0; cell < 6; ++cell) {
      in_order.push_back(shared.Evaluate(std::vector<std::size_t>{cell / 3, cell % 3}));
    }
    for (std::size_t cell : {0u, 3u, 1u, 4u, 2u, 5u}) {
      SCOPED_TRACE("cell " + std::to_string(cell));
      const CellOutcome own = alone.Evaluate(std::vector<std::size_t>{cell / 3, cell % 3});
      const CellOutcome& got = in_order[cell];
      ASSERT_EQ(got.status, own.status);
      ASSERT_EQ(got.responses.size(), own.responses.size());
      for (std::size_t r = 0; r < own.responses.size(); ++r) {
        EXPECT_EQ(std::memcmp(&got.responses[r], &own.responses[r], sizeof(double)), 0)
            << names[r].name << ": " << got.responses[r] << " against " << own.responses[r];
      }
      EXPECT_EQ(got.stats.events, own.stats.events);
      EXPECT_EQ(got.stats.steps, own.stats.steps);
      if (cell % 3 > 0) {
        EXPECT_NE(got.responses[margin], in_order[cell - 1].responses[margin]);
      }
    }
  }
}

// The stripes of a record share its contact-free response: the pilot bridge under the two real
// records of tests/data/records scaled to eight Sa(T1) stripes (0.3-4 g: the joints close from
// about 1 g), two skews and two seat widths, evaluated in cube order, against each cell's own run
// (EvaluateScaled at the cell's factor: no trace, no sharing). Statuses and event counts are the
// same in every cell. A stripe without impacts has the steps of its own run and every response
// within 1e-12 (a residual relative to the peak of its degree of freedom, a margin to the seat
// width). With impacts the run goes on from the scaled state, which differs from the own run's in
// its last bits; the impact sequence carries that difference (as it carries a change of the
// factor by one ulp, measured beside it), so those cells are held to 1e-8.
TEST(ModelFileEvaluator, StripesOfARecordAreEachStripesOwnRun) {
  const std::filesystem::path root = std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / ".." / "..";
  const std::string body =
      "[records]\nset = \"" + (root / "tests" / "data" / "records" / "two-records.toml").string() +
      "\"\nscale_to = { measure = \"Sa\", period = \"T1\", xi = 0.05 }\n"
      "[axes]\nrecord = \"*\"\nim_g = {logspace = [0.3, 4.0, 8]}\na_deg = [20, 45]\n"
      "seat_over_L = [0.0005, 0.002]\n"
      "[limit_states]\nunseating = true\nrotation = {above_rad = 0.0005}\njoint_closing = true\n";
  const std::string model = (root / "docs" / "examples" / "pilot-bridge.toml").string();
  const ModelFileEvaluator shared(Spec(body, model));
  const ModelFileEvaluator alone(Spec(body, model));
  const std::vector<spectra::ResponseInfo> names = shared.Responses();
  std::map<std::string, std::size_t> at;
  for (std::size_t r = 0; r < names.size(); ++r) at[names[r].name] = r;
  // The scale of response r: its peak for a residual, the seat width for a margin.
  const auto scale_of = [&](const CellOutcome& o, std::size_t r) {
    const std::string& name = names[r].name;
    const std::size_t end = name.find("_end");
    if (name.starts_with("margin_")) {
      const double seat = o.responses[at["margin_m_d0"]] + o.responses[at["travel_m_d0"]];
      return name.starts_with("margin_norm")
                 ? seat * std::abs(o.responses[r] / o.responses[at["margin_m_d0"]])
                 : seat;
    }
    if (end != std::string::npos) {
      std::string peak =
          name.substr(0, end) + (name.starts_with("travel") ? "" : "_m") + name.substr(end + 4);
      if (name.starts_with("theta_end_norm")) peak = "theta_norm_d0";
      if (name.starts_with("travel_end")) peak = "travel_m_d0";
      return std::abs(o.responses[at.at(peak)]);
    }
    return std::abs(o.responses[r]);
  };
  const auto difference = [&](const CellOutcome& a, const CellOutcome& b) {
    double largest = 0.0;
    for (std::size_t r = 0; r < b.responses.size(); ++r) {
      const double x = a.responses[r], y = b.responses[r];
      if (std::isinf(x) || std::isinf(y)) {
        largest = std::max(largest, x == y ? 0.0 : 1.0);
        continue;
      }
      const double scale = std::max(scale_of(a, r), scale_of(b, r));
      largest = std::max(largest, std::abs(x - y) / (scale > 0.0 ? scale : 1.0));
    }
    return largest;
  };
  int with_impacts = 0, without = 0;
  double largest_free = 0.0, largest_impacts = 0.0, one_ulp = 0.0;
  for (std::size_t cell = 0; cell < 2 * 8 * 2 * 2; ++cell) {
    const std::vector<std::size_t> index{cell / 32, cell / 4 % 8, cell / 2 % 2, cell % 2};
    SCOPED_TRACE("cell " + std::to_string(cell));
    const CellOutcome got = shared.Evaluate(index);
    const double factor = alone.Scaling(index)->factor;
    const CellOutcome own = alone.EvaluateScaled(index, factor);
    ASSERT_EQ(got.status, own.status);
    ASSERT_EQ(got.stats.events, own.stats.events);
    ASSERT_EQ(got.responses.size(), own.responses.size());
    const double diff = difference(got, own);
    if (own.stats.events == 0) {
      ++without;
      EXPECT_EQ(got.stats.steps, own.stats.steps);
      EXPECT_LE(diff, 1e-12);
      largest_free = std::max(largest_free, diff);
    } else {
      ++with_impacts;
      EXPECT_LE(diff, 1e-8);
      largest_impacts = std::max(largest_impacts, diff);
      if (cell % 2 == 0) {
        const CellOutcome next = alone.EvaluateScaled(index, std::nextafter(factor, 2 * factor));
        one_ulp = std::max(one_ulp, difference(next, own));
      }
    }
  }
  EXPECT_GE(with_impacts, 8);
  EXPECT_GE(without, 8);
  std::cout << without << " cells without impacts, largest difference " << largest_free << "; "
            << with_impacts << " with impacts, largest " << largest_impacts
            << " (own runs at factors one ulp apart: " << one_ulp << ")\n";
}

TEST(ModelFileEvaluator, CellModelFollowsTheDefinitions) {
  const ModelFileEvaluator evaluator(
      Spec("[axes]\na_deg = [45]\nk_factor = [1, 2]\nPi_delta = [0.5]\n[fixed]\neps_N = 0.7\n"));
  const std::vector<std::size_t> k1{0, 0, 0}, k2{0, 0, 1};  // a_deg, Pi_delta, k_factor
  const ModelFileCell one = evaluator.MakeCell(k1, true);
  const ModelFileCell two = evaluator.MakeCell(k2, true);
  const model::Body& deck = one.model->body(0);
  // W = L sin 2a / (2 eta0) at the new angle: 30 x 1 / 3 = 10 m; uniform I_m of that deck.
  EXPECT_NEAR(deck.geometry.width_m, 10.0, 1e-12);
  EXPECT_DOUBLE_EQ(deck.geometry.skew_rad, std::numbers::pi / 4);
  EXPECT_DOUBLE_EQ(deck.inertia_kgm2, 500e3 * (900.0 + 100.0 / 0.5) / 12.0);
  // K = diag(m w0^2, m w0^2, I_m W0^2), doubled exactly by k_factor = 2.
  EXPECT_DOUBLE_EQ(one.model->K()(0, 0), 500e3 * 100.0);
  EXPECT_DOUBLE_EQ(one.model->K()(2, 2), deck.inertia_kgm2 * 144.0);
  EXPECT_EQ(two.model->K(), one.model->K() * 2.0);
  // Gaps of Pi_delta L_e with L_e = a_g / w_g^2 of the file's pulse; eps_N on every contact.
  const double w_g = 2.0 * std::numbers::pi / 0.6;
  EXPECT_DOUBLE_EQ(one.persistency_m, 0.5 * kG / (w_g * w_g));
  EXPECT_DOUBLE_EQ(one.gap_m, 0.5 * one.persistency_m);
  ASSERT_EQ(one.model->n_contacts(), 4);
  for (const model::Contact& c : one.model->contacts()) EXPECT_EQ(c.restitution, 0.7);
  // A record cell: a_g, w_g, L_e are the record's measures times scale.
  const ModelFileEvaluator records(
      Spec("[records]\nset = \"set.toml\"\n[axes]\nrecord = \"*\"\nscale = [2.0]\n"));
  const std::vector<std::size_t> r{1, 0};
  const ModelFileCell cell = records.MakeCell(r, true);
  ASSERT_NE(cell.record, nullptr);
  EXPECT_EQ(cell.record->label, "b.txt");
  EXPECT_EQ(cell.a_g_mps2, 2.0 * cell.record->measures.pga_mps2);
  EXPECT_EQ(cell.persistency_m, 2.0 * cell.record->measures.persistency_m);
  EXPECT_NEAR(cell.record->measures.pga_mps2, 3.0, 0.01);
  // The same samples as the model file's excitation file: the same scales, read by the run's
  // reader instead of the record reader.
  const ModelFileEvaluator file(
      Spec("[axes]\nPi_delta = [2.0]\nscale = [2.0]\n", "deck-file.toml"));
  const std::vector<std::size_t> f{0, 0};
  const ModelFileCell from_file = file.MakeCell(f, true);
  EXPECT_NEAR(from_file.persistency_m, cell.persistency_m, 1e-12 * cell.persistency_m);
  EXPECT_NEAR(from_file.gap_m, 2.0 * cell.persistency_m, 1e-12 * cell.persistency_m);
  EXPECT_EQ(from_file.excitation->Duration(), cell.excitation->Duration());
}

// Records scaled to stripes: the deck of DeckText() has K = diag(m w0^2, m w0^2, I_m W0^2) with
// w0 = 10 and W0 = 12 rad/s, so T1 = 2 pi / (10 sqrt(k_factor)) s in closed form.
constexpr const char* kStripes =
    "[records]\nset = \"set.toml\"\nscale_to = {measure = \"Sa\", period = \"T1\", xi = 0.05}\n"
    "[axes]\nrecord = \"*\"\nim_g = [0.1, 0.5]\nk_factor = [1, 4]\n";

TEST(Stripes, EveryScaledRecordHasTheStripesSaAtTheClosedFormT1) {
  const ModelFileEvaluator evaluator(Spec(kStripes));
  const SweepSpec spec = Spec(kStripes);
  ASSERT_EQ(spec.CellCount(), 8u);
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    const std::vector<std::size_t> index = spec.AxisIndex(cell);  // record, im_g, k_factor
    const ModelFileCell c = evaluator.MakeCell(index, true);
    const double im_g = spec.axes[1].values[index[1]];
    const double t1 = 2.0 * std::numbers::pi / (10.0 * std::sqrt(spec.axes[2].values[index[2]]));
    std::vector<double> scaled = c.record->motion.acc_mps2;
    for (double& a : scaled) a *= c.scale;
    const std::vector<double> period{t1};
    const double sa =
        records::ElasticResponseSpectrum(scaled, c.record->motion.dt_s, period, 0.05).psa_mps2[0];
    EXPECT_NEAR(sa, im_g * kG, 1e-9 * im_g * kG) << cell;
    // The response columns say the same.
    const CellOutcome out = evaluator.Evaluate(index);
    ASSERT_EQ(out.status, kStatusOk);
    auto column = [&](const std::string& name) { return ValueOf(evaluator, out, name); };
    EXPECT_NEAR(column("T1"), t1, 1e-12 * t1);
    EXPECT_NEAR(column("im"), im_g, 1e-12 * im_g);
    EXPECT_DOUBLE_EQ(column("scale_factor"), c.scale);
    EXPECT_DOUBLE_EQ(column("im_unscaled") * c.scale, column("im"));
    EXPECT_EQ(column("scaled_too_far"), 0.0);
    EXPECT_NEAR(column("pga"), c.scale * c.record->measures.pga_mps2, 1e-12 * column("pga"));
  }
  // T1 varies with k_factor: no single Sa(T1) for the record table.
  EXPECT_TRUE(std::isnan((*evaluator.Records())[0].sa_t1_mps2));
  EXPECT_TRUE(evaluator.Notes().empty());  // no max_scale
}

TEST(Stripes, PgaPgvAndAvgSaScaleToTheirOwnMeasure) {
  for (const auto& [measure, axis, unit] :
       {std::tuple{"PGA", "im_g", kG}, std::tuple{"PGV", "im_mps", 1.0}}) {
    const ModelFileEvaluator evaluator(Spec(std::string("[records]\nset = \"set.toml\"\n") +
                                            "scale_to = {measure = \"" + measure + "\"}\n" +
                                            "[axes]\nrecord = \"*\"\n" + axis + " = [0.3]\n"));
    for (std::size_t r = 0; r < 2; ++r) {
      const std::vector<std::size_t> index{r, 0};
      const ModelFileCell c = evaluator.MakeCell(index, true);
      const records::IntensityMeasures m = c.record->measures;
      const double own = std::string(measure) == "PGA" ? m.pga_mps2 : m.pgv_mps;
      EXPECT_NEAR(c.scale * own, 0.3 * unit, 1e-12) << measure;
    }
  }
  // AvgSa at a given conditioning period: the geometric mean over 0.2-3 T of the scaled record.
  const ModelFileEvaluator avg(
      Spec("[records]\nset = \"set.toml\"\nscale_to = {measure = \"AvgSa\", period = 0.4, "
           "xi = 0.02}\n[axes]\nrecord = \"*\"\nim_g = [0.2]\n"));
  const std::vector<std::size_t> index{0, 0};
  const ModelFileCell c = avg.MakeCell(index, true);
  std::vector<double> scaled = c.record->motion.acc_mps2;
  for (double& a : scaled) a *= c.scale;
  const std::vector<double> periods = records::AvgSaPeriods(0.4);
  const std::vector<double> sa =
      records::ElasticResponseSpectrum(scaled, c.record->motion.dt_s, periods, 0.02).psa_mps2;
  double log_sum = 0.0;
  for (const double v : sa) log_sum += std::log(v);
  EXPECT_NEAR(std::exp(log_sum / static_cast<double>(sa.size())), 0.2 * kG, 1e-9);
  // One T1 for the sweep: the record table gets Sa(T1) and AvgSa(T1) at T1 = 2 pi / 10 s.
  const SweepRecord& r = (*avg.Records())[0];
  const double t1 = 2.0 * std::numbers::pi / 10.0;
  EXPECT_NEAR(r.t1_s, t1, 1e-12);
  EXPECT_EQ(r.spectral_xi, 0.02);
  const std::vector<double> at_t1{t1};
  EXPECT_DOUBLE_EQ(
      r.sa_t1_mps2,
      records::ElasticResponseSpectrum(r.motion.acc_mps2, r.motion.dt_s, at_t1, 0.02).psa_mps2[0]);
  EXPECT_GT(r.avgsa_mps2, 0.0);
  // AvgSa at "T1" with one T1 (taken from the record table's own value): the scaled record's
  // AvgSa over 0.2-3 T1 is the stripe.
  const ModelFileEvaluator conditioned(
      Spec("[records]\nset = \"set.toml\"\nscale_to = {measure = \"AvgSa\", period = \"T1\"}\n"
           "[axes]\nrecord = \"*\"\nim_g = [0.3]\n"));
  for (std::size_t k = 0; k < 2; ++k) {
    const std::vector<std::size_t> cell{k, 0};
    const ModelFileCell one = conditioned.MakeCell(cell, true);
    std::vector<double> acc = one.record->motion.acc_mps2;
    for (double& a : acc) a *= one.scale;
    EXPECT_NEAR(records::AverageSpectralAcceleration(acc, one.record->motion.dt_s,
                                                     records::AvgSaPeriods(t1)),
                0.3 * kG, 1e-9);
  }
}

TEST(Stripes, MaxScaleFlagsTheCellsBeyondItAndCountsThem) {
  const SweepSpec spec = Spec(kStripes);
  const ModelFileEvaluator free(spec);
  // The factors without a limit, then a limit between them.
  std::vector<double> factors;
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    factors.push_back(free.MakeCell(spec.AxisIndex(cell), false).scale);
  }
  std::vector<double> sorted = factors;
  std::sort(sorted.begin(), sorted.end());
  const double limit = (sorted[4] + sorted[5]) / 2.0;  // three cells above it
  std::string text = kStripes;
  text.insert(text.find("[axes]"), "max_scale = " + fmt::format("{}", limit) + "\n");
  const ModelFileEvaluator limited(Spec(text));
  ASSERT_EQ(limited.Notes().size(), 1u);
  EXPECT_THAT(limited.Notes()[0], HasSubstr("3 of 8 cells scaled beyond max_scale"));
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    const CellOutcome out = limited.Evaluate(spec.AxisIndex(cell));
    EXPECT_EQ(ValueOf(limited, out, "scaled_too_far"), factors[cell] > limit ? 1.0 : 0.0) << cell;
  }
}

TEST(Stripes, ImLeavesTheRecordsUnscaled) {
  const ModelFileEvaluator cloud(
      Spec("[records]\nset = \"set.toml\"\nim = {measure = \"Sa\", period = 0.5}\n"
           "[axes]\nrecord = \"*\"\n"));
  const std::vector<std::size_t> index{1};
  const CellOutcome out = cloud.Evaluate(index);
  const ModelFileCell c = cloud.MakeCell(index, false);
  EXPECT_EQ(c.scale, 1.0);
  const std::vector<double> period{0.5};
  const double sa =
      records::ElasticResponseSpectrum(c.record->motion.acc_mps2, c.record->motion.dt_s, period)
          .psa_mps2[0];
  EXPECT_DOUBLE_EQ(ValueOf(cloud, out, "im"), sa / kG);
  EXPECT_DOUBLE_EQ(ValueOf(cloud, out, "scale_factor"), 1.0);
}

TEST(Stripes, SpecErrorsNameTheKey) {
  const std::string set = "[records]\nset = \"set.toml\"\n";
  const std::string axes = "[axes]\nrecord = \"*\"\nim_g = [0.1]\n";
  auto with = [&](const std::string& scale_to) { return set + scale_to + axes; };
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"Sd\", period = 1}\n")),
              HasSubstr("spec.toml:7: records.scale_to.measure: unknown measure 'Sd'; allowed: "
                        "Sa, AvgSa, PGA, PGV"));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"Sa\", period = 0}\n")),
              HasSubstr("records.scale_to.period: must be a period > 0 s or \"T1\""));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"Sa\", period = \"T2\"}\n")),
              HasSubstr("records.scale_to.period: 'T2' is not a period"));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"Sa\"}\n")),
              HasSubstr("records.scale_to.period: missing: Sa needs a period"));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"PGA\", period = 1}\n")),
              HasSubstr("records.scale_to.period: only for Sa, AvgSa, RotD50, RotD100, GM and "
                        "AvgSa_RotD50"));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"RotD50\"}\n")),
              HasSubstr("records.scale_to.period: missing: RotD50 needs a period"));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"RotD5\", period = 1}\n")),
              HasSubstr("unknown measure 'RotD5'; allowed: Sa, AvgSa, PGA, PGV (single records), "
                        "RotD50, RotD100, GM, AvgSa_RotD50 (record pairs); did you mean `RotD50`"));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"Sa\", period = 1, xi = 1}\n")),
              HasSubstr("records.scale_to.xi: must be a damping ratio in [0, 1)"));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"Sa\", period = 1, T = 1}\n")),
              HasSubstr("records.scale_to.T: unknown key; allowed: measure, period, xi"));
  EXPECT_THAT(SpecErrorOf(set + "scale_to = {measure = \"Sa\", period = 1}\n[axes]\nrecord = "
                                "\"*\"\n"),
              HasSubstr("spec.toml: axes.im_g: missing: records.scale_to needs an intensity "
                        "axis im_g"));
  EXPECT_THAT(SpecErrorOf(set + axes), HasSubstr("im_g: an intensity axis needs [records] "
                                                 "scale_to"));
  EXPECT_THAT(SpecErrorOf(set + "scale_to = {measure = \"PGV\"}\n" + axes),
              HasSubstr("im_g: not the axis of PGV: give im_mps (m/s)"));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"PGA\"}\n") + "scale = [2]\n"),
              HasSubstr("scale: give scale or records.scale_to, not both"));
  EXPECT_THAT(SpecErrorOf(with("scale_to = {measure = \"PGA\"}\nmax_scale = 0\n")),
              HasSubstr("records.max_scale: must be a number > 0"));
  EXPECT_THAT(SpecErrorOf(set + "max_scale = 4\n[axes]\nrecord = \"*\"\n"),
              HasSubstr("records.max_scale: needs records.scale_to"));
  EXPECT_THAT(SpecErrorOf(set + "im = {measure = \"PGA\"}\n" + axes),
              HasSubstr("im_g: records.im leaves the records unscaled (cloud)"));
  EXPECT_THAT(SpecErrorOf("[axes]\nim_g = [0.1]\n"), HasSubstr("im_g: an intensity axis needs"));
  try {
    Spec(set + "scale_to = {measure = \"PGA\"}\n[axes]\nrecord = \"*\"\nim_g = [0.1]\n", "",
         "pilot-bridge");
    ADD_FAILURE() << "pilot-bridge stripes accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("records.scale_to: only for family \"model-file\""));
  }
}

}  // namespace
}  // namespace skewbridge::jobs::model_file_evaluator_test
