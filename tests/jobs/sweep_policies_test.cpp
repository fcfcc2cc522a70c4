// A sweep's [event_policy] and [time_stepping_policy] (docs/sweep-format.md): members set by
// their stored names, each bad one refused in one line naming it; every family's evaluator,
// decorated or not, holds the policies and its runs use them (a cell equals the point's run
// under those policies and differs from the run under the defaults, for either integrator); the
// cube stores the policies the evaluator ran with, and the sweep's identity changes with them.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "jobs/evaluator_factory.h"
#include "jobs/h5/h5.h"
#include "jobs/sweep_runner.h"
#include "records/excitations.h"
#include "solver/common/error.h"
#include "spectra/event_policy.h"
#include "spectra/point.h"
#include "spectra/spectra_evaluator.h"

namespace skewbridge::jobs::sweep_policies_test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const std::string kSubsystem = R"([sweep]
name = "policy"
family = "subsystem"
[axes]
Pi_delta = [0.3, 1.0]
w0_over_wg = [0.7, 1.9]
[fixed]
a_deg = 30
eta0 = 1.2
mu = 0.2
)";

const std::string kPolicy = R"([event_policy]
steps_per_period = 7.5
jam = false
finite_check_steps = 32
contact.tie_tolerance = 2.5e-9
)";

// Moreau-Jean's thresholds away from the defaults: the contacts enter the step's problem a whole
// step before they close, and the normal rows are softer.
const std::string kTimeSteppingPolicy = R"([time_stepping_policy]
active_set_lookahead = 1.0
normal_compliance = 1e-6
)";

// The values of the members of `policy`, in the order of its description.
template <typename Policy>
std::vector<double> ValuesOf(const Policy& policy) {
  std::vector<double> out;
  for (const schema::Entry& e : schema::Entries(policy)) out.push_back(e.value);
  return out;
}

TEST(SweepPolicies, SetTheNamedMembersAndKeepEveryOtherDefault) {
  const SweepSpec spec = ParseSweepSpec(kSubsystem + kPolicy, "spec.toml", ".");
  dynamics::EventPolicy expected;
  expected.steps_per_period = 7.5;
  expected.jam = false;
  expected.finite_check_steps = 32;
  expected.contact.tie_tolerance = 2.5e-9;
  EXPECT_EQ(ValuesOf(spec.policies.event), ValuesOf(expected));
  EXPECT_EQ(ValuesOf(spec.policies.time_stepping), ValuesOf(dynamics::TimeSteppingPolicy{}));
  // A table [event_policy.contact] reads as the dotted key.
  const SweepSpec nested = ParseSweepSpec(
      kSubsystem + "[event_policy.contact]\ntie_tolerance = 2.5e-9\n", "spec.toml", ".");
  EXPECT_EQ(nested.policies.event.contact.tie_tolerance, 2.5e-9);
  const SweepSpec stepping = ParseSweepSpec(
      kSubsystem + "method = \"time-stepping\"\n" + kTimeSteppingPolicy, "spec.toml", ".");
  dynamics::TimeSteppingPolicy expected_stepping;
  expected_stepping.active_set_lookahead = 1.0;
  expected_stepping.normal_compliance = 1e-6;
  EXPECT_EQ(ValuesOf(stepping.policies.time_stepping), ValuesOf(expected_stepping));
  EXPECT_EQ(ValuesOf(stepping.policies.event), ValuesOf(dynamics::EventPolicy{}));

  // Only the members away from the defaults enter the identity: a table of defaults adds none.
  const SweepSpec plain = ParseSweepSpec(kSubsystem, "spec.toml", ".");
  EXPECT_THAT(plain.CanonicalText(), Not(HasSubstr("_policy.")));
  EXPECT_EQ(ParseSweepSpec(kSubsystem + "[event_policy]\nsteps_per_period = 20\n"
                                        "[time_stepping_policy]\nnormal_compliance = 1e-9\n",
                           "spec.toml", ".")
                .Hash(),
            plain.Hash());
  EXPECT_THAT(spec.CanonicalText(), HasSubstr("event_policy.steps_per_period = 7.5\n"));
  EXPECT_THAT(spec.CanonicalText(), HasSubstr("event_policy.jam = 0\n"));
  EXPECT_THAT(spec.CanonicalText(), HasSubstr("event_policy.contact.tie_tolerance = 2.5e-09\n"));
  EXPECT_NE(spec.Hash(), plain.Hash());
  EXPECT_THAT(stepping.CanonicalText(),
              HasSubstr("time_stepping_policy.active_set_lookahead = 1\n"
                        "time_stepping_policy.normal_compliance = 1e-06\n"));
}

// The message of the InputError that parsing `text` throws.
std::string ErrorOf(const std::string& text) {
  try {
    ParseSweepSpec(text, "spec.toml", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SweepPolicies, ABadMemberIsOneLineNamingItAndWhatIsAllowed) {
  const std::string head = kSubsystem + "[event_policy]\n";  // the member's line is 12
  EXPECT_EQ(ErrorOf(head + "steps_per_perod = 10\n"),
            "spec.toml:12: event_policy.steps_per_perod: not a member of the event policy "
            "(docs/theory.md §3.16, its table); did you mean `steps_per_period`?");
  EXPECT_EQ(ErrorOf(head + "steps_per_period = 0.5\n"),
            "spec.toml:12: event_policy.steps_per_period: must be at least 1 (got 0.5)");
  EXPECT_EQ(ErrorOf(head + "finite_check_steps = 10\n"),
            "spec.toml:12: event_policy.finite_check_steps: must be a power of two (1, 2, 4, "
            "...) (got 10)");
  EXPECT_EQ(ErrorOf(head + "finite_check_steps = 2.5\n"),
            "spec.toml:12: event_policy.finite_check_steps: must be an integer, a power of two "
            "(1, 2, 4, ...)");
  EXPECT_EQ(ErrorOf(head + "jam = 1\n"),
            "spec.toml:12: event_policy.jam: must be true or false (a rule)");
  EXPECT_EQ(ErrorOf(head + "velocity_tolerance = \"small\"\n"),
            "spec.toml:12: event_policy.velocity_tolerance: must be a number, in (0, 1)");
  EXPECT_EQ(ErrorOf(head + "contact.tie_tolerance = -1.0\n"),
            "spec.toml:12: event_policy.contact.tie_tolerance: must be at least 0 (got -1)");
  const std::string stepping = kSubsystem + "[time_stepping_policy]\n";
  EXPECT_EQ(ErrorOf(stepping + "active_set_lookahead = 1.5\n"),
            "spec.toml:12: time_stepping_policy.active_set_lookahead: must be in [0, 1] (got 1.5)");
  EXPECT_EQ(ErrorOf(stepping + "velocity_tolerence = 1e-6\n"),
            "spec.toml:12: time_stepping_policy.velocity_tolerence: not a member of the "
            "time-stepping policy (docs/theory.md §3.16, its table); did you mean "
            "`velocity_tolerance`?");
  EXPECT_EQ(ErrorOf(stepping + "normal_compliance = 1.0\n"),
            "spec.toml:12: time_stepping_policy.normal_compliance: must be in [0, 1) (got 1)");
}

// The message of the InputError that making the evaluator of `text` throws.
std::string EvaluatorErrorOf(const std::string& text) {
  try {
    MakeEvaluator(ParseSweepSpec(text, "spec.toml", "."));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SweepPolicies, APolicyNoCellReadsIsRefused) {
  EXPECT_EQ(EvaluatorErrorOf(kSubsystem + kTimeSteppingPolicy),
            "spec.toml: time_stepping_policy: sets Moreau-Jean's thresholds, but no cell of the "
            "sweep runs method \"time-stepping\" (give method = \"time-stepping\" as an axis or a "
            "fixed value, or run.method in the model file)");
  EXPECT_EQ(EvaluatorErrorOf(kSubsystem + "method = \"time-stepping\"\n" + kPolicy),
            "spec.toml: event_policy: sets the event-driven integrator's rules, but every cell "
            "of the sweep runs method \"time-stepping\" (its thresholds are "
            "[time_stepping_policy])");
  EXPECT_EQ(EvaluatorErrorOf(kSubsystem + kPolicy), "no error");
}

// Every cell of `spec` (a subsystem sweep of pulses) against the point's own runs: equal to the
// run under the spec's policies, and the number of cells whose run under the defaults differs.
int CompareWithPointRuns(const SweepSpec& spec, const CellEvaluator& evaluator) {
  const spectra::SpectraEvaluator direct(spec);
  int differ = 0;
  for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
    const std::vector<std::size_t> index = spec.AxisIndex(c);
    const CellOutcome out = evaluator.Evaluate(index);
    EXPECT_EQ(out.status, kStatusOk) << out.status_text;
    const spectra::SweepRecord* record = nullptr;
    const spectra::PointParameters p = direct.Parameters(index, &record);
    const spectra::ExcitationScales scales = spectra::PulseScales(p);
    const spectra::DimensionalPoint point = spectra::ToDimensional(p, scales);
    const records::PulseExcitation pulse(p.pulse, scales.a_g_mps2, scales.w_g_radps);
    const spectra::PointResult with = spectra::EvaluatePoint(point, pulse, spec.policies);
    const spectra::PointResult without = spectra::EvaluatePoint(point, pulse);
    EXPECT_EQ(out.responses[0], with.x_m) << c;        // x_m
    EXPECT_EQ(out.responses[2], with.theta_rad) << c;  // theta_m
    EXPECT_EQ(out.stats.steps, with.steps) << c;
    differ += with.steps != without.steps || with.x_m != without.x_m ||
              with.theta_rad != without.theta_rad;
  }
  return differ;
}

// The attributes of the group `path` of the cube `file` against the entries of `policy`.
template <typename Policy>
void ExpectStored(const std::filesystem::path& file, const std::string& path,
                  const Policy& policy) {
  h5::Id f = h5::OpenFile(file.string(), false);
  h5::Id group = h5::OpenGroup(f.get(), path);
  const std::vector<schema::Entry> entries = schema::Entries(policy);
  EXPECT_EQ(h5::GetStringListAttr(group.get(), "keys").size(), entries.size());
  for (const schema::Entry& e : entries) {
    const double stored = e.integral() ? static_cast<double>(h5::GetIntAttr(group.get(), e.name))
                                       : h5::GetDoubleAttr(group.get(), e.name);
    EXPECT_EQ(stored, e.value) << path << ": " << e.name;
  }
}

TEST(SweepPolicies, EveryFamilyRunsWithThemAndTheCubeStoresThem) {
  const SweepSpec spec = ParseSweepSpec(kSubsystem + kPolicy, "spec.toml", ".");
  const std::unique_ptr<CellEvaluator> evaluator = MakeEvaluator(spec);
  EXPECT_EQ(ValuesOf(evaluator->policies().event), ValuesOf(spec.policies.event));
  // Each cell is the point's own run under the policy; the defaults give other numbers.
  EXPECT_EQ(CompareWithPointRuns(spec, *evaluator), static_cast<int>(spec.CellCount()));

  // The decorated families hold them too.
  const std::string limit_states = "[limit_states]\nrotation = {above_rad = 0.01}\n";
  for (const std::string& text :
       {kSubsystem + kPolicy + limit_states,
        "[sweep]\nname = \"ms\"\nfamily = \"multi-span\"\n[axes]\nspans = [1, 2]\n[fixed]\n"
        "W_over_L = 0.3\n" +
            kPolicy + limit_states}) {
    const SweepSpec decorated = ParseSweepSpec(text, "spec.toml", ".");
    EXPECT_EQ(ValuesOf(MakeEvaluator(decorated)->policies().event), ValuesOf(spec.policies.event));
  }

  // The cube's event_policy group is the evaluator's policy, member by member.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sb_sweep_policies";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  SweepOptions options;
  options.out = dir / "cube.h5";
  ASSERT_TRUE(RunSweep(spec, *evaluator, *MakeInProcessTransport(), options).complete);
  ExpectStored(options.out, "sweeps/policy/event_policy", evaluator->policies().event);
  {
    h5::Id f = h5::OpenFile(options.out.string(), false);
    h5::Id group = h5::OpenGroup(f.get(), "sweeps/policy/event_policy");
    EXPECT_EQ(h5::GetDoubleAttr(group.get(), "steps_per_period"), 7.5);
    EXPECT_EQ(h5::GetIntAttr(group.get(), "jam"), 0);
    EXPECT_EQ(h5::GetIntAttr(group.get(), "finite_check_steps"), 32);
    EXPECT_EQ(h5::GetDoubleAttr(group.get(), "contact.tie_tolerance"), 2.5e-9);
  }
  std::filesystem::remove_all(dir);
}

TEST(SweepPolicies, EachIntegratorRunsWithItsOwnPolicyAndTheCubeStoresBoth) {
  const std::string both = R"([sweep]
name = "both"
family = "subsystem"
[axes]
method = ["event-driven", "time-stepping"]
w0_over_wg = [0.7, 1.9]
[fixed]
Pi_delta = 0.3
a_deg = 30
eta0 = 1.2
mu = 0.2
)";
  const SweepSpec spec = ParseSweepSpec(both + kPolicy + kTimeSteppingPolicy, "spec.toml", ".");
  const std::unique_ptr<CellEvaluator> evaluator = MakeEvaluator(spec);
  EXPECT_EQ(ValuesOf(evaluator->policies().time_stepping), ValuesOf(spec.policies.time_stepping));
  // Every cell, of either method, moves with its method's policy.
  EXPECT_EQ(CompareWithPointRuns(spec, *evaluator), static_cast<int>(spec.CellCount()));

  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sb_sweep_both";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  SweepOptions options;
  options.out = dir / "cube.h5";
  ASSERT_TRUE(RunSweep(spec, *evaluator, *MakeInProcessTransport(), options).complete);
  ExpectStored(options.out, "sweeps/both/event_policy", spec.policies.event);
  ExpectStored(options.out, "sweeps/both/time_stepping_policy", spec.policies.time_stepping);
  {
    h5::Id f = h5::OpenFile(options.out.string(), false);
    h5::Id group = h5::OpenGroup(f.get(), "sweeps/both/time_stepping_policy");
    EXPECT_EQ(h5::GetDoubleAttr(group.get(), "active_set_lookahead"), 1.0);
    EXPECT_EQ(h5::GetDoubleAttr(group.get(), "normal_compliance"), 1e-6);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace skewbridge::jobs::sweep_policies_test
