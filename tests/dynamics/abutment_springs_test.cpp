// A model file's compliant abutments ([abutments] law = "compliant"): the run the file asks for
// (dynamics::RunUnderLaw on the parsed file) against SimulateCompliant called directly with
// springs built by hand, the three forms of the backfill against their formulas (Caltrans SDC 2.0
// for PyPBEE's Bridge_A worked by hand), the shear keys of [abutments.shear_keys] (the run with
// keys against SimulateCompliant with keys built by hand, Bridge_A's key capacity from its concrete
// and steel against Megally's formula in US units), and the one-line refusals of bad keys.
#include "solver/dynamics/abutment_springs.h"

#include <gtest/gtest.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/common/error.h"
#include "solver/dynamics/run.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"
#include "tests/dynamics/pilot_abutments.h"

namespace skewbridge::dynamics::abutment_springs_test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kKip_N = 4448.2216152605;
constexpr double kInch_m = 0.0254;
constexpr double kFoot_m = 0.3048;
constexpr double kKsi_Pa = 6.894757293168e6;

using testing::CompliantWith;
using testing::Examples;
using testing::Pilot;
using testing::ReadText;
using testing::Refusal;
using testing::WithAbutments;

TEST(AbutmentSprings, TheModelFilesRunIsSimulateCompliantWithSpringsBuiltByHand) {
  // The example file: Wilson and Elgamal's per-metre law over W / cos a, five springs per wall.
  const model::ModelFile file = model::ParseModelFile(Examples() + "/pilot-bridge-compliant.toml");
  ASSERT_TRUE(file.compliant.has_value());
  ASSERT_EQ(file.compliant->walls.size(), 2u);
  for (const model::CompliantWall& w : file.compliant->walls) EXPECT_EQ(w.springs, 5);
  // The pulse: one sine cycle of 1.2 g and 1 s along x (a pulse keeps the test independent of
  // the signal's reader; the law is what is compared).
  const records::PulseExcitation ex(records::PulseShape::kSine, 1.2 * 9.80665, 2.0 * kPi / 1.0,
                                    Eigen::Vector2d::UnitX());
  model::RunControl control = file.run;
  control.end_time_s = 3.0;
  control.output_interval_s = 0.0;
  const LawRun via_file = RunUnderLaw(file.model, file.compliant, ex, control);

  // By hand: the rigid model of the same deck with gaps 8 mm, its contacts P1 P2 and P3 P4 in
  // the builder's order, the wall's constants times W / cos a.
  model::DeckSpec deck = file.deck;
  deck.restitution = 0.5;
  deck.friction = 0.0;
  const model::Model rigid = model::BuildDeckModel(deck);
  const double wall_m = 19.36 / std::cos(20.0 * kPi / 180.0);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 0, 1, wall, 5, "+x");
  const std::vector<CompliantSpring> minus = WallSprings(rigid, 2, 3, wall, 5, "-x");
  springs.insert(springs.end(), minus.begin(), minus.end());
  const CompliantRunResult direct = SimulateCompliant(WithoutContacts(rigid), springs, ex, control);

  ASSERT_EQ(direct.run.status, RunStatus::kOk) << direct.run.message;
  ASSERT_EQ(via_file.run.status, RunStatus::kOk) << via_file.run.message;
  EXPECT_GT(direct.run.impacts, 0) << "the pulse must close a wall's springs";
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(via_file.run.max_abs_q(i), direct.run.max_abs_q(i)) << "dof " << i;
    EXPECT_EQ(via_file.run.q_end(i), direct.run.q_end(i)) << "dof " << i;
  }
  EXPECT_EQ(via_file.run.impacts, direct.run.impacts);
  EXPECT_EQ(via_file.run.max_travel_m(0), direct.run.max_travel_m(0));
  // The walls' maxima are the largest of their five springs'.
  ASSERT_EQ(via_file.walls.size(), 2u);
  EXPECT_EQ(via_file.walls[0].wall, "+x");
  EXPECT_EQ(via_file.walls[1].wall, "-x");
  for (int w = 0; w < 2; ++w) {
    double force = 0.0, deformation = 0.0;
    for (int j = 5 * w; j < 5 * w + 5; ++j) {
      force = std::max(force, direct.max_spring_force_N(j));
      deformation = std::max(deformation, direct.max_spring_deformation_m(j));
    }
    EXPECT_EQ(via_file.walls[w].spring_force_N, force);
    EXPECT_EQ(via_file.walls[w].deformation_m, deformation);
  }
  EXPECT_GT(via_file.walls[0].spring_force_N + via_file.walls[1].spring_force_N, 0.0);
  EXPECT_EQ(via_file.joint_dissipated_J, direct.joint_dissipated_J);

  // The rigid law of the same file without `law` is Run itself, bit for bit.
  const model::ModelFile rigid_file = model::ParseModelFile(Examples() + "/pilot-bridge.toml");
  ASSERT_FALSE(rigid_file.compliant.has_value());
  const LawRun rigid_run = RunUnderLaw(rigid_file.model, rigid_file.compliant, ex, control);
  const RunResult run = dynamics::Run(rigid_file.model, ex, control);
  EXPECT_TRUE(rigid_run.walls.empty());
  for (int i = 0; i < 3; ++i) EXPECT_EQ(rigid_run.run.max_abs_q(i), run.max_abs_q(i));
  EXPECT_EQ(rigid_run.run.impacts, run.impacts);
}

TEST(AbutmentSprings, TheFilesWallFrictionIsTheSpringsCoulombLaw) {
  // abutments.mu and stick_stiffness_Npm: every spring of both walls with the wall's mu and an
  // n-th of its stick stiffness; the run is SimulateCompliant with those springs, bit for bit.
  const std::string abutments =
      "[abutments]\nset = \"both\"\ngap_m = 0.008\nlaw = \"compliant\"\nmu = 0.25\n"
      "stick_stiffness_Npm = 2e9\n[abutments.backfill]\nform = \"hyperbolic-gap\"\n"
      "k_max_Npm_per_m = 20.3e6\nr_f = 0.7\nf_ult_N_per_m = 326e3\n";
  const model::ModelFile file = Pilot(abutments);
  ASSERT_TRUE(file.compliant.has_value());
  for (const model::CompliantWall& w : file.compliant->walls) {
    EXPECT_EQ(w.friction, 0.25);
    EXPECT_EQ(w.stick_stiffness_Npm, 2e9);
  }
  const std::vector<CompliantSpring> from_file = AbutmentSprings(file.model, *file.compliant);
  ASSERT_EQ(from_file.size(), 10u);
  for (const CompliantSpring& s : from_file) {
    EXPECT_EQ(s.mu, 0.25);
    EXPECT_EQ(s.k_t_N_per_m, 2e9 / 5);
  }
  const records::PulseExcitation ex(records::PulseShape::kSine, 1.2 * 9.80665, 2.0 * kPi / 1.0,
                                    Eigen::Vector2d(0.8, 0.6));
  model::RunControl control = file.run;
  control.end_time_s = 3.0;
  control.output_interval_s = 0.0;
  const LawRun via_file = RunUnderLaw(file.model, file.compliant, ex, control);
  model::DeckSpec deck = file.deck;
  deck.restitution = 0.5;
  deck.friction = 0.0;
  const model::Model rigid = model::BuildDeckModel(deck);
  const double wall_m = 19.36 / std::cos(20.0 * kPi / 180.0);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 0, 1, wall, 5, "+x");
  const std::vector<CompliantSpring> minus = WallSprings(rigid, 2, 3, wall, 5, "-x");
  springs.insert(springs.end(), minus.begin(), minus.end());
  for (CompliantSpring& s : springs) {
    s.mu = 0.25;
    s.k_t_N_per_m = 4e8;
  }
  const CompliantRunResult direct = SimulateCompliant(WithoutContacts(rigid), springs, ex, control);
  ASSERT_EQ(direct.run.status, RunStatus::kOk) << direct.run.message;
  EXPECT_GT(direct.run.energy.friction_J, 0.0) << "the pulse must slip a spring on its wall";
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(via_file.run.max_abs_q(i), direct.run.max_abs_q(i)) << "dof " << i;
    EXPECT_EQ(via_file.run.q_end(i), direct.run.q_end(i)) << "dof " << i;
  }
  EXPECT_EQ(via_file.run.energy.friction_J, direct.run.energy.friction_J);
  // Without mu the file's springs are frictionless.
  const model::ModelFile plain = model::ParseModelFile(Examples() + "/pilot-bridge-compliant.toml");
  for (const CompliantSpring& s : AbutmentSprings(plain.model, *plain.compliant)) {
    EXPECT_EQ(s.mu, 0.0);
    EXPECT_EQ(s.k_t_N_per_m, 0.0);
  }
}

TEST(AbutmentSprings, CaltransFormOfBridgeAMeetsTheFormulasByHand) {
  // PyPBEE's Bridge_A: backwall w = 27.13 ft, h = 4.64 ft, skew 33 deg. By hand (kip, in, ft):
  //   R_sk = exp(-33 / 45) = 0.480305,
  //   K = w (5.5 h + 20) R_sk = 27.13 x 45.52 x 0.480305 = 593.157 kip/in,
  //   P = w 5.5 h^2.5 / (1 + 2.37 h) R_sk = 27.13 x 255.07 / 11.9968 x 0.480305 = 277.051 kip,
  //   y_max = 0.05 h = 2.784 in, R_f = 1 - P / (K y_max) = 0.832228.
  const double w = 27.13, h = 4.64, r_sk = std::exp(-33.0 / 45.0);
  const double k_kip_per_in = w * (5.5 * h + 20.0) * r_sk;
  const double p_kip = w * 5.5 * std::pow(h, 2.5) / (1.0 + 2.37 * h) * r_sk;
  EXPECT_NEAR(k_kip_per_in, 593.157, 1e-3);
  EXPECT_NEAR(p_kip, 277.051, 1e-3);
  const std::string text = ReadText(Examples() + "/bridge-a.toml");
  const auto parse = [&](const std::string& reduction) {
    return model::ParseModelString(
        WithAbutments(text,
                      "[abutments]\nset = \"both\"\ngap_m = 0.030286\nlaw = \"compliant\"\n"
                      "springs = 4\n[abutments.backfill]\nform = \"caltrans\"\n"
                      "width_ft = 27.13\nheight_ft = 4.64\n" +
                          reduction + "\n"),
        "bridge-a.toml", Examples());
  };
  for (const bool reduced : {true, false}) {
    const model::ModelFile file = parse(reduced ? "" : "skew_reduction = \"none\"");
    ASSERT_TRUE(file.compliant);
    const std::vector<CompliantSpring> springs = AbutmentSprings(file.model, *file.compliant);
    ASSERT_EQ(springs.size(), 8u);
    const double r = reduced ? 1.0 : 1.0 / r_sk;
    for (int wall = 0; wall < 2; ++wall) {
      double k = 0.0, f = 0.0;
      for (int j = 4 * wall; j < 4 * wall + 4; ++j) {
        k += springs[j].backfill.k_max_N_per_m;
        f += springs[j].backfill.f_ult_N;
        EXPECT_NEAR(springs[j].backfill.r_f, 0.832228, 1e-6);
        EXPECT_EQ(springs[j].backfill.k_ur_N_per_m, springs[j].backfill.k_max_N_per_m);
      }
      EXPECT_NEAR(k, k_kip_per_in * r * kKip_N / kInch_m, 1e-9 * k);
      EXPECT_NEAR(f, p_kip * r * kKip_N, 1e-9 * f);
      // The envelope reaches the capacity at y_max = 0.05 h.
      joint::HyperbolicGap whole = springs[4 * wall].backfill;
      whole.k_max_N_per_m = k;
      whole.k_ur_N_per_m = k;
      whole.f_ult_N = f;
      EXPECT_NEAR(joint::EnvelopeForce_N(whole, 0.05 * h * kFoot_m), f, 1e-9 * f);
    }
    // The springs stand on the end lines from corner to corner, at the contacts' faces.
    EXPECT_EQ(springs[0].point_m, file.model.contact(0).point_m);
    EXPECT_EQ(springs[3].point_m, file.model.contact(1).point_m);
    EXPECT_EQ(springs[4].face.normal, file.model.contact(2).face.normal);
  }
}

TEST(AbutmentSprings, ShamsabadiAndPerWallFormsGiveTheirConstants) {
  // Shamsabadi with H: y_max = 0.05 H; K_max = 2 K50 - F_ult / y_max, R_f = 1 - F_ult /
  // (2 K50 y_max - F_ult). K50 = 170 MN/m, F_ult = 2 MN, H = 1.6 m: y_max = 0.08 m, K_max =
  // 315 MN/m, R_f = 1 - 2 / 25.2.
  const model::ModelFile file = Pilot(
      "[abutments]\nset = \"+x\"\ngap_m = 0.02\nlaw = \"compliant\"\nsprings = 2\n"
      "[abutments.backfill]\nform = \"shamsabadi\"\nk50_Npm = 170e6\nf_ult_N = 2e6\n"
      "height_m = 1.6\n");
  const std::vector<CompliantSpring> s = AbutmentSprings(file.model, *file.compliant);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_NEAR(2.0 * s[0].backfill.k_max_N_per_m, 315e6, 1e-3);
  EXPECT_NEAR(s[0].backfill.r_f, 1.0 - 2.0 / 25.2, 1e-14);
  EXPECT_NEAR(2.0 * s[1].backfill.f_ult_N, 2e6, 1e-6);
  // Per wall: the constants as written, halved over two springs; K_ur given.
  const model::ModelFile per_wall = Pilot(
      "[abutments]\nset = \"+x\"\ngap_m = 0.02\nlaw = \"compliant\"\nsprings = 2\n"
      "[abutments.backfill]\nform = \"hyperbolic-gap\"\nk_max_Npm = 4e8\nk_ur_Npm = 6e8\n"
      "r_f = 0.7\nf_ult_N = 6e6\n");
  const std::vector<CompliantSpring> p = AbutmentSprings(per_wall.model, *per_wall.compliant);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[1].backfill.k_max_N_per_m, 2e8);
  EXPECT_EQ(p[1].backfill.k_ur_N_per_m, 3e8);
  EXPECT_EQ(p[1].backfill.f_ult_N, 3e6);
  EXPECT_EQ(p[1].backfill.r_f, 0.7);
}

TEST(AbutmentSprings, BadKeysAreRefusedInOneLineNamingFileLineAndKey) {
  const std::string head = "[abutments]\nset = \"both\"\ngap_m = 0.03\nlaw = \"compliant\"\n";
  const auto refused = [&](const std::string& abutments, const std::string& expected) {
    const std::string message = Refusal(abutments);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  refused("[abutments]\nset = \"both\"\ngap_m = 0.03\nlaw = \"springy\"\n",
          "abutments.law: must be one of impact, compliant");
  refused(head, "abutments.backfill: missing required key");
  refused(head + "eps_N = 0.5\n[abutments.backfill]\nform = \"caltrans\"\n",
          "abutments.eps_N: belongs to law = \"impact\"");
  refused("[abutments]\nset = \"both\"\ngap_m = 0.03\nsprings = 5\n",
          "abutments.springs: belongs to law = \"compliant\"");
  refused(head + "springs = 1\n[abutments.backfill]\nform = \"caltrans\"\n",
          "m.toml:28: abutments.springs: must be a whole number of springs per wall from 2 to "
          "1000 (got 1)");
  refused(head + "[abutments.backfill]\nk_max_Npm = 1e8\n",
          "abutments.backfill.form: missing required key");
  refused(head + "[abutments.backfill]\nform = \"caltrans\"\nheight_m = 1.5\n",
          "abutments.backfill.width_m: missing required key (backwall width w, m (or width_ft");
  refused(head +
              "[abutments.backfill]\nform = \"caltrans\"\nwidth_m = 8\nwidth_ft = 27\n"
              "height_m = 1.5\n",
          "abutments.backfill.width_ft: give width_m or width_ft, not both");
  refused(head +
              "[abutments.backfill]\nform = \"caltrans\"\nwidth_m = 8\nheight_m = 1.5\n"
              "k50_Npm = 1e8\n",
          "abutments.backfill.k50_Npm: unknown key (allowed: form, width_m");
  refused(head +
              "[abutments.backfill]\nform = \"caltrans\"\nwidth_m = 8\nheight_m = 1.5\n"
              "skew_reduction = \"cos\"\n",
          "abutments.backfill.skew_reduction: must be one of exp, none");
  refused(head +
              "[abutments.backfill]\nform = \"hyperbolic-gap\"\nk_max_Npm = 1e8\n"
              "r_f = 0.7\nf_ult_N_per_m = 3e5\n",
          "abutments.backfill.k_max_Npm: give the constants per wall");
  refused(head +
              "[abutments.backfill]\nform = \"hyperbolic-gap\"\nk_max_Npm = 1e8\n"
              "r_f = 0\nf_ult_N = 3e5\n",
          "abutments.backfill.r_f: must be in (0, 1] (got 0)");
  refused(head +
              "[abutments.backfill]\nform = \"hyperbolic-gap\"\nk_max_Npm = 1e8\n"
              "r_f = 0.7\nf_ult_N = 3e5\ngap_m = 0.02\n",
          "m.toml:33: abutments.backfill.gap_m: the joint's gap is abutments.gap_m");
  refused(head +
              "[abutments.backfill]\nform = \"shamsabadi\"\nk50_Npm = 1e7\nf_ult_N = 2e6\n"
              "height_m = 1.6\n",
          "abutments.backfill.k50_Npm: K50 y_max must exceed F_ult");
  refused(head + "mu = -0.1\n[abutments.backfill]\nform = \"caltrans\"\n",
          "m.toml:28: abutments.mu: must be >= 0 (got -0.1)");
  refused(head + "mu = \"rough\"\n[abutments.backfill]\nform = \"caltrans\"\n",
          "m.toml:28: abutments.mu: must be a number");
  refused(head + "stick_stiffness_Npm = 1e9\n[abutments.backfill]\nform = \"caltrans\"\n",
          "m.toml:28: abutments.stick_stiffness_Npm: belongs to a wall with friction (mu > 0)");
  refused(head + "mu = 0.2\nstick_stiffness_Npm = 0\n[abutments.backfill]\nform = \"caltrans\"\n",
          "m.toml:29: abutments.stick_stiffness_Npm: must be a stiffness > 0 N/m");
  refused("[abutments]\nset = \"both\"\ngap_m = 0.03\nstick_stiffness_Npm = 1e9\n",
          "abutments.stick_stiffness_Npm: belongs to law = \"compliant\"");
  // A compliant model runs with the event-driven method only.
  const std::string text = WithAbutments(
      ReadText(Examples() + "/pilot-bridge.toml"),
      head + "[abutments.backfill]\nform = \"caltrans\"\nwidth_m = 8\nheight_m = 1.5\n");
  try {
    model::ParseModelString(text + "method = \"time-stepping\"\ntime_step_s = 1e-3\n", "m.toml",
                            Examples());
    ADD_FAILURE() << "time-stepping accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "m.toml:42: run.method: the compliant abutments (abutments.law = "
                  "\"compliant\") run with the event-driven method only"),
              std::string::npos)
        << e.what();
  }
}

TEST(AbutmentSprings, TheModelFilesKeysRunAsSimulateCompliantWithKeysBuiltByHand) {
  // Keys that engage, soften and break under the pulse: gap 5 mm, V_n = 0.5 MN at D3 = 2 mm,
  // V_res = 0.1 MN at 4 mm, broken at DD = 8 mm.
  const model::ModelFile file = Pilot(CompliantWith(
      "[abutments.shear_keys]\ngap_m = 0.005\nv_n_N = 0.5e6\nd3_m = 0.002\nv_res_N = 0.1e6\n"
      "d_res_m = 0.004\ndd_m = 0.008\n"));
  ASSERT_TRUE(file.compliant && file.compliant->walls.size() == 2);
  for (const model::CompliantWall& w : file.compliant->walls) {
    ASSERT_TRUE(w.shear_keys);
    EXPECT_FALSE(w.shear_keys->details);
  }
  // One sine cycle of 1.2 g and 1 s at 60 deg from x: the walls and the keys both engage.
  const double angle = 60.0 * kPi / 180.0;
  const records::PulseExcitation ex(records::PulseShape::kSine, 1.2 * 9.80665, 2.0 * kPi / 1.0,
                                    Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  model::RunControl control = file.run;
  control.end_time_s = 3.0;
  control.output_interval_s = 0.0;
  const LawRun via_file = RunUnderLaw(file.model, file.compliant, ex, control);

  // By hand: the walls' springs as in the test above, then the two keys of each abutment.
  model::DeckSpec deck = file.deck;
  const model::Model rigid = model::BuildDeckModel(deck);
  const double wall_m = 19.36 / std::cos(20.0 * kPi / 180.0);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  const joint::ShearKey key{0.005, 0.5e6, 0.002, 0.1e6, 0.004, 0.008};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 0, 1, wall, 5, "+x");
  for (const auto& more :
       {WallSprings(rigid, 2, 3, wall, 5, "-x"), AbutmentShearKeys(rigid, 0, 1, key, "+x"),
        AbutmentShearKeys(rigid, 2, 3, key, "-x")}) {
    springs.insert(springs.end(), more.begin(), more.end());
  }
  ASSERT_EQ(springs.size(), 14u);
  const CompliantRunResult direct = SimulateCompliant(WithoutContacts(rigid), springs, ex, control);
  ASSERT_EQ(direct.run.status, RunStatus::kOk) << direct.run.message;
  ASSERT_EQ(via_file.run.status, RunStatus::kOk) << via_file.run.message;
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(via_file.run.max_abs_q(i), direct.run.max_abs_q(i)) << "dof " << i;
    EXPECT_EQ(via_file.run.q_end(i), direct.run.q_end(i)) << "dof " << i;
  }
  EXPECT_EQ(via_file.run.impacts, direct.run.impacts);
  EXPECT_EQ(via_file.joint_dissipated_J, direct.joint_dissipated_J);
  // The walls' maxima are their backfill springs' alone; the keys are reported one by one.
  ASSERT_EQ(via_file.walls.size(), 2u);
  for (int w = 0; w < 2; ++w) {
    double force = 0.0, deformation = 0.0;
    for (int j = 5 * w; j < 5 * w + 5; ++j) {
      force = std::max(force, direct.max_spring_force_N(j));
      deformation = std::max(deformation, direct.max_spring_deformation_m(j));
    }
    EXPECT_EQ(via_file.walls[w].spring_force_N, force);
    EXPECT_EQ(via_file.walls[w].deformation_m, deformation);
  }
  ASSERT_EQ(via_file.keys.size(), 4u);
  int broken = 0;
  for (int k = 0; k < 4; ++k) {
    const KeyMaxima& m = via_file.keys[static_cast<std::size_t>(k)];
    EXPECT_EQ(m.name, springs[static_cast<std::size_t>(10 + k)].name);
    EXPECT_EQ(m.wall, k < 2 ? "+x" : "-x");
    EXPECT_EQ(m.force_N, direct.max_spring_force_N(10 + k));
    EXPECT_EQ(m.deformation_m, direct.max_spring_deformation_m(10 + k));
    if (std::isnan(direct.key_break_time_s(10 + k))) {
      EXPECT_EQ(m.break_time_s, std::numeric_limits<double>::infinity());
    } else {
      EXPECT_EQ(m.break_time_s, direct.key_break_time_s(10 + k));
      EXPECT_GE(m.deformation_m, key.dd_m);
      ++broken;
    }
    EXPECT_LE(m.force_N, key.v_n_N * (1.0 + 1e-6));
  }
  EXPECT_GT(broken, 0) << "the pulse must break a key";
  // A key that broke dissipated its backbone's whole area, 0.5 MN x 2 mm / 2 + (0.5 + 0.1) MN x
  // 2 mm / 2 + 0.1 MN x 4 mm / 2 = 1.3 kJ; the walls dissipate the rest.
  EXPECT_GT(via_file.joint_dissipated_J, broken * 1300.0);

  // The same file without the keys is the backfill alone: the keys change the run.
  const model::ModelFile bare = Pilot(CompliantWith(""));
  const LawRun without = RunUnderLaw(bare.model, bare.compliant, ex, control);
  EXPECT_TRUE(without.keys.empty());
  EXPECT_NE(without.run.max_abs_q(1), via_file.run.max_abs_q(1));
}

TEST(AbutmentSprings, BridgeAsKeyCapacityFromConcreteAndSteelMeetsMegallysFormulaByHand) {
  // PyPBEE's Bridge_A (examples/Bridge_A, nltha_params.tcl and generateAbutment.tcl at commit
  // 8b35e30): stem b = 43.2824 in, h = 74.7891 in, key base d = 46.2188 in, load height
  // a = 8.865 in; 12 #8 (0.9929 in) first horizontal ties, 4 22.225 mm first vertical ties,
  // 15.875 mm horizontal side bars at 17.73 in and 19.05 mm vertical side bars at 11.82 in on both
  // faces; f'c = 6.5 ksi, f_y = 69.144 ksi (osb_info_Bridge_A.py). Megally's sum in US units as
  // PyPBEE evaluates it, by hand (kip, in):
  //   V_c = 2.4 sqrt(6500) x 43.2824 x 74.7891 / 1000 = 626.351 kip,
  //   V_s = [T1 h + T2 d + 2 T_h h^2 / (2 s_h) + 2 T_v d^2 / (2 s_v)] / (h + a) = 812.244 kip,
  //   V_n = 1438.594 kip (docs/compliant.md §5: 1 438.6 kip).
  const double in = kInch_m, fy = 69.144 * kKsi_Pa;
  const auto bar = [&](double diameter_m) { return kPi / 4.0 * diameter_m * diameter_m * fy; };
  const double t1 = 12.0 * bar(0.9929 * in), t2 = 4.0 * bar(22.225e-3);
  const double th = bar(15.875e-3), tv = bar(19.05e-3);
  const double b_in = 43.2824, h_in = 74.7891, d_in = 46.2188, a_in = 8.865;
  const double sh_in = 17.73, sv_in = 11.82;
  const double vs_kip = (t1 * h_in + t2 * d_in + 2.0 * th * h_in * h_in / (2.0 * sh_in) +
                         2.0 * tv * d_in * d_in / (2.0 * sv_in)) /
                        (h_in + a_in) / kKip_N;
  const double vc_kip = 2.4 * std::sqrt(6500.0) * b_in * h_in / 1000.0;
  EXPECT_NEAR(vc_kip, 626.351, 1e-3);
  EXPECT_NEAR(vs_kip, 812.244, 1e-3);
  EXPECT_NEAR(vc_kip + vs_kip, 1438.594, 1e-3);

  const std::string details = fmt::format(
      "[abutments.shear_keys]\ngap_m = 0.0\nd3_m = {:.17g}\ndd_m = {:.17g}\n"
      "[abutments.shear_keys.details]\nf_c_MPa = {:.17g}\nstem_width_m = {:.17g}\n"
      "stem_height_m = {:.17g}\nkey_length_m = {:.17g}\nload_height_m = {:.17g}\n"
      "tie1_N = {:.17g}\ntie2_N = {:.17g}\nside_bar_h_N = {:.17g}\nside_bar_v_N = {:.17g}\n"
      "side_spacing_m = {:.17g}\nside_spacing_v_m = {:.17g}\n",
      1.234 * in, 5.428 * in, 6.5 * kKsi_Pa / 1e6, b_in * in, h_in * in, d_in * in, a_in * in, t1,
      t2, th, tv, sh_in * in, sv_in * in);
  const model::ModelFile file = Pilot(CompliantWith(details));
  ASSERT_TRUE(file.compliant && file.compliant->walls.front().shear_keys &&
              file.compliant->walls.front().shear_keys->details);
  const model::ShearKeysSpec& keys = *file.compliant->walls.front().shear_keys;
  const joint::ShearKeyDetails& k = *keys.details;
  // The steel's share is Megally's moment balance exactly; the concrete's is its SI form
  // 0.2 sqrt(f'c / MPa) MPa b h, 0.4 % above 2.4 sqrt(psi) psi (0.1993 MPa).
  EXPECT_NEAR(joint::ShearKeySteel_N(k) / kKip_N, vs_kip, 1e-9 * vs_kip);
  EXPECT_NEAR(joint::ShearKeyConcrete_N(k) / kKip_N / vc_kip, 1.0, 0.004);
  const double v_n_kip = keys.key.v_n_N / kKip_N;
  EXPECT_NEAR(v_n_kip / 1438.594, 1.0, 0.002) << v_n_kip;
  // The keys placed on the deck carry that capacity, two per abutment, after the walls' springs.
  const std::vector<CompliantSpring> springs = AbutmentSprings(file.model, *file.compliant);
  ASSERT_EQ(springs.size(), 14u);
  for (int j = 10; j < 14; ++j) {
    EXPECT_EQ(springs[static_cast<std::size_t>(j)].law, SpringLaw::kShearKey);
    EXPECT_EQ(springs[static_cast<std::size_t>(j)].key.v_n_N, v_n_kip * kKip_N);
    EXPECT_EQ(springs[static_cast<std::size_t>(j)].key.d_res_m, 5.428 * in);
  }
  EXPECT_EQ(springs[10].name, "+x.key+y");
  EXPECT_EQ(springs[13].name, "-x.key-y");
}

TEST(AbutmentSprings, BadShearKeysAreRefusedInOneLineNamingFileLineAndKey) {
  const auto refused = [&](const std::string& abutments, const std::string& expected) {
    const std::string message = Refusal(abutments);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  const std::string keys = "[abutments.shear_keys]\n";  // line 34 of the pilot's file
  refused(CompliantWith(keys + "gap_m = 0.01\nv_n_N = -2e6\nd3_m = 0.02\ndd_m = 0.1\n"),
          "m.toml:36: abutments.shear_keys.v_n_N: must be > 0 (got -2e+06)");
  refused(CompliantWith(keys + "gap_m = 0.01\nv_n_N = 2e6\nd3_m = 0.02\ndd_m = 0.02\n"),
          "m.toml:38: abutments.shear_keys.dd_m: must be > d3_m = 0.02 m (got 0.02)");
  refused(CompliantWith(keys + "gap_m = -0.01\nv_n_N = 2e6\nd3_m = 0.02\ndd_m = 0.1\n"),
          "m.toml:35: abutments.shear_keys.gap_m: must be >= 0 (got -0.01)");
  refused(CompliantWith(keys + "gap_m = 0.01\nv_n_N = 2e6\nd3_m = 0.02\ndd_m = 0.1\n"
                               "v_res_N = 3e6\nd_res_m = 0.05\n"),
          "m.toml:39: abutments.shear_keys.v_res_N: must be in [0, V_n = 2e+06 N] (got 3e+06)");
  refused(CompliantWith(keys + "gap_m = 0.01\nv_n_N = 2e6\nd3_m = 0.02\ndd_m = 0.1\n"
                               "v_res_N = 0.5e6\nd_res_m = 0.1\n"),
          "m.toml:40: abutments.shear_keys.d_res_m: must be in [d3_m, dd_m) = [0.02, 0.1) m");
  refused(CompliantWith(keys + "gap_m = 0.01\nv_n_N = 2e6\nd3_m = 0.02\ndd_m = 0.1\n"
                               "d_res_m = 0.05\n"),
          "m.toml:39: abutments.shear_keys.d_res_m: belongs to a residual force v_res_N > 0");
  refused(CompliantWith(keys + "gap_m = 0.01\nv_n = 2e6\nd3_m = 0.02\ndd_m = 0.1\n"),
          "m.toml:36: abutments.shear_keys.v_n: unknown key (allowed: gap_m, v_n_N, details, "
          "d3_m, v_res_N, d_res_m, dd_m); did you mean `v_n_N`?");
  refused(CompliantWith(keys + "gap_m = 0.01\nd3_m = 0.02\ndd_m = 0.1\n"),
          "m.toml:34: abutments.shear_keys.v_n_N: missing required key (the key's capacity V_n");
  refused(CompliantWith(keys + "gap_m = 0.01\nv_n_N = 2e6\nd3_m = 0.02\ndd_m = 0.1\n"
                               "[abutments.shear_keys.details]\nf_c_MPa = 30\n"),
          "m.toml:36: abutments.shear_keys.v_n_N: give the capacity v_n_N or the key's concrete "
          "and steel");
  refused(CompliantWith(keys + "gap_m = 0.01\nd3_m = 0.02\ndd_m = 0.1\n"
                               "[abutments.shear_keys.details]\nf_c_MPa = 30\n"
                               "stem_width_m = 1\nstem_height_m = 1.8\nkey_length_m = 1.2\n"
                               "tie1_N = -4e5\n"),
          "m.toml:43: abutments.shear_keys.details.tie1_N: must be >= 0 (got -4e+05)");
  refused(CompliantWith(keys + "gap_m = 0.01\nd3_m = 0.02\ndd_m = 0.1\n"
                               "[abutments.shear_keys.details]\nf_c_MPa = 30\n"
                               "stem_width_m = 1\nstem_height_m = 1.8\nkey_length_m = 1.2\n"
                               "side_bar_h_N = 1e5\n"),
          "m.toml:38: abutments.shear_keys.details.side_spacing_m: missing required key");
  // Keys belong to the compliant law.
  refused("[abutments]\nset = \"both\"\ngap_m = 0.03\n[abutments.shear_keys]\ngap_m = 0.01\n",
          "m.toml:27: abutments.shear_keys: belongs to law = \"compliant\" (the law here is "
          "\"impact\")");
}

TEST(AbutmentSprings, TheRowOfDecksRunIsSimulateCompliantWithJointSpringsBuiltByHand) {
  // docs/examples/three-span-compliant.toml: the walls on deck[2]'s +x end and deck[0]'s -x end,
  // joint[0] a spring-dashpot and joint[1] the per-metre hyperbolic law, each on deck[i]'s P1, P2
  // against deck[i + 1]'s end face (equal widths: the left deck's corners).
  const model::ModelFile file = model::ParseModelFile(Examples() + "/three-span-compliant.toml");
  ASSERT_TRUE(file.compliant.has_value());
  ASSERT_EQ(file.compliant->joints.size(), 2u);
  const model::Model& rigid = file.model;
  ASSERT_EQ(rigid.contact(6).name, "D2.P1");
  ASSERT_EQ(rigid.contact(0).name, "D0.P3");
  ASSERT_EQ(rigid.contact(2).name, "D0.P1/D1");
  ASSERT_EQ(rigid.contact(5).name, "D1.P2/D2");
  const double wall_m = 12.0 / std::cos(30.0 * kPi / 180.0);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 6, 7, wall, 5, "+x");
  for (const std::vector<CompliantSpring>& more :
       {WallSprings(rigid, 0, 1, wall, 5, "-x"), SpringDashpots(rigid, 2, 3, 1.0e9, 7.4e6, 5, "J0"),
        WallSprings(rigid, 4, 5, wall, 5, "J1")}) {
    springs.insert(springs.end(), more.begin(), more.end());
  }
  const records::PulseExcitation ex(records::PulseShape::kCosine, 0.4 * 9.80665, 2.0 * kPi / 0.6,
                                    Eigen::Vector2d::UnitX());
  model::RunControl control = file.run;
  control.output_interval_s = 0.0;
  const LawRun via_file = RunUnderLaw(rigid, file.compliant, ex, control);
  const CompliantRunResult direct = SimulateCompliant(WithoutContacts(rigid), springs, ex, control);
  ASSERT_EQ(direct.run.status, RunStatus::kOk) << direct.run.message;
  ASSERT_EQ(via_file.run.status, RunStatus::kOk) << via_file.run.message;
  EXPECT_TRUE(via_file.run.max_abs_q == direct.run.max_abs_q);
  EXPECT_TRUE(via_file.run.q_end == direct.run.q_end);
  EXPECT_EQ(via_file.run.impacts, direct.run.impacts);
  ASSERT_EQ(via_file.walls.size(), 2u);
  ASSERT_EQ(via_file.joints.size(), 2u);
  EXPECT_EQ(via_file.joints[0].wall, "J0");
  for (int g = 0; g < 4; ++g) {
    const WallMaxima& m = g < 2 ? via_file.walls[g] : via_file.joints[g - 2];
    double force = 0.0, deformation = 0.0;
    for (int j = 5 * g; j < 5 * g + 5; ++j) {
      force = std::max(force, direct.max_spring_force_N(j));
      deformation = std::max(deformation, direct.max_spring_deformation_m(j));
    }
    EXPECT_EQ(m.spring_force_N, force) << m.wall;
    EXPECT_EQ(m.deformation_m, deformation) << m.wall;
    EXPECT_GT(force, 1e5) << m.wall << ": the pulse closes every joint and wall";
  }
  // The responses a cube and a run file store: per joint its largest force and deformation.
  const std::vector<JointResponse> responses = JointResponses(*file.compliant, true);
  ASSERT_EQ(responses.size(), 8u);
  EXPECT_EQ(responses[4].name, "joint_force_j0");
  EXPECT_EQ(responses[7].name, "joint_def_j1");
  EXPECT_EQ(responses[7].value(via_file), via_file.joints[1].deformation_m);
  EXPECT_LT(std::abs(direct.run.energy.balance_error_J), 1e-6 * direct.run.energy.input_J);
}

TEST(AbutmentSprings, ARowOfDecksTakesALawPerJointAndRefusesTheRestInOneLine) {
  // A joint may keep the impact law beside compliant abutments, and compliant joints may sit
  // between rigid abutments (tests/dynamics/mixed_row_test.cpp runs such rows); what a joint's
  // table holds is refused in one line naming the field.
  const std::string text = ReadText(Examples() + "/three-span-compliant.toml");
  const auto refusal = [&](const std::string& from, const std::string& to,
                           const std::string& expected) {
    std::string changed = text;
    const std::size_t at = changed.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    changed.replace(at, from.size(), to);
    try {
      model::ParseModelString(changed, "three-span.toml", Examples());
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  const std::string joint1 = "gap_m = 0.04\nlaw = \"compliant\"\n\n[joint.backfill]";
  const std::string joint1_backfill =
      "form = \"hyperbolic-gap\"\nk_max_Npm_per_m = 20.3e6    # N/m per m of joint\nr_f = 0.7\n"
      "f_ult_N_per_m = 326e3       # N per m of joint\n";
  // joint[1] back to the impact law, the abutments compliant: a mixed row.
  std::string impact_joint = text;
  impact_joint.replace(impact_joint.find(joint1), joint1.size(),
                       "gap_m = 0.04\nlaw = \"impact\"\n");
  impact_joint.erase(impact_joint.find(joint1_backfill), joint1_backfill.size());
  const model::ModelFile mixed =
      model::ParseModelString(impact_joint, "three-span.toml", Examples());
  ASSERT_TRUE(mixed.compliant.has_value());
  EXPECT_TRUE(mixed.compliant->Mixed());
  ASSERT_EQ(mixed.compliant->joints.size(), 2u);
  EXPECT_EQ(mixed.compliant->joints[0].law, model::JointLaw::kCompliant);
  EXPECT_EQ(mixed.compliant->joints[1].law, model::JointLaw::kImpact);
  EXPECT_EQ(mixed.compliant->walls[0].law, model::JointLaw::kCompliant);
  // The abutments back to the impact law, the joints compliant: both walls rigid.
  const std::string abutments =
      "gap_m = 0.05\nlaw = \"compliant\"\nsprings = 5\n\n[abutments.backfill]\nform = "
      "\"hyperbolic-gap\"\nk_max_Npm_per_m = 20.3e6\nr_f = 0.7\nf_ult_N_per_m = 326e3\n";
  std::string rigid_walls = text;
  rigid_walls.replace(rigid_walls.find(abutments), abutments.size(), "gap_m = 0.05\nmu = 0.1\n");
  const model::ModelFile joints =
      model::ParseModelString(rigid_walls, "three-span.toml", Examples());
  ASSERT_TRUE(joints.compliant.has_value());
  EXPECT_TRUE(joints.compliant->Mixed());
  for (const model::CompliantWall& w : joints.compliant->walls) {
    EXPECT_EQ(w.law, model::JointLaw::kImpact);
    EXPECT_EQ(w.friction, 0.1);
  }
  EXPECT_EQ(joints.compliant->joints[1].law, model::JointLaw::kCompliant);
  // A joint's law once: a backfill or a spring-dashpot; eps_N belongs to the impact law.
  refusal("c_Nspm = 7.4e6       # N s/m\n",
          "c_Nspm = 7.4e6\n\n[joint.backfill]\nform = \"hyperbolic-gap\"\nk_max_Npm = 1e9\nr_f = "
          "0.7\nf_ult_N = 1e6\n",
          "three-span.toml:32: joint[0].spring_dashpot: give the joint's law once");
  refusal(
      "springs = 5\n\n[joint.spring_dashpot]", "springs = 5\neps_N = 0.5\n\n[joint.spring_dashpot]",
      "three-span.toml:31: joint[0].eps_N: unknown key (allowed: gap_m, law, springs, backfill, "
      "spring_dashpot); it is a key of law = \"impact\"");
  refusal("k_Npm = 1.0e9", "k_Npm = -1.0e9", "joint[0].spring_dashpot.k_Npm: must be > 0");
}

}  // namespace
}  // namespace skewbridge::dynamics::abutment_springs_test
