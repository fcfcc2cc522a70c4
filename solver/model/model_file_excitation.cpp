#include <cmath>
#include <sstream>

#include "solver/model/model_file_tables.h"

namespace skewbridge::model {

using detail::Fail;
using detail::Where;

std::optional<double> ExcitationSpec::Duration() const {
  if (kind == Kind::kPulse) {
    return 2.0 * std::numbers::pi / omega_radps;
  }
  if (file.empty() && dt_s && !values.empty()) {
    return *dt_s * static_cast<double>(values.size() - 1);
  }
  return std::nullopt;
}

void ExcitationSpec::CheckPga(double pga_mps2, std::string_view source, long line,
                              std::string_view field) const {
  const double as_given_mps2 = scale != 0.0 ? pga_mps2 / std::abs(scale) : 0.0;
  if (!(as_given_mps2 > max_pga_g * kStandardGravity_mps2)) {
    return;
  }
  std::ostringstream text;
  text.precision(4);
  text << "PGA " << as_given_mps2 << " m/s^2 (" << as_given_mps2 / kStandardGravity_mps2
       << " g) in the units " << UnitsName(units) << " is above max_pga_g = " << max_pga_g
       << " g, beyond any recorded ground motion; allowed: the true excitation.units ("
       << AllowedUnitsText() << "), or a larger excitation.max_pga_g (inf: no bound) if the "
       << "motion means it";
  Fail(Where{source, line}, field, text.str());
}

namespace {

// The longest run accepted [s]: event times keep a resolution of 1.2e-10 s up to here (one ulp
// of 1e6), below the default simultaneity tolerance of 1e-9 s; beyond, a run length is a unit
// error or an overflow (a pulse period of 1e308 s).
constexpr double kMaxEndTime_s = 1e6;
// The most history samples a run may store (3 DOFs, positions and velocities: 0.5 GB).
constexpr double kMaxHistorySamples = 1e7;

}  // namespace

void CheckRunSize(const RunControl& run, double excitation_duration_s,
                  std::size_t excitation_samples, std::string_view source,
                  std::string_view excitation_field) {
  const Where where{source, 0};
  const double t_end = run.EndTime(excitation_duration_s);
  const std::string field = run.end_time_s ? "run.end_time_s" : std::string(excitation_field);
  if (!std::isfinite(t_end) || !(t_end <= kMaxEndTime_s)) {
    Fail(where, field,
         "the run would end at t = " + detail::Show(t_end) +
             " s (the excitation's duration plus run.tail_s, or run.end_time_s); allowed: a "
             "finite end time up to 1e6 s");
  }
  if (run.output_interval_s > 0.0) {
    const double samples = t_end / run.output_interval_s;
    if (!(samples <= kMaxHistorySamples)) {
      Fail(where, "run.output_interval_s",
           "the run of " + detail::Show(t_end) + " s would store " + detail::Show(samples) +
               " history samples; allowed at most 1e7 (a larger interval, or 0 for none)");
    }
  }
  if (run.method == Method::kTimeStepping) {
    const double steps = t_end / run.time_step_s;
    if (!(steps <= static_cast<double>(run.max_steps))) {
      Fail(where, "run.time_step_s",
           "the run of " + detail::Show(t_end) + " s would take " + detail::Show(steps) +
               " steps, more than run.max_steps = " + std::to_string(run.max_steps));
    }
  } else if (excitation_samples > 1 &&
             static_cast<double>(excitation_samples - 1) > static_cast<double>(run.max_steps)) {
    // Each sample is a kink of the ground motion, so each interval is one step at least.
    Fail(where, std::string(excitation_field),
         "its " + std::to_string(excitation_samples) +
             " samples take one step each at least, more than run.max_steps = " +
             std::to_string(run.max_steps));
  }
}

namespace detail {
namespace {

// The largest ground acceleration accepted [m/s^2] (about 1e5 g: beyond any ground motion, a
// unit error; far enough from overflow that responses stay finite).
constexpr double kMaxAcceleration_mps2 = 1e6;
// The largest factor on a sampled excitation's values.
constexpr double kMaxScale = 1e6;

// The keys of [excitation] for each kind.
constexpr std::array<std::pair<std::string_view, std::string_view>, 2> kExcitationKeys{{
    {"pulse", "kind, shape, a_g, a_g_g, w_g, T_g, direction, angle_deg (with kind = \"pulse\")"},
    {"sampled",
     "kind, file, values, dt_s, units, scale, max_pga_g, direction, angle_deg (with kind = "
     "\"sampled\")"},
}};

}  // namespace

void ReadExcitation(Section& s, const std::filesystem::path& base_dir, ExcitationSpec& spec) {
  s.Expect(
      "kind, shape, a_g, a_g_g, w_g, T_g, file, values, dt_s, units, scale, max_pga_g, "
      "direction, angle_deg");
  const std::optional<std::string> kind = s.String("kind", {"pulse", "sampled"});
  if (!kind) {
    s.Missing("kind", "\"pulse\" or \"sampled\"");
  }
  ExpectForm(s, *kind, kExcitationKeys);
  // Direction: "x", "y" or an angle from x (CCW, deg).
  if (s.Has("direction")) {
    s.Reject("angle_deg", "give either direction or angle_deg, not both");
    const std::string d = *s.String("direction", {"x", "y"});
    spec.direction = d == "x" ? Eigen::Vector2d::UnitX() : Eigen::Vector2d::UnitY();
  } else if (const std::optional<double> angle = s.Number("angle_deg")) {
    spec.direction = {std::cos(*angle * kDegToRad), std::sin(*angle * kDegToRad)};
  }
  if (*kind == "pulse") {
    spec.kind = ExcitationSpec::Kind::kPulse;
    const std::optional<std::string> shape = s.String("shape", {"cosine", "sine"});
    if (!shape) {
      s.Missing("shape", "\"cosine\" or \"sine\"");
    }
    spec.shape = *shape == "cosine" ? ExcitationSpec::PulseShape::kCosine
                                    : ExcitationSpec::PulseShape::kSine;
    if (s.Has("a_g")) {
      s.Reject("a_g_g", "give either a_g (m/s^2) or a_g_g (g), not both");
      spec.amplitude_mps2 = *s.Number("a_g");
    } else if (s.Has("a_g_g")) {
      spec.amplitude_mps2 = *s.Number("a_g_g") * kStandardGravity_mps2;
    } else {
      s.Missing("a_g", "pulse amplitude in m/s^2, or a_g_g in g");
    }
    // In m/s^2 after the conversion from g, which can overflow (a_g_g = 1e308).
    const std::string amplitude_key = s.Has("a_g") ? "a_g" : "a_g_g";
    if (!(std::abs(spec.amplitude_mps2) <= kMaxAcceleration_mps2)) {
      Fail(s.At(amplitude_key), s.Field(amplitude_key),
           "the amplitude is " + detail::Show(spec.amplitude_mps2) +
               " m/s^2; allowed: finite, at most 1e6 m/s^2 (about 1e5 g) in magnitude");
    }
    if (s.Has("w_g")) {
      s.Reject("T_g", "give either w_g (rad/s) or T_g (s), not both");
      spec.omega_radps = *s.Number("w_g");
      CheckPositive(spec.omega_radps, s.Field("w_g"), s.At("w_g"));
    } else if (s.Has("T_g")) {
      const double T_g = *s.Number("T_g");
      CheckPositive(T_g, s.Field("T_g"), s.At("T_g"));
      spec.omega_radps = 2.0 * std::numbers::pi / T_g;
    } else {
      s.Missing("w_g", "pulse frequency in rad/s, or T_g in s");
    }
    s.Finish(kExcitationKeys[0].second);
    return;
  }
  spec.kind = ExcitationSpec::Kind::kSampled;
  // The units vocabulary of every reader of accelerations (solver/common/units.h).
  AccelerationUnits units = AccelerationUnits::kMetresPerSecond2;
  if (const std::optional<std::string> name = s.String("units", {})) {
    const std::optional<AccelerationUnits> parsed = ParseAccelerationUnits(*name);
    if (!parsed) {
      Fail(s.At("units"), s.Field("units"),
           "unknown units \"" + *name + "\" (allowed: " + std::string(AllowedUnitsText()) + ")");
    }
    units = *parsed;
  }
  const double scale = s.Number("scale").value_or(1.0);
  if (!(std::abs(scale) <= kMaxScale)) {
    Fail(s.At("scale"), s.Field("scale"),
         "must be finite and at most 1e6 in magnitude (got " + detail::Show(scale) + ")");
  }
  spec.units = units;
  spec.scale = scale;
  spec.to_mps2 = ToMetresPerSecond2(units) * scale;
  if (const toml::node* bound = s.Get("max_pga_g")) {
    // A number > 0 in g, or inf: the user means the amplitudes as they are.
    const std::optional<double> value =
        bound->is_integer() ? std::optional<double>(static_cast<double>(*bound->value<int64_t>()))
                            : bound->value<double>();
    if (!value || !(*value > 0.0)) {
      Fail(s.At("max_pga_g"), s.Field("max_pga_g"),
           "must be a number > 0 (g), or inf for no bound");
    }
    spec.max_pga_g = *value;
  }
  if (const std::optional<double> dt = s.Number("dt_s")) {
    CheckPositive(*dt, s.Field("dt_s"), s.At("dt_s"));
    spec.dt_s = dt;
  }
  if (s.Has("file")) {
    s.Reject("values", "give either file or values, not both");
    const std::string file = *s.String("file", {});
    if (file.empty()) {
      Fail(s.At("file"), s.Field("file"), "must name a file");
    }
    const std::filesystem::path p(file);
    spec.file = p.is_absolute() ? p : base_dir / p;
  } else if (s.Has("values")) {
    const toml::node* node = s.Get("values");
    const toml::array* values = node->as_array();
    if (values == nullptr || values->empty()) {
      Fail(s.At("values"), s.Field("values"), "must be a non-empty array of numbers");
    }
    spec.values.clear();
    for (const toml::node& v : *values) {
      if (!v.is_number()) {
        Fail(Where{s.source(), LineOf(v)}, s.Field("values"),
             "must be a non-empty array of numbers");
      }
      const double a =
          v.is_integer() ? static_cast<double>(*v.value<int64_t>()) : *v.value<double>();
      CheckFinite(a, s.Field("values"), Where{s.source(), LineOf(v)});
      spec.values.push_back(a * spec.to_mps2);
    }
    if (!spec.dt_s) {
      s.Missing("dt_s", "sample interval in s, required with values");
    }
    double pga_mps2 = 0.0;
    for (double a : spec.values) pga_mps2 = std::max(pga_mps2, std::abs(a));
    spec.CheckPga(pga_mps2, s.source(), s.At("values").line, s.Field("values"));
  } else {
    s.Missing("file", "a two-column (time, acceleration) file, or inline values with dt_s");
  }
  s.Finish(kExcitationKeys[1].second);
}

void ReadRun(Section& s, RunControl& run) {
  if (const std::optional<double> v = s.Number("end_time_s")) {
    CheckPositive(*v, s.Field("end_time_s"), s.At("end_time_s"));
    run.end_time_s = v;
  }
  run.tail_s = s.Number("tail_s").value_or(run.tail_s);
  CheckNonNegative(run.tail_s, s.Field("tail_s"), s.At("tail_s"));
  run.output_interval_s = s.Number("output_interval_s").value_or(run.output_interval_s);
  CheckNonNegative(run.output_interval_s, s.Field("output_interval_s"), s.At("output_interval_s"));
  run.relative_tolerance = s.Number("rel_tol").value_or(run.relative_tolerance);
  CheckRange(run.relative_tolerance, 1e-15, 1e-2, false, s.Field("rel_tol"), s.At("rel_tol"));
  run.absolute_tolerance = s.Number("abs_tol").value_or(run.absolute_tolerance);
  CheckPositive(run.absolute_tolerance, s.Field("abs_tol"), s.At("abs_tol"));
  run.accumulation_threshold =
      s.Number("accumulation_threshold").value_or(run.accumulation_threshold);
  CheckRange(run.accumulation_threshold, 0.0, 1.0, true, s.Field("accumulation_threshold"),
             s.At("accumulation_threshold"));
  run.simultaneity_tolerance_s =
      s.Number("simultaneity_tol_s").value_or(run.simultaneity_tolerance_s);
  CheckNonNegative(run.simultaneity_tolerance_s, s.Field("simultaneity_tol_s"),
                   s.At("simultaneity_tol_s"));
  if (const auto method =
          s.String("method", {ToString(Method::kEventDriven), ToString(Method::kTimeStepping)})) {
    run.method = *ParseMethod(*method);
  }
  run.linear_algebra =
      s.String("linear_algebra", {"auto", "dense", "sparse"}).value_or(run.linear_algebra);
  run.time_step_s = s.Number("time_step_s").value_or(run.time_step_s);
  CheckPositive(run.time_step_s, s.Field("time_step_s"), s.At("time_step_s"));
  if (const std::optional<double> v = s.Number("max_steps")) {
    if (!(*v >= 1.0) || *v != std::floor(*v) || *v > 1e15) {
      Fail(s.At("max_steps"), s.Field("max_steps"),
           "must be a whole number >= 1 (got " + detail::Show(*v) + ")");
    }
    run.max_steps = static_cast<long>(*v);
  }
  s.Finish(
      "end_time_s, tail_s, output_interval_s, rel_tol, abs_tol, accumulation_threshold, "
      "simultaneity_tol_s, method, time_step_s, max_steps, linear_algebra");
}

void CheckRunLength(const ExcitationSpec& excitation, const RunControl& run,
                    std::string_view source) {
  const std::optional<double> duration = excitation.Duration();
  if (!run.end_time_s && !duration) {
    return;
  }
  const std::size_t samples = excitation.file.empty() ? excitation.values.size() : 0;
  CheckRunSize(run, duration.value_or(0.0), samples, source, "excitation");
}

}  // namespace detail
}  // namespace skewbridge::model
