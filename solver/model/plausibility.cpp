#include "solver/model/plausibility.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "solver/model/builders.h"

namespace skewbridge::model {

std::optional<std::string> WidthWarning(std::string_view field, std::string_view what,
                                        double width_m, double span_m) {
  if (!(width_m > kMaxGapOverSpan * span_m)) return std::nullopt;
  return fmt::format(
      "{}: a {} of {:.4g} m is more than a tenth of the {:.4g} m span: a width in millimetres "
      "typed as metres?",
      field, what, width_m, span_m);
}

std::optional<std::string> MassWarning(std::string_view field, double mass_kg, double span_m) {
  const double per_m = mass_kg / span_m;
  if (!(per_m < kMinMassPerSpan_kgpm)) return std::nullopt;
  return fmt::format(
      "{}: {:.4g} kg is {:.3g} kg per metre of the {:.4g} m span, below 1 t/m (road decks weigh "
      "10-30 t/m): a mass in tonnes typed as kg?",
      field, mass_kg, per_m, span_m);
}

std::optional<std::string> PeriodWarning(std::string_view what, double period_s) {
  if (period_s < kMinPeriod_s) {
    return fmt::format("{} is {:.3g} s, below {:g} s: a mass in tonnes typed as kg?", what,
                       period_s, kMinPeriod_s);
  }
  if (std::isinf(period_s)) {
    return fmt::format(
        "{} is infinite (a direction without stiffness; `skewbridge modes` lists the "
        "frequencies): a stiffness left out?",
        what);
  }
  if (period_s > kMaxPeriod_s) {
    return fmt::format("{} is {:.3g} s, above {:g} s: a stiffness in kN/m or MN/m typed as N/m?",
                       what, period_s, kMaxPeriod_s);
  }
  return std::nullopt;
}

std::optional<std::string> IntensityWarning(std::string_view field, double largest_g) {
  if (!(largest_g > kMaxIntensity_g)) return std::nullopt;
  return fmt::format(
      "{}: up to {:.4g} g, above {:g} g (beyond the strongest recorded motions): accelerations "
      "in m/s^2 or cm/s^2 typed as g?",
      field, largest_g, kMaxIntensity_g);
}

double FundamentalPeriod(const Model& model) {
  const double w1 = LowestFrequency(model);
  return w1 > 0.0 ? 2.0 * std::numbers::pi / w1 : std::numeric_limits<double>::infinity();
}

std::vector<std::string> PlausibilityWarnings(const ModelFile& file) {
  std::vector<std::string> out;
  const std::string& source = file.model.source();
  auto add = [&](std::optional<std::string> warning) {
    if (warning) out.push_back(source + ": " + *warning);
  };
  if (file.decks) {
    const MultiDeckSpec& m = *file.decks;
    const std::size_t n = m.decks.size();
    for (std::size_t i = 0; i < n; ++i) {
      add(MassWarning(fmt::format("deck[{}].m", i), m.decks[i].mass_kg,
                      m.decks[i].geometry.length_m));
    }
    // A gap against the shorter of the spans beside it.
    add(WidthWarning("abutments.gap_m (-x)", "gap", m.gap_minus_m,
                     m.decks.front().geometry.length_m));
    for (std::size_t i = 0; i + 1 < n && i < m.joints.size(); ++i) {
      add(WidthWarning(fmt::format("joint[{}].gap_m", i), "gap", m.joints[i].gap_m,
                       std::min(m.decks[i].geometry.length_m, m.decks[i + 1].geometry.length_m)));
    }
    add(WidthWarning("abutments.gap_m (+x)", "gap", m.gap_plus_m,
                     m.decks.back().geometry.length_m));
  } else {
    const DeckSpec& d = file.deck;
    const double span = d.geometry.length_m;
    add(MassWarning("deck.m", d.mass_kg, span));
    const bool both = d.abutments == AbutmentSet::kBoth;
    if (both && d.gap_minus_m != d.gap_plus_m) {
      add(WidthWarning("abutments.gap_m (-x)", "gap", d.gap_minus_m, span));
      add(WidthWarning("abutments.gap_m (+x)", "gap", d.gap_plus_m, span));
    } else {
      add(WidthWarning("abutments.gap_m", "gap", d.gap_plus_m, span));
    }
  }
  add(PeriodWarning("the fundamental period T1 of the model", FundamentalPeriod(file.model)));
  return out;
}

}  // namespace skewbridge::model
