// A substructure given by bearings and piers (kind = "elements"): the deck's frequencies against a
// hand calculation (series springs, sums, the closed-form eigenvalues of a point-symmetric layout
// and the rotation of the translational axes), the centre of rigidity against the weighted mean
// of isotropic supports and against the principal-axes builder, a pier carrying two bearings
// against its own closed form, and every rejected key against the words of its one-line message.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "solver/common/error.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"
#include "solver/model/substructure.h"

namespace skewbridge::model::substructure_test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The element stiffnesses of the pilot bridge [Dimitrakopoulos 2011, §4] (N/m).
constexpr double kBearing_Npm = 34776e3;
constexpr double kPierStrong_Npm = 111199e3;
constexpr double kPierWeak_Npm = 81990e3;
constexpr double kMass_kg = 1547e3;
constexpr double kInertia_kgm2 = 1079100e3;

// Four piers at (+-a, +-b) from the mass centre, strong axes at 20 deg, one bearing on each.
std::string SymmetricBridge(double a_m, double b_m) {
  std::string text = R"(
[deck]
m = 1547e3
I_m = 1079100e3
L = 89.14
W = 19.36
skew_deg = 20.0

[substructure]
kind = "elements"
xi = 0.05
)";
  const std::array<std::array<double, 2>, 4> at{
      {{a_m, b_m}, {-a_m, b_m}, {-a_m, -b_m}, {a_m, -b_m}}};
  for (std::size_t i = 0; i < at.size(); ++i) {
    text += "\n[[substructure.pier]]\nx_m = " + std::to_string(at[i][0]) +
            "\ny_m = " + std::to_string(at[i][1]) +
            "\nk_strong_Npm = 111199e3\nk_weak_Npm = 81990e3\nstrong_axis_deg = 20.0\n";
    text += "\n[[substructure.bearing]]\npier = " + std::to_string(i) + "\nk_Npm = 34776e3\n";
  }
  text += R"(
[abutments]
set = "both"
gap_m = 0.03

[excitation]
kind = "pulse"
shape = "cosine"
a_g = 3.0
w_g = 6.0
)";
  return text;
}

TEST(ElementsSubstructure, PaperStiffnessesInASymmetricLayoutGiveTheHandFrequencies) {
  const double a = 20.0, b = 5.0;
  const ModelFile file = ParseModelString(SymmetricBridge(a, b), "bridge.toml");
  EXPECT_EQ(file.deck.stiffness, DeckSpec::StiffnessKind::kElements);
  // Hand calculation. A bearing (isotropic) in series with its pier, along each pier axis:
  const double s_strong = kBearing_Npm * kPierStrong_Npm / (kBearing_Npm + kPierStrong_Npm);
  const double s_weak = kBearing_Npm * kPierWeak_Npm / (kBearing_Npm + kPierWeak_Npm);
  // Four equal supports placed point-symmetrically: no translation-rotation coupling, the
  // translations along the 20 deg axes with 4 s each; the torsion sums k_perp r^2 with the
  // series spring's components k_xx = s_s cos^2 + s_w sin^2, k_yy = s_s sin^2 + s_w cos^2 (the
  // x y cross terms cancel over the four corners).
  const double c = std::cos(20.0 * kDeg), s = std::sin(20.0 * kDeg);
  const double k_xx = s_strong * c * c + s_weak * s * s;
  const double k_yy = s_strong * s * s + s_weak * c * c;
  const double k_theta = 4.0 * (b * b * k_xx + a * a * k_yy);
  std::vector<double> expected{std::sqrt(4.0 * s_weak / kMass_kg),
                               std::sqrt(4.0 * s_strong / kMass_kg),
                               std::sqrt(k_theta / kInertia_kgm2)};
  std::sort(expected.begin(), expected.end());  // torsion (6.24 rad/s) first here
  const Modes modes = ComputeModes(file.model.M(), file.model.K());
  ASSERT_EQ(modes.omega_radps.size(), 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(modes.omega_radps(k), expected[static_cast<std::size_t>(k)],
                1e-12 * expected[static_cast<std::size_t>(k)])
        << "mode " << k;
  }
  // The numbers themselves, so that a wrong hand formula cannot agree with a wrong assembly:
  // s_w = 34776 * 81990 / 116766 kN/m = 24 418.6 kN/m, w = sqrt(4 s_w / m) = 7.9457 rad/s.
  EXPECT_NEAR(std::sqrt(4.0 * s_weak / kMass_kg), 7.9457, 5e-4);
  EXPECT_NEAR(modes.omega_radps(1), 7.9457, 5e-4);

  // The classical damping from xi = 5 %: Phi^T C Phi = diag(2 xi w_k).
  const Eigen::MatrixXd modal = modes.phi.transpose() * file.model.C() * modes.phi;
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) {
      const double want = j == k ? 2.0 * 0.05 * modes.omega_radps(k) : 0.0;
      EXPECT_NEAR(modal(k, j), want, 1e-9) << k << "," << j;
    }
  }

  const StiffnessCentre centre = AnalyseStiffness(file.model.K().topLeftCorner<3, 3>());
  ASSERT_TRUE(centre.has_centre);
  EXPECT_NEAR(centre.centre_of_rigidity_m.norm(), 0.0, 1e-12);
  EXPECT_NEAR(centre.principal_Npm(0), 4.0 * s_weak, 1e-6);
  EXPECT_NEAR(centre.principal_Npm(1), 4.0 * s_strong, 1e-6);
  // The weak axis is perpendicular to the strong one at 20 deg: 110 deg, i.e. -70 deg.
  EXPECT_NEAR(centre.axis1_rad, -70.0 * kDeg, 1e-12);
  EXPECT_NEAR(centre.torsion_about_centre_Nmprad, k_theta, 1e-12 * k_theta);
}

TEST(ElementsSubstructure, CentreOfRigidityOfIsotropicSupportsIsTheirWeightedMean) {
  // Three isotropic bearings on the ground: e = sum k_i p_i / sum k_i, torsion about e
  // sum k_i |p_i - e|^2, the translational stiffness sum k_i in every direction.
  const std::vector<double> k{1e6, 2e6, 3e6};
  const std::vector<Eigen::Vector2d> p{{10.0, 1.0}, {-5.0, 2.0}, {0.5, -4.0}};
  std::vector<BearingSpec> bearings;
  Eigen::Vector2d weighted = Eigen::Vector2d::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < k.size(); ++i) {
    BearingSpec b;
    b.position_m = p[i];
    b.spring = {k[i], k[i], 0.3};
    bearings.push_back(b);
    weighted += k[i] * p[i];
    total += k[i];
  }
  const Eigen::Vector2d e = weighted / total;
  double torsion = 0.0;
  for (std::size_t i = 0; i < k.size(); ++i) {
    torsion += k[i] * (p[i] - e).squaredNorm();
  }
  const StiffnessCentre c = AnalyseStiffness(ElementsStiffness(bearings, {}));
  ASSERT_TRUE(c.has_centre);
  EXPECT_NEAR(c.centre_of_rigidity_m.x(), e.x(), 1e-12);
  EXPECT_NEAR(c.centre_of_rigidity_m.y(), e.y(), 1e-12);
  EXPECT_NEAR(c.torsion_about_centre_Nmprad, torsion, 1e-9 * torsion);
  EXPECT_NEAR(c.principal_Npm(0), total, 1e-9 * total);
  EXPECT_NEAR(c.principal_Npm(1), total, 1e-9 * total);
}

TEST(ElementsSubstructure, AnalysisRecoversThePrincipalAxesBuildersData) {
  // A second route to the same numbers: the pilot bridge's K = T^T K_cr T (builders.h).
  Body body;
  body.mass_kg = kMass_kg;
  body.inertia_kgm2 = kInertia_kgm2;
  const Eigen::Matrix3d K =
      PrincipalAxesStiffness(body, 18.0, 19.0, 26.0, 20.0 * kDeg, Eigen::Vector2d(-0.24, 0.01));
  const StiffnessCentre c = AnalyseStiffness(K);
  ASSERT_TRUE(c.has_centre);
  EXPECT_NEAR(c.centre_of_rigidity_m.x(), -0.24, 1e-12);
  EXPECT_NEAR(c.centre_of_rigidity_m.y(), 0.01, 1e-12);
  EXPECT_NEAR(c.axis1_rad, 20.0 * kDeg, 1e-12);
  EXPECT_NEAR(c.principal_Npm(0), kMass_kg * 18.0 * 18.0, 1e-6);
  EXPECT_NEAR(c.principal_Npm(1), kMass_kg * 19.0 * 19.0, 1e-6);
  EXPECT_NEAR(c.torsion_about_centre_Nmprad, kInertia_kgm2 * 26.0 * 26.0, 1e-9 * K(2, 2));
}

TEST(ElementsSubstructure, BearingsOnOnePierShareItsTop) {
  // Two isotropic bearings at (0, +-c) on one isotropic pier: in translation the bearings act
  // in parallel, then in series with the pier, 2 k_b k_p / (2 k_b + k_p); in rotation the pier
  // top stays put by symmetry and the torsion is 2 k_b c^2. A bearing on the ground adds k_g.
  const double k_b = 3e6, k_p = 5e6, k_g = 7e6, c = 2.5;
  PierSpec pier;
  pier.spring = {k_p, k_p, 0.0};
  BearingSpec upper, lower, ground;
  upper.position_m = {0.0, c};
  lower.position_m = {0.0, -c};
  upper.spring = lower.spring = {k_b, k_b, 0.0};
  upper.pier = lower.pier = 0;
  ground.spring = {k_g, 0.0, 0.0};  // stiff along x only (a guided bearing)
  const Eigen::Matrix3d K = ElementsStiffness({upper, lower, ground}, {pier});
  const double series = 2.0 * k_b * k_p / (2.0 * k_b + k_p);
  EXPECT_NEAR(K(0, 0), series + k_g, 1e-6);
  EXPECT_NEAR(K(1, 1), series, 1e-6);
  EXPECT_NEAR(K(2, 2), 2.0 * k_b * c * c, 1e-6);
  EXPECT_NEAR(K(0, 1), 0.0, 1e-6);
  EXPECT_NEAR(K(0, 2), 0.0, 1e-6);
  EXPECT_NEAR(K(1, 2), 0.0, 1e-6);
  // One bearing on one pier along common axes: the series spring k_b k_p / (k_b + k_p).
  const Eigen::Matrix3d single = ElementsStiffness({upper}, {pier});
  EXPECT_NEAR(single(0, 0), k_b * k_p / (k_b + k_p), 1e-6);
}

TEST(ElementsSubstructure, DisplayShapesHaveTheirLargestEntryAtPlusOne) {
  const ModelFile file = ParseModelString(SymmetricBridge(20.0, 5.0), "bridge.toml");
  const Modes modes = ComputeModes(file.model.M(), file.model.K());
  const Eigen::MatrixXd shapes = DisplayModeShapes(modes, {file.model.body(0)});
  const double rho = std::sqrt(kInertia_kgm2 / kMass_kg);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(shapes.col(k).cwiseAbs().maxCoeff(), 1.0, 1e-15);
    EXPECT_NEAR(shapes.col(k).maxCoeff(), 1.0, 1e-15);
    // The same direction as phi_k, with theta scaled by rho.
    Eigen::Vector3d phi = modes.phi.col(k);
    phi(2) *= rho;
    EXPECT_NEAR(std::abs(phi.normalized().dot(shapes.col(k).normalized())), 1.0, 1e-12);
  }
}

TEST(ElementsSubstructure, TheExampleReproducesThePilotBridgeFromItsElements) {
  // [Dimitrakopoulos 2011, §4]: 18 and 19 rad/s along principal axes at 20 deg, 26 rad/s in
  // torsion about the centre of rigidity at (-0.24, 0.01) m, from five bearings on each seat and
  // two columns built into the deck (bearings on the ground with the columns' stiffnesses).
  const ModelFile file = ParseModelFile(std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / ".." /
                                        ".." / "docs" / "examples" / "pilot-elements.toml");
  ASSERT_EQ(file.deck.bearings.size(), 12u);
  ASSERT_EQ(file.deck.piers.size(), 0u);
  const StiffnessCentre c = AnalyseStiffness(file.model.K().topLeftCorner<3, 3>());
  // Isotropic bearings in parallel with two columns whose weak axes lie along +20 deg.
  EXPECT_NEAR(c.principal_Npm(0), 10.0 * kBearing_Npm + 2.0 * kPierWeak_Npm, 1e-6);
  EXPECT_NEAR(c.principal_Npm(1), 10.0 * kBearing_Npm + 2.0 * kPierStrong_Npm, 1e-6);
  EXPECT_NEAR(c.axis1_rad, 20.0 * kDeg, 1e-9);
  // The paper's numbers are given to two digits (rad/s) and 0.01 m.
  EXPECT_EQ(std::lround(std::sqrt(c.principal_Npm(0) / kMass_kg)), 18);
  EXPECT_EQ(std::lround(std::sqrt(c.principal_Npm(1) / kMass_kg)), 19);
  EXPECT_EQ(std::lround(std::sqrt(c.torsion_about_centre_Nmprad / kInertia_kgm2)), 26);
  EXPECT_NEAR(c.centre_of_rigidity_m.x(), -0.24, 5e-6);
  EXPECT_NEAR(c.centre_of_rigidity_m.y(), 0.01, 5e-6);
}

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
    EXPECT_EQ(what.rfind("bridge.toml:", 0), 0u) << what;
    for (const std::string& w : words) {
      EXPECT_NE(what.find(w), std::string::npos) << "'" << w << "' not in: " << what;
    }
  }
}

TEST(ElementsSubstructure, EveryBadKeyIsNamedInOneLine) {
  const std::string good = SymmetricBridge(20.0, 5.0);
  ParseModelString(good, "bridge.toml");  // the base text is valid
  ExpectRejected(Replace(good, "k_weak_Npm = 81990e3", "k_weak_Npm = -1.0"),
                 {"substructure.pier[0].k_weak_Npm", "must be > 0", "got -1"});
  ExpectRejected(Replace(good, "k_weak_Npm = 81990e3", "k_weak_Npm = 0"),
                 {"substructure.pier[0].k_weak_Npm", "must be > 0"});
  ExpectRejected(Replace(good, "pier = 1\nk_Npm = 34776e3", "pier = 1\nk_Npm = -5"),
                 {"substructure.bearing[1].k_Npm", "must be >= 0", "got -5"});
  ExpectRejected(Replace(good, "x_m = 20.000000\n", ""),
                 {"substructure.pier[0]", "missing required key", "x_m"});
  // A bearing on the ground has no pier to take its position from.
  ExpectRejected(Replace(good, "pier = 3\n", ""), {"substructure.bearing[3]", "x_m", "ground"});
  ExpectRejected(Replace(good, "pier = 2\n", "pier = 4\n"),
                 {"substructure.bearing[2].pier", "[0, 4)", "got 4"});
  ExpectRejected(Replace(good, "pier = 2\n", "pier = -1\n"),
                 {"substructure.bearing[2].pier", "[0, 4)"});
  ExpectRejected(Replace(good, "pier = 2\n", "pier = 0\n"),
                 {"substructure.pier[2]", "no bearing sits on it"});
  ExpectRejected(Replace(good, "pier = 0\n", "pier = 0\nstiffness = 3\n"),
                 {"substructure.bearing[0].stiffness", "unknown key", "k_strong_Npm"});
  ExpectRejected(Replace(good, "strong_axis_deg = 20.0\n", "strong_axis_deg = 20.0\nk_Npm = 1\n"),
                 {"substructure.pier[0].k_strong_Npm", "either k_Npm"});
  ExpectRejected(Replace(good, "kind = \"elements\"", "kind = \"elements\"\nw0 = 3.0"),
                 {"substructure.w0", "unknown key", "with kind = \"elements\""});
  ExpectRejected(Replace(good, "pier = 0\nk_Npm = 34776e3", "pier = 0\nk_strong_Npm = 1e6"),
                 {"substructure.bearing[0]", "missing required key", "k_weak_Npm"});
  // No bearing at all.
  std::string bare = good.substr(0, good.find("[[substructure.pier]]"));
  bare += good.substr(good.find("[abutments]"));
  ExpectRejected(bare, {"substructure.bearing", "at least one"});
}

TEST(ElementsSubstructure, BuildDeckModelChecksTheElementsItIsGiven) {
  // The same checks for a DeckSpec built in code (no file, no line).
  DeckSpec spec;
  spec.mass_kg = kMass_kg;
  spec.geometry = {30.0, 10.0, 0.0};
  spec.stiffness = DeckSpec::StiffnessKind::kElements;
  BearingSpec b;
  b.spring = {1e6, 1e6, 0.0};
  b.pier = 1;
  spec.bearings = {b};
  spec.piers = {PierSpec{{0.0, 0.0}, {1e6, 1e6, 0.0}}};
  try {
    BuildDeckModel(spec, "spec");
    ADD_FAILURE() << "accepted a bearing on pier 1 of 1";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("substructure.bearing[0].pier"), std::string::npos)
        << e.what();
  }
  spec.bearings[0].pier = 0;
  spec.piers[0].spring.k_strong_Npm = -1.0;
  EXPECT_THROW(BuildDeckModel(spec, "spec"), InputError);
  spec.piers[0].spring.k_strong_Npm = 1e6;
  const Model model = BuildDeckModel(spec, "spec");
  EXPECT_NEAR(model.K()(0, 0), 0.5e6, 1e-6);
}

}  // namespace
}  // namespace skewbridge::model::substructure_test
