#include "records/synthetic.h"

#include <fftw3.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <complex>
#include <cstring>
#include <fstream>
#include <memory>
#include <numbers>
#include <random>

#include <fmt/format.h>

#include "records/measures.h"
#include "solver/common/error.h"

namespace skewbridge::records {
namespace {

using std::numbers::pi;

constexpr double kLowestGroundFrequency_hz = 0.05;
constexpr double kHighestGroundFrequency_hz = 40.0;
constexpr int kMaxTuningIterations = 200;
// PGA targets keep this relative margin inside the range: the 8 printed digits of the .AT2
// text move the PGA by at most 5e-9 relative.
constexpr double kPgaMargin = 1e-6;

// Portable variates from the standard-specified 64-bit Mersenne Twister.
class Variates {
 public:
  explicit Variates(std::uint64_t seed) : engine_(seed) {}
  /// Uniform on [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Standard normal by Box-Muller (the sine branch is dropped to keep the stream simple).
  double Normal() {
    const double u1 = 1.0 - Uniform();  // (0, 1]
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * pi * u2);
  }

 private:
  std::mt19937_64 engine_;
};

// A distinct, well-mixed seed per record [Steele et al. 2014, SplitMix64].
std::uint64_t RecordSeed(std::uint64_t seed, int index) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (static_cast<std::uint64_t>(index) + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
struct PlanDestroy {
  void operator()(fftw_plan_s* p) const { fftw_destroy_plan(p); }
};

// White noise in the frequency domain, filtered for a given ground frequency and enveloped.
class Filter {
 public:
  Filter(const SynthOptions& options, const std::vector<double>& noise)
      : options_(options),
        n_(noise.size()),
        n_dft_(std::bit_ceil(2 * noise.size())),
        bins_(n_dft_ / 2 + 1),
        spectrum_(bins_),
        time_(static_cast<double*>(fftw_malloc(sizeof(double) * n_dft_))),
        freq_(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins_))) {
    SB_DEMAND(time_ && freq_, "fftw_malloc failed");
    // Zero padding to twice the length keeps the circular convolution from wrapping around.
    std::copy(noise.begin(), noise.end(), time_.get());
    std::fill(time_.get() + n_, time_.get() + n_dft_, 0.0);
    const std::unique_ptr<fftw_plan_s, PlanDestroy> forward(
        fftw_plan_dft_r2c_1d(static_cast<int>(n_dft_), time_.get(), freq_.get(), FFTW_ESTIMATE));
    SB_DEMAND(forward != nullptr, "fftw plan failed");
    fftw_execute(forward.get());
    for (std::size_t i = 0; i < bins_; ++i) spectrum_[i] = {freq_.get()[i][0], freq_.get()[i][1]};
    backward_.reset(
        fftw_plan_dft_c2r_1d(static_cast<int>(n_dft_), freq_.get(), time_.get(), FFTW_ESTIMATE));
    SB_DEMAND(backward_ != nullptr, "fftw plan failed");
    // Saragoni-Hart (gamma) envelope (t / t_p)^2 exp(2 (1 - t / t_p)), peak 1 at t_p: the
    // same factors for every trial w_g, so computed once.
    const double t_peak = options_.envelope_peak_fraction * options_.duration_s;
    envelope_.resize(n_);
    for (std::size_t k = 0; k < n_; ++k) {
      const double r = static_cast<double>(k) * options_.dt_s / t_peak;
      envelope_[k] = r * r * std::exp(2.0 * (1.0 - r));
    }
    // MeanPeriod plans a transform of its own length on every call; while a plan of that
    // length lives, FFTW shares its twiddle factors instead of recomputing them (the sines
    // and cosines were most of a trial's cost). The plan is never executed; the transforms,
    // and so the bytes, are those of MeanPeriod's own plan.
    const std::size_t n_measure = MeanPeriodDftLength(n_);
    measure_in_.reset(static_cast<double*>(fftw_malloc(sizeof(double) * n_measure)));
    measure_out_.reset(
        static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * (n_measure / 2 + 1))));
    SB_DEMAND(measure_in_ && measure_out_, "fftw_malloc failed");
    measure_plan_.reset(fftw_plan_dft_r2c_1d(static_cast<int>(n_measure), measure_in_.get(),
                                             measure_out_.get(), FFTW_ESTIMATE));
    SB_DEMAND(measure_plan_ != nullptr, "fftw plan failed");
  }

  // Clough-Penzien filtered noise for ground frequency w_g, times the envelope.
  std::vector<double> Motion(double omega_g) {
    const double omega_f = options_.cp_ratio * omega_g;
    const double dw = 2.0 * pi / (static_cast<double>(n_dft_) * options_.dt_s);
    const std::complex<double> j(0.0, 1.0);
    for (std::size_t i = 0; i < bins_; ++i) {
      const double w = dw * static_cast<double>(i);
      // Kanai-Tajimi [Kanai 1957; Tajimi 1960] and the Clough-Penzien high-pass.
      const std::complex<double> kt =
          (omega_g * omega_g + 2.0 * j * options_.zeta_g * omega_g * w) /
          (omega_g * omega_g - w * w + 2.0 * j * options_.zeta_g * omega_g * w);
      const std::complex<double> cp =
          (w * w) / (omega_f * omega_f - w * w + 2.0 * j * options_.zeta_f * omega_f * w);
      const std::complex<double> y = spectrum_[i] * kt * cp;
      freq_.get()[i][0] = y.real();
      freq_.get()[i][1] = y.imag();
    }
    fftw_execute(backward_.get());
    std::vector<double> acc(time_.get(), time_.get() + n_);
    for (std::size_t k = 0; k < n_; ++k) {
      acc[k] *= envelope_[k];
    }
    return acc;
  }

 private:
  const SynthOptions& options_;
  std::size_t n_;
  std::size_t n_dft_;
  std::size_t bins_;
  std::vector<std::complex<double>> spectrum_;
  std::unique_ptr<double, FftwFree> time_;
  std::unique_ptr<fftw_complex, FftwFree> freq_;
  std::unique_ptr<fftw_plan_s, PlanDestroy> backward_;
  std::vector<double> envelope_;
  std::unique_ptr<double, FftwFree> measure_in_;
  std::unique_ptr<fftw_complex, FftwFree> measure_out_;
  std::unique_ptr<fftw_plan_s, PlanDestroy> measure_plan_;  // keeps MeanPeriod's twiddles
};

void AppendFixed(std::string& out, std::string_view text, std::size_t width) {
  if (text.size() < width) out.append(width - text.size(), ' ');
  out += text;
}

std::string Shortest(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

double DrawIn(Variates& variates, double lo, double hi, double margin) {
  const double a = lo * (1.0 + margin);
  const double b = hi * (1.0 - margin);
  const double u = variates.Uniform();
  return a < b ? a + (b - a) * u : 0.5 * (lo + hi);
}

std::string IndexName(int index, int count) {
  const std::size_t width = std::max<std::size_t>(3, std::to_string(std::max(count - 1, 0)).size());
  std::string digits = std::to_string(index);
  return std::string(width - std::min(width, digits.size()), '0') + digits;
}

}  // namespace

// ---- Baseline correction: a post-processing step of the filtered motion ----------------------

namespace {

constexpr int kTerms = 5;  // c(t) = b_0 + b_1 s + ... + b_4 s^4, s = t / T
constexpr int kUnknowns = kTerms + 2;

// RemoveBaselineDrift for records of one length and sample interval. Everything that does not
// depend on the record (the high-pass gains, the FFT plans, the basis displacements and their
// normal matrix) is computed once, since the T_m bisection corrects about twenty trial motions
// of one record; the arithmetic per record is the same, operation for operation, as computing
// it afresh, so the bytes do not depend on the reuse.
class BaselineCorrection {
 public:
  BaselineCorrection(std::size_t n, double dt_s)
      : n_(n), dt_s_(dt_s), n_dft_(std::bit_ceil(2 * n)), bins_(n_dft_ / 2 + 1) {
    SB_DEMAND(n >= 6 && dt_s > 0.0, "baseline correction needs 6 samples and dt > 0");
    // Zero-phase high-pass of magnitude 1 / sqrt(1 + (f_c / f)^8) (a 4th-order Butterworth's,
    // applied forward and backward in effect), on the record padded with zeros to twice its
    // length so that the filter's response does not wrap around.
    time_.reset(static_cast<double*>(fftw_malloc(sizeof(double) * n_dft_)));
    freq_.reset(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins_)));
    SB_DEMAND(time_ && freq_, "fftw_malloc failed");
    forward_.reset(
        fftw_plan_dft_r2c_1d(static_cast<int>(n_dft_), time_.get(), freq_.get(), FFTW_ESTIMATE));
    backward_.reset(
        fftw_plan_dft_c2r_1d(static_cast<int>(n_dft_), freq_.get(), time_.get(), FFTW_ESTIMATE));
    SB_DEMAND(forward_ != nullptr && backward_ != nullptr, "fftw plan failed");
    const double df = 1.0 / (static_cast<double>(n_dft_) * dt_s);
    scale_.resize(bins_);
    for (std::size_t i = 0; i < bins_; ++i) {
      const double f = df * static_cast<double>(i);
      const double gain =
          i == 0 ? 0.0 : 1.0 / std::sqrt(1.0 + std::pow(kBaselineHighPass_hz / f, 8));
      scale_[i] = gain / static_cast<double>(n_dft_);  // FFTW's transforms are unscaled
    }
    // The displacement and end velocity of each basis acceleration, by the same discrete rule
    // as the record's.
    length_s_ = dt_s * static_cast<double>(n - 1);
    std::vector<double> phi(n), phi_vel;
    for (int k = 0; k < kTerms; ++k) {
      for (std::size_t i = 0; i < n; ++i) {
        phi[i] = std::pow(static_cast<double>(i) * dt_s / length_s_, k);
      }
      IntegrateMotion(phi, dt_s, phi_vel, basis_disp_[k]);
      basis_v_end_[k] = phi_vel.back();
    }
    // KKT system of min |disp - D b|^2 subject to D_end b = disp_end, V_end b = vel_end; the
    // last column (the record's) is filled per record.
    for (int j = 0; j < kTerms; ++j) {
      for (int k = 0; k < kTerms; ++k) {
        for (std::size_t i = 0; i < n; ++i) kkt_[j][k] += basis_disp_[j][i] * basis_disp_[k][i];
      }
      kkt_[j][kTerms] = kkt_[kTerms][j] = basis_disp_[j].back();
      kkt_[j][kTerms + 1] = kkt_[kTerms + 1][j] = basis_v_end_[j];
    }
  }

  void Apply(std::vector<double>& acc) {
    SB_DEMAND(acc.size() == n_, "baseline correction of a record of another length");
    HighPass(acc);
    std::vector<double> vel, disp;
    IntegrateMotion(acc, dt_s_, vel, disp);
    constexpr int m = kUnknowns;
    double a[m][m + 1];
    std::memcpy(a, kkt_, sizeof a);
    for (int j = 0; j < kTerms; ++j) {
      for (std::size_t i = 0; i < n_; ++i) a[j][m] += basis_disp_[j][i] * disp[i];
    }
    a[kTerms][m] = disp.back();
    a[kTerms + 1][m] = vel.back();
    // Gaussian elimination with partial pivoting (7 unknowns).
    for (int col = 0; col < m; ++col) {
      int pivot = col;
      for (int r = col + 1; r < m; ++r) {
        if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
      }
      SB_DEMAND(a[pivot][col] != 0.0, "baseline correction: singular fit");
      for (int c = 0; c <= m; ++c) std::swap(a[col][c], a[pivot][c]);
      for (int r = 0; r < m; ++r) {
        if (r == col) continue;
        const double f = a[r][col] / a[col][col];
        for (int c = col; c <= m; ++c) a[r][c] -= f * a[col][c];
      }
    }
    for (std::size_t i = 0; i < n_; ++i) {
      const double s = static_cast<double>(i) * dt_s_ / length_s_;
      double c = 0.0;
      for (int k = kTerms - 1; k >= 0; --k) c = c * s + a[k][m] / a[k][k];
      acc[i] -= c;
    }
  }

 private:
  void HighPass(std::vector<double>& acc) {
    std::copy(acc.begin(), acc.end(), time_.get());
    std::fill(time_.get() + n_, time_.get() + n_dft_, 0.0);
    fftw_execute(forward_.get());
    for (std::size_t i = 0; i < bins_; ++i) {
      freq_.get()[i][0] *= scale_[i];
      freq_.get()[i][1] *= scale_[i];
    }
    fftw_execute(backward_.get());
    std::copy(time_.get(), time_.get() + n_, acc.begin());
  }

  std::size_t n_;
  double dt_s_;
  std::size_t n_dft_;
  std::size_t bins_;
  double length_s_ = 0.0;
  std::unique_ptr<double, FftwFree> time_;
  std::unique_ptr<fftw_complex, FftwFree> freq_;
  std::unique_ptr<fftw_plan_s, PlanDestroy> forward_;
  std::unique_ptr<fftw_plan_s, PlanDestroy> backward_;
  std::vector<double> scale_;  // high-pass gain / n_dft per frequency bin
  std::vector<double> basis_disp_[kTerms];
  double basis_v_end_[kTerms] = {};
  double kkt_[kUnknowns][kUnknowns + 1] = {};
};

}  // namespace

void RemoveBaselineDrift(std::vector<double>& acc, double dt_s) {
  BaselineCorrection(acc.size(), dt_s).Apply(acc);
}

// ---- end of the baseline correction ----------------------------------------------------------

void ValidateSynthOptions(const SynthOptions& o) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (o.count < 1) throw InputError::AtField("synth", "count", "must be >= 1");
  if (!positive(o.pga_min_g) || !positive(o.pga_max_g) || o.pga_min_g > o.pga_max_g) {
    throw InputError::AtField("synth", "PGA range", "needs 0 < pga-min-g <= pga-max-g");
  }
  if (!positive(o.tm_min_s) || !positive(o.tm_max_s) || o.tm_min_s > o.tm_max_s) {
    throw InputError::AtField("synth", "T_m range", "needs 0 < tm-min-s <= tm-max-s");
  }
  if (!positive(o.dt_s) || o.dt_s > 0.02) {
    throw InputError::AtField("synth", "dt", "must be in (0, 0.02] s (the T_m band ends at 20 Hz)");
  }
  if (!positive(o.duration_s) || o.duration_s < 20.0 * o.dt_s || o.duration_s / o.dt_s > 1e7) {
    throw InputError::AtField("synth", "duration", "must be >= 20 dt and <= 1e7 dt");
  }
  if (!(o.zeta_g > 0.0 && o.zeta_g < 1.0) || !(o.zeta_f > 0.0 && o.zeta_f < 1.0) ||
      !(o.cp_ratio > 0.0 && o.cp_ratio < 1.0) ||
      !(o.envelope_peak_fraction > 0.0 && o.envelope_peak_fraction < 1.0) ||
      !(o.tm_tolerance > 0.0 && o.tm_tolerance < 0.1)) {
    throw InputError::AtField("synth", "filter",
                              "damping ratios, cp_ratio, envelope fraction in "
                              "(0, 1) and tm_tolerance in (0, 0.1)");
  }
}

GroundMotion SynthesizeRecord(const SynthOptions& options, int index) {
  ValidateSynthOptions(options);
  Variates variates(RecordSeed(options.seed, index));
  const double pga_g = DrawIn(variates, options.pga_min_g, options.pga_max_g, kPgaMargin);
  const double tm_target =
      DrawIn(variates, options.tm_min_s, options.tm_max_s, 2.0 * options.tm_tolerance);
  const auto n = static_cast<std::size_t>(std::llround(options.duration_s / options.dt_s)) + 1;
  std::vector<double> noise(n);
  for (double& x : noise) x = variates.Normal();
  Filter filter(options, noise);

  // T_m falls as w_g rises: bisect on log w_g.
  // The filtered motion after its baseline correction (RemoveBaselineDrift), the motion written.
  BaselineCorrection baseline(n, options.dt_s);
  const auto motion_of = [&](double omega) {
    std::vector<double> acc = filter.Motion(omega);
    baseline.Apply(acc);
    return acc;
  };
  const auto tm_of = [&](double omega) { return MeanPeriod(motion_of(omega), options.dt_s); };
  double lo = 2.0 * pi * kLowestGroundFrequency_hz;
  double hi = 2.0 * pi * std::min(kHighestGroundFrequency_hz, 0.4 / options.dt_s);
  const double tm_longest = tm_of(lo);
  const double tm_shortest = tm_of(hi);
  if (!(tm_shortest <= tm_target && tm_target <= tm_longest)) {
    throw InputError::AtField(
        "synth", "T_m range",
        fmt::format("target {:.3g} s is out of reach ({:.3g} to {:.3g} s with this "
                    "dt and duration)",
                    tm_target, tm_shortest, tm_longest));
  }
  double omega = std::sqrt(lo * hi);
  double tm = tm_of(omega);
  for (int it = 0;
       it < kMaxTuningIterations && std::abs(tm - tm_target) > options.tm_tolerance * tm_target;
       ++it) {
    (tm > tm_target ? lo : hi) = omega;
    omega = std::sqrt(lo * hi);
    tm = tm_of(omega);
  }
  std::vector<double> acc = motion_of(omega);
  double peak = 0.0;
  for (double a : acc) peak = std::max(peak, std::abs(a));
  SB_DEMAND(peak > 0.0, "filtered noise is identically zero");
  const double scale = pga_g * kStandardGravity_mps2 / peak;
  for (double& a : acc) a *= scale;

  GroundMotion motion;
  const std::string name = SyntheticLabel(options, index);
  motion.file = name + ".AT2";
  motion.format = std::string(FormatName(Format::kAt2));
  motion.event = "Synthetic Clough-Penzien (seed ";
  motion.event += std::to_string(options.seed);
  motion.event += ')';
  motion.station = name;
  motion.component = std::string(1, 'H');
  motion.original_units = std::string(UnitsName(Units::kG));
  motion.dt_s = options.dt_s;
  motion.acc_mps2 = std::move(acc);
  // Return exactly what a reader will see in the file.
  GroundMotion printed = ParseRecord(FormatAt2(motion), motion.file);
  printed.event = motion.event;
  return printed;
}

std::vector<GroundMotion> SynthesizeSuite(const SynthOptions& options) {
  ValidateSynthOptions(options);
  std::vector<GroundMotion> suite;
  suite.reserve(static_cast<std::size_t>(options.count));
  for (int i = 0; i < options.count; ++i) suite.push_back(SynthesizeRecord(options, i));
  return suite;
}

std::string FormatAt2(const GroundMotion& motion) {
  std::string out = "PEER NGA STRONG MOTION DATABASE RECORD\n";
  out += motion.event + ", " + motion.file + ", " + motion.station + ", " + motion.component + "\n";
  out += "ACCELERATION TIME SERIES IN UNITS OF G\n";
  out += "NPTS= " + std::to_string(motion.npts()) + ", DT= " + Shortest(motion.dt_s) + " SEC\n";
  char buffer[64];
  for (std::size_t k = 0; k < motion.npts(); ++k) {
    const double g = motion.acc_mps2[k] / kStandardGravity_mps2;
    const auto result =
        std::to_chars(buffer, buffer + sizeof(buffer), g, std::chars_format::scientific, 7);
    std::string text(buffer, result.ptr);
    for (char& c : text) {
      if (c == 'e') c = 'E';
    }
    AppendFixed(out, text, 15);
    if (k % 5 == 4 || k + 1 == motion.npts()) out += '\n';
  }
  return out;
}

void WriteAt2(const std::filesystem::path& path, const GroundMotion& motion) {
  std::ofstream out(path, std::ios::binary);
  out << FormatAt2(motion);
  if (!out) throw InputError::AtLine(path.string(), 0, "cannot write the record file");
}

std::filesystem::path WriteSuite(const std::filesystem::path& directory,
                                 const SynthOptions& options) {
  ValidateSynthOptions(options);
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw InputError::AtLine(directory.string(), 0, "cannot create: " + ec.message());
  std::string manifest = "# Synthetic suite: Clough-Penzien filtered noise, seed " +
                         std::to_string(options.seed) + ", PGA " + Shortest(options.pga_min_g) +
                         "-" + Shortest(options.pga_max_g) + " g, T_m " +
                         Shortest(options.tm_min_s) + "-" + Shortest(options.tm_max_s) + " s.\n";
  manifest += "name = \"synth-seed-" + std::to_string(options.seed) + "\"\n";
  for (int i = 0; i < options.count; ++i) {
    const GroundMotion motion = SynthesizeRecord(options, i);
    const std::string file = "synth_" + IndexName(i, options.count) + ".AT2";
    WriteAt2(directory / file, motion);
    manifest += "\n[[record]]\nfile = \"" + file + "\"\nlabel = \"" + motion.station + "\"\n";
  }
  const std::filesystem::path path = directory / "set.toml";
  std::ofstream out(path, std::ios::binary);
  out << manifest;
  if (!out) throw InputError::AtLine(path.string(), 0, "cannot write the manifest");
  return path;
}

std::string SyntheticLabel(const SynthOptions& options, int index) {
  // Appending (not "literal" + string) avoids g++ 12's false -Wrestrict warning.
  std::string name = "synth-";
  name += std::to_string(options.seed);
  name += '-';
  name += IndexName(index, options.count);
  return name;
}

}  // namespace skewbridge::records
