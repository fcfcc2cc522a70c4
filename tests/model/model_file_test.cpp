// The model-file parser: the shipped examples against the numbers they state, and every
// rejected input against the words (key path, line, allowed range) of its one-line message.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "solver/common/error.h"
#include "solver/model/model_file.h"

namespace skewbridge::model::model_file_test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const std::filesystem::path kExamples =
    std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / ".." / ".." / "docs" / "examples";

TEST(ModelFile, SubsystemExampleHasExactlyTheRequestedSkewRatio) {
  const ModelFile file = ParseModelFile(kExamples / "subsystem.toml");
  const Model& model = file.model;
  ASSERT_EQ(model.n_contacts(), 2);
  EXPECT_EQ(model.contact(0).name, "P1");
  EXPECT_EQ(model.contact(1).name, "P2");
  const DeckGeometry& deck = model.body(0).geometry;
  EXPECT_NEAR(Eta0(deck), 2.0, 4 * std::numeric_limits<double>::epsilon());
  EXPECT_NEAR(deck.skew_rad, 30.0 * kDeg, 1e-15);
  EXPECT_NEAR(deck.width_m, 30.0 * std::sin(60.0 * kDeg) / 4.0, 1e-13);
  EXPECT_NEAR(model.body(0).inertia_kgm2, UniformDeckInertia(500e3, deck), 1e-6);
  EXPECT_NEAR(model.K()(0, 0), 500e3 * 144.0, 1e-6);
  EXPECT_NEAR(model.K()(1, 1), 500e3 * 144.0, 1e-6);
  EXPECT_NEAR(model.K()(2, 2), model.body(0).inertia_kgm2 * 144.0, 1e-3);
  // Classical damping of an uncoupled system: C = diag(2 xi w_k m_k).
  EXPECT_NEAR(model.C()(0, 0), 2.0 * 0.05 * 12.0 * 500e3, 1e-6);
  EXPECT_NEAR(model.C()(0, 1), 0.0, 1e-6);
  for (int c = 0; c < 2; ++c) {
    EXPECT_EQ(model.contact(c).restitution, 0.5);
    EXPECT_EQ(model.contact(c).friction, 0.0);
  }
  const ExcitationSpec& ex = file.excitation;
  EXPECT_EQ(ex.kind, ExcitationSpec::Kind::kPulse);
  EXPECT_EQ(ex.shape, ExcitationSpec::PulseShape::kCosine);
  EXPECT_NEAR(ex.amplitude_mps2, 0.5 * kStandardGravity_mps2, 1e-15);
  EXPECT_NEAR(ex.omega_radps, 4.0 * std::numbers::pi, 1e-13);
  EXPECT_NEAR(*ex.Duration(), 0.5, 1e-15);
  EXPECT_NEAR(file.run.EndTime(*ex.Duration()), 2.5, 1e-15);
  EXPECT_EQ(file.run.output_interval_s, 0.005);
}

TEST(ModelFile, PilotBridgeExampleCarriesTheStudyData) {
  const ModelFile file = ParseModelFile(kExamples / "pilot-bridge.toml");
  const Model& model = file.model;
  ASSERT_EQ(model.n_contacts(), 4);
  EXPECT_EQ(model.body(0).mass_kg, 1547e3);
  EXPECT_EQ(model.body(0).inertia_kgm2, 1079100e3);
  EXPECT_NEAR(Eta0(model.body(0).geometry), 1.48, 0.5e-2);
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(model.contact(c).friction, 0.3);
    EXPECT_EQ(model.contact(c).restitution, 0.5);
  }
  const Modes modes = ComputeModes(model.M(), model.K());
  EXPECT_NEAR(modes.omega_radps(0), 18.0, 0.01);
  EXPECT_NEAR(modes.omega_radps(1), 19.0, 0.01);
  EXPECT_NEAR(modes.omega_radps(2), 26.0, 0.01);
  const ExcitationSpec& ex = file.excitation;
  EXPECT_EQ(ex.kind, ExcitationSpec::Kind::kSampled);
  EXPECT_TRUE(std::filesystem::exists(ex.file)) << ex.file;
  EXPECT_EQ(ex.to_mps2, 1.0);
  EXPECT_FALSE(ex.Duration().has_value());
}

// A valid subsystem text, edited by the cases below.
const char* kValid = R"(
[deck]
m = 1000.0
L = 20.0
W = 5.0
skew_deg = 30.0

[substructure]
w0 = 10.0
W0 = 12.0
xi = 0.05

[abutments]
set = "+x"
gap_m = 0.02
eps_N = 0.5
mu = 0.2

[excitation]
kind = "pulse"
shape = "sine"
a_g = 3.0
w_g = 6.0
)";

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

void ExpectRejected(const std::string& text, const std::vector<std::string>& words) {
  try {
    ParseModelString(text, "bridge.toml");
    ADD_FAILURE() << "accepted; expected a message with '" << words.front() << "'";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.rfind("bridge.toml", 0), 0u) << what;
    for (const std::string& w : words) {
      EXPECT_NE(what.find(w), std::string::npos) << "'" << w << "' not in: " << what;
    }
  }
}

TEST(ModelFile, ValidTextGivesTheDeckItDescribes) {
  const ModelFile file = ParseModelString(kValid, "bridge.toml");
  EXPECT_EQ(file.model.body(0).geometry.width_m, 5.0);
  EXPECT_EQ(file.model.K()(0, 0), 1000.0 * 100.0);
  EXPECT_EQ(file.model.contact(1).friction, 0.2);
  EXPECT_EQ(file.excitation.shape, ExcitationSpec::PulseShape::kSine);
  EXPECT_EQ(file.excitation.direction, Eigen::Vector2d::UnitX());
  EXPECT_FALSE(file.run.end_time_s.has_value());
  EXPECT_EQ(file.run.method, model::Method::kEventDriven);
}

TEST(ModelFile, RunMethodIsTheEnumOfItsSpelling) {
  const ModelFile file = ParseModelString(
      Replace(kValid, "[excitation]", "[run]\nmethod = \"time-stepping\"\n[excitation]"),
      "bridge.toml");
  EXPECT_EQ(file.run.method, model::Method::kTimeStepping);
  for (const model::Method m : {model::Method::kEventDriven, model::Method::kTimeStepping}) {
    EXPECT_EQ(model::ParseMethod(model::ToString(m)), m);
  }
  EXPECT_EQ(std::string(model::ToString(model::Method::kTimeStepping)), "time-stepping");
  EXPECT_EQ(std::string(model::ToString(model::Method::kEventDriven)), "event-driven");
  EXPECT_FALSE(model::ParseMethod("Event-driven").has_value());
  EXPECT_FALSE(model::ParseMethod("").has_value());
}

TEST(ModelFile, AlternativeSpellingsAgree) {
  // (eta0, a, L) instead of (L, W, a); a_g_g and T_g instead of a_g and w_g; gap per abutment.
  const std::string alt =
      Replace(Replace(Replace(kValid, "W = 5.0", "eta0 = 1.7320508075688772"),
                      "a_g = 3.0\nw_g = 6.0", "a_g_g = 0.5\nT_g = 2.0\nangle_deg = 90.0"),
              "gap_m = 0.02", "gap_m = { \"+x\" = 0.02 }");
  const ModelFile file = ParseModelString(alt, "alt.toml");
  EXPECT_NEAR(file.model.body(0).geometry.width_m, 5.0, 1e-14);
  EXPECT_NEAR(file.excitation.amplitude_mps2, 0.5 * 9.80665, 1e-15);
  EXPECT_NEAR(file.excitation.omega_radps, std::numbers::pi, 1e-15);
  EXPECT_NEAR(file.excitation.direction.y(), 1.0, 1e-15);
  const std::string both = Replace(Replace(kValid, "set = \"+x\"", "set = \"both\""),
                                   "gap_m = 0.02", "gap_m = { \"+x\" = 0.02, \"-x\" = 0.04 }");
  const Model model = ParseModelString(both, "both.toml").model;
  ASSERT_EQ(model.n_contacts(), 4);
  EXPECT_NEAR(model.contact(3).face.point_m.x(), -10.04, 1e-14);
  const std::string sampled =
      Replace(kValid, "kind = \"pulse\"\nshape = \"sine\"\na_g = 3.0\nw_g = 6.0",
              "kind = \"sampled\"\nvalues = [0.0, 1.0, -2.0, 0.0]\ndt_s = 0.5\nunits = "
              "\"cmps2\"\nscale = 2.0");
  const ExcitationSpec ex = ParseModelString(sampled, "s.toml").excitation;
  ASSERT_EQ(ex.values.size(), 4u);
  EXPECT_NEAR(ex.values[2], -0.04, 1e-16);
  EXPECT_NEAR(*ex.Duration(), 1.5, 1e-15);
}

TEST(ModelFile, EveryBadValueNamesItsKeyLineAndRange) {
  ExpectRejected(Replace(kValid, "W = 5.0", "W = 0.0"),
                 {"bridge.toml:5:", "deck.W", "must be > 0", "got 0"});
  ExpectRejected(Replace(kValid, "L = 20.0", "L = -1"), {":4:", "deck.L", "must be > 0"});
  ExpectRejected(Replace(kValid, "m = 1000.0", "m = 0"), {":3:", "deck.m", "must be > 0"});
  ExpectRejected(Replace(kValid, "skew_deg = 30.0", "skew_deg = 90"),
                 {":6:", "deck.skew_deg", "[0, 90) deg", "got 90"});
  ExpectRejected(Replace(kValid, "skew_deg = 30.0", "skew_deg = -5"),
                 {"deck.skew_deg", "[0, 90) deg"});
  ExpectRejected(Replace(kValid, "eps_N = 0.5", "eps_N = 1.2"),
                 {":16:", "abutments.eps_N", "[0, 1]", "got 1.2"});
  ExpectRejected(Replace(kValid, "mu = 0.2", "mu = -0.2"), {":17:", "abutments.mu", ">= 0"});
  ExpectRejected(Replace(kValid, "gap_m = 0.02", "gap_m = -0.02"),
                 {":15:", "abutments.gap_m", ">= 0"});
  ExpectRejected(Replace(kValid, "xi = 0.05", "xi = 1.0"), {":11:", "substructure.xi", "[0, 1)"});
  ExpectRejected(Replace(kValid, "W = 5.0", "W = nan"), {":5:", "deck.W", "finite"});
  ExpectRejected(Replace(kValid, "m = 1000.0", "m = \"heavy\""), {"deck.m", "must be a number"});
  ExpectRejected(Replace(kValid, "W = 5.0", "I_m = 0.0\nW = 5.0"), {"deck.I_m", "must be > 0"});
  ExpectRejected(Replace(kValid, "a_g = 3.0", "a_g = inf"), {"excitation.a_g", "finite"});
  ExpectRejected(Replace(kValid, "w_g = 6.0", "w_g = 0.0"), {"excitation.w_g", "must be > 0"});
  ExpectRejected(Replace(kValid, "mu = 0.2", "mu = 0.2\n[abutments.contacts.P2]\nmu = -1"),
                 {"abutments.contacts.P2.mu", ">= 0"});
  ExpectRejected(Replace(kValid, "mu = 0.2", "mu = 0.2\n[abutments.contacts.P1]\neps_N = 2"),
                 {"abutments.contacts.P1.eps_N", "[0, 1]"});
  ExpectRejected(Replace(kValid, "[excitation]", "[run]\nrel_tol = 0.5\n[excitation]"),
                 {"run.rel_tol", "[1e-15, 0.01]"});
  ExpectRejected(Replace(kValid, "[excitation]", "[run]\nmethod = \"euler\"\n[excitation]"),
                 {"run.method", "event-driven, time-stepping", "euler"});
}

TEST(ModelFile, MatricesMustBeSymmetricAndPositiveSemiDefinite) {
  const std::string matrix = Replace(kValid, "w0 = 10.0\nW0 = 12.0",
                                     "kind = \"matrix\"\nK = [[1, 2, 0], [0, 1, 0], [0, 0, 1]]");
  ExpectRejected(matrix, {"substructure.K", "symmetric"});
  ExpectRejected(Replace(matrix, "[[1, 2, 0], [0, 1, 0]", "[[1, 0, 0], [0, -1, 0]"),
                 {"substructure.K", "positive semi-definite"});
  ExpectRejected(Replace(matrix, "[0, 0, 1]]", "[0, 0]]"), {"substructure.K", "3 x 3"});
  const std::string with_c =
      Replace(Replace(matrix, "[[1, 2, 0], [0, 1, 0]", "[[1, 0, 0], [0, 1, 0]"), "xi = 0.05",
              "C = [[1, 0, 5], [0, 1, 0], [0, 0, 1]]");
  ExpectRejected(with_c, {"substructure.C", "symmetric"});
  const ModelFile ok = ParseModelString(Replace(with_c, "[[1, 0, 5]", "[[1, 0, 0]"), "ok.toml");
  EXPECT_EQ(ok.model.C()(0, 0), 1.0);
  EXPECT_EQ(ok.model.K()(1, 1), 1.0);
}

TEST(ModelFile, UnknownKeysAreReportedAtEveryLevel) {
  ExpectRejected(Replace(kValid, "[deck]", "colour = 1\n[deck]"),
                 {":2:", "colour", "unknown section (allowed: deck, substructure,"});
  ExpectRejected(Replace(kValid, "W = 5.0", "W = 5.0\nwidth = 5.0"),
                 {":6:", "deck.width", "unknown key", "allowed: m, I_m, L, W, eta0, skew_deg"});
  ExpectRejected(Replace(kValid, "xi = 0.05", "xi = 0.05\nw1 = 3"),
                 {"substructure.w1", "unknown key", "kind = \"uncoupled\""});
  ExpectRejected(Replace(kValid, "mu = 0.2", "mu = 0.2\nfriction = 0.1"),
                 {"abutments.friction", "unknown key"});
  ExpectRejected(Replace(kValid, "gap_m = 0.02", "gap_m = { \"+x\" = 0.02, \"-x\" = 0.1 }"),
                 {"abutments.gap_m.\"-x\"", "unknown key"});
  ExpectRejected(Replace(kValid, "mu = 0.2", "mu = 0.2\n[abutments.contacts.P3]\nmu = 0.1"),
                 {"abutments.contacts.P3", "unknown key", "P1, P2"});
  ExpectRejected(Replace(kValid, "mu = 0.2", "mu = 0.2\n[abutments.contacts.P1]\nmuu = 0.1"),
                 {"abutments.contacts.P1.muu", "unknown key", "eps_N, mu"});
  ExpectRejected(Replace(kValid, "w_g = 6.0", "w_g = 6.0\nfile = \"x.txt\""),
                 {"excitation.file", "unknown key", "kind = \"pulse\""});
  ExpectRejected(Replace(kValid, "[excitation]", "[run]\ndt = 0.1\n[excitation]"),
                 {"run.dt", "unknown key", "end_time_s"});
}

// A misspelt required key is an unknown key with the allowed ones and the nearest of them (or
// the form of the table that takes it), not a missing required key.
TEST(ModelFile, MisspeltKeysAreNamedAsUnknownWithTheNearest) {
  ExpectRejected(Replace(kValid, "skew_deg = 30.0", "skew = 30.0"),
                 {"bridge.toml:6: deck.skew: unknown key (allowed: m, I_m, L, W, eta0, skew_deg); "
                  "did you mean `skew_deg`?"});
  ExpectRejected(Replace(kValid, "W0 = 12.0", "w_theta = 12"),
                 {"bridge.toml:10: substructure.w_theta: unknown key (allowed: kind, w0, w0x, w0y, "
                  "W0, xi, C (with kind = \"uncoupled\")); it is a key of kind = \"principal\""});
  ExpectRejected(Replace(kValid, "w_g = 6.0", "wg = 6.0"),
                 {"bridge.toml:23: excitation.wg: unknown key", "did you mean `w_g`?"});
  ExpectRejected(Replace(kValid, "[deck]", "[dekc]"),
                 {"bridge.toml:2: dekc: unknown section (allowed: deck, substructure, abutments, "
                  "excitation, run); did you mean `deck`?"});
  ExpectRejected(Replace(kValid, "set = \"+x\"", "sett = \"+x\""),
                 {"abutments.sett: unknown key", "did you mean `set`?"});
  // Nothing near: the allowed keys, no guess.
  ExpectRejected(Replace(kValid, "L = 20.0", "length_of_deck = 20.0"),
                 {"deck.length_of_deck: unknown key (allowed: m, I_m, L, W, eta0, skew_deg)"});
}

// A sweep specification or a record-set manifest is named as what it is.
TEST(ModelFile, OtherKindsOfFileAreNamed) {
  ExpectRejected("[sweep]\nname = \"s\"\nfamily = \"subsystem\"\n[axes]\na_deg = [10]\n",
                 {"bridge.toml: this is a sweep specification ([sweep] table), not a model file"});
  ExpectRejected("name = \"set\"\n[[record]]\nfile = \"a.AT2\"\n",
                 {"bridge.toml: this is a record-set manifest ([[record]] tables), not a model "
                  "file"});
}

TEST(ModelFile, MissingKeysAndSectionsAreNamed) {
  ExpectRejected(Replace(kValid, "L = 20.0\n", ""), {"deck.L", "missing required key"});
  ExpectRejected(Replace(kValid, "W = 5.0\n", ""), {"deck.W", "missing", "eta0"});
  ExpectRejected(Replace(kValid, "W0 = 12.0\n", ""), {"substructure.W0", "missing"});
  ExpectRejected(Replace(kValid, "set = \"+x\"\n", ""), {"abutments.set", "missing", "\"both\""});
  ExpectRejected(Replace(kValid, "gap_m = 0.02\n", ""), {"abutments.gap_m", "missing"});
  ExpectRejected(Replace(kValid, "shape = \"sine\"\n", ""), {"excitation.shape", "missing"});
  ExpectRejected(Replace(kValid, "w_g = 6.0\n", ""), {"excitation.w_g", "missing", "T_g"});
  ExpectRejected(Replace(kValid, "[substructure]\nw0 = 10.0\nW0 = 12.0\nxi = 0.05\n", ""),
                 {"substructure", "missing required section"});
  ExpectRejected(Replace(Replace(kValid, "set = \"+x\"", "set = \"both\""), "gap_m = 0.02",
                         "gap_m = { \"+x\" = 0.02 }"),
                 {"abutments.gap_m.\"-x\"", "missing"});
  ExpectRejected(Replace(kValid, "W = 5.0", "W = 5.0\neta0 = 1.0"),
                 {"deck.eta0", "either W or eta0"});
  ExpectRejected(Replace(kValid, "a_g = 3.0", "kind2 = 1\na_g = 3.0"), {"excitation.kind2"});
}

TEST(ModelFile, SyntaxErrorsAndUnreadableFilesSayWhere) {
  ExpectRejected(Replace(kValid, "L = 20.0", "L = = 20.0"), {"bridge.toml:4:", "syntax error"});
  try {
    ParseModelFile("/nonexistent/dir/model.toml");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/model.toml: cannot open"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace skewbridge::model::model_file_test
