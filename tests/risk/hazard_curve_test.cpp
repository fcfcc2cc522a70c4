// The hazard-curve readers (spectra/hazard_curve.h) on files written by hand: an OpenQuake CSV
// read back to the rates -ln(1 - poe) / T computed here, a two-column file with its IMT in a
// header line or an option, and every malformed input refused with the file and line; then the
// measure check (spectra/hazard_measure.h): what it accepts, what it refuses with both measures
// named, and a component conversion only when asked for by name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "solver/common/error.h"
#include "spectra/hazard_curve.h"
#include "spectra/hazard_measure.h"
#include "spectra/study.h"

namespace skewbridge::spectra::hazard_curve_test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// The layout of the OpenQuake manual's listing ("Outputs from Classical PSHA"), two sites, with
// an investigation time of 50 years.
constexpr const char* kOpenQuake =
    "#,,,,,\"generated_by='OpenQuake engine 3.18.0', start_date='2023-10-03T06:09:08', "
    "checksum=2107362341, kind='mean', investigation_time=50.0, imt='SA(0.35)'\"\n"
    "lon,lat,depth,poe-0.1000000,poe-0.4000000,poe-0.6000000,poe-1.2000000\n"
    "0.00000,0.00000,-0.10000,9.553860E-01,2.754042E-01,6.354511E-02,0.000000E+00\n"
    "0.10000,0.20000,-0.10000,1.522632E-01,3.000000E-02,1.000000E-03,1.000000E-05\n";

class HazardFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sb_hazard_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Write(const std::string& name, const std::string& contents) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << contents;
    return p;
  }
  // The message of the InputError that `f` throws, or "" when it throws none.
  template <class F>
  static std::string ErrorOf(F&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(HazardFiles, OpenQuakeCsvReadsBackToPoissonRates) {
  const fs::path p = Write("hazard_curve-mean-SA(0.35)_1.csv", kOpenQuake);
  HazardReadOptions options;
  options.site = 1;
  const HazardCurve c = ReadHazardCurve(p, options);
  EXPECT_EQ(c.format, "openquake-csv");
  EXPECT_EQ(c.kind, "mean");
  EXPECT_EQ(c.sites, 2);
  EXPECT_EQ(c.site, 1);
  EXPECT_DOUBLE_EQ(c.investigation_time_yr, 50.0);
  EXPECT_DOUBLE_EQ(c.lon_deg, 0.1);
  EXPECT_DOUBLE_EQ(c.lat_deg, 0.2);
  EXPECT_EQ(c.imt.measure, "SA");
  EXPECT_DOUBLE_EQ(c.imt.period_s, 0.35);
  EXPECT_DOUBLE_EQ(c.imt.damping, 0.05);
  EXPECT_EQ(c.imt.component, HorizontalComponent::kUnknown);
  ASSERT_EQ(c.im.size(), 4u);
  const double levels[] = {0.1, 0.4, 0.6, 1.2};
  const double poe[] = {1.522632E-01, 3.0E-02, 1.0E-03, 1.0E-05};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(c.im[i], levels[i]);
    // Poisson: P = 1 - exp(-lambda T), so lambda = -ln(1 - P) / T, here with std::log.
    EXPECT_NEAR(c.rate_per_yr[i], -std::log(1.0 - poe[i]) / 50.0, 1e-15);
    EXPECT_EQ(c.line[i], 4);
  }
  // Small probabilities: lambda -> P / T.
  EXPECT_NEAR(c.rate_per_yr[3] / (1e-5 / 50.0), 1.0, 1e-5);
}

TEST_F(HazardFiles, OpenQuakeFirstSiteZeroRateAndComponentOption) {
  const fs::path p = Write("a.csv", kOpenQuake);
  HazardReadOptions options;
  options.site = 0;
  options.component = "RotD50";
  const HazardCurve c = ReadOpenQuakeHazardCsv(p, options);
  EXPECT_EQ(c.imt.component, HorizontalComponent::kRotD50);
  EXPECT_EQ(c.rate_per_yr[3], 0.0);
  EXPECT_NEAR(c.rate_per_yr[0], -std::log(1.0 - 9.553860E-01) / 50.0, 1e-15);
}

TEST_F(HazardFiles, OpenQuakeProbabilityOneIsAnInfiniteRate) {
  const fs::path p = Write("a.csv",
                           "#,,,,,\"kind='mean', investigation_time=1.0, imt='PGA'\"\n"
                           "lon,lat,poe-0.01,poe-0.1,poe-1.0\n"
                           "1.0,2.0,1.0,0.5,0.001\n");
  const HazardCurve c = ReadHazardCurve(p, {});
  EXPECT_EQ(c.imt.measure, "PGA");
  EXPECT_TRUE(std::isinf(c.rate_per_yr[0]));
  EXPECT_NEAR(c.rate_per_yr[1], std::log(2.0), 1e-15);
}

TEST_F(HazardFiles, OpenQuakeRefusesWhatItCannotRead) {
  const std::string head = "#,,,,,\"kind='mean', investigation_time=1.0, imt='PGA'\"\n";
  struct Case {
    std::string contents;
    std::string expect;
  };
  const Case cases[] = {
      {head + "lon,lat,poe-0.1,poe-0.2\n1,2,0.5,1.5\n",
       "a.csv:3: column 4 (poe-0.2): probability 1.5 outside [0, 1]"},
      {head + "lon,lat,poe-0.1,poe-0.2\n1,2,0.5,0.6\n",
       "a.csv:3: column 4 (poe-0.2): probability 0.6 rises"},
      {head + "lon,lat,poe-0.2,poe-0.1\n1,2,0.5,0.4\n",
       "a.csv:2: column 4 'poe-0.1': levels must increase"},
      {head + "lon,lat,vs30,poe-0.1,poe-0.2\n1,2,760,0.5,0.4\n",
       "a.csv:2: column 3 'vs30' is not a hazard-curve column"},
      {head + "lon,lat,poe-0.1,poe-0.2\n1,2,0.5\n",
       "a.csv:3: 3 cells where the header has 4 columns"},
      {head + "lon,lat,poe-0.1,poe-0.2\n1,2,0.5,x\n",
       "a.csv:3: column 4 (poe-0.2): 'x' is not a finite number"},
      {head + "lon,lat,poe-0.1,poe-0.2\n1,2,0.5,0.4\n3,4,0.5,0.4\n",
       "a.csv:4: 2 sites; choose one with --site N (0 to 1)"},
      {head + "lon,lat,poe-0.1\n1,2,0.5\n",
       "a.csv:3: 1 intensity level(s); a hazard curve needs at least 2"},
      {"#,,,,,\"kind='mean', imt='PGA'\"\nlon,lat,poe-0.1,poe-0.2\n1,2,0.5,0.4\n",
       "a.csv:1: the header comment has no investigation_time > 0"},
      {"#,,,,,\"investigation_time=1.0, imt='PGV'\"\nlon,lat,poe-0.1,poe-0.2\n1,2,0.5,0.4\n",
       "a.csv:1: imt 'PGV' is not read"},
      {"#,,,,,\"investigation_time=1.0\"\nlon,lat,poe-0.1,poe-0.2\n1,2,0.5,0.4\n",
       "a.csv: names no intensity measure"},
      {"lon,lat,poe-0.1,poe-0.2\n1,2,0.5,0.4\n",
       "a.csv:1: an OpenQuake hazard-curve CSV starts with its header comment"},
  };
  for (const Case& c : cases) {
    const fs::path p = Write("a.csv", c.contents);
    const std::string error = ErrorOf([&] { ReadOpenQuakeHazardCsv(p, {}); });
    EXPECT_THAT(error, HasSubstr(c.expect)) << c.contents;
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
  }
  const fs::path p = Write("a.csv", kOpenQuake);
  HazardReadOptions out_of_range;
  out_of_range.site = 2;
  EXPECT_THAT(ErrorOf([&] { ReadOpenQuakeHazardCsv(p, out_of_range); }),
              HasSubstr("holds 2 site(s): allowed 0 to 1"));
  HazardReadOptions other_imt;
  other_imt.site = 0;
  other_imt.imt = "SA(1.0)";
  EXPECT_THAT(ErrorOf([&] { ReadOpenQuakeHazardCsv(p, other_imt); }),
              HasSubstr("a.csv:1: the file's IMT SA(0.35 s"));
}

TEST_F(HazardFiles, TwoColumnWithItsMeasureInHeaderLines) {
  const fs::path p = Write("h.txt",
                           "# A hazard curve: any comment, even one with a colon: here\n"
                           "# imt = SA(1.0)\n"
                           "# component: RotD50\n"
                           "# damping = 0.05\n"
                           "0.1  0.02\n"
                           "0.2,0.005\n"
                           "\n"
                           "0.5\t0.0004\n");
  const HazardCurve c = ReadHazardCurve(p, {});
  EXPECT_EQ(c.format, "two-column");
  EXPECT_EQ(c.imt.measure, "SA");
  EXPECT_DOUBLE_EQ(c.imt.period_s, 1.0);
  EXPECT_EQ(c.imt.component, HorizontalComponent::kRotD50);
  ASSERT_EQ(c.im.size(), 3u);
  EXPECT_DOUBLE_EQ(c.im[2], 0.5);
  EXPECT_DOUBLE_EQ(c.rate_per_yr[2], 0.0004);
  EXPECT_EQ(c.line[2], 8);
}

TEST_F(HazardFiles, TwoColumnWithItsMeasureByOption) {
  const fs::path p = Write("h.txt", "0.1 0.02\n0.2 0.005\n");
  EXPECT_THAT(ErrorOf([&] { ReadHazardCurve(p, {}); }),
              HasSubstr("h.txt: names no intensity measure; add a line '# imt = SA(T)'"));
  HazardReadOptions options;
  options.imt = "pga";
  options.component = "geomean";
  const HazardCurve c = ReadHazardCurve(p, options);
  EXPECT_EQ(c.imt.measure, "PGA");
  EXPECT_EQ(c.imt.component, HorizontalComponent::kGeometricMean);
}

TEST_F(HazardFiles, TwoColumnRefusesWhatItCannotRead) {
  struct Case {
    std::string contents;
    std::string expect;
  };
  const Case cases[] = {
      {"# imt = PGA\n0.1 0.02\n0.2 0.005 7\n", "h.txt:3: 3 value(s); a line holds two"},
      {"# imt = PGA\n0.1 0.02\n0.1 0.005\n", "h.txt:3: IM 0.1 does not increase"},
      {"# imt = PGA\n0.1 0.02\n0.2 0.05\n", "h.txt:3: rate 0.05 rises above the 0.02"},
      {"# imt = PGA\n0.1 0.02\n0.2 -1\n", "h.txt:3: rate '-1' is not a finite number >= 0"},
      {"# imt = PGA\n0 0.02\n0.2 0.01\n", "h.txt:2: IM '0' is not a finite number > 0"},
      {"# imt = PGA\n0.1 nan\n0.2 0.01\n", "h.txt:2: rate 'nan' is not a finite number >= 0"},
      {"# imt = PGA\n0.1 0.02\n", "h.txt:2: 1 intensity level(s)"},
      {"# imt = SA(0.3s)\n0.1 0.02\n0.2 0.01\n", "h.txt:1: imt 'SA(0.3s)' is not read"},
      {"# imt = PGA\n# component = max\n0.1 0.02\n0.2 0.01\n", "h.txt:2: component 'max' unknown"},
      {"# imt = SA(0.3)\n# damping = 5\n0.1 0.02\n0.2 0.01\n",
       "h.txt: damping 5 is not a ratio in (0, 1)"},
  };
  for (const Case& c : cases) {
    const fs::path p = Write("h.txt", c.contents);
    const std::string error = ErrorOf([&] { ReadTwoColumnHazard(p, {}); });
    EXPECT_THAT(error, HasSubstr(c.expect)) << c.contents;
  }
  const fs::path p = Write("h.txt", "# imt = SA(0.3)\n# component = RotD50\n0.1 0.02\n0.2 0.01\n");
  HazardReadOptions other;
  other.imt = "SA(0.4)";
  EXPECT_THAT(ErrorOf([&] { ReadTwoColumnHazard(p, other); }),
              HasSubstr("h.txt:1: the file's IMT SA(0.3 s"));
  HazardReadOptions other_component;
  other_component.component = "arbitrary";
  EXPECT_THAT(ErrorOf([&] { ReadTwoColumnHazard(p, other_component); }),
              HasSubstr("h.txt:2: the file's component RotD50 differs from --hazard-component "
                        "arbitrary"));
  EXPECT_THAT(ErrorOf([&] { ReadHazardCurve(dir_ / "missing.txt", {}); }),
              HasSubstr("missing.txt: cannot open the hazard file"));
}

TEST(ParseImt, ReadsOpenQuakeSpellings) {
  EXPECT_EQ(ParseImt("PGA")->measure, "PGA");
  EXPECT_DOUBLE_EQ(ParseImt("SA(0.3)")->period_s, 0.3);
  EXPECT_DOUBLE_EQ(ParseImt(" sa( 1.25 ) ")->period_s, 1.25);
  EXPECT_FALSE(ParseImt("PGV"));
  EXPECT_FALSE(ParseImt("SA(0)"));
  EXPECT_FALSE(ParseImt("SA(-1)"));
  EXPECT_FALSE(ParseImt("SA 0.3"));
  EXPECT_FALSE(ParseImt("AvgSA"));
}

IntensityMeasureId Sa(double t, HorizontalComponent c, double xi = 0.05) {
  IntensityMeasureId id;
  id.measure = "SA";
  id.period_s = t;
  id.damping = xi;
  id.component = c;
  return id;
}

std::string MatchError(const IntensityMeasureId& h, const IntensityMeasureId& f,
                       double tol = kDefaultPeriodTolerance, std::string_view conv = "") {
  try {
    MatchMeasures(h, f, tol, conv);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MatchMeasures, AcceptsTheSameMeasureAndAPeriodWithinTolerance) {
  const auto arb = HorizontalComponent::kArbitrary;
  const MeasureMatch same = MatchMeasures(Sa(0.349, arb), Sa(0.349, arb), 0.05, "");
  EXPECT_EQ(same.period_gap, 0.0);
  EXPECT_TRUE(same.notes.empty());
  const MeasureMatch near = MatchMeasures(Sa(0.35, arb), Sa(0.349, arb), 0.05, "");
  EXPECT_NEAR(near.period_gap, 0.001 / 0.349, 1e-12);
  ASSERT_EQ(near.notes.size(), 1u);
  EXPECT_THAT(near.notes[0], HasSubstr("0.29 % from the fragility's 0.349 s"));
}

TEST(MatchMeasures, RefusesEachMismatchNamingBothMeasures) {
  const auto arb = HorizontalComponent::kArbitrary;
  const auto rotd50 = HorizontalComponent::kRotD50;
  EXPECT_THAT(MatchError(Sa(0.3, arb), Sa(0.349, arb)),
              HasSubstr("hazard SA(0.3 s, 5 % damping, arbitrary component) and fragility "
                        "SA(0.349 s, 5 % damping, arbitrary component): periods 14.0 % apart, "
                        "beyond the tolerance of 5 %"));
  // A wider tolerance given by the user admits it.
  EXPECT_EQ(MatchError(Sa(0.3, arb), Sa(0.349, arb), 0.15), "");
  EXPECT_THAT(MatchError(Sa(0.349, arb, 0.02), Sa(0.349, arb)), HasSubstr("different damping"));
  IntensityMeasureId pga;
  pga.measure = "PGA";
  pga.component = arb;
  EXPECT_THAT(MatchError(pga, Sa(0.349, arb)),
              HasSubstr("hazard PGA (arbitrary component) and fragility SA(0.349 s"));
  EXPECT_THAT(MatchError(Sa(0.349, HorizontalComponent::kUnknown), Sa(0.349, arb)),
              HasSubstr("the hazard's horizontal component is not stated"));
  EXPECT_THAT(MatchError(Sa(0.349, rotd50), Sa(0.349, arb)),
              HasSubstr("different horizontal components; --convert rotd50-as-arbitrary reads "
                        "one as the other"));
  EXPECT_THAT(MatchError(Sa(0.349, HorizontalComponent::kRotD100), Sa(0.349, arb)),
              HasSubstr("no conversion between them is known"));
  EXPECT_THAT(MatchError(Sa(0.349, rotd50), Sa(0.349, arb), 0.05, "geometric-mean-as-arbitrary"),
              HasSubstr("converts geometric-mean to arbitrary, not the hazard's component"));
  EXPECT_THAT(MatchError(Sa(0.349, arb), Sa(0.349, arb), 0.05, "rotd50-as-arbitrary"),
              HasSubstr("the components agree, no conversion applies"));
  EXPECT_THAT(MatchError(Sa(0.349, rotd50), Sa(0.349, arb), 0.05, "rotd50"),
              HasSubstr("unknown conversion (allowed: geometric-mean-as-arbitrary"));
}

TEST(MatchMeasures, AppliesAConversionOnlyByName) {
  const MeasureMatch m =
      MatchMeasures(Sa(0.349, HorizontalComponent::kRotD50),
                    Sa(0.349, HorizontalComponent::kArbitrary), 0.05, "rotd50-as-arbitrary");
  ASSERT_NE(m.conversion, nullptr);
  EXPECT_EQ(m.conversion->name, "rotd50-as-arbitrary");
  EXPECT_EQ(m.im_factor, 1.0);
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_THAT(m.notes[0], HasSubstr("Boore 2010"));
}

// What a cube says of its fragility's measure (im_measure, im_description) reads back to the
// measure that wrote it, and nothing else reads.
TEST(ParseIntensityDescription, RoundTripsEveryMeasure) {
  std::vector<IntensityMeasureSpec> specs(5);
  specs[0].measure = "Sa";
  specs[0].at_t1 = true;
  specs[1].measure = "Sa";
  specs[1].period_s = 0.349;
  specs[1].xi = 0.02;
  specs[2].measure = "AvgSa";
  specs[2].at_t1 = true;
  specs[3].measure = "PGA";
  specs[4].measure = "PGV";
  for (const IntensityMeasureSpec& im : specs) {
    const std::optional<IntensityMeasureSpec> back =
        ParseIntensityDescription(im.measure, IntensityDescription(im));
    ASSERT_TRUE(back) << IntensityDescription(im);
    EXPECT_EQ(back->measure, im.measure);
    EXPECT_EQ(back->at_t1, im.at_t1);
    EXPECT_EQ(back->period_s, im.period_s);
    EXPECT_EQ(back->xi, im.xi);
  }
  EXPECT_FALSE(ParseIntensityDescription("Sa", "Sa(T1, xi = 0.05): something else"));
  EXPECT_FALSE(ParseIntensityDescription("PGA", IntensityDescription(specs[0])));
  EXPECT_FALSE(ParseIntensityDescription("Sd", "Sd(T1, xi = 0.05)"));
}

}  // namespace
}  // namespace skewbridge::spectra::hazard_curve_test
