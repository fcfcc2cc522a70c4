// A model file's law per abutment ([abutments] law = { "+x" = "impact", "-x" = "compliant" },
// docs/examples/pilot-bridge-mixed.toml) run by RunUnderLaw against the two laws alone, each from
// its own model file: a compliant wall out of reach gives the rigid run of the +x abutment alone
// bit for bit, a rigid wall out of reach gives the all-compliant run to the Runge-Kutta tolerance,
// and with both walls struck the energy ledger (a conservation law) closes to 1e-6 of the input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/abutment_springs.h"
#include "solver/model/model_file.h"
#include "tests/dynamics/benchmark_cases.h"
#include "tests/dynamics/mixed_checks.h"
#include "tests/dynamics/run_bits.h"

namespace skewbridge::dynamics::mixed_law_test {
namespace {

const std::string kExamplesDir = std::string(SKEWBRIDGE_TEST_DATA_DIR) + "/../../docs/examples";

// docs/examples/pilot-bridge-mixed.toml with each (start of a line, whole new line) pair applied to
// the line that starts with it, parsed.
model::ModelFile Mixed(const std::vector<std::pair<std::string, std::string>>& edits) {
  std::ifstream in(kExamplesDir + "/pilot-bridge-mixed.toml");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  for (const auto& [from, to] : edits) {
    const std::size_t at = text.find("\n" + from);
    EXPECT_NE(at, std::string::npos) << "no line starting \"" << from << "\"";
    if (at == std::string::npos) continue;
    text.replace(at + 1, text.find('\n', at + 1) - at - 1, to);
  }
  return model::ParseModelString(text, "mixed.toml", kExamplesDir);
}

// One run of a parsed file under its law, with the ledger, 40 s of the record-like signal.
LawRun RunFile(const model::ModelFile& file) {
  records::SampledExcitation ex(0.01, bench::RecordLikeSignal());
  model::RunControl control = file.run;
  control.end_time_s = 40.0;
  control.energy_ledger = true;
  control.output_interval_s = 0.0;
  return RunUnderLaw(file.model, file.compliant, ex, control);
}

TEST(MixedLaw, TheFileGivesOneRigidWallAndOneCompliant) {
  const model::ModelFile file = Mixed({});
  ASSERT_TRUE(file.compliant.has_value());
  ASSERT_EQ(file.compliant->walls.size(), 2u);
  EXPECT_TRUE(file.compliant->Mixed());
  EXPECT_EQ(file.compliant->walls[0].law, model::JointLaw::kImpact);
  EXPECT_EQ(file.compliant->walls[1].law, model::JointLaw::kCompliant);
  EXPECT_EQ(file.compliant->walls[1].springs, 5);
  // The model keeps every corner; the run's keeps the rigid wall's, with eps_N and mu of the +x.
  EXPECT_EQ(file.model.n_contacts(), 4);
  const model::Model run_model = LawModel(file.model, *file.compliant);
  ASSERT_EQ(run_model.n_contacts(), 2);
  EXPECT_EQ(run_model.contact(0).name, "P1");
  EXPECT_EQ(run_model.contact(1).name, "P2");
  EXPECT_EQ(run_model.contact(0).restitution, 0.5);
  EXPECT_EQ(run_model.contact(0).friction, 0.3);
  // The springs are the -x wall's only.
  const std::vector<CompliantSpring> springs = AbutmentSprings(file.model, *file.compliant);
  ASSERT_EQ(springs.size(), 5u);
  for (const CompliantSpring& s : springs) EXPECT_EQ(s.name.substr(0, 3), "-x.");
  // A law per abutment whose two laws agree is that law for both, bit for bit in its run.
  const model::ModelFile both =
      Mixed({{"law = ", R"(law = { "+x" = "compliant", "-x" = "compliant" })"},
             {"eps_N = ", ""},
             {"mu = ", "mu = 0.0"}});
  ASSERT_TRUE(both.compliant.has_value());
  EXPECT_FALSE(both.compliant->Mixed());
  const model::ModelFile named =
      Mixed({{"law = ", R"(law = "compliant")"}, {"eps_N = ", ""}, {"mu = ", "mu = 0.0"}});
  testing::ExpectSameRunAndLedgerBits(RunFile(both).run, RunFile(named).run);
}

// The example under the rigid law at every abutment it keeps: `edits` first, then the law
// "impact", mu 0.3 and the backfill's table turned into the +x corner P1's.
model::ModelFile AllRigid(std::vector<std::pair<std::string, std::string>> edits) {
  const std::vector<std::pair<std::string, std::string>> rigid = {
      {"law = ", R"(law = "impact")"},
      {"mu = ", "mu = 0.3"},
      {"springs = ", ""},
      {"[abutments.backfill]", "[abutments.contacts.P1]"},
      {"form = ", ""},
      {"k_max_Npm_per_m = ", ""},
      {"r_f = ", ""},
      {"f_ult_N_per_m = ", ""}};
  edits.insert(edits.end(), rigid.begin(), rigid.end());
  return Mixed(edits);
}

TEST(MixedLaw, ACompliantWallOutOfReachGivesTheRigidRunBitForBit) {
  const LawRun mixed = RunFile(Mixed({{"gap_m = ", R"(gap_m = { "+x" = 0.0095, "-x" = 10.0 })"}}));
  // The +x abutment alone under the rigid law: its own file, set = "+x", no springs.
  const LawRun rigid =
      RunFile(AllRigid({{"set = ", R"(set = "+x")"}, {"gap_m = ", "gap_m = 0.0095"}}));
  ASSERT_EQ(rigid.run.status, RunStatus::kOk) << rigid.run.message;
  ASSERT_GT(rigid.run.impacts, 5) << "the rigid wall is struck";
  ASSERT_EQ(mixed.walls.size(), 1u);
  EXPECT_EQ(mixed.walls[0].wall, "-x");
  EXPECT_EQ(mixed.walls[0].spring_force_N, 0.0) << "the backfill is out of reach";
  EXPECT_EQ(mixed.joint_dissipated_J, 0.0);
  testing::ExpectSameRunAndLedgerBits(mixed.run, rigid.run);
  // And the rigid law at both abutments, the -x corners out of reach.
  const LawRun both =
      RunFile(AllRigid({{"gap_m = ", R"(gap_m = { "+x" = 0.0095, "-x" = 10.0 })"}}));
  testing::ExpectSameRunAndLedgerBits(mixed.run, both.run);
}

TEST(MixedLaw, ARigidWallOutOfReachGivesTheCompliantRun) {
  const LawRun mixed = RunFile(Mixed({{"gap_m = ", R"(gap_m = { "+x" = 10.0, "-x" = 0.0095 })"}}));
  // Both walls compliant, the +x wall's springs out of reach: the -x wall's run alone.
  const LawRun compliant = RunFile(Mixed({{"gap_m = ", R"(gap_m = { "+x" = 10.0, "-x" = 0.0095 })"},
                                          {"law = ", R"(law = "compliant")"},
                                          {"eps_N = ", ""},
                                          {"mu = ", "mu = 0.0"}}));
  ASSERT_EQ(compliant.run.status, RunStatus::kOk) << compliant.run.message;
  ASSERT_EQ(mixed.run.status, RunStatus::kOk) << mixed.run.message;
  ASSERT_EQ(compliant.walls.size(), 2u);
  EXPECT_EQ(compliant.walls[0].spring_force_N, 0.0) << "the +x wall is out of reach";
  ASSERT_GT(compliant.run.impacts, 5) << "the -x backfill is struck";
  EXPECT_EQ(mixed.run.impacts, compliant.run.impacts);
  // The two integrators' step controls differ: the responses agree to the Runge-Kutta
  // tolerance's order, relative to each (the largest difference is printed).
  const double tol = 1e-8;
  ASSERT_EQ(mixed.run.max_abs_q.size(), compliant.run.max_abs_q.size());
  const double worst = testing::ExpectMaximaWithin(mixed.run, compliant.run, tol);
  ASSERT_EQ(mixed.walls.size(), 1u);
  const WallMaxima& minus_x = compliant.walls[1];
  EXPECT_NEAR(mixed.walls[0].spring_force_N, minus_x.spring_force_N, tol * minus_x.spring_force_N);
  EXPECT_NEAR(mixed.walls[0].deformation_m, minus_x.deformation_m, tol * minus_x.deformation_m);
  EXPECT_NEAR(mixed.joint_dissipated_J, compliant.joint_dissipated_J,
              1e-6 * compliant.joint_dissipated_J);
  std::printf(
      "largest relative difference in max|q_i|: %.3e; spring force %.3e; dissipated %.3e\n", worst,
      std::abs(mixed.walls[0].spring_force_N - minus_x.spring_force_N) / minus_x.spring_force_N,
      std::abs(mixed.joint_dissipated_J - compliant.joint_dissipated_J) /
          compliant.joint_dissipated_J);
}

TEST(MixedLaw, EnergyLedgerClosesWithBothWallsStruck) {
  const model::ModelFile file = Mixed({{"gap_m = ", "gap_m = 0.0095"}});
  const LawRun mixed = RunFile(file);
  const RunResult& r = mixed.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  long contact_impacts = 0;
  for (const EventRecord& e : r.events) contact_impacts += e.kind == EventKind::kImpact ? 1 : 0;
  EXPECT_GT(contact_impacts, 0) << "the rigid wall is struck";
  ASSERT_EQ(mixed.walls.size(), 1u);
  EXPECT_GT(mixed.walls[0].spring_force_N, 0.0) << "the backfill is struck";
  testing::ExpectMixedLedgerCloses(mixed);
  // The stored responses: the -x wall's only (the +x wall is rigid).
  std::vector<std::string> names;
  for (const JointResponse& j : JointResponses(*file.compliant, true)) {
    names.push_back(j.name);
    EXPECT_TRUE(std::isfinite(j.value(mixed))) << j.name;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"spring_force_mx", "backwall_def_mx"}));
}

}  // namespace
}  // namespace skewbridge::dynamics::mixed_law_test
