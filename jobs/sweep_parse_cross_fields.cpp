#include <algorithm>
#include <array>

#include "jobs/sweep_parser.h"

namespace skewbridge::jobs {

void SpecParser::CheckCrossFields(const SweepSpec& spec) const {
  auto given = [&spec](std::string_view key) {
    return spec.FindAxis(key) != nullptr || spec.FindFixed(key) != nullptr;
  };
  if (spec.ida.enabled && !(spec.im.scale && !spec.im.measure.empty())) {
    throw InputError::AtField(source_, "ida",
                              "needs [records] scale_to = {measure = \"Sa\", period = \"T1\", "
                              "xi = 0.05} (or another measure): the intensity it scales to");
  }
  if (spec.ida.enabled && !spec.responses.empty()) {
    throw InputError::AtField(source_, "sweep.responses",
                              "not with [ida]: an IDA cell stores its search (the runs and the "
                              "capacities), not the responses of one run");
  }
  if (spec.im.exclude_beyond_max_scale && !spec.responses.empty() &&
      std::find(spec.responses.begin(), spec.responses.end(), "scaled_too_far") ==
          spec.responses.end()) {
    throw InputError::AtField(source_, "sweep.responses",
                              "records.beyond_max_scale = \"exclude\" needs the response "
                              "scaled_too_far in the list (the fits read it to leave cells out)");
  }
  if (spec.ida.enabled && spec.limit_states.empty()) {
    throw InputError::AtField(source_, "ida",
                              "needs [limit_states]: the search scales each record until they "
                              "are exceeded");
  }
  for (const Axis& axis : spec.axes) {
    if (spec.FindFixed(axis.key) != nullptr) {
      throw InputError::AtField(source_, "fixed." + axis.key, "is also an axis");
    }
  }
  if (given("eta0") && given("W_over_L")) {
    throw InputError::AtField(source_, "eta0",
                              "give eta0 or W_over_L, not both (eta0 = sin 2a / (2 W/L))");
  }
  static constexpr std::array<std::string_view, 5> kModelFileOnly{"w_g", "T_g", "scale", "gap_m",
                                                                  "k_factor"};
  if (spec.family != "model-file") {
    for (std::string_view key : kModelFileOnly) {
      if (given(key)) {
        throw InputError::AtField(source_, key,
                                  "only a parameter of family \"model-file\" (this sweep's "
                                  "family is \"" +
                                      spec.family + "\")");
      }
    }
  }
  if (given("w_g") && given("T_g")) {
    throw InputError::AtField(source_, "T_g", "give w_g or T_g, not both (T_g = 2 pi / w_g)");
  }
  if (given("gap_m") && given("Pi_delta")) {
    throw InputError::AtField(source_, "gap_m",
                              "give gap_m or Pi_delta, not both (the gap is Pi_delta L_e)");
  }
  if (given("seat_over_L") && given("seat_m")) {
    throw InputError::AtField(source_, "seat_m",
                              "give seat_over_L or seat_m, not both (the seat width is "
                              "seat_over_L L, or seat_m in metres)");
  }
  if (given("pulse") && given("record")) {
    throw InputError::AtField(source_, "record",
                              "give pulse or record, not both (one excitation per cell)");
  }
  if (given("record") && spec.record_set.empty() && spec.record_folder.empty() &&
      spec.synthetic_count == 0) {
    throw InputError::AtField(source_, "records.set",
                              "missing: a record axis or value needs [records] set = \"FILE\"");
  }
  CheckIntensityFields(spec, given);
}

// The intensity axis and [records] scale_to / im belong together (docs/sweep-format.md).
template <typename Given>
void SpecParser::CheckIntensityFields(const SweepSpec& spec, const Given& given) const {
  const spectra::IntensityMeasureSpec& im = spec.im;
  if (im.measure.empty()) {
    for (std::string_view key : {"im_g", "im_mps"}) {
      if (given(key)) {
        throw InputError::AtField(source_, key,
                                  "an intensity axis needs [records] scale_to = {measure = "
                                  "\"Sa\", period = \"T1\", xi = 0.05} (or another measure) "
                                  "to scale the records to it");
      }
    }
    return;
  }
  const std::string name = im.scale ? "records.scale_to" : "records.im";
  if (spec.family != "model-file") {
    throw InputError::AtField(
        source_, name,
        "only for family \"model-file\": in \"" + spec.family +
            "\" the gap is Pi_delta L_e of each record, so a scaled record gives the same "
            "dimensionless responses (self-similarity, docs/theory.md §4); give the bridge as "
            "a model file with gaps in metres");
  }
  if (!given("record")) {
    throw InputError::AtField(source_, name,
                              "needs records: a [records] set, folder or synthetic suite");
  }
  const std::string axis = im.AxisKey();
  const std::string other = axis == "im_g" ? "im_mps" : "im_g";
  if (given(other)) {
    throw InputError::AtField(source_, other,
                              "not the axis of " + im.measure + ": give " + axis + " (" +
                                  (axis == "im_g" ? "g" : "m/s") + ")");
  }
  if (im.scale && spec.ida.enabled) {
    // The hunt-and-fill search chooses each cell's intensities: no stripes to give.
    for (std::string_view key : {std::string_view(axis), std::string_view("scale")}) {
      if (given(key)) {
        throw InputError::AtField(source_, key,
                                  "not with [ida]: the hunt-and-fill search chooses each "
                                  "record's intensities (remove it, or remove [ida] for "
                                  "stripes)");
      }
    }
  } else if (im.scale) {
    if (!given(axis)) {
      throw InputError::AtField(source_, "axes." + axis,
                                "missing: records.scale_to needs an intensity axis " + axis +
                                    " = [...] (" + (axis == "im_g" ? "g" : "m/s") +
                                    "), the values each record is scaled to");
    }
    if (given("scale")) {
      throw InputError::AtField(source_, "scale",
                                "give scale or records.scale_to, not both (scale_to sets "
                                "each cell's factor)");
    }
  } else if (given(axis)) {
    throw InputError::AtField(source_, axis,
                              "records.im leaves the records unscaled (cloud); to scale them "
                              "to " +
                                  axis + " use records.scale_to");
  }
}

}  // namespace skewbridge::jobs
