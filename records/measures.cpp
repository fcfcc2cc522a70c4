#include "records/measures.h"

#include <fftw3.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "solver/common/error.h"

namespace skewbridge::records {
namespace {

void RequireRecord(std::span<const double> acc, double dt_s, std::string_view what) {
  if (acc.empty()) throw InputError::AtField(what, "acceleration", "must not be empty");
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) {
    throw InputError::AtField(what, "dt", fmt::format("must be > 0 s (got {})", dt_s));
  }
}

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
struct PlanDestroy {
  void operator()(fftw_plan_s* p) const { fftw_destroy_plan(p); }
};

// Cumulative int_0^{t_k} a^2 dt at the samples, exact for linear a.
std::vector<double> CumulativeSquare(std::span<const double> acc, double dt_s) {
  std::vector<double> cumulative(acc.size(), 0.0);
  for (std::size_t k = 1; k < acc.size(); ++k) {
    const double a0 = acc[k - 1];
    const double a1 = acc[k];
    cumulative[k] = cumulative[k - 1] + dt_s * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0;
  }
  return cumulative;
}

double CrossingTime(const std::vector<double>& cumulative, double level, double dt_s) {
  const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), level);
  const auto k = static_cast<std::size_t>(it - cumulative.begin());
  if (k == 0) return 0.0;
  const double c0 = cumulative[k - 1];
  const double c1 = cumulative[k];
  const double fraction = c1 > c0 ? (level - c0) / (c1 - c0) : 0.0;
  return (static_cast<double>(k - 1) + fraction) * dt_s;
}

}  // namespace

void IntegrateMotion(std::span<const double> acc, double dt_s, std::vector<double>& vel,
                     std::vector<double>& disp) {
  RequireRecord(acc, dt_s, "integration");
  vel.assign(acc.size(), 0.0);
  disp.assign(acc.size(), 0.0);
  for (std::size_t k = 1; k < acc.size(); ++k) {
    vel[k] = vel[k - 1] + dt_s * (acc[k - 1] + acc[k]) / 2.0;
    disp[k] = disp[k - 1] + dt_s * vel[k - 1] + dt_s * dt_s * (2.0 * acc[k - 1] + acc[k]) / 6.0;
  }
}

std::size_t MeanPeriodDftLength(std::size_t n) {
  return std::bit_ceil(std::max<std::size_t>(n, 1));
}

double MeanPeriod(std::span<const double> acc, double dt_s) {
  RequireRecord(acc, dt_s, "mean period");
  const std::size_t n = MeanPeriodDftLength(acc.size());
  const std::size_t bins = n / 2 + 1;
  std::unique_ptr<double, FftwFree> in(static_cast<double*>(fftw_malloc(sizeof(double) * n)));
  std::unique_ptr<fftw_complex, FftwFree> out(
      static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins)));
  SB_DEMAND(in && out, "fftw_malloc failed");
  // FFTW_ESTIMATE does not touch the arrays while planning; planning is not thread-safe, so
  // callers running measures on several threads must serialise (the sweep does not).
  std::unique_ptr<fftw_plan_s, PlanDestroy> plan(
      fftw_plan_dft_r2c_1d(static_cast<int>(n), in.get(), out.get(), FFTW_ESTIMATE));
  SB_DEMAND(plan != nullptr, "fftw_plan_dft_r2c_1d failed");
  std::copy(acc.begin(), acc.end(), in.get());
  std::fill(in.get() + acc.size(), in.get() + n, 0.0);
  fftw_execute(plan.get());
  const double df_hz = 1.0 / (static_cast<double>(n) * dt_s);
  double weighted = 0.0;
  double total = 0.0;
  for (std::size_t i = 1; i < bins; ++i) {
    const double f = static_cast<double>(i) * df_hz;
    if (f < kMeanPeriodMinFrequency_hz || f > kMeanPeriodMaxFrequency_hz) continue;
    const double c2 = out.get()[i][0] * out.get()[i][0] + out.get()[i][1] * out.get()[i][1];
    weighted += c2 / f;
    total += c2;
  }
  if (!(total > 0.0)) {
    throw InputError::AtField("mean period", "record",
                              "has no Fourier amplitude in 0.25-20 Hz: T_m is undefined");
  }
  return weighted / total;
}

double AriasIntensity(std::span<const double> acc, double dt_s) {
  RequireRecord(acc, dt_s, "Arias intensity");
  return std::numbers::pi / (2.0 * kStandardGravity_mps2) * CumulativeSquare(acc, dt_s).back();
}

double SignificantDuration(std::span<const double> acc, double dt_s, double from, double to) {
  RequireRecord(acc, dt_s, "significant duration");
  if (!(0.0 <= from && from < to && to <= 1.0)) {
    throw InputError::AtField("significant duration", "fractions", "need 0 <= from < to <= 1");
  }
  const std::vector<double> cumulative = CumulativeSquare(acc, dt_s);
  const double total = cumulative.back();
  if (!(total > 0.0)) return 0.0;
  return CrossingTime(cumulative, to * total, dt_s) - CrossingTime(cumulative, from * total, dt_s);
}

namespace {

// The recurrence of [Nigam and Jennings 1969]: [u, v]_{k+1} = A [u, v]_k + B [a_k, a_{k+1}] for
// u'' + 2 xi w u' + w^2 u = -a(t) with a linear on [t_k, t_{k+1}], exact for that excitation.
struct OscillatorStep {
  double a11, a12, a21, a22, b11, b12, b21, b22;

  OscillatorStep(double period_s, double xi, double h) {
    const double w = 2.0 * std::numbers::pi / period_s;
    const double root = std::sqrt(1.0 - xi * xi);
    const double wd = w * root;
    const double e = std::exp(-xi * w * h);
    const double s = std::sin(wd * h);
    const double c = std::cos(wd * h);
    const double r = xi / root;
    a11 = e * (r * s + c);
    a12 = e * s / wd;
    a21 = -w / root * e * s;
    a22 = e * (c - r * s);
    const double k1 = (2.0 * xi * xi - 1.0) / (w * w * h);
    const double k2 = 2.0 * xi / (w * w * w * h);
    b11 = e * ((k1 + xi / w) * s / wd + (k2 + 1.0 / (w * w)) * c) - k2;
    b12 = -e * (k1 * s / wd + k2 * c) - 1.0 / (w * w) + k2;
    b21 = e * ((k1 + xi / w) * (c - r * s) - (k2 + 1.0 / (w * w)) * (wd * s + xi * w * c)) +
          1.0 / (w * w * h);
    b22 = -e * (k1 * (c - r * s) - k2 * (wd * s + xi * w * c)) - 1.0 / (w * w * h);
  }

  /// Runs the recurrence from rest over the record and hands visit(k + 1, u_{k+1}) each step's
  /// displacement [m].
  template <class Visit>
  void Displacements(std::span<const double> acc, Visit&& visit) const {
    double u = 0.0;
    double v = 0.0;
    for (std::size_t k = 0; k + 1 < acc.size(); ++k) {
      const double u_next = a11 * u + a12 * v + b11 * acc[k] + b12 * acc[k + 1];
      const double v_next = a21 * u + a22 * v + b21 * acc[k] + b22 * acc[k + 1];
      u = u_next;
      v = v_next;
      visit(k + 1, u);
    }
  }
};

void RequireDampingAndPeriod(double xi, double period, std::string_view what) {
  if (!(xi >= 0.0 && xi < 1.0)) {
    throw InputError::AtField(what, "xi", fmt::format("must be in [0, 1) (got {})", xi));
  }
  if (!(std::isfinite(period) && period > 0.0)) {
    throw InputError::AtField(what, "period", fmt::format("must be > 0 s (got {})", period));
  }
}

}  // namespace

ResponseSpectrum ElasticResponseSpectrum(std::span<const double> acc, double dt_s,
                                         std::span<const double> periods_s, double xi) {
  RequireRecord(acc, dt_s, "response spectrum");
  if (!(xi >= 0.0 && xi < 1.0)) {
    throw InputError::AtField("response spectrum", "xi",
                              fmt::format("must be in [0, 1) (got {})", xi));
  }
  for (const double period : periods_s) RequireDampingAndPeriod(xi, period, "response spectrum");
  ResponseSpectrum out;
  out.xi = xi;
  out.periods_s.assign(periods_s.begin(), periods_s.end());
  // The oscillators of kLanes periods at a time advance together, sample by sample: each is
  // OscillatorStep::Displacements's recurrence with its operations in the same order (so the same
  // bits), and the independent recurrences of the lanes overlap where one alone waits on its own
  // previous step. Lanes past the last period have zero coefficients and stay at rest.
  constexpr std::size_t kLanes = 8;
  for (std::size_t first = 0; first < periods_s.size(); first += kLanes) {
    const std::size_t lanes = std::min(kLanes, periods_s.size() - first);
    std::array<double, kLanes> a11{}, a12{}, a21{}, a22{}, b11{}, b12{}, b21{}, b22{};
    for (std::size_t j = 0; j < lanes; ++j) {
      const OscillatorStep step(periods_s[first + j], xi, dt_s);
      a11[j] = step.a11;
      a12[j] = step.a12;
      a21[j] = step.a21;
      a22[j] = step.a22;
      b11[j] = step.b11;
      b12[j] = step.b12;
      b21[j] = step.b21;
      b22[j] = step.b22;
    }
    std::array<double, kLanes> u{}, v{}, peak{};
    for (std::size_t k = 0; k + 1 < acc.size(); ++k) {
      const double a0 = acc[k];
      const double a1 = acc[k + 1];
      for (std::size_t j = 0; j < kLanes; ++j) {
        const double u_next = a11[j] * u[j] + a12[j] * v[j] + b11[j] * a0 + b12[j] * a1;
        const double v_next = a21[j] * u[j] + a22[j] * v[j] + b21[j] * a0 + b22[j] * a1;
        u[j] = u_next;
        v[j] = v_next;
        peak[j] = std::max(peak[j], std::abs(u_next));
      }
    }
    for (std::size_t j = 0; j < lanes; ++j) {
      const double w = 2.0 * std::numbers::pi / periods_s[first + j];
      out.sd_m.push_back(peak[j]);
      out.psv_mps.push_back(w * peak[j]);
      out.psa_mps2.push_back(w * w * peak[j]);
    }
  }
  return out;
}

std::vector<double> OscillatorDisplacement(std::span<const double> acc, double dt_s,
                                           double period_s, double xi) {
  RequireRecord(acc, dt_s, "oscillator response");
  RequireDampingAndPeriod(xi, period_s, "oscillator response");
  std::vector<double> out(acc.size(), 0.0);
  OscillatorStep(period_s, xi, dt_s).Displacements(acc, [&out](std::size_t k, double u) {
    out[k] = u;
  });
  return out;
}

RotDValues RotDFromHistories(std::span<const double> u1, std::span<const double> u2) {
  SB_DEMAND(u1.size() == u2.size() && !u1.empty(), "two response histories of one length");
  std::array<double, kRotDAngles> peak{};
  for (int angle = 0; angle < kRotDAngles; ++angle) {
    const double theta = angle * std::numbers::pi / 180.0;
    const double c = std::cos(theta);
    const double s = std::sin(theta);
    double m = 0.0;
    for (std::size_t k = 0; k < u1.size(); ++k) m = std::max(m, std::abs(c * u1[k] + s * u2[k]));
    peak[static_cast<std::size_t>(angle)] = m;
  }
  RotDValues out;
  const auto largest = std::max_element(peak.begin(), peak.end());
  out.rotd100 = *largest;
  out.rotd100_angle_deg = static_cast<double>(largest - peak.begin());
  out.rotd0 = *std::min_element(peak.begin(), peak.end());
  std::array<double, kRotDAngles> sorted = peak;
  std::sort(sorted.begin(), sorted.end());
  out.rotd50 = 0.5 * (sorted[kRotDAngles / 2 - 1] + sorted[kRotDAngles / 2]);
  return out;
}

PairSpectrum PairResponseSpectrum(std::span<const double> h1, std::span<const double> h2,
                                  double dt_s, std::span<const double> periods_s, double xi) {
  if (h1.size() != h2.size()) {
    throw InputError::AtField(
        "pair spectrum", "components",
        fmt::format("H1 and H2 differ in length ({} and {} samples)", h1.size(), h2.size()));
  }
  PairSpectrum out;
  out.xi = xi;
  out.periods_s.assign(periods_s.begin(), periods_s.end());
  for (const double period : periods_s) {
    const double w = 2.0 * std::numbers::pi / period;
    const double w2 = w * w;  // as ElasticResponseSpectrum's PSa = w^2 Sd
    const std::vector<double> u1 = OscillatorDisplacement(h1, dt_s, period, xi);
    const std::vector<double> u2 = OscillatorDisplacement(h2, dt_s, period, xi);
    double peak1 = 0.0;
    double peak2 = 0.0;
    for (std::size_t k = 0; k < u1.size(); ++k) {
      peak1 = std::max(peak1, std::abs(u1[k]));
      peak2 = std::max(peak2, std::abs(u2[k]));
    }
    const RotDValues rotd = RotDFromHistories(u1, u2);
    out.sa_h1_mps2.push_back(w2 * peak1);
    out.sa_h2_mps2.push_back(w2 * peak2);
    out.gm_mps2.push_back(w2 * std::sqrt(peak1 * peak2));
    out.rotd0_mps2.push_back(w2 * rotd.rotd0);
    out.rotd50_mps2.push_back(w2 * rotd.rotd50);
    out.rotd100_mps2.push_back(w2 * rotd.rotd100);
    out.rotd100_angle_deg.push_back(rotd.rotd100_angle_deg);
  }
  return out;
}

std::vector<double> PseudoAccelerationSpectrum(std::span<const double> acc, double dt_s,
                                               std::span<const double> periods_s, double xi) {
  return ElasticResponseSpectrum(acc, dt_s, periods_s, xi).psa_mps2;
}

std::vector<double> AvgSaPeriods(double t1_s, double from_t1, double to_t1, int count) {
  if (!(std::isfinite(t1_s) && t1_s > 0.0)) {
    throw InputError::AtField("AvgSa", "T1", fmt::format("must be > 0 s (got {})", t1_s));
  }
  if (!(std::isfinite(from_t1) && std::isfinite(to_t1) && 0.0 < from_t1 && from_t1 <= to_t1)) {
    throw InputError::AtField("AvgSa", "range", "needs 0 < from <= to (multiples of T1)");
  }
  if (count < 1) throw InputError::AtField("AvgSa", "count", "must be a whole number >= 1");
  std::vector<double> periods(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double f = count == 1 ? 0.0 : static_cast<double>(i) / (count - 1);
    periods[static_cast<std::size_t>(i)] = t1_s * (from_t1 + (to_t1 - from_t1) * f);
  }
  periods.back() = t1_s * (count == 1 ? from_t1 : to_t1);
  return periods;
}

double AverageSpectralAcceleration(std::span<const double> acc, double dt_s,
                                   std::span<const double> periods_s, double xi) {
  if (periods_s.empty()) throw InputError::AtField("AvgSa", "periods", "must not be empty");
  const ResponseSpectrum spectrum = ElasticResponseSpectrum(acc, dt_s, periods_s, xi);
  double log_sum = 0.0;
  for (const double sa : spectrum.psa_mps2) {
    if (!(sa > 0.0)) return 0.0;
    log_sum += std::log(sa);
  }
  return std::exp(log_sum / static_cast<double>(spectrum.psa_mps2.size()));
}

double AverageRotD50(std::span<const double> h1, std::span<const double> h2, double dt_s,
                     std::span<const double> periods_s, double xi) {
  if (periods_s.empty()) throw InputError::AtField("AvgSa", "periods", "must not be empty");
  const PairSpectrum spectrum = PairResponseSpectrum(h1, h2, dt_s, periods_s, xi);
  double log_sum = 0.0;
  for (const double sa : spectrum.rotd50_mps2) {
    if (!(sa > 0.0)) return 0.0;
    log_sum += std::log(sa);
  }
  return std::exp(log_sum / static_cast<double>(spectrum.rotd50_mps2.size()));
}

double CumulativeAbsoluteVelocity(std::span<const double> acc, double dt_s) {
  RequireRecord(acc, dt_s, "cumulative absolute velocity");
  double cav = 0.0;
  for (std::size_t k = 1; k < acc.size(); ++k) {
    const double a0 = acc[k - 1];
    const double a1 = acc[k];
    if ((a0 >= 0.0) == (a1 >= 0.0) || a0 == 0.0 || a1 == 0.0) {
      cav += dt_s * std::abs(a0 + a1) / 2.0;
    } else {
      // A sign change at t0 + dt |a0| / (|a0| + |a1|): two triangles.
      cav += dt_s * (a0 * a0 + a1 * a1) / (2.0 * (std::abs(a0) + std::abs(a1)));
    }
  }
  return cav;
}

IntensityMeasures ComputeMeasures(const GroundMotion& motion) {
  const std::span<const double> acc(motion.acc_mps2);
  IntensityMeasures m;
  for (const double a : acc) m.pga_mps2 = std::max(m.pga_mps2, std::abs(a));
  std::vector<double> vel;
  std::vector<double> disp;
  IntegrateMotion(acc, motion.dt_s, vel, disp);
  for (std::size_t k = 0; k < acc.size(); ++k) {
    m.pgv_mps = std::max(m.pgv_mps, std::abs(vel[k]));
    m.pgd_m = std::max(m.pgd_m, std::abs(disp[k]));
  }
  m.mean_period_s = MeanPeriod(acc, motion.dt_s);
  m.omega_g_radps = 2.0 * std::numbers::pi / m.mean_period_s;
  m.persistency_m = m.pga_mps2 / (m.omega_g_radps * m.omega_g_radps);
  m.arias_mps = AriasIntensity(acc, motion.dt_s);
  m.significant_duration_s = SignificantDuration(acc, motion.dt_s);
  m.cav_mps = CumulativeAbsoluteVelocity(acc, motion.dt_s);
  return m;
}

}  // namespace skewbridge::records
