// Synthetic suites: reproducible to the byte, different per seed, and inside the requested
// PGA and T_m ranges when read back through the AT2 reader.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "records/ground_motion.h"
#include "records/measures.h"
#include "records/record_set.h"
#include "records/synthetic.h"
#include "solver/common/error.h"

namespace skewbridge::records::synthetic_test {
namespace {

std::string Slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path FreshDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  return dir;
}

SynthOptions SmallSuite(std::uint64_t seed) {
  SynthOptions o;
  o.count = 6;
  o.seed = seed;
  o.duration_s = 20.0;
  o.dt_s = 0.01;
  return o;
}

TEST(SynthesizeSuite, SameSeedGivesTheSameBytes) {
  const std::filesystem::path a = FreshDir("synth_a");
  const std::filesystem::path b = FreshDir("synth_b");
  WriteSuite(a, SmallSuite(7));
  WriteSuite(b, SmallSuite(7));
  for (const std::string file : {"synth_000.AT2", "synth_003.AT2", "synth_005.AT2", "set.toml"}) {
    const std::string bytes = Slurp(a / file);
    ASSERT_FALSE(bytes.empty()) << file;
    EXPECT_EQ(bytes, Slurp(b / file)) << file;
  }
}

// FNV-1a 64 of the .AT2 texts of a suite, in index order: the text fixes every sample the
// program uses (SynthesizeRecord returns the text read back).
std::uint64_t SuiteHash(const SynthOptions& options) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (int i = 0; i < options.count; ++i) {
    for (const char c : FormatAt2(SynthesizeRecord(options, i))) {
      h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
    }
  }
  return h;
}

// The hashes were taken from the program before the generator was made faster (a plan and
// twiddles per T_m evaluation, the envelope recomputed per trial), with the baseline correction
// (RemoveBaselineDrift) applied to every trial; the faster one must produce the same bytes. The
// pilot study's suite, and a second sample interval and length.
TEST(SynthesizeSuite, FasterGeneratorKeepsTheBytesOfEarlierSuites) {
  SynthOptions pilot;
  pilot.count = 62;
  pilot.seed = 2011;
  EXPECT_EQ(SuiteHash(pilot), 0x6e9fc9c28c6c699eULL);
  SynthOptions other = SmallSuite(3);
  other.count = 4;
  other.dt_s = 0.005;
  other.duration_s = 12.5;
  EXPECT_EQ(SuiteHash(other), 0xb70366d39ee3bb3fULL);
}

TEST(SynthesizeSuite, DifferentSeedsGiveDifferentRecords) {
  const GroundMotion r1 = SynthesizeRecord(SmallSuite(1), 0);
  const GroundMotion r2 = SynthesizeRecord(SmallSuite(2), 0);
  const GroundMotion r1b = SynthesizeRecord(SmallSuite(1), 1);
  ASSERT_EQ(r1.npts(), r2.npts());
  EXPECT_NE(r1.acc_mps2, r2.acc_mps2);
  EXPECT_NE(r1.acc_mps2, r1b.acc_mps2);
  EXPECT_NE(FormatAt2(r1), FormatAt2(r2));
}

TEST(SynthesizeSuite, RequestedRangesAreMetAfterReadingTheFilesBack) {
  SynthOptions o = SmallSuite(11);
  o.count = 8;
  o.pga_min_g = 0.15;
  o.pga_max_g = 0.35;
  o.tm_min_s = 0.3;
  o.tm_max_s = 0.7;
  const std::filesystem::path dir = FreshDir("synth_ranges");
  const RecordSet set = LoadRecordSet(WriteSuite(dir, o));
  ASSERT_EQ(set.records.size(), 8u);
  double tm_lowest = 1e9;
  double tm_highest = 0.0;
  for (const RecordEntry& entry : set.records) {
    const GroundMotion m = LoadRecord(entry);
    EXPECT_EQ(m.npts(), 2001u);
    EXPECT_EQ(m.dt_s, 0.01);
    const IntensityMeasures im = ComputeMeasures(m);
    const double pga_g = im.pga_mps2 / kStandardGravity_mps2;
    EXPECT_GE(pga_g, o.pga_min_g) << entry.file;
    EXPECT_LE(pga_g, o.pga_max_g) << entry.file;
    EXPECT_GE(im.mean_period_s, o.tm_min_s) << entry.file;
    EXPECT_LE(im.mean_period_s, o.tm_max_s) << entry.file;
    tm_lowest = std::min(tm_lowest, im.mean_period_s);
    tm_highest = std::max(tm_highest, im.mean_period_s);
  }
  // The draws spread over the range rather than collapsing onto one value.
  EXPECT_GT(tm_highest - tm_lowest, 0.1);
}

TEST(SynthesizeRecord, MatchesWhatTheReaderSeesInTheFile) {
  const GroundMotion m = SynthesizeRecord(SmallSuite(3), 2);
  const GroundMotion back = ParseRecord(FormatAt2(m), "back.AT2");
  EXPECT_EQ(back.acc_mps2, m.acc_mps2);
  EXPECT_EQ(back.dt_s, m.dt_s);
}

TEST(SynthesizeRecord, UnreachableMeanPeriodIsAnInputError) {
  SynthOptions o = SmallSuite(1);
  o.tm_min_s = 30.0;
  o.tm_max_s = 40.0;
  EXPECT_THROW(SynthesizeRecord(o, 0), InputError);
}

// A 2 Hz sine of amplitude A plus a constant offset b: a record whose displacement drifts by
// b T^2 / 2 = 10 m (and by A T / w from the sine's own mean velocity). The correction must end
// it at rest (zero velocity and displacement at the end, to round-off), keep its 2 Hz motion
// (the least-squares amplitude of sin(w t) in the corrected record within 1 % of A) and leave a
// peak displacement of centimetres, not metres: below (A / w) x 1 s = 0.16 m, the distance the
// sine's mean velocity A / w covers in one second, against the 10 m of drift.
TEST(RemoveBaselineDrift, EndsARecordAtRestAndKeepsItsMotion) {
  const double dt = 0.01, amplitude = 2.0, offset = 0.05, w = 2.0 * std::numbers::pi * 2.0;
  std::vector<double> acc(2001);
  for (std::size_t k = 0; k < acc.size(); ++k) {
    acc[k] = amplitude * std::sin(w * static_cast<double>(k) * dt) + offset;
  }
  std::vector<double> vel, disp;
  IntegrateMotion(acc, dt, vel, disp);
  EXPECT_GT(std::abs(disp.back()), 9.0);
  RemoveBaselineDrift(acc, dt);
  IntegrateMotion(acc, dt, vel, disp);
  double pgd = 0.0, pgv = 0.0, sum_as = 0.0, sum_ss = 0.0;
  for (std::size_t k = 0; k < acc.size(); ++k) {
    pgd = std::max(pgd, std::abs(disp[k]));
    pgv = std::max(pgv, std::abs(vel[k]));
    const double s = std::sin(w * static_cast<double>(k) * dt);
    sum_as += acc[k] * s;
    sum_ss += s * s;
  }
  EXPECT_LT(std::abs(vel.back()), 1e-9 * pgv);
  EXPECT_LT(std::abs(disp.back()), 1e-9 * pgd);
  EXPECT_NEAR(sum_as / sum_ss, amplitude, 0.01 * amplitude);
  EXPECT_LT(pgd, amplitude / w * 1.0) << "peak displacement " << pgd << " m";
}

// The suite the pilot study uses (62 records, seed 2011, 30 s): every record read back from its
// file ends at rest with no displacement drift, has a PGD below 1 m (before the baseline
// correction the largest was 16 m), and keeps its PGA and T_m inside the requested ranges.
TEST(SynthesizeSuite, SixtyTwoRecordsEndAtRestWithPgdBelowOneMetre) {
  SynthOptions o;
  o.count = 62;
  o.seed = 2011;
  const std::filesystem::path dir = FreshDir("synth62");
  const RecordSet set = LoadRecordSet(WriteSuite(dir, o));
  ASSERT_EQ(set.records.size(), 62u);
  double pgd_max = 0.0;
  for (const RecordEntry& entry : set.records) {
    const GroundMotion motion = LoadRecord(entry);
    const IntensityMeasures im = ComputeMeasures(motion);
    std::vector<double> vel, disp;
    IntegrateMotion(motion.acc_mps2, motion.dt_s, vel, disp);
    EXPECT_LT(im.pgd_m, 1.0) << entry.file;
    // The file holds 8 significant digits: the end state is zero to that rounding.
    EXPECT_LT(std::abs(vel.back()), 1e-5 * im.pgv_mps) << entry.file;
    EXPECT_LT(std::abs(disp.back()), 1e-4 * im.pgd_m) << entry.file;
    EXPECT_GE(im.pga_mps2, o.pga_min_g * kStandardGravity_mps2 * (1 - 1e-6)) << entry.file;
    EXPECT_LE(im.pga_mps2, o.pga_max_g * kStandardGravity_mps2 * (1 + 1e-6)) << entry.file;
    EXPECT_GE(im.mean_period_s, o.tm_min_s) << entry.file;
    EXPECT_LE(im.mean_period_s, o.tm_max_s) << entry.file;
    pgd_max = std::max(pgd_max, im.pgd_m);
  }
  std::printf("62-record suite (seed 2011): largest PGD %.3f m\n", pgd_max);
}

}  // namespace
}  // namespace skewbridge::records::synthetic_test
