// Multi-deck models: the N-span generator against the single-deck builder (bit for bit at N = 1)
// and against hand-computed positions, gaps and matrices; the [[deck]] file form against the
// generator; supports between decks against their strain energy; and every rejected input
// against the field its one-line message names.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>

#include "solver/common/error.h"
#include "solver/model/model_file.h"
#include "solver/model/multispan.h"

namespace skewbridge::model::multispan_model_test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const std::filesystem::path kExamples =
    std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / ".." / ".." / "docs" / "examples";

MultiSpanSpec ThreeSpanSpec() {
  MultiSpanSpec spec;
  spec.n_spans = 3;
  spec.span_lengths_m = {30.0, 40.0, 30.0};
  spec.width_m = 12.0;
  spec.skew_rad = 30.0 * kDeg;
  spec.mass_per_length_kgpm = 20e3;
  spec.w0x_radps = spec.w0y_radps = 10.0;
  spec.W0_radps = 12.0;
  spec.xi = 0.05;
  spec.abutment_gap_m = 0.05;
  spec.joint_gap_m = 0.04;
  spec.restitution = 0.5;
  spec.friction = 0.2;
  return spec;
}

// The gap of a body-fixed point against a face at q = 0, from the rest positions.
double GapAtRest(const Model& model, const Contact& c) {
  const Eigen::Vector2d P = model.body(c.body).rest_position_m + c.point_m;
  Eigen::Vector2d A = c.face.point_m;
  if (c.face.body != kGround) {
    A += model.body(c.face.body).rest_position_m;
  }
  return c.face.normal.dot(P - A);
}

TEST(MultiSpanModel, OneSpanIsTheSingleDeckModelBitForBit) {
  MultiSpanSpec spec;
  spec.n_spans = 1;
  spec.span_lengths_m = {30.0};
  spec.width_m = 8.0;
  spec.skew_rad = 35.0 * kDeg;
  spec.mass_per_length_kgpm = 15e3;
  spec.w0x_radps = 9.0;
  spec.w0y_radps = 11.0;
  spec.W0_radps = 13.0;
  spec.xi = 0.05;
  spec.abutment_gap_m = 0.03;
  spec.restitution = 0.6;
  spec.friction = 0.25;
  const Model generated = BuildMultiSpanBridge(spec);

  DeckSpec deck;
  deck.mass_kg = 15e3 * 30.0;
  deck.geometry = {30.0, 8.0, 35.0 * kDeg};
  deck.w0x_radps = 9.0;
  deck.w0y_radps = 11.0;
  deck.W0_radps = 13.0;
  deck.xi = 0.05;
  deck.abutments = AbutmentSet::kBoth;
  deck.gap_plus_m = deck.gap_minus_m = 0.03;
  deck.restitution = 0.6;
  deck.friction = 0.25;
  const Model single = BuildDeckModel(deck);

  EXPECT_EQ(generated.body(0).mass_kg, single.body(0).mass_kg);
  EXPECT_EQ(generated.body(0).inertia_kgm2, single.body(0).inertia_kgm2);
  EXPECT_TRUE(generated.body(0).rest_position_m.isZero(0.0));
  EXPECT_TRUE((generated.M().array() == single.M().array()).all());
  EXPECT_TRUE((generated.K().array() == single.K().array()).all());
  EXPECT_TRUE((generated.C().array() == single.C().array()).all());
  EXPECT_TRUE((generated.r().array() == single.r().array()).all());
  ASSERT_EQ(generated.n_contacts(), single.n_contacts());
  for (int c = 0; c < single.n_contacts(); ++c) {
    const Contact& a = generated.contact(c);
    const Contact& b = single.contact(c);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.body, b.body);
    EXPECT_EQ(a.point_m, b.point_m);
    EXPECT_EQ(a.face.body, b.face.body);
    EXPECT_EQ(a.face.point_m, b.face.point_m);
    EXPECT_EQ(a.face.normal, b.face.normal);
    EXPECT_EQ(a.face.tangent, b.face.tangent);
    EXPECT_EQ(a.restitution, b.restitution);
    EXPECT_EQ(a.friction, b.friction);
  }
}

TEST(MultiSpanModel, DecksSitInARowWithEveryGapEqualToDeltaCosA) {
  const MultiSpanSpec spec = ThreeSpanSpec();
  const Model model = BuildMultiSpanBridge(spec);
  ASSERT_EQ(model.n_bodies(), 3);
  ASSERT_EQ(model.n_dof(), 9);
  EXPECT_EQ(model.body(0).rest_position_m, Eigen::Vector2d(0.0, 0.0));
  EXPECT_NEAR(model.body(1).rest_position_m.x(), 15.0 + 0.04 + 20.0, 1e-12);
  EXPECT_NEAR(model.body(2).rest_position_m.x(), 2 * (15.0 + 0.04 + 20.0), 1e-12);
  EXPECT_NEAR(model.body(1).mass_kg, 20e3 * 40.0, 1e-6);
  // 2 contacts at each abutment, 2 at each joint.
  ASSERT_EQ(model.n_contacts(), 8);
  const double c = std::cos(30.0 * kDeg);
  for (const Contact& contact : model.contacts()) {
    const bool joint = contact.face.body != kGround;
    EXPECT_NEAR(GapAtRest(model, contact), (joint ? 0.04 : 0.05) * c, 1e-12) << contact.name;
    if (joint) {
      EXPECT_EQ(contact.face.body, contact.body + 1) << contact.name;
    }
  }
  EXPECT_EQ(model.contact(0).name, "D0.P3");
  EXPECT_EQ(model.contact(2).name, "D0.P1/D1");
  EXPECT_EQ(model.contact(7).name, "D2.P2");
  // Decks are coupled only through contacts: K and C block diagonal.
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) {
      if (i / 3 != j / 3) {
        EXPECT_EQ(model.K()(i, j), 0.0);
        EXPECT_EQ(model.C()(i, j), 0.0);
      }
    }
  }
  EXPECT_NEAR(model.K()(3, 3), 800e3 * 100.0, 1e-6);
  EXPECT_NEAR(model.C()(3, 3), 2.0 * 0.05 * 10.0 * 800e3, 1e-6);
}

TEST(MultiSpanModel, NarrowerEndStrikesTheWiderFace) {
  MultiDeckSpec spec = MultiSpanDecks(ThreeSpanSpec());
  spec.decks[1].geometry.width_m = 10.0;  // narrower middle deck
  spec.decks[1].inertia_kgm2 = UniformDeckInertia(spec.decks[1].mass_kg, spec.decks[1].geometry);
  const Model model = BuildMultiDeckModel(spec);
  // Joint 0: deck 1 is narrower, so its -x corners P3, P4 strike deck 0's +x face.
  EXPECT_EQ(model.contact(2).name, "D1.P3/D0");
  EXPECT_EQ(model.contact(3).name, "D1.P4/D0");
  // Joint 1: deck 1 is narrower, its +x corners strike deck 2's -x face.
  EXPECT_EQ(model.contact(4).name, "D1.P1/D2");
  for (int c = 2; c < 6; ++c) {
    EXPECT_NEAR(GapAtRest(model, model.contact(c)), 0.04 * std::cos(30.0 * kDeg), 1e-12);
  }
}

TEST(MultiSpanModel, ThreeSpanExampleFileEqualsTheGenerator) {
  const ModelFile file = ParseModelFile(kExamples / "three-span.toml");
  ASSERT_TRUE(file.decks.has_value());
  const Model generated = BuildMultiSpanBridge(ThreeSpanSpec());
  const Model& model = file.model;
  ASSERT_EQ(model.n_bodies(), 3);
  EXPECT_TRUE(model.M().isApprox(generated.M(), 1e-15));
  EXPECT_TRUE(model.K().isApprox(generated.K(), 1e-12));
  EXPECT_TRUE(model.C().isApprox(generated.C(), 1e-12));
  ASSERT_EQ(model.n_contacts(), generated.n_contacts());
  for (int c = 0; c < model.n_contacts(); ++c) {
    EXPECT_EQ(model.contact(c).name, generated.contact(c).name);
    EXPECT_TRUE(model.contact(c).point_m.isApprox(generated.contact(c).point_m, 1e-15));
    EXPECT_TRUE(model.contact(c).face.point_m.isApprox(generated.contact(c).face.point_m, 1e-15));
    EXPECT_EQ(model.contact(c).friction, 0.2);
  }
  EXPECT_EQ(file.excitation.kind, ExcitationSpec::Kind::kPulse);
}

TEST(MultiSpanModel, LinkBetweenDecksStoresTheStrainEnergyOfTheRelativeDisplacement) {
  MultiDeckSpec spec = MultiSpanDecks(ThreeSpanSpec());
  SupportSpec link;
  link.deck = 0;
  link.other = 2;
  link.stiffness = {1e6, 2e6, 3e8};
  link.damping = Eigen::Vector3d(1e4, 2e4, 3e6);
  spec.supports.push_back(link);
  const Model with_link = BuildMultiDeckModel(spec);
  const Model without = BuildMultiSpanBridge(ThreeSpanSpec());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::VectorXd q(9);
    for (int k = 0; k < 9; ++k) {
      q(k) = unit(rng);
    }
    const Eigen::Vector3d d = q.segment<3>(6) - q.segment<3>(0);
    const double link_energy = 0.5 * d.dot(link.stiffness.cwiseProduct(d));
    const double zero_u = 0.0;
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(9, zero_u);
    EXPECT_NEAR(with_link.MechanicalEnergy(q, u) - without.MechanicalEnergy(q, u), link_energy,
                1e-9 * link_energy);
    const double dissipation = d.dot(link.damping->cwiseProduct(d));
    EXPECT_NEAR(q.dot((with_link.C() - without.C()) * q), dissipation, 1e-9 * dissipation);
  }
}

// Parses `text` and returns the error message ("" if it parsed).
std::string ErrorOf(const std::string& text) {
  try {
    ParseModelString(text, "bridge.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string TwoDeckFile(const std::string& deck1_extra, const std::string& joint_extra,
                        const std::string& support_extra) {
  return "[[deck]]\nm = 1e5\nL = 20\nW = 8\nskew_deg = 20\n"
         "[[deck]]\nm = 1e5\nL = 20\nskew_deg = 20\n" +
         deck1_extra + "[[joint]]\n" + joint_extra +
         "[abutments]\ngap_m = 0.02\n"
         "[[support]]\ndeck = 0\nk_x = 1e6\nk_y = 1e6\nk_theta = 1e8\n"
         "[[support]]\n" +
         support_extra + "[excitation]\nkind = \"pulse\"\nshape = \"sine\"\na_g = 2\nw_g = 10\n";
}

TEST(MultiSpanModel, ValidTwoDeckFileParses) {
  EXPECT_EQ(ErrorOf(TwoDeckFile("W = 8\n", "gap_m = 0.01\n", "deck = 1\nk_x = 1e6\n")), "");
}

TEST(MultiSpanModel, BadInputsNameTheirFieldInOneLine) {
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {TwoDeckFile("W = -1\n", "gap_m = 0.01\n", "deck = 1\n"),
       "bridge.toml:10: deck[1].W: must be > 0 (got -1)"},
      {TwoDeckFile("W = 8\n", "gap_m = -0.01\n", "deck = 1\n"),
       "bridge.toml:12: joint[0].gap_m: must be >= 0 (got -0.01)"},
      {TwoDeckFile("W = 8\n", "gap = 0.01\n", "deck = 1\n"),
       "bridge.toml:12: joint[0].gap: unknown key (allowed: gap_m, eps_N, mu, law); did you mean "
       "`gap_m`?"},
      {TwoDeckFile("W = 8\n", "eps_N = 0.5\n", "deck = 1\n"),
       "joint[0].gap_m: missing required key"},
      {TwoDeckFile("W = 8\n", "gap_m = 0.01\n", "deck = 2\n"),
       "support[1].deck: must be a deck index, a whole number in [0, 2) (got 2)"},
      {TwoDeckFile("W = 8\n", "gap_m = 0.01\n", "deck = 1\nk_y = -5\n"),
       "support[1].k_y: must be >= 0 (got -5)"},
      {TwoDeckFile("W = 8\n", "gap_m = 0.01\n", "deck = 1\nk_z = 5\n"),
       "support[1].k_z: unknown key (allowed: deck, between, k_x, k_y, k_theta"},
      {TwoDeckFile("W = 8\n", "gap_m = 0.01\n", "between = [0, 1]\nk_x = 1e6\nxi = 0.05\n"),
       "support[1].xi: a link between decks takes c_x, c_y, c_theta"},
      {TwoDeckFile("W = 8\n", "gap_m = 0.01\n", "deck = 1\nxi = 0.05\nc_x = 1\n"),
       "support[1].xi: give either xi or c_x, c_y, c_theta, not both"},
      {TwoDeckFile("W = 8\nskew_dg = 3\n", "gap_m = 0.01\n", "deck = 1\n"),
       "deck[1].skew_dg: unknown key"},
  };
  for (const auto& c : cases) {
    const std::string message = ErrorOf(c.text);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected: " << c.expected << "\n     got: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(MultiSpanModel, AbutmentsFollowTheSingleDeckRulesWithBothEndsAlways) {
  const std::string base = TwoDeckFile("W = 8\n", "gap_m = 0.01\n", "deck = 1\n");
  const auto with = [&](const std::string& abutments) {
    std::string text = base;
    const std::string from = "[abutments]\ngap_m = 0.02\n";
    return text.replace(text.find(from), from.size(), "[abutments]\n" + abutments);
  };
  // Per-abutment gaps, as for a single deck with set = "both".
  const ModelFile file =
      ParseModelString(with("gap_m = { \"+x\" = 0.02, \"-x\" = 0.05 }\nmu = 0.1\n"), "b.toml");
  ASSERT_TRUE(file.decks.has_value());
  EXPECT_EQ(file.decks->gap_plus_m, 0.02);
  EXPECT_EQ(file.decks->gap_minus_m, 0.05);
  EXPECT_EQ(file.decks->friction, 0.1);
  const struct {
    std::string abutments;
    std::string expected;
  } cases[] = {
      {"gap_m = -0.02\n", "abutments.gap_m: must be >= 0 (got -0.02)"},
      {"gap_m = { \"+x\" = 0.02 }\n", "abutments.gap_m.\"-x\": missing required key"},
      {"gap_m = 0.02\neps_N = 1.5\n", "abutments.eps_N: must be in [0, 1]"},
      {"set = \"+x\"\ngap_m = 0.02\n", "abutments.set: must be one of both"},
      {"gap_m = 0.02\n[abutments.contacts.P1]\nmu = 0.1\n",
       "abutments.contacts: unknown key (allowed: set, gap_m, law, eps_N, mu (with [[deck]] "
       "tables))"},
      {"eps_N = 0.5\n", "abutments.gap_m: missing required key"},
  };
  for (const auto& c : cases) {
    const std::string message = ErrorOf(with(c.abutments));
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected: " << c.expected << "\n     got: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(MultiSpanModel, JointCountAndSkewMismatchAndSubstructureAreRejected) {
  const std::string decks =
      "[[deck]]\nm = 1e5\nL = 20\nW = 8\nskew_deg = 20\n"
      "[[deck]]\nm = 1e5\nL = 20\nW = 8\nskew_deg = 25\n";
  const std::string rest =
      "[abutments]\ngap_m = 0.02\n"
      "[excitation]\nkind = \"pulse\"\nshape = \"sine\"\na_g = 2\nw_g = 10\n";
  EXPECT_NE(ErrorOf(decks + rest).find("joint: needs 1 [[joint]] tables for 2 [[deck]] tables"),
            std::string::npos);
  EXPECT_NE(ErrorOf(decks + "[[joint]]\ngap_m = 0.01\n" + rest)
                .find("joint[0].gap_m: decks 0 and 1 must have the same skew_deg"),
            std::string::npos);
  EXPECT_NE(ErrorOf("[[deck]]\nm = 1e5\nL = 20\nW = 8\nskew_deg = 20\n" + rest +
                    "[substructure]\nw0 = 3\nW0 = 3\n")
                .find("substructure: not used with [[deck]] tables"),
            std::string::npos);
}

TEST(MultiSpanModel, GeneratorRejectsBadParametersByName) {
  MultiSpanSpec spec = ThreeSpanSpec();
  spec.span_lengths_m = {30.0, 40.0};
  try {
    BuildMultiSpanBridge(spec, "generator");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("multispan.span_lengths_m: must hold 1 or n_spans = 3"),
              std::string::npos)
        << e.what();
  }
  spec = ThreeSpanSpec();
  spec.n_spans = 0;
  EXPECT_THROW(BuildMultiSpanBridge(spec), InputError);
  spec = ThreeSpanSpec();
  spec.joint_gap_m = -0.1;
  try {
    BuildMultiSpanBridge(spec, "generator");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("joint[0].gap_m: must be >= 0"), std::string::npos)
        << e.what();
  }
}

TEST(MultiSpanModel, UnseatingMarginOfARotatedDeckIsSeatWidthMinusTheCornerTravel) {
  Body deck;
  deck.geometry = {30.0, 10.0, 0.0};
  // a = 0: end-line normal x; corner (15, 5) turned by theta moves 15 (cos - 1) - 5 sin along x.
  const double theta = 0.01;
  const double corner = std::abs(15.0 * (std::cos(theta) - 1.0) - 5.0 * std::sin(theta));
  EXPECT_NEAR(UnseatingMargin(deck, 0.5, {0.1, 0.3, theta}), 0.5 - 0.1 - corner, 1e-15);
}

}  // namespace
}  // namespace skewbridge::model::multispan_model_test
