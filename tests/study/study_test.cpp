// The study machinery of jobs/study.h: the [study] and [records] synthetic keys, the w0x/w_g
// groups, in-memory synthetic records against the files `records synth` writes, the grouping
// of the correlation table, and the pilot bridge under records with gaps that never close
// against the contact-free deck.

#include "jobs/study.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "jobs/h5/cube_file.h"
#include "jobs/sweep_runner.h"
#include "jobs/transport.h"
#include "records/excitations.h"
#include "records/incidence.h"
#include "records/synthetic.h"
#include "solver/common/error.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/builders.h"
#include "solver/model/model.h"
#include "spectra/correlation.h"
#include "spectra/point.h"
#include "spectra/spectra_evaluator.h"

namespace skewbridge::jobs::study_test {
namespace {

namespace fs = std::filesystem;
using spectra::FitLogLog;
using spectra::Pearson;
using spectra::Spearman;
using spectra::SpectraEvaluator;

// A folder of its own per test process, removed afterwards.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(fs::temp_directory_path() /
              ("skewbridge_study_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string Labels(int seed, int count) {
  std::string out = "[";
  for (int i = 0; i < count; ++i) {
    const std::string digits = std::to_string(i);
    out += std::string(i ? ", " : "") + "\"synth-" + std::to_string(seed) + "-" +
           std::string(3 - digits.size(), '0') + digits + "\"";
  }
  return out + "]";
}

// A pilot-bridge spec named `name` over `count` synthetic records of seed 3 (the record axis),
// followed by `rest` (further axes, or a [fixed] table).
SweepSpec SyntheticPilotSpec(const std::string& name, int count, const std::string& rest) {
  return ParseSweepSpec("[sweep]\nname = \"" + name +
                            "\"\nfamily = \"pilot-bridge\"\n[records]\nsynthetic = {count = " +
                            std::to_string(count) +
                            ", seed = 3}\n[axes]\nrecord = " + Labels(3, count) + "\n" + rest,
                        name + ".toml", fs::temp_directory_path());
}

// A cube layout of `responses`, each stored in its own column in that order.
CubeLayout OwnColumns(std::vector<ResponseInfo> responses) {
  CubeLayout layout;
  layout.responses = std::move(responses);
  for (std::size_t i = 0; i < layout.responses.size(); ++i) {
    layout.source_index.push_back(i);
  }
  return layout;
}

std::size_t Column(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  EXPECT_NE(it, names.end()) << name;
  return static_cast<std::size_t>(it - names.begin());
}

TEST(StudySpec, ReadsBandsAndASyntheticSuiteIntoTheCanonicalText) {
  const SweepSpec spec = ParseSweepSpec(R"([sweep]
name = "s"
family = "pilot-bridge"
[records]
synthetic = {count = 4, seed = 9}
[study]
bands = [0.25, 1.5]
[axes]
record = ["synth-9-000", "synth-9-003"]
Pi_delta = [1.0]
)",
                                        "s.toml", fs::temp_directory_path());
  EXPECT_EQ(spec.synthetic_count, 4);
  EXPECT_EQ(spec.synthetic_seed, 9U);
  EXPECT_EQ(spec.study_bands, (std::vector<double>{0.25, 1.5}));
  EXPECT_EQ(BandEdges(spec), (std::vector<double>{0.25, 1.5}));
  const std::string canonical = spec.CanonicalText();
  EXPECT_NE(canonical.find("records.synthetic = {count = 4, seed = 9}\n"), std::string::npos);
  EXPECT_NE(canonical.find("study.bands = [0.25, 1.5]\n"), std::string::npos);
}

// Specifications without the new keys keep their canonical text, hence their hash and the
// resume identity of cubes written before the keys existed.
TEST(StudySpec, LeavesTheCanonicalTextOfOtherSpecsAlone) {
  const SweepSpec spec = ParseSweepSpec(R"([sweep]
name = "p"
family = "subsystem"
[axes]
w0_over_wg = [1.0, 2.0]
)",
                                        "p.toml", fs::temp_directory_path());
  EXPECT_EQ(spec.CanonicalText(),
            "sweep.name = \"p\"\nsweep.family = \"subsystem\"\naxes.w0_over_wg = [1, 2]\n"
            "sweep.responses = []\n");
  EXPECT_EQ(BandEdges(spec), (std::vector<double>{0.5, 1.0, 2.0}));
}

TEST(StudySpec, RefusesBadBandsAndAmbiguousRecordSources) {
  const auto message = [](const std::string& text) {
    try {
      ParseSweepSpec(text, "bad.toml", fs::temp_directory_path());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string head = "[sweep]\nname = \"b\"\nfamily = \"pilot-bridge\"\n";
  const std::string axes = "[axes]\nrecord = [\"synth-1-000\"]\n";
  EXPECT_NE(message(head +
                    "[records]\nsynthetic = {count = 2, seed = 1}\n[study]\nbands = "
                    "[1.0, 0.5]\n" +
                    axes)
                .find("study.bands: must be a list of increasing"),
            std::string::npos);
  EXPECT_NE(message(head +
                    "[records]\nsynthetic = {count = 2, seed = 1}\n[study]\nbands = "
                    "[0.0]\n" +
                    axes)
                .find("study.bands"),
            std::string::npos);
  EXPECT_NE(message(head +
                    "[records]\nsynthetic = {count = 2, seed = 1}\n[study]\nedges = "
                    "[1.0]\n" +
                    axes)
                .find("study.edges: unknown key; allowed: bands"),
            std::string::npos);
  EXPECT_NE(message(head + "[records]\nsynthetic = {count = 0, seed = 1}\n" + axes)
                .find("records.synthetic.count"),
            std::string::npos);
  EXPECT_NE(
      message(head + "[records]\nsynthetic = {count = 2}\n" + axes).find("records.synthetic.seed"),
      std::string::npos);
  EXPECT_NE(
      message(head + "[records]\nset = \"x.toml\"\nsynthetic = {count = 2, seed = 1}\n" + axes)
          .find("records: give set"),
      std::string::npos);
}

TEST(BandOf, PutsEachRatioInTheHalfOpenGroupOfItsEdges) {
  const std::vector<double> edges{0.5, 1.0, 2.0};
  EXPECT_EQ(BandOf(0.0, edges), 0.0);
  EXPECT_EQ(BandOf(0.3, edges), 0.0);
  EXPECT_EQ(BandOf(0.5, edges), 1.0);
  EXPECT_EQ(BandOf(0.999, edges), 1.0);
  EXPECT_EQ(BandOf(1.0, edges), 2.0);
  EXPECT_EQ(BandOf(2.0, edges), 3.0);
  EXPECT_EQ(BandOf(40.0, edges), 3.0);
  EXPECT_TRUE(std::isnan(BandOf(std::numeric_limits<double>::quiet_NaN(), edges)));
}

// [records] synthetic makes in memory the samples that `skewbridge records synth` writes: the
// same suite read back from its .AT2 files through a manifest gives identical accelerations
// and measures.
TEST(LoadSweepRecords, SyntheticSuiteInMemoryEqualsTheWrittenFiles) {
  const TempDir dir("synth");
  records::SynthOptions options;
  options.count = 3;
  options.seed = 77;
  records::WriteSuite(dir.path() / "suite", options);
  const std::string tail = "[axes]\nrecord = " + Labels(77, 3) + "\nPi_delta = [1.0]\n";
  const SweepSpec from_files = ParseSweepSpec(
      "[sweep]\nname = \"f\"\nfamily = \"pilot-bridge\"\n[records]\nset = \"suite/set.toml\"\n" +
          tail,
      "f.toml", dir.path());
  const SweepSpec in_memory = ParseSweepSpec(
      "[sweep]\nname = \"m\"\nfamily = \"pilot-bridge\"\n[records]\nsynthetic = {count = 3, "
      "seed = 77}\n" +
          tail,
      "m.toml", dir.path());
  const std::vector<SweepRecord> a = LoadSweepRecords(from_files);
  const std::vector<SweepRecord> b = LoadSweepRecords(in_memory);
  ASSERT_EQ(a.size(), 3U);
  ASSERT_EQ(b.size(), 3U);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].label, b[i].label);
    EXPECT_EQ(a[i].file, "synth_00" + std::to_string(i) + ".AT2");
    EXPECT_EQ(b[i].file, "");
    EXPECT_EQ(a[i].motion.dt_s, b[i].motion.dt_s);
    EXPECT_EQ(a[i].motion.acc_mps2, b[i].motion.acc_mps2);
    EXPECT_EQ(a[i].measures.pga_mps2, b[i].measures.pga_mps2);
    EXPECT_EQ(a[i].measures.mean_period_s, b[i].measures.mean_period_s);
    EXPECT_EQ(a[i].measures.persistency_m, b[i].measures.persistency_m);
    // The suite's PGA range starts at 0.1 g.
    EXPECT_GE(b[i].measures.pga_mps2, 0.1 * 9.80665 * (1.0 - 1e-6));
  }
  const SweepSpec wrong = ParseSweepSpec(
      "[sweep]\nname = \"w\"\nfamily = \"pilot-bridge\"\n[records]\nsynthetic = {count = 3, "
      "seed = 77}\n[axes]\nrecord = [\"synth-77-003\"]\n",
      "w.toml", dir.path());
  try {
    LoadSweepRecords(wrong);
    ADD_FAILURE() << "a label beyond the suite was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'synth-77-003' is not in the synthetic suite"),
              std::string::npos)
        << e.what();
  }
}

// A synthesised record of a sweep is what the reader makes of its .AT2 text (every field, every
// sample to the bit), without a second trip through the text.
TEST(LoadSweepRecords, SyntheticRecordsAreTheAt2TextReadBack) {
  const SweepSpec spec = LoadSweepSpec(fs::path(SKEWBRIDGE_SPECS_DIR) / "pilot-study.toml");
  const std::vector<SweepRecord> loaded = LoadSweepRecords(spec);
  ASSERT_EQ(loaded.size(), 62U);
  records::SynthOptions options;
  options.count = 62;
  options.seed = 2011;
  for (const int i : {0, 1, 17, 40, 61}) {
    const SweepRecord& r = loaded[static_cast<std::size_t>(i)];
    const records::GroundMotion oracle =
        records::ParseRecord(records::FormatAt2(records::SynthesizeRecord(options, i)), r.label);
    EXPECT_EQ(r.motion.file, oracle.file);
    EXPECT_EQ(r.motion.format, oracle.format);
    EXPECT_EQ(r.motion.event, oracle.event);
    EXPECT_EQ(r.motion.station, oracle.station);
    EXPECT_EQ(r.motion.component, oracle.component);
    EXPECT_EQ(r.motion.original_units, oracle.original_units);
    EXPECT_EQ(r.motion.notes, oracle.notes);
    EXPECT_EQ(std::memcmp(&r.motion.dt_s, &oracle.dt_s, sizeof(double)), 0);
    ASSERT_EQ(r.motion.npts(), oracle.npts());
    EXPECT_EQ(std::memcmp(r.motion.acc_mps2.data(), oracle.acc_mps2.data(),
                          oracle.npts() * sizeof(double)),
              0)
        << r.label;
  }
}

// Rank 0 builds the record table from the evaluator's records instead of making the suite a
// second time: the tables are those of loading the records afresh.
TEST(MakeStudyTables, TheEvaluatorsRecordsGiveTheTablesOfLoadingThemAgain) {
  const SweepSpec spec = LoadSweepSpec(fs::path(SKEWBRIDGE_SPECS_DIR) / "pilot-study.toml");
  const SpectraEvaluator evaluator(spec);
  ASSERT_NE(evaluator.Records(), nullptr);
  const CubeLayout layout = MakeCubeLayout(evaluator, spec.responses, spec.source);
  CubeData data;
  data.Reset(spec.CellCount(), layout.responses.size());
  const StudyTables shared = MakeStudyTables(spec, layout, data, evaluator.Records());
  const StudyTables fresh = MakeStudyTables(spec, layout, data);
  ASSERT_EQ(shared.records.size(), fresh.records.size());
  for (std::size_t i = 0; i < fresh.records.size(); ++i) {
    EXPECT_EQ(shared.records[i].label, fresh.records[i].label);
    EXPECT_EQ(shared.records[i].file, fresh.records[i].file);
    EXPECT_EQ(shared.records[i].motion.acc_mps2, fresh.records[i].motion.acc_mps2);
    EXPECT_EQ(shared.records[i].measures.persistency_m, fresh.records[i].measures.persistency_m);
    EXPECT_EQ(shared.records[i].measures.arias_mps, fresh.records[i].measures.arias_mps);
  }
  EXPECT_EQ(shared.records_set, fresh.records_set);
}

// A one-deck model-file sweep names its rotation theta_m_d0: the statistics are those of that
// column, and a two-deck layout (no single rotation) gets none.
TEST(MakeStudyTables, AOneDeckModelFileSweepCorrelatesItsDecksRotation) {
  const SweepSpec spec = SyntheticPilotSpec("g", 5, "Pi_delta = [0.5]\n");
  CubeLayout layout = OwnColumns({{"theta_m_d0", "rad", ""}, {"L_e", "m", ""}});
  CubeData data;
  data.Reset(spec.CellCount(), 2);
  std::vector<double> x;
  std::vector<double> y;
  for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
    const double le = 0.01 * static_cast<double>(1 + c);
    const double theta = 1e-4 * le * le + 1e-7 * static_cast<double>((c * 3) % 4);
    data.Store(c, kStatusOk, {theta, le}, CellStats{}, 1);
    data.done[c] = 1;
    x.push_back(le);
    y.push_back(theta);
  }
  const StudyTables one = MakeStudyTables(spec, layout, data);
  ASSERT_TRUE(one.correlation.has_value());
  EXPECT_EQ(one.correlation->y, "theta_m_d0");
  EXPECT_EQ(one.correlation->n[0], 5);
  EXPECT_EQ(one.correlation->pearson[0], Pearson(x, y).value);
  EXPECT_EQ(one.correlation->spearman[0], Spearman(x, y).value);

  layout.responses.push_back({"theta_m_d1", "rad", ""});
  layout.source_index.push_back(2);
  data.Reset(spec.CellCount(), 3);
  EXPECT_FALSE(MakeStudyTables(spec, layout, data).correlation.has_value());
}

// With an axis besides record and Pi_delta, each (Pi_delta, mu) pair gets its own statistics
// over the records: the table equals the statistics of the cells picked by hand, and a failed
// cell is left out.
TEST(MakeStudyTables, GroupsTheRecordAxisPerCombinationOfTheOtherAxes) {
  const SweepSpec spec = SyntheticPilotSpec("g", 4, "Pi_delta = [0.5, 2.0]\nmu = [0.0, 0.3]\n");
  // Canonical axis order: record, mu, Pi_delta.
  ASSERT_EQ(spec.axes[0].key, "record");
  ASSERT_EQ(spec.axes[2].key, "Pi_delta");
  const CubeLayout layout =
      OwnColumns({{"theta_m", "rad", ""}, {"L_e", "m", ""}, {"band", "1", ""}});
  CubeData data;
  data.Reset(spec.CellCount(), 3);
  for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
    const std::vector<std::size_t> i = spec.AxisIndex(c);
    const double le = 0.01 * static_cast<double>(1 + i[0]);
    const double theta = 1e-4 * std::pow(le, 1.0 + static_cast<double>(i[1] + 2 * i[2])) +
                         1e-9 * static_cast<double>((i[0] * 7) % 3);
    data.Store(c, kStatusOk, {theta, le, static_cast<double>(i[0] % 2)}, CellStats{}, 1);
    data.done[c] = 1;
  }
  // Record 2 at (mu 0.3, Pi_delta 2) failed.
  const std::uint64_t failed = (2 * 2 + 1) * 2 + 1;
  data.status[failed] = spectra::kStatusPainleve;
  const StudyTables tables = MakeStudyTables(spec, layout, data);
  EXPECT_EQ(tables.band_edges, (std::vector<double>{0.5, 1.0, 2.0}));
  EXPECT_EQ(tables.records_source, "synthetic");
  EXPECT_EQ(tables.records_set, "synthetic count=4 seed=3");
  ASSERT_EQ(tables.records.size(), 4U);
  ASSERT_TRUE(tables.correlation.has_value());
  const CorrelationTable& t = *tables.correlation;
  EXPECT_EQ(t.axis_order, (std::vector<std::string>{"mu", "Pi_delta"}));
  EXPECT_EQ(t.shape, (std::vector<std::size_t>{2, 2}));
  EXPECT_EQ(t.bands, 4U);
  for (std::size_t mu = 0; mu < 2; ++mu) {
    for (std::size_t pd = 0; pd < 2; ++pd) {
      std::vector<double> x;
      std::vector<double> y;
      for (std::size_t r = 0; r < 4; ++r) {
        const std::uint64_t c = (r * 2 + mu) * 2 + pd;
        if (c == failed) continue;
        x.push_back(data.responses[1][c]);
        y.push_back(data.responses[0][c]);
      }
      const std::size_t g = mu * 2 + pd;
      EXPECT_EQ(t.n[g], static_cast<std::int64_t>(x.size()));
      EXPECT_EQ(t.pearson[g], Pearson(x, y).value);
      EXPECT_EQ(t.spearman[g], Spearman(x, y).value);
      EXPECT_EQ(t.loglog_slope[g], FitLogLog(x, y).slope.value);
      // Bands 0 and 1 hold records {0, 2} and {1, 3}: fewer than 3, so no statistics.
      EXPECT_EQ(t.band_n[g * 4 + 0] + t.band_n[g * 4 + 1], t.n[g]);
      EXPECT_EQ(t.band_n[g * 4 + 2], 0);
      EXPECT_TRUE(std::isnan(t.band_pearson[g * 4 + 0]));
    }
  }
  EXPECT_EQ(t.n[3], 3);
}

// A sweep without a Pi_delta axis gets the record table but no correlation table.
TEST(MakeStudyTables, NeedsAPiDeltaAxisForTheCorrelation) {
  const SweepSpec spec = SyntheticPilotSpec("r", 2, "[fixed]\nPi_delta = 1.0\n");
  const CubeLayout layout = OwnColumns({{"theta_m", "rad", ""}, {"L_e", "m", ""}});
  CubeData data;
  data.Reset(spec.CellCount(), 2);
  const StudyTables tables = MakeStudyTables(spec, layout, data);
  EXPECT_EQ(tables.records.size(), 2U);
  EXPECT_TRUE(tables.band_edges.empty());
  EXPECT_FALSE(tables.correlation.has_value());
}

// Rotations below the round-off floor (spectra::kRotationRoundOffFloor_rad), as cells with
// impacts and no physical rotation store them, are zero for the fits: the cloud fit of the
// rotation limit state equals least squares written out here over the other cells only, it
// counts the sub-floor cells as left out, and a threshold of 0 is not exceeded by them.
TEST(MakeStudyTables, ReadsRotationsBelowTheRoundOffFloorAsZero) {
  for (const double threshold : {1e-4, 0.0}) {
    const SweepSpec spec =
        SyntheticPilotSpec("r", 12,
                           "[fixed]\na_deg = 20\n[limit_states]\nrotation = {above_rad = " +
                               std::string(threshold > 0.0 ? "1e-4" : "0.0") + "}\n");
    const CubeLayout layout = OwnColumns(
        {{"a_g", "m/s2", ""}, {"ls_rotation", "1", ""}, {"ls_rotation_demand", "rad", ""}});
    CubeData data;
    data.Reset(spec.CellCount(), 3);
    std::vector<double> ln_im, ln_dc;  // the cells above the floor
    std::int64_t exceeded = 0;
    for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
      const double im_g = 0.2 + 0.15 * static_cast<double>(c);
      const bool round_off = c == 2 || c == 7 || c == 9;
      const double theta =
          round_off ? 1e-20 * static_cast<double>(c * c)
                    : 2e-4 * std::pow(im_g, 1.5) * (1.0 + 0.2 * static_cast<double>((c * 5) % 3));
      // Stored as the limit state stores it: exceeded when above the threshold.
      data.Store(c, kStatusOk,
                 {im_g * records::kStandardGravity_mps2, theta > threshold ? 1.0 : 0.0, theta},
                 CellStats{}, 1);
      data.done[c] = 1;
      if (round_off) continue;
      exceeded += theta > threshold ? 1 : 0;
      ln_im.push_back(std::log(im_g));
      ln_dc.push_back(std::log(threshold > 0.0 ? theta / threshold : theta));
    }
    const StudyTables tables = MakeStudyTables(spec, layout, data);
    ASSERT_EQ(tables.fragility.size(), 1U);
    const spectra::FragilityTable& t = tables.fragility[0].table;
    EXPECT_EQ(t.n_cells[0], 12);
    EXPECT_EQ(t.n_exceeded[0], exceeded) << "threshold " << threshold;
    if (threshold == 0.0) {
      EXPECT_EQ(t.cloud_reason[0], "a threshold of 0 or less: no ln(demand / capacity)");
      continue;
    }
    // Least squares of ln(D / C) on ln(IM) over the 9 cells above the floor.
    const double n = static_cast<double>(ln_im.size());
    double mx = 0.0, my = 0.0;
    for (std::size_t i = 0; i < ln_im.size(); ++i) {
      mx += ln_im[i] / n;
      my += ln_dc[i] / n;
    }
    double sxx = 0.0, sxy = 0.0;
    for (std::size_t i = 0; i < ln_im.size(); ++i) {
      sxx += (ln_im[i] - mx) * (ln_im[i] - mx);
      sxy += (ln_im[i] - mx) * (ln_dc[i] - my);
    }
    const double slope = sxy / sxx, intercept = my - slope * mx;
    double ss = 0.0;
    for (std::size_t i = 0; i < ln_im.size(); ++i) {
      const double r = ln_dc[i] - intercept - slope * ln_im[i];
      ss += r * r;
    }
    const double sigma = std::sqrt(ss / (n - 2.0));
    EXPECT_EQ(t.cloud_reason[0], "");
    EXPECT_EQ(t.cloud_n[0], 9);
    EXPECT_EQ(t.cloud_excluded[0], 3);
    EXPECT_NEAR(t.cloud_slope[0], slope, 1e-12 * slope);
    EXPECT_NEAR(t.cloud_intercept[0], intercept, 1e-12 * std::abs(intercept));
    EXPECT_NEAR(t.cloud_sigma[0], sigma, 1e-10 * sigma);
    EXPECT_NEAR(t.cloud_beta[0], sigma / slope, 1e-10 * sigma / slope);
  }
}

// The default study needs no generated files: its spec names the 62-record suite of seed 2011,
// at least 0.1 g each, 3 Pi_delta values.
TEST(StudySpecs, TheDefaultStudyMakesItsSixtyTwoRecordsInMemory) {
  const SweepSpec spec = LoadSweepSpec(fs::path(SKEWBRIDGE_SPECS_DIR) / "pilot-study.toml");
  EXPECT_EQ(spec.synthetic_count, 62);
  EXPECT_EQ(spec.synthetic_seed, 2011U);
  EXPECT_EQ(spec.FindAxis("record")->labels, [] {
    std::vector<std::string> labels;
    for (int i = 0; i < 62; ++i) {
      const std::string digits = std::to_string(i);
      labels.push_back("synth-2011-" + std::string(3 - digits.size(), '0') + digits);
    }
    return labels;
  }());
  EXPECT_EQ(spec.FindAxis("Pi_delta")->values, (std::vector<double>{0.5, 1.0, 2.0}));
  EXPECT_EQ(BandEdges(spec), (std::vector<double>{0.5, 1.0, 2.0}));
}

// The same study over the real records of ../shared/records through records/sets/shared.toml:
// every record of the manifest, in its order, measured as the manifest scales it.
TEST(StudySpecs, TheSharedStudyReadsEveryRecordOfTheSharedManifest) {
  const fs::path shared_records = fs::path(SKEWBRIDGE_SHARED_DIR) / "records";
  if (!fs::exists(shared_records)) GTEST_SKIP() << shared_records << " is absent";
  const SweepSpec spec =
      LoadSweepSpec(fs::path(SKEWBRIDGE_SPECS_DIR) / "real" / "pilot-study-shared.toml");
  const std::vector<SweepRecord> loaded = LoadSweepRecords(spec);
  const std::vector<std::string>& labels = spec.FindAxis("record")->labels;
  ASSERT_EQ(loaded.size(), labels.size());
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    SCOPED_TRACE(loaded[i].label);
    EXPECT_EQ(loaded[i].label, labels[i]);
    // The manifest names each file relative to itself, ../../../shared/records/...
    EXPECT_EQ(loaded[i].file.rfind("../../../shared/records/", 0), 0U) << loaded[i].file;
    EXPECT_TRUE(fs::exists(spec.record_set_path.parent_path() / loaded[i].file));
    const records::IntensityMeasures& m = loaded[i].measures;
    EXPECT_NEAR(m.persistency_m, m.pga_mps2 / (m.omega_g_radps * m.omega_g_radps),
                1e-12 * m.persistency_m);
  }
  const SpectraEvaluator evaluator(spec);
  EXPECT_EQ(spec.CellCount(), 3 * labels.size());
}

// A sweep stopped after some cells and resumed writes the statistics of all its cells: its
// correlation and record tables equal those of the uninterrupted sweep, bit for bit.
TEST(PilotStudy, AResumedSweepRecomputesTheStatisticsFromTheCellsOfEveryRun) {
  const TempDir dir("resume");
  const SweepSpec spec = ParseSweepSpec(
      "[sweep]\nname = \"r\"\nfamily = \"pilot-bridge\"\n[records]\nsynthetic = {count = 5, "
      "seed = 2011}\n[axes]\nrecord = " +
          Labels(2011, 5) + "\nPi_delta = [0.5, 1.0, 2.0]\n",
      "r.toml", dir.path());
  const SpectraEvaluator evaluator(spec);
  const auto transport = MakeInProcessTransport();
  SweepOptions whole;
  whole.out = dir.path() / "whole.h5";
  RunSweep(spec, evaluator, *transport, whole);

  volatile std::sig_atomic_t stop = 0;
  SweepOptions first;
  first.out = dir.path() / "resumed.h5";
  first.checkpoint_cells = 1;
  first.progress_seconds = 0.0;
  first.max_chunk = 1;
  first.stop = &stop;
  first.progress = [&stop](const SweepProgress& p) {
    if (p.run_done >= 6) stop = 1;
  };
  const SweepReport stopped = RunSweep(spec, evaluator, *transport, first);
  ASSERT_TRUE(stopped.interrupted);
  ASSERT_LT(stopped.cells_done, spec.CellCount());
  ASSERT_TRUE(fs::exists(PartialPath(first.out)));
  SweepOptions second;
  second.out = first.out;
  second.resume = true;
  const SweepReport resumed = RunSweep(spec, evaluator, *transport, second);
  ASSERT_FALSE(resumed.interrupted);
  EXPECT_EQ(resumed.run, 2);

  std::vector<std::string> names;
  const CubeData cube = h5::ReadCubeData(first.out, "r", &names);
  EXPECT_NE(std::count(cube.run.begin(), cube.run.end(), 1), 0);
  EXPECT_NE(std::count(cube.run.begin(), cube.run.end(), 2), 0);
  CubeLayout layout;
  layout.responses = evaluator.Responses();
  for (std::size_t r = 0; r < layout.responses.size(); ++r) layout.source_index.push_back(r);
  const StudyTables from_resumed = MakeStudyTables(spec, layout, cube);
  const StudyTables from_whole =
      MakeStudyTables(spec, layout, h5::ReadCubeData(whole.out, "r", &names));
  ASSERT_TRUE(from_resumed.correlation && from_whole.correlation);
  EXPECT_EQ(from_resumed.correlation->n, (std::vector<std::int64_t>{5, 5, 5}));
  EXPECT_EQ(from_resumed.correlation->pearson, from_whole.correlation->pearson);
  EXPECT_EQ(from_resumed.correlation->spearman, from_whole.correlation->spearman);
  EXPECT_EQ(from_resumed.correlation->loglog_slope, from_whole.correlation->loglog_slope);
  // And the stored tables are those: the cube's statistics equal the recomputed ones.
  EXPECT_EQ(h5::ReadSweepArray(first.out, "r", "correlation/pearson_theta_Le"),
            from_whole.correlation->pearson);
  EXPECT_EQ(h5::ReadSweepArray(whole.out, "r", "correlation/loglog_r2"),
            from_whole.correlation->loglog_r2);
}

// Under records, with both gaps 1000 persistencies wide, no contact closes: the cube's theta_m
// (through RunSweep and the final file) is the rotation that the eccentricity of the centre of
// rigidity alone produces, i.e. that of the same deck without contacts. Extends
// tests/sweeps PilotBridge.GapsThatNeverClose... (pulses, evaluator) to records and the cube.
TEST(PilotStudy, RecordsWithGapsThatNeverCloseRotateAsTheContactFreeDeck) {
  const TempDir dir("open");
  const SweepSpec spec = ParseSweepSpec(
      "[sweep]\nname = \"open\"\nfamily = \"pilot-bridge\"\n[records]\nsynthetic = {count = 2, "
      "seed = 2011}\n[axes]\nrecord = " +
          Labels(2011, 2) + "\nPi_delta = [1e3]\n",
      "open.toml", dir.path());
  const SpectraEvaluator evaluator(spec);
  SweepOptions options;
  options.out = dir.path() / "open.h5";
  const auto transport = MakeInProcessTransport();
  RunSweep(spec, evaluator, *transport, options);
  std::vector<std::string> names;
  const CubeData cube = h5::ReadCubeData(options.out, "open", &names);
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    SCOPED_TRACE("cell " + std::to_string(cell));
    ASSERT_EQ(cube.status[cell], kStatusOk);
    EXPECT_EQ(cube.responses[Column(names, "impacts")][cell], 0.0);
    const SweepRecord* record = nullptr;
    const spectra::PointParameters p = evaluator.Parameters(spec.AxisIndex(cell), &record);
    ASSERT_NE(record, nullptr);
    const spectra::DimensionalPoint point = spectra::ToDimensional(
        p, spectra::ExcitationScales{record->measures.pga_mps2, record->measures.omega_g_radps});
    EXPECT_NEAR(point.delta_m, 1e3 * record->measures.persistency_m, 1e-12 * point.delta_m);
    const model::Model with_contacts = model::BuildDeckModel(point.deck, "pilot");
    const model::Model free_deck(with_contacts.bodies(), with_contacts.K(), with_contacts.C(),
                                 with_contacts.r(), {}, "pilot-free");
    const records::SampledExcitation ground = records::ToExcitation(record->motion);
    const model::Modes modes = model::ComputeModes(free_deck.M(), free_deck.K());
    model::RunControl control;
    control.absolute_tolerance = 1e-11 * point.persistency_m;
    control.end_time_s =
        ground.Duration() + 2.0 * std::max(2.0 * std::numbers::pi / point.scales.w_g_radps,
                                           2.0 * std::numbers::pi / modes.omega_radps.minCoeff());
    dynamics::SimulationWorkspace workspace(free_deck);
    const dynamics::RunResult free_run = dynamics::Simulate(free_deck, ground, control, workspace);
    ASSERT_EQ(free_run.status, dynamics::RunStatus::kOk);
    const double theta_m = cube.responses[Column(names, "theta_m")][cell];
    EXPECT_GT(theta_m, 0.0);
    EXPECT_NEAR(theta_m, free_run.max_abs_q(2), 1e-9 * free_run.max_abs_q(2));
    EXPECT_NEAR(cube.responses[Column(names, "x_m")][cell], free_run.max_abs_q(0),
                1e-9 * free_run.max_abs_q(0));
  }
}

// A pilot-bridge cell's record excitation carries the pieces of its record that hold the peak
// (found once per record): its scale has the bits of the walk over every piece of the record as
// read, for each record and incidence, and its samples are the record's. Pieces kept for
// another record, or for the unscaled direction only, would give another scale.
TEST(PilotBridgeRecords, ACellsScaleIsTheWalkOverEveryPieceOfItsRecord) {
  const SweepSpec spec = SyntheticPilotSpec("peak", 4, "incidence_deg = [0.0, 35.0, 90.0]\n");
  const SpectraEvaluator evaluator(spec);
  const double horizon = evaluator.policies().event.ramp_horizon_s;
  ASSERT_EQ(spec.CellCount(), 12u);
  for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
    SCOPED_TRACE("cell " + std::to_string(c));
    const std::vector<std::size_t> index = spec.AxisIndex(c);
    const spectra::SweepRecord* record = nullptr;
    const spectra::PointParameters p = evaluator.Parameters(index, &record);
    ASSERT_NE(record, nullptr);
    const spectra::ExcitationScales scales{record->measures.pga_mps2,
                                           record->measures.omega_g_radps};
    const std::unique_ptr<Excitation> got = evaluator.MakeExcitation(index, p, record, scales);
    double incidence_deg = 0.0;
    for (std::size_t k = 0; k < spec.axes.size(); ++k) {
      if (spec.axes[k].key == "incidence_deg") incidence_deg = spec.axes[k].values[index[k]];
    }
    const records::SampledExcitation own = records::ToExcitation(
        record->motion,
        incidence_deg == 0.0 ? Eigen::Vector2d::UnitX() : records::DirectionAt(incidence_deg));
    const SampleView a = got->Samples(), b = own.Samples();
    ASSERT_EQ(a.count, b.count);
    ASSERT_EQ(a.ay_mps2 == nullptr, b.ay_mps2 == nullptr);
    EXPECT_EQ(std::memcmp(a.ax_mps2, b.ax_mps2, a.count * sizeof(double)), 0);
    if (b.ay_mps2 != nullptr) {
      EXPECT_EQ(std::memcmp(a.ay_mps2, b.ay_mps2, a.count * sizeof(double)), 0);
    }
    const double walk = own.Excitation::Peak(horizon);
    const double peak = got->Peak(horizon);
    EXPECT_EQ(std::memcmp(&peak, &walk, sizeof(double)), 0) << peak << " against " << walk;
  }
}

}  // namespace
}  // namespace skewbridge::jobs::study_test
