// A [[deck]] model file with a law per abutment and per deck-deck joint (docs/model-format.md,
// "Several decks") run by RunUnderLaw against each law alone, each from its own model file: the
// compliant parts out of reach give the all-rigid file's run bit for bit, the rigid parts out of
// reach give the all-compliant file's run to the Runge-Kutta tolerance, the joints' law taken from
// the abutments is the law named on each joint bit for bit, and with rigid and compliant parts
// struck the energy ledger (a conservation law) closes to 1e-6 of the input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/common/error.h"
#include "solver/dynamics/abutment_springs.h"
#include "solver/model/model_file.h"
#include "tests/dynamics/benchmark_cases.h"
#include "tests/dynamics/mixed_checks.h"
#include "tests/dynamics/run_bits.h"

namespace skewbridge::dynamics::mixed_row_test {
namespace {

// The decks and bearings of docs/examples/three-span.toml (three decks of 30, 40 and 30 m, W 12
// m, 30 deg skew, each on its own bearings); joints and abutments are each test's.
constexpr const char* kDecks = R"([[deck]]
m = 600e3
L = 30.0
W = 12.0
skew_deg = 30.0

[[deck]]
m = 800e3
L = 40.0
W = 12.0
skew_deg = 30.0

[[deck]]
m = 600e3
L = 30.0
W = 12.0
skew_deg = 30.0

)";
constexpr const char* kSupports = R"(
[[support]]
deck = 0
k_x = 6.0e7
k_y = 6.0e7
k_theta = 7.8624e9
xi = 0.05

[[support]]
deck = 1
k_x = K_X1
k_y = 8.0e7
k_theta = 1.72032e10
xi = 0.05

[[support]]
deck = 2
k_x = 6.0e7
k_y = 6.0e7
k_theta = 7.8624e9
xi = 0.05

[excitation]
kind = "pulse"
shape = "cosine"
a_g_g = 0.4
T_g = 0.6
direction = "x"

[run]
tail_s = 1.5
)";

// A rigid joint with gap `gap_m`, eps_N 0.5 and mu 0.2 (as three-span.toml's).
std::string RigidJoint(const std::string& gap_m, bool named = true) {
  return "[[joint]]\ngap_m = " + gap_m + (named ? "\nlaw = \"impact\"" : "") +
         "\neps_N = 0.5\nmu = 0.2\n\n";
}

// A compliant joint with gap `gap_m` and Wilson and Elgamal's per-metre backfill law (as
// three-span-compliant.toml's joint[1]); `law` its law line ("" to take the abutments').
std::string BackfillJoint(const std::string& gap_m,
                          const std::string& law = "law = \"compliant\"") {
  return "[[joint]]\ngap_m = " + gap_m + "\n" + law +
         "\n\n[joint.backfill]\nform = \"hyperbolic-gap\"\nk_max_Npm_per_m = 20.3e6\nr_f = 0.7\n"
         "f_ult_N_per_m = 326e3\n\n";
}

// A compliant joint with gap `gap_m`, a linear spring-dashpot (three-span-compliant.toml's
// joint[0]).
std::string DashpotJoint(const std::string& gap_m, const std::string& law = "law = \"compliant\"") {
  return "[[joint]]\ngap_m = " + gap_m + "\n" + law +
         "\n\n[joint.spring_dashpot]\nk_Npm = 1.0e9\nc_Nspm = 7.4e6\n\n";
}

// [abutments] with gap `gap_m` (a number or a per-abutment table) and `law` its law line: the
// rigid walls' eps_N 0.5, mu 0.2 (`mu` a line) and, when a wall is compliant, 5 springs with
// Wilson and Elgamal's backfill.
std::string Abutments(const std::string& gap_m, const std::string& law, bool any_compliant,
                      bool any_rigid, const std::string& mu = "mu = 0.2") {
  std::string text = "[abutments]\ngap_m = " + gap_m + "\n" + law + "\n";
  if (any_rigid) text += "eps_N = 0.5\n";
  text += mu + "\n";
  if (any_compliant) {
    text +=
        "springs = 5\n\n[abutments.backfill]\nform = \"hyperbolic-gap\"\nk_max_Npm_per_m = 20.3e6\n"
        "r_f = 0.7\nf_ult_N_per_m = 326e3\n";
  }
  return text;
}

// The file of kDecks, `joints`, `abutments` and kSupports with deck[1]'s bearing k_x `k_x1` (N/m;
// three-span.toml's 8e7 gives every deck w0 = 10 rad/s, so that under a ground motion along x the
// decks move as one until an abutment is struck; 4e7 gives deck[1] 7.1 rad/s and the joints close
// on their own).
model::ModelFile Parse(const std::string& joints, const std::string& abutments,
                       const std::string& k_x1 = "8.0e7") {
  std::string supports = kSupports;
  supports.replace(supports.find("K_X1"), 4, k_x1);
  return model::ParseModelString(std::string(kDecks) + joints + abutments + supports, "row.toml",
                                 ".");
}

// One run of a parsed file under its law, with the ledger, `end_s` of the record-like signal
// scaled by `scale`.
LawRun RunFile(const model::ModelFile& file, double end_s = 40.0, double scale = 1.0) {
  std::vector<double> a = bench::RecordLikeSignal();
  for (double& x : a) x *= scale;
  records::SampledExcitation ex(0.01, a);
  model::RunControl control = file.run;
  control.end_time_s = end_s;
  control.energy_ledger = true;
  control.output_interval_s = 0.0;
  return RunUnderLaw(file.model, file.compliant, ex, control);
}

TEST(MixedRow, TheFileGivesALawPerAbutmentAndPerJoint) {
  const model::ModelFile file =
      Parse(RigidJoint("0.04") + BackfillJoint("0.04"),
            Abutments("0.05", R"(law = { "+x" = "compliant", "-x" = "impact" })", true, true));
  ASSERT_TRUE(file.compliant.has_value());
  EXPECT_TRUE(file.compliant->Mixed());
  ASSERT_EQ(file.compliant->walls.size(), 2u);
  EXPECT_EQ(file.compliant->walls[0].law, model::JointLaw::kCompliant);
  EXPECT_EQ(file.compliant->walls[1].law, model::JointLaw::kImpact);
  ASSERT_EQ(file.compliant->joints.size(), 2u);
  EXPECT_EQ(file.compliant->joints[0].law, model::JointLaw::kImpact);
  EXPECT_EQ(file.compliant->joints[1].law, model::JointLaw::kCompliant);
  // The model keeps every corner (2 per wall, 2 per joint); the run's keeps the rigid ones in
  // order, with their eps_N and mu.
  ASSERT_EQ(file.model.n_contacts(), 8);
  const model::Model run_model = LawModel(file.model, *file.compliant);
  ASSERT_EQ(run_model.n_contacts(), 4);
  const std::vector<std::string> names = {"D0.P3", "D0.P4", "D0.P1/D1", "D0.P2/D1"};
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(run_model.contact(c).name, names[static_cast<std::size_t>(c)]);
    EXPECT_EQ(run_model.contact(c).restitution, 0.5);
    EXPECT_EQ(run_model.contact(c).friction, 0.2);
  }
  // The springs: the +x wall's five, then joint[1]'s five.
  const std::vector<CompliantSpring> springs = AbutmentSprings(file.model, *file.compliant);
  ASSERT_EQ(springs.size(), 10u);
  for (std::size_t j = 0; j < 5; ++j) EXPECT_EQ(springs[j].name.substr(0, 3), "+x.");
  for (std::size_t j = 5; j < 10; ++j) EXPECT_EQ(springs[j].name.substr(0, 3), "J1.");
  // Rigid abutments beside a compliant joint: both walls keep their contacts.
  const model::ModelFile joint_only = Parse(DashpotJoint("0.04") + RigidJoint("0.04"),
                                            Abutments("0.05", "law = \"impact\"", false, true));
  ASSERT_TRUE(joint_only.compliant.has_value());
  EXPECT_TRUE(joint_only.compliant->Mixed());
  EXPECT_EQ(LawModel(joint_only.model, *joint_only.compliant).n_contacts(), 6);
  EXPECT_EQ(AbutmentSprings(joint_only.model, *joint_only.compliant).size(), 5u);
  // Every part rigid: no compliant law at all (the rigid run, unchanged).
  EXPECT_FALSE(Parse(RigidJoint("0.04", false) + RigidJoint("0.04", false),
                     Abutments("0.05", "", false, true))
                   .compliant.has_value());
}

TEST(MixedRow, CompliantPartsOutOfReachGiveTheRigidRunBitForBit) {
  // joint[0] and the -x abutment rigid and struck; joint[1] and the +x backfill 10 m away.
  const std::string gaps = R"({ "+x" = 10.0, "-x" = 0.05 })";
  const LawRun mixed = RunFile(
      Parse(RigidJoint("0.02") + BackfillJoint("10.0"),
            Abutments(gaps, R"(law = { "+x" = "compliant", "-x" = "impact" })", true, true)));
  // The same row with every part rigid, from its own file.
  const LawRun rigid = RunFile(Parse(RigidJoint("0.02", false) + RigidJoint("10.0", false),
                                     Abutments(gaps, "", false, true)));
  ASSERT_EQ(rigid.run.status, RunStatus::kOk) << rigid.run.message;
  ASSERT_GT(rigid.run.impacts, 5) << "the rigid joint and wall are struck";
  EXPECT_GT(rigid.run.energy.impact_J, 0.0);
  ASSERT_EQ(mixed.walls.size(), 1u);
  ASSERT_EQ(mixed.joints.size(), 1u);
  EXPECT_EQ(mixed.walls[0].wall, "+x");
  EXPECT_EQ(mixed.joints[0].wall, "J1");
  EXPECT_EQ(mixed.walls[0].spring_force_N, 0.0) << "the backfill is out of reach";
  EXPECT_EQ(mixed.joints[0].spring_force_N, 0.0) << "joint[1] is out of reach";
  EXPECT_EQ(mixed.joint_dissipated_J, 0.0);
  testing::ExpectSameRunAndLedgerBits(mixed.run, rigid.run);
  // A spring-dashpot joint out of reach, the abutments rigid: the same.
  const LawRun dashpot = RunFile(Parse(RigidJoint("0.02") + DashpotJoint("10.0"),
                                       Abutments(gaps, "law = \"impact\"", false, true)));
  testing::ExpectSameRunAndLedgerBits(dashpot.run, rigid.run);
}

TEST(MixedRow, TheJointsLawTakenFromTheAbutmentsIsTheLawNamedOnEachJoint) {
  // docs/examples/three-span-compliant.toml's parts: every joint naming law = "compliant", against
  // the abutments' law given per abutment (the same for both) and the joints naming none. The two
  // files parse to the same laws and take the same path (SimulateCompliant): bit for bit.
  const LawRun named =
      RunFile(Parse(DashpotJoint("0.02") + BackfillJoint("0.04"),
                    Abutments("0.05", "law = \"compliant\"", true, false, "mu = 0.0"), "4.0e7"));
  const model::ModelFile taken_file =
      Parse(DashpotJoint("0.02", "") + BackfillJoint("0.04", ""),
            Abutments("0.05", R"(law = { "+x" = "compliant", "-x" = "compliant" })", true, false,
                      "mu = 0.0"),
            "4.0e7");
  ASSERT_TRUE(taken_file.compliant.has_value());
  EXPECT_FALSE(taken_file.compliant->Mixed());
  const LawRun taken = RunFile(taken_file);
  ASSERT_EQ(named.run.status, RunStatus::kOk) << named.run.message;
  ASSERT_GT(named.run.impacts, 5) << "the joints and walls are struck";
  ASSERT_EQ(named.joints.size(), 2u);
  EXPECT_GT(named.joints[0].spring_force_N, 0.0);
  EXPECT_GT(named.joints[1].spring_force_N, 0.0);
  testing::ExpectSameRunAndLedgerBits(taken.run, named.run);
  EXPECT_EQ(taken.joint_dissipated_J, named.joint_dissipated_J);
}

TEST(MixedRow, RigidAbutmentsOutOfReachGiveTheCompliantRowsRun) {
  // Every joint compliant, the abutments rigid and 10 m away: SimulateMixed with contacts that
  // never close, against the all-compliant row (law = "compliant") with its walls 10 m away,
  // SimulateCompliant. The two integrators' step controls differ (the mixed one steps exactly
  // between events while no spring is engaged): the responses agree to the Runge-Kutta
  // tolerance's order, relative to each (the largest difference is printed).
  const std::string joints = DashpotJoint("0.02") + BackfillJoint("0.04");
  const LawRun mixed =
      RunFile(Parse(joints, Abutments("10.0", "law = \"impact\"", false, true), "4.0e7"));
  const LawRun compliant = RunFile(
      Parse(joints, Abutments("10.0", "law = \"compliant\"", true, false, "mu = 0.0"), "4.0e7"));
  ASSERT_EQ(compliant.run.status, RunStatus::kOk) << compliant.run.message;
  ASSERT_EQ(mixed.run.status, RunStatus::kOk) << mixed.run.message;
  ASSERT_EQ(compliant.walls.size(), 2u);
  EXPECT_EQ(compliant.walls[0].spring_force_N, 0.0) << "the +x wall is out of reach";
  EXPECT_EQ(compliant.walls[1].spring_force_N, 0.0) << "the -x wall is out of reach";
  ASSERT_GT(compliant.run.impacts, 5) << "the joints are struck";
  EXPECT_EQ(mixed.run.impacts, compliant.run.impacts);
  EXPECT_EQ(mixed.run.energy.impact_J, 0.0);
  const double tol = 1e-8;
  ASSERT_EQ(mixed.run.max_abs_q.size(), compliant.run.max_abs_q.size());
  const double worst = testing::ExpectMaximaWithin(mixed.run, compliant.run, tol);
  ASSERT_EQ(mixed.walls.size(), 0u);
  ASSERT_EQ(mixed.joints.size(), 2u);
  // joint[1]'s backfill springs reach their largest force and deformation at a turn from loading
  // to unloading, an event each integrator locates: to the tolerance. joint[0]'s spring-dashpot
  // has no such event (F = k d + c d' peaks while d still grows), so its maxima are read at step
  // ends, and the two step grids sample them apart (1.6e-4 of their value here).
  double worst_joint[2] = {0.0, 0.0};
  for (std::size_t j = 0; j < 2; ++j) {
    const WallMaxima& a = mixed.joints[j];
    const WallMaxima& b = compliant.joints[j];
    const double joint_tol = j == 0 ? 1e-3 : tol;
    EXPECT_EQ(a.wall, b.wall);
    EXPECT_NEAR(a.spring_force_N, b.spring_force_N, joint_tol * b.spring_force_N) << a.wall;
    EXPECT_NEAR(a.deformation_m, b.deformation_m, joint_tol * b.deformation_m) << a.wall;
    worst_joint[j] = std::max(std::abs(a.spring_force_N - b.spring_force_N) / b.spring_force_N,
                              std::abs(a.deformation_m - b.deformation_m) / b.deformation_m);
  }
  EXPECT_NEAR(mixed.joint_dissipated_J, compliant.joint_dissipated_J,
              1e-6 * compliant.joint_dissipated_J);
  std::printf(
      "largest relative difference in max|q_i|: %.3e; joint[0]'s maxima %.3e, joint[1]'s %.3e; "
      "dissipated %.3e\n",
      worst, worst_joint[0], worst_joint[1],
      std::abs(mixed.joint_dissipated_J - compliant.joint_dissipated_J) /
          compliant.joint_dissipated_J);
}

TEST(MixedRow, EnergyLedgerClosesWithRigidAndCompliantPartsStruck) {
  // joint[0] rigid, joint[1] a backfill, the -x abutment rigid and the +x a backfill: every part
  // within reach of the record.
  const model::ModelFile file =
      Parse(RigidJoint("0.02") + BackfillJoint("0.02"),
            Abutments("0.03", R"(law = { "+x" = "compliant", "-x" = "impact" })", true, true));
  const LawRun mixed = RunFile(file);
  const RunResult& r = mixed.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  // Which rigid corners were struck: the -x wall's (D0.P3, D0.P4) and joint[0]'s.
  const model::Model run_model = LawModel(file.model, *file.compliant);
  bool wall_struck = false, joint_struck = false;
  for (const EventRecord& e : r.events) {
    if (e.kind != EventKind::kImpact) continue;
    if (e.contact < 0) continue;
    const std::string& name = run_model.contact(e.contact).name;
    wall_struck = wall_struck || name.find('/') == std::string::npos;
    joint_struck = joint_struck || name.find('/') != std::string::npos;
  }
  EXPECT_TRUE(wall_struck) << "the rigid -x wall is struck";
  EXPECT_TRUE(joint_struck) << "the rigid joint[0] is struck";
  ASSERT_EQ(mixed.walls.size(), 1u);
  ASSERT_EQ(mixed.joints.size(), 1u);
  EXPECT_GT(mixed.walls[0].spring_force_N, 0.0) << "the +x backfill is struck";
  EXPECT_GT(mixed.joints[0].spring_force_N, 0.0) << "joint[1] is struck";
  EXPECT_GT(r.energy.friction_J, 0.0);
  testing::ExpectMixedLedgerCloses(mixed);
  // The stored responses: the compliant +x wall's and joint[1]'s only.
  std::vector<std::string> names;
  for (const JointResponse& j : JointResponses(*file.compliant, true)) {
    names.push_back(j.name);
    EXPECT_TRUE(std::isfinite(j.value(mixed))) << j.name;
    EXPECT_GT(j.value(mixed), 0.0) << j.name;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"spring_force_px", "backwall_def_px", "joint_force_j1",
                                             "joint_def_j1"}));
}

TEST(MixedRow, RefusalsNameTheFieldInOneLine) {
  const auto refused = [](const std::string& joints, const std::string& abutments,
                          const std::string& expected) {
    try {
      Parse(joints, abutments);
      ADD_FAILURE() << "accepted: " << expected;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  // With a law per abutment of two laws, each joint names its own.
  refused(RigidJoint("0.04", false) + BackfillJoint("0.04"),
          Abutments("0.05", R"(law = { "+x" = "compliant", "-x" = "impact" })", true, true),
          "row.toml:19: joint[0].law: missing required key (the abutments have a law per "
          "abutment, one of each: give each joint its law, \"impact\" or \"compliant\")");
  // A joint taking the abutments' compliant law needs its own law's table.
  refused(RigidJoint("0.04") + "[[joint]]\ngap_m = 0.04\n\n",
          Abutments("0.05", "law = \"compliant\"", true, false, "mu = 0.0"),
          "joint[1].backfill: missing required key (the joint's law, compliant as [abutments] "
          "law is");
  // A [[deck]] file's abutments have no per-corner tables, with any law.
  refused(RigidJoint("0.04") + BackfillJoint("0.04"),
          Abutments("0.05", R"(law = { "+x" = "compliant", "-x" = "impact" })", true, true) +
              "\n[abutments.contacts.D0.P3]\neps_N = 0.6\n",
          "abutments.contacts: unknown key");
}

}  // namespace
}  // namespace skewbridge::dynamics::mixed_row_test
