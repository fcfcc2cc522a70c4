#pragma once
/// @file
/// The model file (TOML, docs/model-format.md): [deck], [substructure], [abutments],
/// [excitation], [run] for one deck, or [[deck]], [[joint]], [abutments], [[support]],
/// [excitation], [run] for several decks in a row (docs/multispan.md). The parser returns plain
/// data: the Model, an ExcitationSpec (turned into a records:: excitation by the program, since the
/// solver does not see records/) and the RunControl of the integrator.

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solver/common/units.h"
#include "solver/model/abutment_law.h"
#include "solver/model/builders.h"
#include "solver/model/model.h"
#include "solver/model/multispan.h"
#include "solver/model/run_control.h"

namespace skewbridge::model {

/// Standard gravity (m/s^2), for accelerations given in g.
inline constexpr double kStandardGravity_mps2 = skewbridge::kStandardGravity_mps2;

/// The ground motion a model file asks for, as pure data (SI units).
struct ExcitationSpec {
  enum class Kind { kPulse, kSampled };
  enum class PulseShape { kCosine, kSine };

  Kind kind = Kind::kPulse;
  /// Unit direction (x, y) of the ground motion (excitation.direction or angle_deg).
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();

  // kind = "pulse": one cycle of a_g cos(w_g t) or a_g sin(w_g t) [docs/theory.md §5].
  PulseShape shape = PulseShape::kCosine;
  double amplitude_mps2 = 0.0;  ///< a_g (m/s^2; the file may give a_g_g in g)
  double omega_radps = 0.0;     ///< w_g (rad/s; the file may give T_g = 2 pi / w_g in s)

  // kind = "sampled": from `file` (resolved against the model file's folder) or inline values.
  std::filesystem::path file;  ///< empty when the values are inline
  std::optional<double> dt_s;  ///< sample interval; empty = from the file's time column
  AccelerationUnits units = AccelerationUnits::kMetresPerSecond2;  ///< excitation.units
  double to_mps2 = 1.0;  ///< factor from the file's numbers to m/s^2 (units x scale)
  double scale = 1.0;    ///< excitation.scale
  /// excitation.max_pga_g: the samples' PGA in their units (before scale) may not exceed it (g).
  double max_pga_g = kMaxPlausiblePga_g;
  std::vector<double> values;  ///< inline samples, already multiplied by to_mps2

  /// Refuses samples whose PGA, read in `units` (before scale), is above max_pga_g: the
  /// accelerations are then in other units than stated. `pga_mps2` is the PGA after units and
  /// scale, as the samples are stored.
  /// @throws InputError "SOURCE[:LINE]: FIELD: PGA ... is above max_pga_g ...".
  void CheckPga(double pga_mps2, std::string_view source, long line, std::string_view field) const;

  /// Duration (s) of a pulse, 2 pi / w_g; for inline samples (n - 1) dt; for a file, empty
  /// (the program knows it after reading the file).
  std::optional<double> Duration() const;
};

/// A parsed model file.
struct ModelFile {
  std::filesystem::path path;  ///< the file read ("" for a string)
  DeckSpec deck;               ///< the single-deck description the model was built from
  Model model;
  ExcitationSpec excitation;
  RunControl run;
  std::optional<MultiDeckSpec> decks;  ///< the [[deck]] form's description (then `deck` unused)
  /// [abutments] law = "compliant": the springs that replace the abutments' contacts and, in a
  /// [[deck]] file, the deck-deck joints' (`model` keeps the contacts, whose faces carry the
  /// gaps; its eps_N and mu are unused). Empty for law = "impact", the default: `model` is then
  /// the whole joint law.
  std::optional<CompliantAbutments> compliant;
};

/// Reads and validates a model file.
/// @throws InputError "FILE:LINE: KEY: problem (allowed ...)" for a syntax error, an unknown or
/// missing key, a wrong type or a value outside its range; "FILE: cannot open" if unreadable.
ModelFile ParseModelFile(const std::filesystem::path& path);

/// Parses model-file text; `source_name` is used in messages and `base_dir` resolves relative
/// paths (excitation.file).
/// @throws InputError as ParseModelFile.
ModelFile ParseModelString(std::string_view text, std::string_view source_name,
                           const std::filesystem::path& base_dir = {});

/// Counts, in floating point so that nothing overflows, what a run asks for before it starts,
/// once its excitation's duration (s) and sample count (0 for a pulse) are known: the end time
/// (at most 1e6 s), the history samples (at most 1e7), the time steps of the time-stepping
/// method and, for the event-driven one, one step per sample interval, both against
/// run.max_steps. ParseModelFile applies it when the duration is known from the file itself;
/// the program applies it again after reading an excitation file, and a sweep for each cell.
/// @throws InputError "SOURCE: KEY: ..." naming run.end_time_s, run.output_interval_s,
/// run.time_step_s or `excitation_field`.
void CheckRunSize(const RunControl& run, double excitation_duration_s,
                  std::size_t excitation_samples, std::string_view source,
                  std::string_view excitation_field = "excitation");

/// What a model file's [deck] (or each [[deck]]) wrote, beyond the DeckSpec it gave: whether the
/// width came from eta0 and whether I_m was a number. A sweep that changes the skew angle needs
/// it to re-derive the deck the way the file defines it (W kept, or W = L sin 2a / (2 eta0)).
struct DeckAsWritten {
  std::optional<double> eta0;  ///< deck.eta0 when the file gives it (then W follows from it)
  bool inertia_given = false;  ///< deck.I_m is a number (else the uniform-deck rule)
};

/// DeckAsWritten of each deck of a model file that ParseModelFile accepted, in deck order (one
/// entry for the [deck] form).
/// @throws InputError "FILE: cannot open" if unreadable, or a syntax error.
std::vector<DeckAsWritten> DecksAsWritten(const std::filesystem::path& path);

}  // namespace skewbridge::model
