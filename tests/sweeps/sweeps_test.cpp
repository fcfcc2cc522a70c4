// The example specifications of jobs/specs against the cell counts their headers state, and the
// pilot bridge with gaps that never close against the same deck built without contacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "jobs/evaluator_factory.h"
#include "jobs/sweep_spec.h"
#include "records/excitations.h"
#include "records/synthetic.h"
#include "solver/common/error.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/builders.h"
#include "solver/model/model.h"
#include "solver/model/model_file.h"
#include "spectra/point.h"
#include "spectra/spectra_evaluator.h"

namespace skewbridge::jobs {
namespace {

namespace fs = std::filesystem;
using spectra::SpectraEvaluator;
using spectra::SweepRecord;

std::string ReadText(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The number the header comment gives as "N cells" (the last such number before [sweep]).
long long StatedCellCount(const std::string& text) {
  const std::string header = text.substr(0, text.find("[sweep]"));
  static const std::regex kCells(R"((\d+) cells)");
  long long stated = -1;
  for (std::sregex_iterator it(header.begin(), header.end(), kCells), end; it != end; ++it) {
    stated = std::stoll((*it)[1].str());
  }
  return stated;
}

// The position of a response in CellOutcome::responses.
std::size_t Column(const CellEvaluator& evaluator, const std::string& name) {
  const std::vector<ResponseInfo> responses = evaluator.Responses();
  for (std::size_t k = 0; k < responses.size(); ++k) {
    if (responses[k].name == name) return k;
  }
  ADD_FAILURE() << "no response " << name;
  return 0;
}

fs::path FreshDirectory(const std::string& name) {
  // The process id keeps concurrent runs of this test (several build trees) apart.
  const fs::path dir = fs::temp_directory_path() /
                       ("skewbridge_sweeps_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(ExampleSpecs, EveryFileBuildsItsEvaluatorWithTheCellCountItsHeaderStates) {
  const fs::path specs = fs::path(SKEWBRIDGE_SPECS_DIR);
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(specs)) {
    if (e.path().extension() == ".toml") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 6u) << "default, eta0-1, eta0-2, pi-delta-family, rotation-vs-eta0, "
                                 "pilot-records";
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const std::string text = ReadText(file);
    fs::path load = file;
    if (text.find("[records]") != std::string::npos) {
      // The record set is generated, as the file's header says, next to a copy of the file.
      const fs::path dir = FreshDirectory("specs");
      records::SynthOptions options;
      options.count = 62;
      options.seed = 2011;
      records::WriteSuite(dir / "synth62", options);
      load = dir / file.filename();
      fs::copy_file(file, load);
    }
    const SweepSpec spec = LoadSweepSpec(load);
    const std::unique_ptr<CellEvaluator> evaluator = MakeEvaluator(spec);
    EXPECT_FALSE(evaluator->Responses().empty());
    EXPECT_EQ(static_cast<long long>(spec.CellCount()), StatedCellCount(text));
    if (load != file) fs::remove_all(load.parent_path());
  }
}

TEST(ExampleSpecs, SubsystemStudiesHoldTheGroupsOfTheirHeaders) {
  const fs::path specs = fs::path(SKEWBRIDGE_SPECS_DIR);
  for (const auto& [name, eta0] : {std::pair{"eta0-1.toml", 1.0}, std::pair{"eta0-2.toml", 2.0}}) {
    const SweepSpec spec = LoadSweepSpec(specs / name);
    ASSERT_NE(spec.FindFixed("eta0"), nullptr);
    EXPECT_EQ(spec.FindFixed("eta0")->value, eta0);
    EXPECT_EQ(spec.FindFixed("Pi_delta")->value, 1.0);
    EXPECT_EQ(spec.FindFixed("xi")->value, 0.05);
    EXPECT_EQ(spec.FindFixed("eps_N")->value, 0.5);
    const Axis* a = spec.FindAxis("a_deg");
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->values.front(), 10.0);
    EXPECT_EQ(a->values.back(), 80.0);
    const Axis* w = spec.FindAxis("w0_over_wg");
    ASSERT_NE(w, nullptr);
    EXPECT_EQ(w->values.front(), 0.1);
    EXPECT_EQ(w->values.back(), 10.0);
    ASSERT_NE(spec.FindAxis("pulse"), nullptr);
    EXPECT_EQ(spec.FindAxis("pulse")->labels, (std::vector<std::string>{"cosine", "sine"}));
  }
  const SweepSpec family = LoadSweepSpec(specs / "pi-delta-family.toml");
  EXPECT_EQ(family.FindFixed("a_deg")->value, 20.0);
  EXPECT_GE(family.FindAxis("Pi_delta")->values.size(), 3u);
  const SweepSpec rotation = LoadSweepSpec(specs / "rotation-vs-eta0.toml");
  EXPECT_GE(rotation.FindAxis("eta0")->values.size(), 10u);
  EXPECT_GE(rotation.FindAxis("W0_over_w0")->values.size(), 3u);
}

// [docs/theory.md §4 fact 1] over a whole sweep: a frictionless deck with eta0 <= 1 leaves every
// impact without rotating, so theta stays at round-off level in every cell, while eta0 > 1
// rotates the deck in the cells that pound.
TEST(SubsystemSweep, RotatesOnlyAboveEta0OfOneWithoutFriction) {
  const SweepSpec spec = ParseSweepSpec(R"([sweep]
name = "eta0-threshold"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [15, 45, 75]
eta0 = [0.5, 1.0, 1.5, 3.0]
w0_over_wg = [0.2, 0.5, 1.0]
[fixed]
Pi_delta = 0.5
mu = 0.0
delta_over_L = 0.002
)",
                                        "eta0-threshold.toml", fs::temp_directory_path());
  const spectra::SpectraEvaluator evaluator(spec);
  const Axis* eta0 = spec.FindAxis("eta0");
  const std::size_t eta0_dim = static_cast<std::size_t>(eta0 - spec.axes.data());
  int rotating_above = 0;
  int pounding_below = 0;
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    const std::vector<std::size_t> index = spec.AxisIndex(cell);
    const CellOutcome out = evaluator.Evaluate(index);
    ASSERT_EQ(out.status, kStatusOk) << out.status_text;
    const double x_m = out.responses[Column(evaluator, "x_m")];
    const double theta_m = out.responses[Column(evaluator, "theta_m")];
    const double impacts = out.responses[Column(evaluator, "impacts")];
    const spectra::PointParameters p = [&] {
      const spectra::SweepRecord* record = nullptr;
      return evaluator.Parameters(index, &record);
    }();
    const double rho_m = spectra::ToDimensional(p, spectra::PulseScales(p)).rho_m;
    if (eta0->values[index[eta0_dim]] <= 1.0) {
      EXPECT_LE(theta_m * rho_m, 1e-12 * x_m) << "cell " << cell;
      if (impacts > 0) ++pounding_below;
    } else if (impacts > 0 && theta_m * rho_m > 1e-3 * x_m) {
      ++rotating_above;
    }
  }
  EXPECT_GE(pounding_below, 10);
  EXPECT_GE(rotating_above, 10);
}

// With Pi_delta = 1e6 the gaps are a million persistencies wide, so no contact can close and
// the sweep's cell is the linear response of the eccentric substructure. The reference run is
// the same deck with no contacts at all, integrated over the same time.
TEST(PilotBridge, GapsThatNeverCloseRotateExactlyAsTheContactFreeDeck) {
  const SweepSpec spec = ParseSweepSpec(R"([sweep]
name = "pilot-open"
family = "pilot-bridge"
[axes]
pulse = ["cosine", "sine"]
w0_over_wg = [0.5, 1.0, 2.0, 4.0]
[fixed]
Pi_delta = 1e6
)",
                                        "pilot-open.toml", fs::temp_directory_path());
  const spectra::SpectraEvaluator evaluator(spec);
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    SCOPED_TRACE("cell " + std::to_string(cell));
    const std::vector<std::size_t> index = spec.AxisIndex(cell);
    const CellOutcome swept = evaluator.Evaluate(index);
    ASSERT_EQ(swept.status, kStatusOk) << swept.status_text;
    EXPECT_EQ(swept.responses[Column(evaluator, "impacts")], 0.0);

    const spectra::SweepRecord* record = nullptr;
    const spectra::PointParameters p = evaluator.Parameters(index, &record);
    const spectra::ExcitationScales scales = spectra::PulseScales(p);
    const spectra::DimensionalPoint point = spectra::ToDimensional(p, scales);
    const model::Model with_contacts = model::BuildDeckModel(point.deck, "pilot");
    ASSERT_EQ(with_contacts.n_contacts(), 4);
    const model::Model free_deck(with_contacts.bodies(), with_contacts.K(), with_contacts.C(),
                                 with_contacts.r(), {}, "pilot-free");
    const records::PulseExcitation pulse(p.pulse, scales.a_g_mps2, scales.w_g_radps);
    const model::Modes modes = model::ComputeModes(free_deck.M(), free_deck.K());
    model::RunControl control;
    control.absolute_tolerance = 1e-11 * point.persistency_m;
    control.end_time_s =
        pulse.Duration() + 2.0 * std::max(2.0 * std::numbers::pi / scales.w_g_radps,
                                          2.0 * std::numbers::pi / modes.omega_radps.minCoeff());
    dynamics::SimulationWorkspace workspace(free_deck);
    const dynamics::RunResult free_run = dynamics::Simulate(free_deck, pulse, control, workspace);
    ASSERT_EQ(free_run.status, dynamics::RunStatus::kOk);

    const double theta_m = swept.responses[Column(evaluator, "theta_m")];
    const double x_m = swept.responses[Column(evaluator, "x_m")];
    EXPECT_NEAR(theta_m, free_run.max_abs_q(2), 1e-9 * free_run.max_abs_q(2));
    EXPECT_NEAR(x_m, free_run.max_abs_q(0), 1e-9 * free_run.max_abs_q(0));
    // The eccentricity (0.24 m against rho = 26.4 m) couples little: the rotation moves the
    // deck's ends by a small fraction of its translation.
    EXPECT_GT(theta_m, 0.0);
    EXPECT_LT(theta_m * point.rho_m, 0.05 * x_m);
  }
}

// The pilot bridge's skew axes: a_deg = 20 given explicitly is the published deck bit for bit,
// another skew or eta0 a plan that reproduces m and I_m by the uniform-deck rule.
TEST(PilotBridge, SkewAxesKeepTheDefaultBitForBitAndReproduceTheInertia) {
  const std::string base = R"([sweep]
name = "pilot-skew"
family = "pilot-bridge"
[axes]
w0_over_wg = [0.5, 2.0]
)";
  const SweepSpec omitted =
      ParseSweepSpec(base + "[fixed]\nPi_delta = 0.5\n", "omitted.toml", fs::temp_directory_path());
  const SweepSpec swept = ParseSweepSpec(base + "a_deg = [20.0, 35.0]\n[fixed]\nPi_delta = 0.5\n",
                                         "swept.toml", fs::temp_directory_path());
  const SpectraEvaluator plain(omitted);
  const SpectraEvaluator skewed(swept);
  ASSERT_EQ(swept.CellCount(), 2 * omitted.CellCount());
  const std::size_t a_axis = swept.axes[0].key == "a_deg" ? 0 : 1;
  for (std::size_t w = 0; w < 2; ++w) {
    SCOPED_TRACE("w0_over_wg index " + std::to_string(w));
    const CellOutcome reference = plain.Evaluate(std::vector<std::size_t>{w});
    ASSERT_EQ(reference.status, kStatusOk) << reference.status_text;
    std::vector<std::size_t> index(2);
    index[1 - a_axis] = w;
    index[a_axis] = 0;  // a_deg = 20, the published skew
    const CellOutcome same = skewed.Evaluate(index);
    ASSERT_EQ(same.responses.size(), reference.responses.size());
    for (std::size_t k = 0; k < reference.responses.size(); ++k) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(same.responses[k]),
                std::bit_cast<std::uint64_t>(reference.responses[k]))
          << plain.Responses()[k].name;
    }
    index[a_axis] = 1;  // a_deg = 35
    const SweepRecord* record = nullptr;
    const spectra::PointParameters p = skewed.Parameters(index, &record);
    const spectra::DimensionalPoint point = spectra::ToDimensional(p, spectra::PulseScales(p));
    EXPECT_NEAR(point.deck.geometry.skew_rad, 35.0 * std::numbers::pi / 180.0, 1e-15);
    EXPECT_NEAR(model::UniformDeckInertia(point.deck.mass_kg, point.deck.geometry), 1079100e3,
                1e-12 * 1079100e3);
    EXPECT_NEAR(point.deck.geometry.width_m / point.deck.geometry.length_m, 19.36 / 89.14, 1e-14);
    const CellOutcome other = skewed.Evaluate(index);
    ASSERT_EQ(other.status, kStatusOk) << other.status_text;
    EXPECT_NE(other.responses[Column(skewed, "theta_m")],
              reference.responses[Column(plain, "theta_m")]);
  }
}

TEST(PilotBridge, ImpossibleSkewsAreRefusedNamingTheKey) {
  const auto message = [](const std::string& extra) {
    try {
      const SweepSpec spec = ParseSweepSpec(
          "[sweep]\nname = \"p\"\nfamily = \"pilot-bridge\"\n[axes]\nPi_delta = [1.0]\n" + extra,
          "p.toml", fs::temp_directory_path());
      const SpectraEvaluator evaluator(spec);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("eta0 = [1.0]\n[fixed]\na_deg = 0.0\n").find("eta0"), std::string::npos);
  EXPECT_NE(message("eta0 = [-1.0]\n").find("eta0"), std::string::npos);
  EXPECT_NE(message("a_deg = [95.0]\n").find("a_deg"), std::string::npos);
  EXPECT_NE(message("W_over_L = [0.2]\n").find("W_over_L"), std::string::npos);
  EXPECT_EQ(message("eta0 = [0.8, 2.0]\n"), "accepted");
}

}  // namespace
}  // namespace skewbridge::jobs
