#pragma once
/// @file
/// The integrators' run settings (the [run] section of a model file, docs/model-format.md) as
/// plain data. The model-file parser fills them from TOML; the integrators in solver/dynamics read
/// them without seeing the parser.

#include <optional>
#include <string>
#include <string_view>

namespace skewbridge::model {

/// The integrator of a run (run.method).
enum class Method {
  kEventDriven,   ///< "event-driven": dynamics::Simulate, the reference
  kTimeStepping,  ///< "time-stepping": dynamics::SimulateTimeStepping, Moreau-Jean, the check
};

/// The spelling of `method` in run.method, sweep specs and stored files.
const char* ToString(Method method);

/// The method spelt `name` ("event-driven" or "time-stepping"), or nothing for another.
std::optional<Method> ParseMethod(std::string_view name);

/// Integration controls from the [run] section (the integrator defines their precise use).
struct RunControl {
  std::optional<double> end_time_s;        ///< run.end_time_s; empty = excitation + tail
  double tail_s = 2.0;                     ///< run.tail_s: free vibration after the excitation
  double output_interval_s = 0.0;          ///< run.output_interval_s; 0 = no histories
  double relative_tolerance = 1e-10;       ///< run.rel_tol of the adaptive steps
  double absolute_tolerance = 1e-12;       ///< run.abs_tol (state units)
  double accumulation_threshold = 1e-6;    ///< run.accumulation_threshold (scaled, see the format)
  double simultaneity_tolerance_s = 1e-9;  ///< run.simultaneity_tol_s for simultaneous impacts
  Method method = Method::kEventDriven;    ///< run.method: the integrator
  double time_step_s = 1e-4;               ///< run.time_step_s (time-stepping only)
  long max_steps = 10'000'000;             ///< run.max_steps
  /// run.linear_algebra: "auto" | "dense" | "sparse", the time-stepping integrator's
  /// factorisation and contact assembly (auto: sparse from kSparseThresholdDof DOFs on).
  std::string linear_algebra = "auto";
  /// Keep the energy ledger's input and damping work (RunResult::energy): the event-driven
  /// integrator then builds each free step's energy forms as well as its transition. Off, the
  /// responses are the same bits, and input_J, damping_J and balance_error_J are NaN. A sweep
  /// cell reads no energy and turns it off.
  bool energy_ledger = true;

  /// The end time (s): end_time_s if given, else excitation_duration_s + tail_s.
  double EndTime(double excitation_duration_s) const;
};

}  // namespace skewbridge::model
