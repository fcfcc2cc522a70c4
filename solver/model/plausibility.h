#pragma once
/// @file
/// Values that a bridge may have but that are far more often a unit slip: a gap or seat of
/// metres typed where millimetres were meant, a mass in tonnes typed as kilograms, a stiffness
/// in kN/m typed as N/m, accelerations in m/s^2 typed as g. Each check returns a warning (one
/// line naming the field, the value, the limit and the likely slip) or nothing; the program
/// prints the warnings and goes on (exit 0), since a bridge may be that unusual.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solver/model/model_file.h"

namespace skewbridge::model {

/// A gap or seat wider than this fraction of the span is warned of (1).
inline constexpr double kMaxGapOverSpan = 0.1;
/// A deck lighter than this per metre of span is warned of (kg/m): 1 t/m, a light footbridge;
/// road decks weigh 10-30 t/m.
inline constexpr double kMinMassPerSpan_kgpm = 1000.0;
/// Fundamental periods outside [kMinPeriod_s, kMaxPeriod_s] are warned of (s).
inline constexpr double kMinPeriod_s = 0.02;
inline constexpr double kMaxPeriod_s = 10.0;
/// Intensities (a spectral or peak ground acceleration) above this are warned of (g).
inline constexpr double kMaxIntensity_g = 5.0;

/// "FIELD: V m is more than a tenth of the L m span: a width in millimetres typed as metres?"
/// for a gap or seat width `width_m` above kMaxGapOverSpan x `span_m`; nothing otherwise.
/// @param what "gap" or "seat", as the message names it.
std::optional<std::string> WidthWarning(std::string_view field, std::string_view what,
                                        double width_m, double span_m);

/// "FIELD: M kg is K kg per metre of the L m span, below 1 t/m: a mass in tonnes typed as kg?"
/// for a deck lighter than kMinMassPerSpan_kgpm per metre; nothing otherwise.
std::optional<std::string> MassWarning(std::string_view field, double mass_kg, double span_m);

/// A fundamental period below kMinPeriod_s (a mass in tonnes typed as kg?) or above
/// kMaxPeriod_s (a stiffness in kN/m or MN/m typed as N/m?), named by `what` ("T1 of the
/// model"); nothing inside the range. An infinite period (a direction without stiffness) is
/// above the range.
std::optional<std::string> PeriodWarning(std::string_view what, double period_s);

/// "FIELD: up to X g, above 5 g: accelerations in m/s^2 (or cm/s^2) typed as g?" for an
/// intensity in g above kMaxIntensity_g; nothing otherwise.
std::optional<std::string> IntensityWarning(std::string_view field, double largest_g);

/// The fundamental period 2 pi / w_1 of a model without contacts (s), w_1 its lowest natural
/// frequency; +inf when w_1 = 0 (a direction without stiffness).
double FundamentalPeriod(const Model& model);

/// The warnings of a model file as written, each prefixed "FILE: ": every deck's mass per metre
/// of span, every abutment and joint gap against the spans beside it, and the fundamental
/// period of the model.
std::vector<std::string> PlausibilityWarnings(const ModelFile& file);

}  // namespace skewbridge::model
