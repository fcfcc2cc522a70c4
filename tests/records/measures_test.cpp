// Intensity measures against independent oracles: a plain O(N^2) DFT for T_m, closed forms for
// pulses and sinusoids, and a fine-step Runge-Kutta integration for the elastic spectrum.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <complex>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <vector>

#include "records/ground_motion.h"
#include "records/measures.h"
#include "solver/common/error.h"

namespace skewbridge::records::measures_test {
namespace {

using std::numbers::pi;

const std::filesystem::path kData = std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / "records";

// T_m from the definition, with a direct DFT of the zero-padded record of length n_dft.
double MeanPeriodByDirectDft(const std::vector<double>& acc, double dt, std::size_t n_dft) {
  std::vector<std::complex<double>> twiddle(n_dft);
  for (std::size_t j = 0; j < n_dft; ++j) {
    twiddle[j] = std::polar(1.0, -2.0 * pi * static_cast<double>(j) / static_cast<double>(n_dft));
  }
  double weighted = 0.0;
  double total = 0.0;
  for (std::size_t i = 1; i <= n_dft / 2; ++i) {
    const double f = static_cast<double>(i) / (static_cast<double>(n_dft) * dt);
    if (f < 0.25 || f > 20.0) continue;
    std::complex<double> x = 0.0;
    for (std::size_t k = 0; k < acc.size(); ++k) x += acc[k] * twiddle[(i * k) % n_dft];
    weighted += std::norm(x) / f;
    total += std::norm(x);
  }
  return weighted / total;
}

TEST(MeanPeriod, FftEqualsDirectDftOnARecord) {
  const GroundMotion m = ReadRecord(kData / "NIS090.AT2");
  const double tm = MeanPeriod(m.acc_mps2, m.dt_s);
  EXPECT_NEAR(tm, MeanPeriodByDirectDft(m.acc_mps2, m.dt_s, 4096), 1e-10 * tm);
}

TEST(MeanPeriod, FftEqualsDirectDftWithZeroPadding) {
  const GroundMotion m = ReadRecord(kData / "RSN763_LOMAP_GIL067.AT2");
  const std::vector<double> head(m.acc_mps2.begin(), m.acc_mps2.begin() + 3001);
  ASSERT_EQ(MeanPeriodDftLength(head.size()), 4096u);
  const double tm = MeanPeriod(head, m.dt_s);
  EXPECT_NEAR(tm, MeanPeriodByDirectDft(head, m.dt_s, 4096), 1e-10 * tm);
}

TEST(MeanPeriod, PureSinusoidInsideTheBandHasPeriodOneOverF) {
  const double dt = 0.01;
  const std::size_t n = 4096;  // 800 cycles: 19.5 Hz, inside the band
  for (const int cycles : {20, 41, 200, 800}) {
    const double f = cycles / (static_cast<double>(n) * dt);  // on the DFT grid: no leakage
    std::vector<double> acc(n);
    for (std::size_t k = 0; k < n; ++k) acc[k] = 3.0 * std::sin(2.0 * pi * f * k * dt + 0.3);
    EXPECT_NEAR(MeanPeriod(acc, dt), 1.0 / f, 1e-9 / f) << f;
  }
}

TEST(MeanPeriod, RecordWithoutEnergyInTheBandIsAnInputError) {
  EXPECT_THROW(MeanPeriod(std::vector<double>(100, 0.0), 0.01), InputError);
}

// A sampled one-cycle sine pulse a_p sin(w t), 0 <= t <= 2 pi / w.
std::vector<double> SinePulse(double a_p, double w, std::size_t steps) {
  const double dt = 2.0 * pi / w / static_cast<double>(steps);
  std::vector<double> acc(steps + 1);
  for (std::size_t k = 0; k <= steps; ++k) acc[k] = a_p * std::sin(w * dt * k);
  return acc;
}

TEST(IntegrateMotion, SinePulsePeaksEqualTheirClosedForms) {
  // v = a_p / w (1 - cos w t) peaks at 2 a_p / w; d = a_p / w (t - sin(w t) / w) ends at
  // 2 pi a_p / w^2, its maximum.
  const double a_p = 4.0;
  const double w = 2.0 * pi * 1.5;
  const std::size_t steps = 4000;
  GroundMotion m;
  m.dt_s = 2.0 * pi / w / steps;
  m.acc_mps2 = SinePulse(a_p, w, steps);
  const IntensityMeasures im = ComputeMeasures(m);
  EXPECT_NEAR(im.pgv_mps, 2.0 * a_p / w, 1e-6 * 2.0 * a_p / w);
  EXPECT_NEAR(im.pgd_m, 2.0 * pi * a_p / (w * w), 1e-6 * 2.0 * pi * a_p / (w * w));
  EXPECT_NEAR(im.pga_mps2, a_p, 1e-6);
}

TEST(IntegrateMotion, IsExactForPiecewiseLinearAcceleration) {
  // a = t on [0, 1]: v = t^2 / 2, d = t^3 / 6, exactly at every sample.
  const double dt = 0.1;
  std::vector<double> acc;
  for (int k = 0; k <= 10; ++k) acc.push_back(k * dt);
  std::vector<double> v;
  std::vector<double> d;
  IntegrateMotion(acc, dt, v, d);
  EXPECT_NEAR(v.back(), 0.5, 1e-14);
  EXPECT_NEAR(d.back(), 1.0 / 6.0, 1e-14);
}

TEST(AriasIntensity, ConstantAccelerationHasClosedFormsForIaAndD595) {
  // a = c over T: I_a = pi c^2 T / (2 g); the Husid curve is linear, so D5-95 = 0.9 T.
  const double c = 2.0;
  const double dt = 0.01;
  const std::vector<double> acc(1001, c);
  const double duration = 10.0;
  EXPECT_NEAR(AriasIntensity(acc, dt), pi * c * c * duration / (2.0 * kStandardGravity_mps2),
              1e-12);
  EXPECT_NEAR(SignificantDuration(acc, dt), 0.9 * duration, 1e-9);
}

// u'' + 2 xi w u' + w^2 u = -a(t), a linear between samples, by RK4 with `sub` steps per sample;
// returns w^2 max |u(t_k)| over the samples.
double PseudoAccelerationByRk4(const std::vector<double>& acc, double dt, double period, double xi,
                               int sub) {
  const double w = 2.0 * pi / period;
  const double h = dt / sub;
  double u = 0.0;
  double v = 0.0;
  double peak = 0.0;
  for (std::size_t k = 0; k + 1 < acc.size(); ++k) {
    const double slope = (acc[k + 1] - acc[k]) / dt;
    const auto a = [&](double tau) { return acc[k] + slope * tau; };
    const auto f = [&](double tau, double uu, double vv) {
      return -a(tau) - 2.0 * xi * w * vv - w * w * uu;
    };
    for (int s = 0; s < sub; ++s) {
      const double t = s * h;
      const double k1u = v;
      const double k1v = f(t, u, v);
      const double k2u = v + 0.5 * h * k1v;
      const double k2v = f(t + 0.5 * h, u + 0.5 * h * k1u, v + 0.5 * h * k1v);
      const double k3u = v + 0.5 * h * k2v;
      const double k3v = f(t + 0.5 * h, u + 0.5 * h * k2u, v + 0.5 * h * k2v);
      const double k4u = v + h * k3v;
      const double k4v = f(t + h, u + h * k3u, v + h * k3v);
      u += h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
      v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
    peak = std::max(peak, std::abs(u));
  }
  return w * w * peak;
}

TEST(PseudoAccelerationSpectrum, EqualsFineStepDirectIntegrationOfARecord) {
  const GroundMotion m = ReadRecord(kData / "NIS090.AT2");
  const std::vector<double> periods = {0.05, 0.1, 0.3, 1.0, 3.0};
  const std::vector<double> sa = PseudoAccelerationSpectrum(m.acc_mps2, m.dt_s, periods);
  for (std::size_t i = 0; i < periods.size(); ++i) {
    const double oracle = PseudoAccelerationByRk4(m.acc_mps2, m.dt_s, periods[i], 0.05, 40);
    EXPECT_NEAR(sa[i], oracle, 1e-6 * oracle) << periods[i];
  }
}

TEST(PseudoAccelerationSpectrum, UndampedShortRecordAgainstRk4WithOtherDamping) {
  const std::vector<double> acc = {0.0, 1.0, -2.0, 0.5, 3.0, 0.0, 0.0, -1.0, 0.0};
  for (const double xi : {0.0, 0.02, 0.2}) {
    const std::vector<double> period = {0.07};
    const double sa = PseudoAccelerationSpectrum(acc, 0.02, period, xi)[0];
    EXPECT_NEAR(sa, PseudoAccelerationByRk4(acc, 0.02, 0.07, xi, 2000), 1e-8 * sa) << xi;
  }
}

TEST(PseudoAccelerationSpectrum, RejectsNonPositivePeriod) {
  const std::vector<double> acc = {0.0, 1.0};
  const std::vector<double> period = {0.0};
  EXPECT_THROW(PseudoAccelerationSpectrum(acc, 0.01, period), InputError);
}

TEST(ElasticResponseSpectrum, PseudoVelocityAndAccelerationAreWTimesSd) {
  const GroundMotion m = ReadRecord(kData / "RSN763_LOMAP_GIL067.AT2");
  const std::vector<double> periods = {0.02, 0.3, 1.0, 4.0};
  const ResponseSpectrum s = ElasticResponseSpectrum(m.acc_mps2, m.dt_s, periods, 0.02);
  ASSERT_EQ(s.sd_m.size(), periods.size());
  for (std::size_t i = 0; i < periods.size(); ++i) {
    const double w = 2.0 * pi / periods[i];
    EXPECT_DOUBLE_EQ(s.psv_mps[i], w * s.sd_m[i]);
    EXPECT_DOUBLE_EQ(s.psa_mps2[i], w * w * s.sd_m[i]);
    const double oracle = PseudoAccelerationByRk4(m.acc_mps2, m.dt_s, periods[i], 0.02, 40);
    EXPECT_NEAR(s.psa_mps2[i], oracle, 1e-6 * oracle) << periods[i];
  }
  // A very stiff oscillator follows the ground: PSa(T -> 0) -> PGA.
  const std::vector<double> stiff = {1e-4};
  double pga = 0.0;
  for (const double a : m.acc_mps2) pga = std::max(pga, std::abs(a));
  EXPECT_NEAR(ElasticResponseSpectrum(m.acc_mps2, m.dt_s, stiff).psa_mps2[0], pga, 1e-3 * pga);
}

TEST(ElasticResponseSpectrum, RejectsDampingOutsideZeroToOne) {
  const std::vector<double> acc = {0.0, 1.0};
  const std::vector<double> period = {1.0};
  EXPECT_THROW(ElasticResponseSpectrum(acc, 0.01, period, 1.0), InputError);
  EXPECT_THROW(ElasticResponseSpectrum(acc, 0.01, period, -0.1), InputError);
}

// The displacement history's largest magnitude is the spectrum's Sd (one recurrence).
TEST(OscillatorDisplacement, PeakIsTheSpectralDisplacement) {
  const GroundMotion m = ReadRecord(kData / "NIS090.AT2");
  for (const double period : {0.1, 1.0, 3.0}) {
    const std::vector<double> u = OscillatorDisplacement(m.acc_mps2, m.dt_s, period, 0.05);
    ASSERT_EQ(u.size(), m.npts());
    EXPECT_EQ(u[0], 0.0);
    double peak = 0.0;
    for (const double x : u) peak = std::max(peak, std::abs(x));
    const std::vector<double> one{period};
    EXPECT_EQ(peak, ElasticResponseSpectrum(m.acc_mps2, m.dt_s, one, 0.05).sd_m[0]);
  }
}

// The spectrum runs its periods' oscillators side by side; each has the bits of the recurrence
// run alone (OscillatorDisplacement), for AvgSa's 50 periods and 13 periods (a last block of 5),
// at two dampings.
TEST(ElasticResponseSpectrum, EachPeriodIsTheBitsOfItsOscillatorAlone) {
  const GroundMotion m = ReadRecord(kData / "NIS090.AT2");
  std::vector<double> thirteen;
  for (int i = 0; i < 13; ++i) thirteen.push_back(0.05 * std::pow(1.4, i));
  for (const std::vector<double>& periods : {AvgSaPeriods(0.7), thirteen}) {
    for (const double xi : {0.0, 0.05}) {
      const ResponseSpectrum s = ElasticResponseSpectrum(m.acc_mps2, m.dt_s, periods, xi);
      ASSERT_EQ(s.sd_m.size(), periods.size());
      for (std::size_t i = 0; i < periods.size(); ++i) {
        const std::vector<double> u = OscillatorDisplacement(m.acc_mps2, m.dt_s, periods[i], xi);
        double peak = 0.0;
        for (const double x : u) peak = std::max(peak, std::abs(x));
        const double w = 2.0 * std::numbers::pi / periods[i];
        EXPECT_EQ(std::bit_cast<std::uint64_t>(s.sd_m[i]), std::bit_cast<std::uint64_t>(peak))
            << "period " << periods[i] << " s, xi " << xi;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(s.psa_mps2[i]),
                  std::bit_cast<std::uint64_t>(w * w * peak));
      }
    }
  }
}

// Closed forms of RotD [Boore 2010]: a circular history has one peak at every angle; a history
// along H1 alone has peaks |cos theta| max|u1|, whose median over 0-179 deg is cos 45 deg (the
// 90th and 91st sorted values are those of 45 and 135 deg), minimum |cos 90 deg| and maximum at 0.
TEST(RotD, ClosedFormsOfACircleAndOfOneComponent) {
  std::vector<double> c(2000), s(2000), zero(2000, 0.0);
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double t = 2.0 * std::numbers::pi * static_cast<double>(k) / 1000.0;
    c[k] = 0.3 * std::cos(t);
    s[k] = 0.3 * std::sin(t);
  }
  const RotDValues circle = RotDFromHistories(c, s);
  EXPECT_NEAR(circle.rotd0, 0.3, 1e-5);  // sampled circle: peaks within 1 - cos(pi/1000)
  EXPECT_NEAR(circle.rotd100, 0.3, 1e-12);
  const RotDValues line = RotDFromHistories(c, zero);
  EXPECT_DOUBLE_EQ(line.rotd100, 0.3);
  EXPECT_EQ(line.rotd100_angle_deg, 0.0);
  EXPECT_NEAR(line.rotd50, 0.3 * std::cos(std::numbers::pi / 4.0), 1e-15);
  EXPECT_NEAR(line.rotd0, 0.0, 1e-16);
  // Along H2 alone, the largest peak is at 90 deg.
  EXPECT_EQ(RotDFromHistories(zero, c).rotd100_angle_deg, 90.0);
}

// A pair of two equal components: GM = Sa, RotD100 = sqrt(2) Sa at 45 deg, RotD00 = 0 at 135
// deg; a pair (a, 0): RotD100 = Sa at 0 deg, RotD50 = Sa cos 45 deg, GM = 0.
TEST(PairResponseSpectrum, EqualComponentsAndOneComponentAlone) {
  const GroundMotion m = ReadRecord(kData / "NIS090.AT2");
  const std::vector<double> periods{0.2, 1.0};
  const std::vector<double> zero(m.npts(), 0.0);
  const std::vector<double> sa = PseudoAccelerationSpectrum(m.acc_mps2, m.dt_s, periods, 0.05);
  const PairSpectrum same = PairResponseSpectrum(m.acc_mps2, m.acc_mps2, m.dt_s, periods, 0.05);
  const PairSpectrum alone = PairResponseSpectrum(m.acc_mps2, zero, m.dt_s, periods, 0.05);
  for (std::size_t p = 0; p < periods.size(); ++p) {
    EXPECT_EQ(same.sa_h1_mps2[p], sa[p]);
    EXPECT_EQ(same.sa_h2_mps2[p], sa[p]);
    EXPECT_NEAR(same.gm_mps2[p], sa[p], 1e-14 * sa[p]);
    EXPECT_NEAR(same.rotd100_mps2[p], std::sqrt(2.0) * sa[p], 1e-14 * sa[p]);
    EXPECT_EQ(same.rotd100_angle_deg[p], 45.0);
    EXPECT_NEAR(same.rotd0_mps2[p], 0.0, 1e-14 * sa[p]);
    EXPECT_EQ(alone.rotd100_mps2[p], sa[p]);
    EXPECT_EQ(alone.rotd100_angle_deg[p], 0.0);
    EXPECT_NEAR(alone.rotd50_mps2[p], sa[p] * std::cos(std::numbers::pi / 4.0), 1e-14 * sa[p]);
    EXPECT_EQ(alone.gm_mps2[p], 0.0);
    EXPECT_GE(same.rotd100_mps2[p], same.rotd50_mps2[p]);
    EXPECT_GE(same.rotd50_mps2[p], same.rotd0_mps2[p]);
  }
  const std::vector<double> shorter(m.npts() - 1, 0.0);
  EXPECT_THROW(PairResponseSpectrum(m.acc_mps2, shorter, m.dt_s, periods, 0.05), InputError);
}

TEST(AvgSa, FiftyPeriodsAreEquallySpacedFromPoint2To3TimesT1) {
  const std::vector<double> p = AvgSaPeriods(0.5);
  ASSERT_EQ(p.size(), 50u);
  EXPECT_DOUBLE_EQ(p.front(), 0.1);
  EXPECT_DOUBLE_EQ(p.back(), 1.5);
  for (std::size_t i = 1; i < p.size(); ++i) EXPECT_NEAR(p[i] - p[i - 1], 1.4 / 49.0, 1e-15);
  EXPECT_EQ(AvgSaPeriods(2.0, 0.5, 0.5, 1), std::vector<double>{1.0});
  EXPECT_THROW(AvgSaPeriods(0.0), InputError);
  EXPECT_THROW(AvgSaPeriods(1.0, 3.0, 0.2), InputError);
  EXPECT_THROW(AvgSaPeriods(1.0, 0.2, 3.0, 0), InputError);
}

TEST(AvgSa, IsTheGeometricMeanOfTheSpectrumAndOfOnePeriodItsSa) {
  const GroundMotion m = ReadRecord(kData / "NIS090.AT2");
  const std::vector<double> periods = AvgSaPeriods(0.8);
  const std::vector<double> sa = PseudoAccelerationSpectrum(m.acc_mps2, m.dt_s, periods);
  double product = 1.0;
  for (const double v : sa) product *= v;
  const double avg = AverageSpectralAcceleration(m.acc_mps2, m.dt_s, periods);
  EXPECT_NEAR(avg, std::pow(product, 1.0 / 50.0), 1e-12 * avg);
  EXPECT_GT(avg, *std::min_element(sa.begin(), sa.end()));
  EXPECT_LT(avg, *std::max_element(sa.begin(), sa.end()));
  const std::vector<double> one = {0.8};
  EXPECT_DOUBLE_EQ(AverageSpectralAcceleration(m.acc_mps2, m.dt_s, one),
                   PseudoAccelerationSpectrum(m.acc_mps2, m.dt_s, one)[0]);
}

// AvgSa of RotD50 of a pair (a, 0) is AvgSa(a) cos 45 deg (each RotD50 is Sa cos 45 deg); of a
// pair (a, b) it does not depend on which component is H1; one period gives its RotD50.
TEST(AverageRotD50, OneComponentAloneSwappedComponentsAndOnePeriod) {
  const GroundMotion a = ReadRecord(kData / "NIS090.AT2");
  const std::vector<double> zero(a.npts(), 0.0);
  std::vector<double> b(a.npts());
  for (std::size_t k = 0; k < b.size(); ++k) b[k] = a.acc_mps2[b.size() - 1 - k];  // reversed
  const std::vector<double> periods = AvgSaPeriods(0.8);
  const double alone = AverageRotD50(a.acc_mps2, zero, a.dt_s, periods);
  const double avgsa = AverageSpectralAcceleration(a.acc_mps2, a.dt_s, periods);
  EXPECT_NEAR(alone, avgsa * std::cos(std::numbers::pi / 4.0), 1e-13 * avgsa);
  const double ab = AverageRotD50(a.acc_mps2, b, a.dt_s, periods);
  EXPECT_NEAR(AverageRotD50(b, a.acc_mps2, a.dt_s, periods), ab, 1e-13 * ab);
  const std::vector<double> one = {0.8};
  EXPECT_DOUBLE_EQ(AverageRotD50(a.acc_mps2, b, a.dt_s, one),
                   PairResponseSpectrum(a.acc_mps2, b, a.dt_s, one, 0.05).rotd50_mps2[0]);
  EXPECT_THROW(AverageRotD50(a.acc_mps2, b, a.dt_s, {}), InputError);
}
TEST(CumulativeAbsoluteVelocity, TriangleWaveHasTheSumOfItsTriangles) {
  // Vertices at the samples: +A, -A, +A, ... with dt: each step crosses zero at its middle and
  // holds two triangles of area A dt / 4, so CAV = (n - 1) A dt / 2.
  const double amplitude = 3.0;
  const double dt = 0.02;
  std::vector<double> acc(101);
  for (std::size_t k = 0; k < acc.size(); ++k) acc[k] = k % 2 == 0 ? amplitude : -amplitude;
  EXPECT_NEAR(CumulativeAbsoluteVelocity(acc, dt), 100 * amplitude * dt / 2.0, 1e-12);
  // One sign: the trapezoid rule, as for velocity.
  const std::vector<double> ramp = {0.0, 1.0, 2.0, 3.0};
  EXPECT_NEAR(CumulativeAbsoluteVelocity(ramp, 0.5), 0.5 * 4.5, 1e-15);
  // Uneven crossing: a from 1 to -3 over dt crosses at dt / 4: 1 dt / 8 + 3 (3 dt / 4) / 2.
  const std::vector<double> step = {1.0, -3.0};
  EXPECT_NEAR(CumulativeAbsoluteVelocity(step, 1.0), 1.0 / 8.0 + 9.0 / 8.0, 1e-15);
}

TEST(CumulativeAbsoluteVelocity, IsAtLeastPgvAndFillsComputeMeasures) {
  const GroundMotion m = ReadRecord(kData / "0111a.smc");
  const IntensityMeasures im = ComputeMeasures(m);
  EXPECT_DOUBLE_EQ(im.cav_mps, CumulativeAbsoluteVelocity(m.acc_mps2, m.dt_s));
  EXPECT_GE(im.cav_mps, im.pgv_mps);  // |v(t)| = |int a| <= int |a|
}

TEST(ComputeMeasures, DerivedQuantitiesFollowFromTm) {
  const GroundMotion m = ReadRecord(kData / "NIS090.AT2");
  const IntensityMeasures im = ComputeMeasures(m);
  EXPECT_DOUBLE_EQ(im.omega_g_radps, 2.0 * pi / im.mean_period_s);
  EXPECT_DOUBLE_EQ(im.persistency_m, im.pga_mps2 / (im.omega_g_radps * im.omega_g_radps));
  EXPECT_GT(im.significant_duration_s, 0.0);
  EXPECT_LT(im.significant_duration_s, (m.npts() - 1) * m.dt_s);
}

}  // namespace
}  // namespace skewbridge::records::measures_test
