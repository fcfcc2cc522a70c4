// Sweep specification parsing: values against their definitions, every bad input refused with
// the key named, and the canonical text / hash as the identity of a sweep.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "jobs/sweep_spec.h"
#include "solver/common/error.h"

namespace skewbridge::jobs::sweep_spec_test {
namespace {

using ::testing::HasSubstr;

const char* kGood = R"(
[sweep]
name = "subsystem-eta1"
family = "subsystem"

[axes]
w0_over_wg = {logspace = [0.1, 10.0, 5]}
a_deg = [15, 30, 45]
pulse = ["cosine", "sine"]
Pi_delta = {linspace = [0.0, 2.0, 3]}

[fixed]
eta0 = 1.0
xi = 0.05
eps_N = 0.5
mu = 0.0
W0_over_w0 = 1.0
)";

SweepSpec Parse(const std::string& text) { return ParseSweepSpec(text, "spec.toml", "."); }

std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(SweepSpec, AxesFollowTheCanonicalOrderWithW0OverWgLast) {
  const SweepSpec spec = Parse(kGood);
  ASSERT_EQ(spec.axes.size(), 4u);
  EXPECT_EQ(spec.axes[0].key, "pulse");
  EXPECT_EQ(spec.axes[1].key, "a_deg");
  EXPECT_EQ(spec.axes[2].key, "Pi_delta");
  EXPECT_EQ(spec.axes[3].key, "w0_over_wg");
  EXPECT_EQ(spec.Shape(), (std::vector<std::size_t>{2, 3, 3, 5}));
  EXPECT_EQ(spec.CellCount(), 90u);
}

TEST(SweepSpec, LogspaceIsGeometricInValuesWithExactEndPoints) {
  const SweepSpec spec = Parse(kGood);
  const std::vector<double>& v = spec.FindAxis("w0_over_wg")->values;
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v.front(), 0.1);
  EXPECT_EQ(v.back(), 10.0);
  for (std::size_t i = 1; i < v.size(); ++i) {
    EXPECT_NEAR(v[i] / v[i - 1], std::sqrt(10.0), 1e-12);  // 100x over 4 steps
  }
  EXPECT_EQ(spec.FindAxis("Pi_delta")->values, (std::vector<double>{0.0, 1.0, 2.0}));
}

TEST(SweepSpec, AxisIndexIsRowMajorWithLastAxisFastest) {
  const SweepSpec spec = Parse(kGood);
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    const std::vector<std::size_t> idx = spec.AxisIndex(cell);
    const std::uint64_t back = ((idx[0] * 3 + idx[1]) * 3 + idx[2]) * 5 + idx[3];
    EXPECT_EQ(back, cell);
  }
}

TEST(SweepSpec, SymbolsAreAcceptedAsQuotedKeys) {
  const SweepSpec spec = Parse(Replace(kGood, "w0_over_wg =", "\"w0/w_g\" ="));
  EXPECT_NE(spec.FindAxis("w0_over_wg"), nullptr);
}

TEST(SweepSpec, HashIgnoresKeyOrderAndSpellingButNotValues) {
  const SweepSpec a = Parse(kGood);
  const std::string moved = Replace(Replace(kGood, "a_deg = [15, 30, 45]\n", ""),
                                    "pulse =", "a_deg = [15.0, 30, 45]\npulse =");
  EXPECT_EQ(Parse(moved).Hash(), a.Hash());
  EXPECT_NE(Parse(Replace(kGood, "xi = 0.05", "xi = 0.02")).Hash(), a.Hash());
  EXPECT_NE(Parse(Replace(kGood, "[15, 30, 45]", "[15, 30, 40]")).Hash(), a.Hash());
  EXPECT_EQ(a.Hash().size(), 16u);
}

TEST(SweepSpec, RefusesUnknownAxisNamingTheKey) {
  EXPECT_THAT(ErrorOf(Replace(kGood, "a_deg =", "skew =")),
              HasSubstr("spec.toml:8: axes.skew: unknown parameter; allowed:"));
}

// The nearest parameter by key, symbol or the model file's key of the same quantity.
TEST(SweepSpec, UnknownNamesGetTheNearestAllowedOne) {
  EXPECT_THAT(ErrorOf(Replace(kGood, "a_deg =", "skew =")),
              HasSubstr("; did you mean `a_deg` (skew angle a)?"));
  EXPECT_THAT(ErrorOf(Replace(kGood, "eta0 =", "eta =")),
              HasSubstr("spec.toml:13: fixed.eta: unknown parameter; allowed: "));
  EXPECT_THAT(ErrorOf(Replace(kGood, "eta0 =", "eta =")), HasSubstr("did you mean `eta0`"));
  EXPECT_THAT(ErrorOf(Replace(kGood, "xi =", "zeta =")), ::testing::Not(HasSubstr("did you")));
  EXPECT_THAT(ErrorOf(Replace(kGood, "[axes]", "[axis]")),
              HasSubstr("spec.toml:6: axis: unknown table; allowed: [sweep], [axes], [fixed], "
                        "[records], [study], [limit_states], [ida], [event_policy], "
                        "[time_stepping_policy]; did you mean `axes`?"));
  EXPECT_THAT(ErrorOf(Replace(kGood, "family =", "famly =")),
              HasSubstr("sweep.famly: unknown key; allowed: name, family, model, responses, "
                        "description; did you mean `family`?"));
}

// A model file or a record-set manifest is named as what it is.
TEST(SweepSpec, OtherKindsOfFileAreNamed) {
  EXPECT_EQ(ErrorOf("[deck]\nm = 1.0\n[substructure]\nw0 = 1.0\n"),
            "spec.toml: this is a model file ([deck] table), not a sweep specification "
            "(docs/sweep-format.md); `skewbridge run` and `skewbridge modes` take it, and a sweep "
            "of it names it in [sweep] model = \"FILE\" with family = \"model-file\"");
  EXPECT_THAT(ErrorOf("name = \"set\"\n[[record]]\nfile = \"a.AT2\"\n"),
              HasSubstr("spec.toml: this is a record-set manifest ([[record]] tables), not a "
                        "sweep specification"));
}

TEST(SweepSpec, RefusesEmptyAxis) {
  EXPECT_THAT(ErrorOf(Replace(kGood, "[15, 30, 45]", "[]")), HasSubstr("axes.a_deg: empty axis"));
}

TEST(SweepSpec, RefusesNegativePiDelta) {
  EXPECT_THAT(ErrorOf(Replace(kGood, "linspace = [0.0, 2.0, 3]", "linspace = [-1.0, 2.0, 3]")),
              HasSubstr("axes.Pi_delta: must be a number >= 0 (got -1)"));
}

TEST(SweepSpec, RefusesZeroPoints) {
  EXPECT_THAT(ErrorOf(Replace(kGood, "[0.1, 10.0, 5]", "[0.1, 10.0, 0]")),
              HasSubstr("axes.w0_over_wg.logspace: n must be a whole number >= 1"));
}

TEST(SweepSpec, RefusesUnknownFamily) {
  EXPECT_THAT(ErrorOf(Replace(kGood, "\"subsystem\"", "\"tower\"")),
              HasSubstr("sweep.family: unknown family 'tower'; allowed: subsystem"));
}

TEST(SweepSpec, RefusesMissingRecordSetFile) {
  std::string text = Replace(kGood, "pulse = [\"cosine\", \"sine\"]", "record = [\"A\", \"B\"]");
  text += "\n[records]\nset = \"no-such-set.toml\"\n";
  EXPECT_THAT(ErrorOf(text), HasSubstr("records.set: file not found"));
}

TEST(SweepSpec, RefusesRecordAxisWithoutRecordSet) {
  EXPECT_THAT(ErrorOf(Replace(kGood, "pulse = [\"cosine\", \"sine\"]", "record = [\"A\"]")),
              HasSubstr("records.set: missing"));
}

TEST(SweepSpec, RefusesOutOfRangeAndWrongTypes) {
  EXPECT_THAT(ErrorOf(Replace(kGood, "eps_N = 0.5", "eps_N = 1.5")),
              HasSubstr("fixed.eps_N: must be a number >= 0 and <= 1 (got 1.5)"));
  EXPECT_THAT(ErrorOf(Replace(kGood, "\"sine\"]", "\"square\"]")),
              HasSubstr("axes.pulse: must be one of cosine|sine (got 'square')"));
  EXPECT_THAT(ErrorOf(Replace(kGood, "xi = 0.05", "xi = \"low\"")),
              HasSubstr("fixed.xi: must be a number"));
  EXPECT_THAT(ErrorOf(Replace(kGood, "mu = 0.0", "mu = 0.0\nWL = 1")),
              HasSubstr("fixed.WL: unknown parameter"));
  EXPECT_THAT(ErrorOf(Replace(kGood, "[15, 30, 45]", "[15, 30, 15]")),
              HasSubstr("axes.a_deg: duplicate coordinate"));
  EXPECT_THAT(ErrorOf(Replace(kGood, "[0.1, 10.0, 5]", "[0.0, 10.0, 5]")),
              HasSubstr("axes.w0_over_wg.logspace: a and b are values (not decades)"));
}

TEST(SweepSpec, RefusesContradictoryCombinations) {
  EXPECT_THAT(ErrorOf(Replace(kGood, "eta0 = 1.0", "eta0 = 1.0\nW_over_L = 0.2")),
              HasSubstr("eta0: give eta0 or W_over_L, not both"));
  EXPECT_THAT(ErrorOf(Replace(kGood, "xi = 0.05", "xi = 0.05\na_deg = 10")),
              HasSubstr("fixed.a_deg: is also an axis"));
  EXPECT_THAT(ErrorOf("[sweep]\nname = \"x\"\nfamily = \"subsystem\"\n"),
              HasSubstr("axes: give at least one axis"));
}

TEST(SweepSpec, ReportsTomlSyntaxErrorsWithTheLine) {
  EXPECT_THAT(ErrorOf("[sweep]\nname = \n"), HasSubstr("spec.toml:2:"));
}

TEST(SweepSpec, LoadsAFileAndResolvesRecordSetRelativeToIt) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sb_spec_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "set.toml") << "# a record set\n";
  std::string text = Replace(kGood, "pulse = [\"cosine\", \"sine\"]", "record = [\"A\", \"B\"]");
  text += "\n[records]\nset = \"set.toml\"\n";
  std::ofstream(dir / "spec.toml") << text;
  const SweepSpec spec = LoadSweepSpec(dir / "spec.toml");
  EXPECT_EQ(spec.record_set_path, dir / "set.toml");
  EXPECT_EQ(spec.FindAxis("record")->labels, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(spec.text, text);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace skewbridge::jobs::sweep_spec_test

namespace skewbridge::jobs::sweep_spec_test {
namespace {

// TOML sees a key and its quoted symbol as two keys; the specification sees one parameter.
TEST(SweepSpec, ParameterNamedTwiceThroughItsSymbolIsRefused) {
  const std::string fixed = ErrorOf(Replace(kGood, "[fixed]\n", "[fixed]\n\"W0/w0\" = 2.0\n"));
  EXPECT_THAT(fixed, HasSubstr("names the parameter W0_over_w0 a second time"));
  EXPECT_THAT(fixed, HasSubstr("spec.toml:"));
  const std::string axes =
      ErrorOf(Replace(kGood, "w0_over_wg =", "\"w0/w_g\" = [3.0]\nw0_over_wg ="));
  EXPECT_THAT(axes, HasSubstr("names the parameter w0_over_wg a second time"));
}

TEST(SweepSpec, CellCountIsTheProductOfTheAxisSizes) {
  EXPECT_EQ(Parse(kGood).CellCount(), 5u * 3u * 2u * 3u);
}

// A folder with a manifest of two records (bytes that only need hashing here) and a spec
// sweeping the first of them.
std::filesystem::path InputsFolder() {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sb_spec_inputs";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "recs");
  std::ofstream(dir / "set.toml") << "name = \"two\"\n[[record]]\nfile = \"recs/a.txt\"\n"
                                     "label = \"A\"\n[[record]]\nfile = \"recs/b.txt\"\n"
                                     "label = \"B\"\n";
  std::ofstream(dir / "recs" / "a.txt") << "abc";
  std::ofstream(dir / "recs" / "b.txt") << "0.0\n";
  std::string text = Replace(kGood, "pulse = [\"cosine\", \"sine\"]", "record = [\"A\"]");
  std::ofstream(dir / "spec.toml") << text << "\n[records]\nset = \"set.toml\"\n";
  return dir;
}

// The input manifest lists the spec, the manifest and the record files the sweep reads (not B),
// by their path from the spec's folder, with the FIPS 180-2 test vector SHA-256("abc").
TEST(SweepSpec, InputsAreTheFilesTheSweepReadsWithTheirSha256) {
  const std::filesystem::path dir = InputsFolder();
  const SweepSpec spec = LoadSweepSpec(dir / "spec.toml");
  ASSERT_EQ(spec.inputs.size(), 3u);
  EXPECT_EQ(spec.inputs[0].role, "spec");
  EXPECT_EQ(spec.inputs[0].file, "spec.toml");
  EXPECT_EQ(spec.inputs[1].role, "record-set");
  EXPECT_EQ(spec.inputs[1].file, "set.toml");
  EXPECT_EQ(spec.inputs[2].role, "record");
  EXPECT_EQ(spec.inputs[2].file, "recs/a.txt");
  EXPECT_EQ(spec.inputs[2].bytes, 3u);
  EXPECT_EQ(spec.inputs[2].sha256,
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_THAT(spec.InputsText(),
              HasSubstr("record \"recs/a.txt\" = "
                        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad\n"));
  EXPECT_THAT(spec.InputsText(), ::testing::StartsWith("program.version = \""));
  // The identity does not depend on the folder the spec is loaded from.
  const std::filesystem::path here = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  const std::string from_inside = LoadSweepSpec("spec.toml").Hash();
  std::filesystem::current_path(here);
  EXPECT_EQ(from_inside, spec.Hash());
  std::filesystem::remove_all(dir);
}

// --resume's reason names the first key of the spec that differs, else the changed file.
TEST(SweepSpec, IdentityChangeNamesTheKeyOrTheFile) {
  const std::filesystem::path dir = InputsFolder();
  const SweepSpec spec = LoadSweepSpec(dir / "spec.toml");
  const std::string canonical = spec.CanonicalText();
  const std::string inputs = spec.InputsText();
  EXPECT_EQ(DescribeIdentityChange(canonical, inputs, spec), "");
  // A comment changes the bytes, not the canonical text: no change.
  std::ofstream(dir / "spec.toml", std::ios::app) << "# a comment\n";
  EXPECT_EQ(DescribeIdentityChange(canonical, inputs, LoadSweepSpec(dir / "spec.toml")), "");
  std::string text = Replace(kGood, "pulse = [\"cosine\", \"sine\"]", "record = [\"A\"]");
  std::ofstream(dir / "spec.toml")
      << Replace(text, "xi = 0.05", "xi = 0.02") << "\n[records]\nset = \"set.toml\"\n";
  const SweepSpec xi = LoadSweepSpec(dir / "spec.toml");
  EXPECT_THAT(DescribeIdentityChange(canonical, inputs, xi),
              HasSubstr("spec.toml: key fixed.xi differs from the specification the cube was "
                        "computed with (cube: 0.05; now: 0.02)"));
  std::ofstream(dir / "spec.toml")
      << Replace(text, "xi = 0.05\n", "") << "\n[records]\nset = \"set.toml\"\n";
  EXPECT_THAT(DescribeIdentityChange(canonical, inputs, LoadSweepSpec(dir / "spec.toml")),
              HasSubstr("key fixed.xi differs from the specification the cube was computed with "
                        "(cube: 0.05; now: (absent))"));
  std::ofstream(dir / "spec.toml") << text << "\n[records]\nset = \"set.toml\"\n";
  std::ofstream(dir / "recs" / "a.txt") << "abd";
  const SweepSpec edited = LoadSweepSpec(dir / "spec.toml");
  EXPECT_EQ(edited.CanonicalText(), canonical);
  EXPECT_NE(edited.Hash(), spec.Hash());
  EXPECT_THAT(DescribeIdentityChange(canonical, inputs, edited),
              HasSubstr((dir / "recs" / "a.txt").string() +
                        " (record) has changed since the cube was computed from it (sha256 "
                        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad, now "));
  // A cube of a program that stored no input manifest, or of another version, is refused.
  EXPECT_THAT(DescribeIdentityChange(canonical, "", spec),
              HasSubstr("the cube holds no input manifest"));
  std::string older = inputs;
  older.replace(0, older.find('\n'), "program.version = \"0.0.9\"");
  EXPECT_THAT(DescribeIdentityChange(canonical, older, spec),
              HasSubstr("the cube was computed by skewbridge 0.0.9, this is "));
  // The unused record B is no input: editing it is no change.
  std::ofstream(dir / "recs" / "a.txt") << "abc";
  std::ofstream(dir / "recs" / "b.txt") << "1.0\n";
  EXPECT_EQ(DescribeIdentityChange(canonical, inputs, LoadSweepSpec(dir / "spec.toml")), "");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace skewbridge::jobs::sweep_spec_test

namespace skewbridge::jobs::sweep_spec_test {
namespace {

TEST(SweepSpec, LimitStatesAreCanonicalAndPartOfTheIdentity) {
  const std::string base = std::string(kGood) + "\n[limit_states]\n";
  const SweepSpec a = ParseSweepSpec(base +
                                         "joint_closing = true\nrotation = {above_rad = 0.01}\n"
                                         "response = {x_m = 0.2, impacts = 3}\n",
                                     "spec.toml", ".");
  const SweepSpec b = ParseSweepSpec(base +
                                         "response = {impacts = 3.0, x_m = 0.2}\n"
                                         "rotation = {above_rad = 1e-2}\njoint_closing = true\n",
                                     "spec.toml", ".");
  ASSERT_EQ(a.limit_states.size(), 4u);
  EXPECT_EQ(a.limit_states[0].name, "rotation");
  EXPECT_EQ(a.limit_states[1].name, "joint_closing");
  EXPECT_EQ(a.limit_states[2].name, "impacts");
  EXPECT_EQ(a.Hash(), b.Hash());
  EXPECT_NE(a.Hash(), ParseSweepSpec(kGood, "spec.toml", ".").Hash());
  const SweepSpec c = ParseSweepSpec(base +
                                         "joint_closing = true\nrotation = {above_rad = 0.02}\n"
                                         "response = {x_m = 0.2, impacts = 3}\n",
                                     "spec.toml", ".");
  EXPECT_NE(a.Hash(), c.Hash());
}

}  // namespace
}  // namespace skewbridge::jobs::sweep_spec_test
