// A compliant law per wall ([abutments.backfill."+x"], [abutments.shear_keys."-x"], `springs`
// per wall; docs/model-format.md, "a law per wall"): one table and the same table per wall give
// the same run bit for bit; a half turn of the parallelogram deck in plan swaps the walls' laws
// and turns the ground motion (law A at +x and B at -x under a_g is B at +x and A at -x under
// -a_g, with x and y turned); per-wall tables that do not fit the set are refused in one line;
// a row of decks takes per-wall tables as a single deck does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/abutment_springs.h"
#include "solver/model/model_file.h"
#include "tests/dynamics/pilot_abutments.h"

namespace skewbridge::dynamics::abutment_walls_test {
namespace {

using testing::CompliantWith;
using testing::Examples;
using testing::Pilot;
using testing::ReadText;
using testing::Refusal;
using testing::WithAbutments;

// The [abutments] of the pilot with a backfill and keys per wall: `plus` and `minus` the walls'
// tables' bodies (the backfill's keys, then optionally a keys table's header and keys).
std::string PerWall(const std::string& head, const std::string& plus, const std::string& minus) {
  return "[abutments]\nset = \"both\"\nlaw = \"compliant\"\n" + head +
         "[abutments.backfill.\"+x\"]\n" + plus + "[abutments.backfill.\"-x\"]\n" + minus;
}

// Wilson and Elgamal's backfill per metre of wall, and a Caltrans wall of a taller backwall.
constexpr const char* kWilson =
    "form = \"hyperbolic-gap\"\nk_max_Npm_per_m = 20.3e6\nr_f = 0.7\nf_ult_N_per_m = 326e3\n";
constexpr const char* kCaltrans = "form = \"caltrans\"\nwidth_m = 19.36\nheight_m = 2.5\n";
constexpr const char* kKeys =
    "gap_m = 0.005\nv_n_N = 0.5e6\nd3_m = 0.002\nv_res_N = 0.1e6\n"
    "d_res_m = 0.004\ndd_m = 0.008\n";

// Every number a run under the law reports, compared bit for bit.
void ExpectSameRun(const LawRun& a, const LawRun& b) {
  ASSERT_EQ(a.run.status, RunStatus::kOk) << a.run.message;
  ASSERT_EQ(b.run.status, RunStatus::kOk) << b.run.message;
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.run.max_abs_q(i), b.run.max_abs_q(i)) << "dof " << i;
    EXPECT_EQ(a.run.time_of_max_s(i), b.run.time_of_max_s(i)) << "dof " << i;
    EXPECT_EQ(a.run.q_end(i), b.run.q_end(i)) << "dof " << i;
    EXPECT_EQ(a.run.u_end(i), b.run.u_end(i)) << "dof " << i;
  }
  EXPECT_EQ(a.run.impacts, b.run.impacts);
  EXPECT_EQ(a.run.rk_steps, b.run.rk_steps);
  EXPECT_EQ(a.run.free_steps, b.run.free_steps);
  EXPECT_EQ(a.joint_stored_J, b.joint_stored_J);
  EXPECT_EQ(a.joint_dissipated_J, b.joint_dissipated_J);
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t w = 0; w < a.walls.size(); ++w) {
    EXPECT_EQ(a.walls[w].spring_force_N, b.walls[w].spring_force_N);
    EXPECT_EQ(a.walls[w].deformation_m, b.walls[w].deformation_m);
  }
  ASSERT_EQ(a.keys.size(), b.keys.size());
  for (std::size_t k = 0; k < a.keys.size(); ++k) {
    EXPECT_EQ(a.keys[k].name, b.keys[k].name);
    EXPECT_EQ(a.keys[k].force_N, b.keys[k].force_N);
    EXPECT_EQ(a.keys[k].break_time_s, b.keys[k].break_time_s);
  }
  ASSERT_EQ(a.springs.size(), b.springs.size());
  for (std::size_t s = 0; s < a.springs.size(); ++s) {
    EXPECT_EQ(a.springs[s].name, b.springs[s].name);
    EXPECT_EQ(a.springs[s].force_N, b.springs[s].force_N);
    EXPECT_EQ(a.springs[s].deformation_m, b.springs[s].deformation_m);
    EXPECT_EQ(a.springs[s].wall_slip_m, b.springs[s].wall_slip_m);
  }
}

// One sine cycle of 1.2 g and 1 s at `angle_deg` from x, times `sign`: walls and keys engage.
records::PulseExcitation Cycle(double angle_deg, double sign = 1.0) {
  const double angle = angle_deg * std::numbers::pi / 180.0;
  return records::PulseExcitation(records::PulseShape::kSine, 1.2 * 9.80665,
                                  2.0 * std::numbers::pi / 1.0,
                                  sign * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
}

model::RunControl ThreeSeconds(const model::ModelFile& file) {
  model::RunControl control = file.run;
  control.end_time_s = 3.0;
  control.output_interval_s = 0.0;
  return control;
}

TEST(AbutmentWalls, OneTableAndTheSameTablePerWallGiveTheSameRunBitForBit) {
  // The same backfill, springs and keys for both walls, once as one table and once per wall.
  const model::ModelFile one =
      Pilot(CompliantWith(std::string("[abutments.shear_keys]\n") + kKeys));
  const model::ModelFile per =
      Pilot(PerWall("gap_m = 0.008\nsprings = { \"+x\" = 5, \"-x\" = 5 }\n", kWilson,
                    std::string(kWilson) + "[abutments.shear_keys.\"+x\"]\n" + kKeys +
                        "[abutments.shear_keys.\"-x\"]\n" + kKeys));
  ASSERT_TRUE(one.compliant && per.compliant);
  ASSERT_EQ(per.compliant->walls.size(), 2u);
  const records::PulseExcitation ex = Cycle(60.0);
  const LawRun a = RunUnderLaw(one.model, one.compliant, ex, ThreeSeconds(one));
  const LawRun b = RunUnderLaw(per.model, per.compliant, ex, ThreeSeconds(per));
  ExpectSameRun(a, b);
  ASSERT_EQ(a.keys.size(), 4u);
  EXPECT_GT(a.walls[1].spring_force_N, 0.0) << "the -x wall must be struck";
  // set = "+x": one table and a "+x" table alike.
  const model::ModelFile plus_one = Pilot(
      "[abutments]\nset = \"+x\"\ngap_m = 0.008\nlaw = \"compliant\"\n[abutments.backfill]\n" +
      std::string(kCaltrans));
  const model::ModelFile plus_per = Pilot(
      "[abutments]\nset = \"+x\"\ngap_m = 0.008\nlaw = \"compliant\"\nsprings = { \"+x\" = 5 }\n"
      "[abutments.backfill.\"+x\"]\n" +
      std::string(kCaltrans));
  ASSERT_EQ(plus_per.compliant->walls.size(), 1u);
  ExpectSameRun(RunUnderLaw(plus_one.model, plus_one.compliant, ex, ThreeSeconds(plus_one)),
                RunUnderLaw(plus_per.model, plus_per.compliant, ex, ThreeSeconds(plus_per)));
}

TEST(AbutmentWalls, OneFrictionAndTheSameFrictionPerWallGiveTheSameRunBitForBit) {
  // mu and stick_stiffness_Npm given once for both walls and given per wall.
  const std::string keys = std::string("[abutments.shear_keys]\n") + kKeys;
  std::string one_text = CompliantWith(keys);
  std::string per_text = one_text;
  const std::string law = "law = \"compliant\"\n";
  one_text.replace(one_text.find(law), law.size(), law + "mu = 0.3\nstick_stiffness_Npm = 2e9\n");
  per_text.replace(per_text.find(law), law.size(),
                   law +
                       "mu = { \"+x\" = 0.3, \"-x\" = 0.3 }\n"
                       "stick_stiffness_Npm = { \"+x\" = 2e9, \"-x\" = 2e9 }\n");
  const model::ModelFile one = Pilot(one_text);
  const model::ModelFile per = Pilot(per_text);
  const records::PulseExcitation ex = Cycle(60.0);
  const LawRun a = RunUnderLaw(one.model, one.compliant, ex, ThreeSeconds(one));
  ExpectSameRun(a, RunUnderLaw(per.model, per.compliant, ex, ThreeSeconds(per)));
  double slip = 0.0;
  for (const SpringMaxima& s : a.springs) slip += s.wall_slip_m;
  EXPECT_GT(slip, 0.0) << "the walls must slip";

  // Unlike walls: each wall's springs carry its own mu and an n-th of its own stick stiffness
  // (a wall left out of the stick stiffness table: 0, its K_max).
  per_text = CompliantWith(keys);
  per_text.replace(per_text.find(law), law.size(),
                   law +
                       "mu = { \"+x\" = 0.3, \"-x\" = 0.1 }\n"
                       "stick_stiffness_Npm = { \"+x\" = 2e9 }\nsprings = { \"+x\" = 5, "
                       "\"-x\" = 4 }\n");
  per_text.erase(per_text.find("springs = 5\n"), 12);
  const model::ModelFile unlike = Pilot(per_text);
  ASSERT_EQ(unlike.compliant->walls.size(), 2u);
  EXPECT_EQ(unlike.compliant->walls[0].friction, 0.3);
  EXPECT_EQ(unlike.compliant->walls[1].friction, 0.1);
  EXPECT_EQ(unlike.compliant->walls[0].stick_stiffness_Npm, 2e9);
  EXPECT_EQ(unlike.compliant->walls[1].stick_stiffness_Npm, 0.0);
  const std::vector<CompliantSpring> springs = AbutmentSprings(unlike.model, *unlike.compliant);
  ASSERT_EQ(springs.size(), 13u);  // 5 + 4 backfill springs, then 4 keys without friction
  for (std::size_t k = 0; k < springs.size(); ++k) {
    const bool plus = k < 5, minus = k >= 5 && k < 9;
    EXPECT_EQ(springs[k].mu, plus ? 0.3 : minus ? 0.1 : 0.0) << springs[k].name;
    EXPECT_EQ(springs[k].k_t_N_per_m, plus ? 2e9 / 5 : 0.0) << springs[k].name;
  }
}

TEST(AbutmentWalls, AFrictionPerWallThatDoesNotFitIsRefusedInOneLine) {
  const auto refused = [&](const std::string& abutments, const std::string& expected) {
    const std::string message = Refusal(abutments);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  const std::string walls = std::string("[abutments.backfill]\n") + kCaltrans;
  const std::string head = "[abutments]\nset = \"both\"\ngap_m = 0.008\nlaw = \"compliant\"\n";
  // mu per wall: both walls of the set, each >= 0, no other key.
  refused(head + "mu = { \"+x\" = 0.2 }\n" + walls,
          "m.toml:28: abutments.mu.\"-x\": missing required key (the Coulomb friction coefficient "
          "of the -x wall, >= 0)");
  refused(head + "mu = { \"+x\" = 0.2, \"-x\" = -0.1 }\n" + walls,
          "m.toml:28: abutments.mu.\"-x\": must be >= 0 (got -0.1)");
  refused(head + "mu = { \"+x\" = 0.2, \"-x\" = \"rough\" }\n" + walls,
          "m.toml:28: abutments.mu.\"-x\": must be a number");
  refused(head + "mu = { \"+x\" = 0.2, \"-x\" = 0.1, \"+y\" = 0.1 }\n" + walls,
          "m.toml:28: abutments.mu.\"+y\": unknown key (allowed: \"+x\", \"-x\")");
  refused(
      "[abutments]\nset = \"+x\"\ngap_m = 0.008\nlaw = \"compliant\"\n"
      "mu = { \"+x\" = 0.2, \"-x\" = 0.1 }\n" +
          walls,
      "m.toml:28: abutments.mu.\"-x\": no -x wall with set = \"+x\" (allowed: \"+x\")");
  // A wall's stick stiffness belongs to a wall with friction; one for both to either wall.
  refused(
      head + "mu = { \"+x\" = 0.2, \"-x\" = 0 }\nstick_stiffness_Npm = { \"-x\" = 1e9 }\n" + walls,
      "m.toml:29: abutments.stick_stiffness_Npm.\"-x\": belongs to a wall with friction (the "
      "-x wall's mu is 0; give it mu > 0 or omit its stick stiffness)");
  refused(head + "mu = { \"+x\" = 0, \"-x\" = 0 }\nstick_stiffness_Npm = 1e9\n" + walls,
          "m.toml:29: abutments.stick_stiffness_Npm: belongs to a wall with friction (mu > 0)");
  refused(head + "mu = 0.2\nstick_stiffness_Npm = { \"+x\" = 1e9, \"-x\" = -1 }\n" + walls,
          "m.toml:29: abutments.stick_stiffness_Npm.\"-x\": must be a stiffness > 0 N/m");
  EXPECT_EQ(
      Refusal(head + "mu = { \"+x\" = 0.2, \"-x\" = 0 }\nstick_stiffness_Npm = 1e9\n" + walls),
      "(accepted)");
  // The rigid law's mu is one number (or per corner).
  refused("[abutments]\nset = \"both\"\ngap_m = 0.008\nmu = { \"+x\" = 0.2, \"-x\" = 0.1 }\n",
          "m.toml:27: abutments.mu: a friction per wall belongs to law = \"compliant\"; with law = "
          "\"impact\" give one number, or one per corner in [abutments.contacts.P1] (mu)");
}

TEST(AbutmentWalls, PerWallTablesThatDoNotFitTheSetAreRefusedInOneLine) {
  const auto refused = [&](const std::string& abutments, const std::string& expected) {
    const std::string message = Refusal(abutments);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  const std::string plus = std::string("[abutments.backfill.\"+x\"]\n") + kCaltrans;
  const std::string minus = std::string("[abutments.backfill.\"-x\"]\n") + kCaltrans;
  const std::string head = "[abutments]\nset = \"both\"\ngap_m = 0.008\nlaw = \"compliant\"\n";
  // A key for both walls beside a wall's own table ([abutments] is line 24 of the pilot's file).
  refused(head + "[abutments.backfill]\n" + kCaltrans + minus,
          "m.toml:29: abutments.backfill.form: a key for both walls beside the per-wall table "
          "[abutments.backfill.\"-x\"]: give one table for both walls or one per wall, not both");
  // A wall's table missing with set = "both"; a -x wall's table with set = "+x".
  refused(head + plus,
          "m.toml:28: abutments.backfill.\"-x\": missing required key (the -x wall's backfill: a "
          "table [abutments.backfill.\"-x\"])");
  refused("[abutments]\nset = \"+x\"\ngap_m = 0.008\nlaw = \"compliant\"\n" + plus + minus,
          "m.toml:32: abutments.backfill.\"-x\": no -x wall with set = \"+x\" (allowed: \"+x\")");
  // A wall's table is read as a whole table of its own, with its path.
  refused(head + plus + "[abutments.backfill.\"-x\"]\nform = \"caltrans\"\nwidth_m = 19\n",
          "m.toml:32: abutments.backfill.\"-x\".height_m: missing required key");
  refused(head + plus + minus +
              "[abutments.shear_keys.\"-x\"]\ngap_m = 0.01\nv_n_N = 1e6\n"
              "d3_m = 0.01\ndd_m = 0.001\n",
          "m.toml:40: abutments.shear_keys.\"-x\".dd_m: must be > d3_m = 0.01 m (got 0.001)");
  refused(head + plus + minus + "[abutments.shear_keys]\ngap_m = 0.01\n" +
              "[abutments.shear_keys.\"+x\"]\n" + kKeys,
          "m.toml:37: abutments.shear_keys.gap_m: a key for both walls beside the per-wall table "
          "[abutments.shear_keys.\"+x\"]");
  // springs per wall: both walls, whole numbers, the set's walls only.
  refused(head + "springs = { \"+x\" = 5 }\n" + plus + minus,
          "m.toml:28: abutments.springs.\"-x\": missing required key (springs along the -x wall");
  refused(head + "springs = { \"+x\" = 5, \"-x\" = 1.5 }\n" + plus + minus,
          "m.toml:28: abutments.springs.\"-x\": must be a whole number of springs per wall from 2 "
          "to 1000 (got 1.5)");
  refused(
      "[abutments]\nset = \"+x\"\ngap_m = 0.008\nlaw = \"compliant\"\n"
      "springs = { \"+x\" = 5, \"-x\" = 4 }\n" +
          plus,
      "m.toml:28: abutments.springs.\"-x\": no -x wall with set = \"+x\" (allowed: \"+x\")");
}

// The pilot bridge with its centre of rigidity at the mass centre (K without x-theta and y-theta
// coupling: unchanged by a half turn in plan) and the given [abutments].
model::ModelFile CentredPilot(const std::string& abutments) {
  std::string text = WithAbutments(ReadText(Examples() + "/pilot-bridge.toml"), abutments);
  for (const char* key : {"e_x = ", "e_y = "}) {
    const std::size_t at = text.find(key);
    EXPECT_NE(at, std::string::npos) << key;
    text.replace(at, text.find('\n', at) - at, std::string(key) + "0.0");
  }
  return model::ParseModelString(text, "m.toml", Examples());
}

// [abutments] with law `plus` at +x and `minus` at -x: each a gap, a springs count and its
// backfill table's body, optionally keys, a wall friction mu and a stick stiffness k_t (N/m).
struct WallLaw {
  std::string gap_m, springs, backfill, keys, mu = "", k_t = "";
};
std::string TwoWalls(const WallLaw& plus, const WallLaw& minus) {
  std::string text =
      "[abutments]\nset = \"both\"\nlaw = \"compliant\"\ngap_m = { \"+x\" = " + plus.gap_m +
      ", \"-x\" = " + minus.gap_m + " }\nsprings = { \"+x\" = " + plus.springs +
      ", \"-x\" = " + minus.springs + " }\n";
  if (!plus.mu.empty() || !minus.mu.empty()) {
    text += "mu = { \"+x\" = " + (plus.mu.empty() ? "0" : plus.mu) +
            ", \"-x\" = " + (minus.mu.empty() ? "0" : minus.mu) + " }\n";
  }
  if (!plus.k_t.empty() || !minus.k_t.empty()) {  // a wall without k_t: its K_max
    text += "stick_stiffness_Npm = { ";
    if (!plus.k_t.empty()) text += "\"+x\" = " + plus.k_t + (minus.k_t.empty() ? " " : ", ");
    if (!minus.k_t.empty()) text += "\"-x\" = " + minus.k_t + " ";
    text += "}\n";
  }
  text += "[abutments.backfill.\"+x\"]\n" + plus.backfill + "[abutments.backfill.\"-x\"]\n" +
          minus.backfill;
  if (!plus.keys.empty()) text += "[abutments.shear_keys.\"+x\"]\n" + plus.keys;
  if (!minus.keys.empty()) text += "[abutments.shear_keys.\"-x\"]\n" + minus.keys;
  return text;
}

// The deck is a parallelogram: a half turn about its mass centre maps P1 <-> P3, P2 <-> P4, the
// +x wall onto the -x wall and (x, y, theta) onto (-x, -y, theta). With K and C unchanged by it,
// law A at +x and B at -x under a_g(t) moves as B at +x and A at -x under -a_g(t), turned: checked
// for `a` of 5 springs with keys at +x and `b` of 7 springs without keys at -x, every number
// compared to 1e-10. The run of A at +x and B at -x is left in `out`.
void ExpectAHalfTurnSwapsTheWalls(const WallLaw& a, const WallLaw& b, LawRun* out = nullptr) {
  const model::ModelFile ab = CentredPilot(TwoWalls(a, b));
  const model::ModelFile ba = CentredPilot(TwoWalls(b, a));
  const LawRun run = RunUnderLaw(ab.model, ab.compliant, Cycle(60.0), ThreeSeconds(ab));
  const LawRun turned = RunUnderLaw(ba.model, ba.compliant, Cycle(60.0, -1.0), ThreeSeconds(ba));
  ASSERT_EQ(run.run.status, RunStatus::kOk) << run.run.message;
  ASSERT_EQ(turned.run.status, RunStatus::kOk) << turned.run.message;
  const double sign[3] = {-1.0, -1.0, 1.0};
  double worst = 0.0;  // the largest relative difference, over every number compared
  const auto near = [&](double got, double want, const std::string& what) {
    const double scale = std::max(std::abs(want), 1e-300);
    worst = std::max(worst, std::abs(got - want) / scale);
    EXPECT_NEAR(got, want, 1e-10 * scale) << what;
  };
  for (int i = 0; i < 3; ++i) {
    near(turned.run.max_abs_q(i), run.run.max_abs_q(i), "max |q| " + std::to_string(i));
    near(turned.run.time_of_max_s(i), run.run.time_of_max_s(i), "t max " + std::to_string(i));
    near(turned.run.q_end(i), sign[i] * run.run.q_end(i), "q_end " + std::to_string(i));
  }
  EXPECT_EQ(turned.run.impacts, run.run.impacts);
  near(turned.joint_dissipated_J, run.joint_dissipated_J, "dissipated");
  // The walls swap: the turned run's +x wall is the run's -x wall, spring k for spring k.
  ASSERT_EQ(run.walls.size(), 2u);
  ASSERT_EQ(turned.walls.size(), 2u);
  for (std::size_t w = 0; w < 2; ++w) {
    near(turned.walls[w].spring_force_N, run.walls[1 - w].spring_force_N, "wall force");
    near(turned.walls[w].deformation_m, run.walls[1 - w].deformation_m, "wall deformation");
  }
  ASSERT_EQ(run.springs.size(), 12u);
  ASSERT_EQ(turned.springs.size(), 12u);
  for (std::size_t k = 0; k < 5; ++k) {  // A: run's +x.k, turned's -x.k (after B's seven)
    near(turned.springs[7 + k].force_N, run.springs[k].force_N, run.springs[k].name);
  }
  for (std::size_t k = 0; k < 7; ++k) {  // B: run's -x.k, turned's +x.k
    near(turned.springs[k].force_N, run.springs[5 + k].force_N, run.springs[5 + k].name);
  }
  // The keys move with A: the +x abutment's +y key onto the -x abutment's -y key.
  ASSERT_EQ(run.keys.size(), 2u);
  ASSERT_EQ(turned.keys.size(), 2u);
  EXPECT_EQ(turned.keys[0].name, "-x.key+y");
  near(turned.keys[0].force_N, run.keys[1].force_N, "key -y");
  near(turned.keys[1].force_N, run.keys[0].force_N, "key +y");
  EXPECT_GT(run.keys[0].force_N, 0.0);
  EXPECT_GT(run.walls[1].spring_force_N, 0.0);
  // Not a symmetry of one model alone: the unlike walls move the deck unlike the turned ground.
  const LawRun same_model =
      RunUnderLaw(ab.model, ab.compliant, Cycle(60.0, -1.0), ThreeSeconds(ab));
  EXPECT_GT(std::abs(same_model.run.max_abs_q(0) / run.run.max_abs_q(0) - 1.0), 1e-3);
  // Each spring's slip along its wall (0 without friction) moves with its wall's law.
  for (std::size_t k = 0; k < 5; ++k) {
    near(turned.springs[7 + k].wall_slip_m, run.springs[k].wall_slip_m, run.springs[k].name);
  }
  for (std::size_t k = 0; k < 7; ++k) {
    near(turned.springs[k].wall_slip_m, run.springs[5 + k].wall_slip_m, run.springs[5 + k].name);
  }
  // The arithmetic is mirrored but not in the same order (the springs' forces are summed +x wall
  // first), so the check is relative; on the release build the two runs agree bit for bit.
  EXPECT_LE(worst, 1e-10);
  if (out != nullptr) *out = run;
}

TEST(AbutmentWalls, AHalfTurnInPlanSwapsTheWallsLawsAndTurnsTheGroundMotion) {
  // A: Wilson and Elgamal, 5 springs, keys, gap 8 mm; B: Caltrans h = 2.5 m, 7 springs, 12 mm.
  ExpectAHalfTurnSwapsTheWalls({"0.008", "5", kWilson, kKeys}, {"0.012", "7", kCaltrans, ""});
}

TEST(AbutmentWalls, AHalfTurnInPlanSwapsTheWallsFrictionWithTheirLaws) {
  // As above with a friction per wall: A's mu = 0.3 with a stick stiffness of 2e9 N/m, B's
  // mu = 0.1 with its K_max. Both walls slip, each by its own law.
  LawRun run;
  ExpectAHalfTurnSwapsTheWalls({"0.008", "5", kWilson, kKeys, "0.3", "2e9"},
                               {"0.012", "7", kCaltrans, "", "0.1", ""}, &run);
  ASSERT_EQ(run.springs.size(), 12u);
  double slip_plus = 0.0, slip_minus = 0.0;
  for (const SpringMaxima& s : run.springs) {
    (s.name.rfind("+x.", 0) == 0 ? slip_plus : slip_minus) += s.wall_slip_m;
  }
  EXPECT_GT(slip_plus, 0.0);
  EXPECT_GT(slip_minus, 0.0);
}

TEST(AbutmentWalls, ARowOfDecksTakesALawPerWallAsTheSingleDeckDoes) {
  // docs/examples/three-span-compliant.toml: the +x wall on deck[2]'s end, the -x wall on
  // deck[0]'s. Its one backfill table given per wall runs the same bits; a -x law of half the
  // per-metre constants lands on deck[0]'s springs only.
  const std::string text = ReadText(Examples() + "/three-span-compliant.toml");
  const std::string head = "[abutments.backfill]\n";
  const std::size_t begin = text.find(head);
  const std::size_t end = text.find("\n\n", begin);
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  const std::string body = text.substr(begin + head.size(), end + 1 - begin - head.size());
  const auto with = [&](const std::string& plus, const std::string& minus) {
    return model::ParseModelString(text.substr(0, begin) + "[abutments.backfill.\"+x\"]\n" + plus +
                                       "[abutments.backfill.\"-x\"]\n" + minus + text.substr(end),
                                   "s.toml", Examples());
  };
  const model::ModelFile one = model::ParseModelString(text, "s.toml", Examples());
  const model::ModelFile per = with(body, body);
  const records::PulseExcitation ex(records::PulseShape::kCosine, 0.4 * 9.80665,
                                    2.0 * std::numbers::pi / 0.6, Eigen::Vector2d::UnitX());
  model::RunControl control = one.run;
  control.output_interval_s = 0.0;
  const LawRun a = RunUnderLaw(one.model, one.compliant, ex, control);
  const LawRun b = RunUnderLaw(per.model, per.compliant, ex, control);
  ExpectSameRun(a, b);
  EXPECT_TRUE(a.run.max_abs_q == b.run.max_abs_q);  // every deck's
  EXPECT_TRUE(a.run.q_end == b.run.q_end);
  ASSERT_EQ(a.joints.size(), 2u);
  EXPECT_GT(a.walls[1].spring_force_N, 0.0) << "the -x wall must be struck";

  std::string half = body;
  for (const char* key : {"k_max_Npm_per_m = 20.3e6", "f_ult_N_per_m = 326e3"}) {
    const std::size_t at = half.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    half.replace(at, std::string(key).size(),
                 key[0] == 'k' ? "k_max_Npm_per_m = 10.15e6" : "f_ult_N_per_m = 163e3");
  }
  const model::ModelFile unlike = with(body, half);
  const std::vector<CompliantSpring> springs = AbutmentSprings(unlike.model, *unlike.compliant);
  ASSERT_GE(springs.size(), 10u);
  for (std::size_t k = 0; k < 5; ++k) {
    const CompliantSpring& plus = springs[k];
    const CompliantSpring& minus = springs[5 + k];
    EXPECT_EQ(plus.name, "+x." + std::to_string(k + 1));
    EXPECT_EQ(minus.name, "-x." + std::to_string(k + 1));
    EXPECT_EQ(plus.body, 2);
    EXPECT_EQ(minus.body, 0);
    // Halving is exact in binary: the -x springs' constants are the +x springs' over 2.
    EXPECT_EQ(minus.backfill.k_max_N_per_m, plus.backfill.k_max_N_per_m / 2.0);
    EXPECT_EQ(minus.backfill.f_ult_N, plus.backfill.f_ult_N / 2.0);
    EXPECT_EQ(minus.backfill.r_f, plus.backfill.r_f);
  }

  // A friction per wall: deck[2]'s +x springs carry the +x wall's, deck[0]'s -x springs the -x
  // wall's (with its stick stiffness over 5), the deck-deck joints' springs none.
  std::string rough = text;
  const std::string law = "law = \"compliant\"\n";
  rough.replace(
      rough.find(law, rough.find("[abutments]")), law.size(),
      law + "mu = { \"+x\" = 0.3, \"-x\" = 0.1 }\nstick_stiffness_Npm = { \"-x\" = 1e9 }\n");
  const model::ModelFile walls = model::ParseModelString(rough, "s.toml", Examples());
  const std::vector<CompliantSpring> rough_springs = AbutmentSprings(walls.model, *walls.compliant);
  ASSERT_EQ(rough_springs.size(), springs.size());
  for (const CompliantSpring& s : rough_springs) {
    const bool plus = s.name.rfind("+x.", 0) == 0, minus = s.name.rfind("-x.", 0) == 0;
    EXPECT_EQ(s.mu, plus ? 0.3 : minus ? 0.1 : 0.0) << s.name;
    EXPECT_EQ(s.k_t_N_per_m, minus ? 1e9 / 5 : 0.0) << s.name;
    EXPECT_EQ(s.body, plus ? 2 : minus ? 0 : s.body) << s.name;
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::abutment_walls_test
