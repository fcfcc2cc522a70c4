#include "spectra/hazard_measure.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "solver/common/error.h"

namespace skewbridge::spectra {
namespace {

// The median ratios are taken as 1: the sources give the medians as equal (Baker and Cornell
// 2006) or within a few percent (Boore et al. 2006: GMRotI50 over the as-recorded geometric
// mean by less than 3 %; Boore 2010: RotD50 over GMRotI50 by a factor growing to about 1.07 at
// 10 s), and none of them a period-by-period ratio to the as-recorded single component.
constexpr std::array kConversions = {
    ComponentConversion{
        "geometric-mean-as-arbitrary", HorizontalComponent::kGeometricMean,
        HorizontalComponent::kArbitrary, 1.0,
        "levels kept: an arbitrary component has the median of the two components' geometric "
        "mean, with a larger dispersion (the component-to-component variability) that a hazard "
        "curve cannot take in, so the arbitrary component's hazard is higher at rare levels and "
        "the rate computed is low [Baker and Cornell 2006, Earthquake Spectra 22(2):293-312]"},
    ComponentConversion{
        "gmroti50-as-arbitrary", HorizontalComponent::kGmRotI50, HorizontalComponent::kArbitrary,
        1.0,
        "levels kept: GMRotI50 exceeds the as-recorded geometric mean by less than 3 % [Boore et "
        "al. 2006, BSSA 96(4A):1502-1511], whose median an arbitrary component shares, with a "
        "larger dispersion the curve cannot take in (the rate computed is low for it) [Baker and "
        "Cornell 2006, Earthquake Spectra 22(2):293-312]"},
    ComponentConversion{
        "rotd50-as-arbitrary", HorizontalComponent::kRotD50, HorizontalComponent::kArbitrary, 1.0,
        "levels kept: RotD50 is close to GMRotI50, larger by a factor growing to about 1.07 at "
        "10 s [Boore 2010, BSSA 100(4):1830-1835], which exceeds the as-recorded geometric mean "
        "by less than 3 % [Boore et al. 2006, BSSA 96(4A):1502-1511], whose median an arbitrary "
        "component shares, with a larger dispersion [Baker and Cornell 2006, Earthquake Spectra "
        "22(2):293-312]: the kept levels make the rate high by those few percent of IM, the "
        "missing dispersion makes it low at rare levels"},
};

std::string ConversionChoices() {
  std::string out;
  for (const ComponentConversion& c : kConversions) {
    out += (out.empty() ? "" : ", ") + std::string(c.name);
  }
  return out;
}

}  // namespace

std::span<const ComponentConversion> ComponentConversions() { return kConversions; }

MeasureMatch MatchMeasures(const IntensityMeasureId& hazard, const IntensityMeasureId& fragility,
                           double period_tolerance, std::string_view conversion) {
  const std::string both =
      fmt::format("hazard {} and fragility {}", hazard.Describe(), fragility.Describe());
  MeasureMatch m;
  const ComponentConversion* asked = nullptr;
  if (!conversion.empty()) {
    for (const ComponentConversion& c : kConversions) {
      if (c.name == conversion) asked = &c;
    }
    if (asked == nullptr) {
      throw InputError::AtField("--convert", conversion,
                                "unknown conversion (allowed: " + ConversionChoices() + ")");
    }
  }
  if (hazard.measure != fragility.measure) {
    throw InputError(both + ": different measures, and no conversion between measures is made");
  }
  if (hazard.measure == "SA") {
    if (std::abs(hazard.damping - fragility.damping) > kDampingTolerance) {
      throw InputError(both + ": different damping, and no damping scaling is made");
    }
    m.period_gap = std::abs(hazard.period_s - fragility.period_s) / fragility.period_s;
    if (m.period_gap > period_tolerance) {
      throw InputError(
          fmt::format("{}: periods {:.1f} % apart, beyond the tolerance of {:g} % "
                      "(--period-tolerance)",
                      both, 100.0 * m.period_gap, 100.0 * period_tolerance));
    }
    if (m.period_gap > 0.0) {
      m.notes.push_back(fmt::format(
          "the hazard's period {:g} s is {:.2f} % from the fragility's "
          "{:.4g} s (tolerance {:g} %)",
          hazard.period_s, 100.0 * m.period_gap, fragility.period_s, 100.0 * period_tolerance));
    }
  }
  if (hazard.component == HorizontalComponent::kUnknown) {
    throw InputError(both +
                     ": the hazard's horizontal component is not stated (--hazard-component "
                     "or a '# component = ...' line; allowed: " +
                     ComponentChoices() + ")");
  }
  if (hazard.component == fragility.component) {
    if (asked != nullptr) {
      throw InputError::AtField("--convert", conversion,
                                both + ": the components agree, no conversion applies");
    }
    return m;
  }
  if (asked == nullptr) {
    std::string offer;
    for (const ComponentConversion& c : kConversions) {
      if (c.from == hazard.component && c.to == fragility.component) {
        offer = fmt::format("; --convert {} reads one as the other", c.name);
      }
    }
    throw InputError(both + ": different horizontal components" +
                     (offer.empty() ? ", and no conversion between them is known" : offer));
  }
  if (asked->from != hazard.component || asked->to != fragility.component) {
    throw InputError::AtField(
        "--convert", conversion,
        fmt::format("{}: converts {} to {}, not the hazard's component to "
                    "the fragility's",
                    both, ComponentName(asked->from), ComponentName(asked->to)));
  }
  m.conversion = asked;
  m.im_factor = asked->median_ratio;
  m.notes.push_back(fmt::format("the hazard's {} read as {} (--convert {}): {}",
                                ComponentName(asked->from), ComponentName(asked->to), asked->name,
                                asked->source));
  return m;
}

}  // namespace skewbridge::spectra
