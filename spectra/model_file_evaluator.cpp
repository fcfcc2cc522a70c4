#include "spectra/model_file_evaluator.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>

#include "records/excitations.h"
#include "solver/common/error.h"
#include "solver/dynamics/run.h"
#include "solver/model/builders.h"
#include "solver/model/deck.h"
#include "solver/model/multispan.h"
#include "solver/model/plausibility.h"

namespace skewbridge::spectra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegToRad = std::numbers::pi / 180.0;

// "a_deg = 20, Pi_delta = 0.5": the cell's coordinates, for messages.
std::string CellText(const CellGrid& spec, std::span<const std::size_t> index) {
  std::string text;
  for (std::size_t k = 0; k < spec.axes.size(); ++k) {
    const Axis& axis = spec.axes[k];
    text += (k ? ", " : "") + axis.key + " = " +
            (axis.kind == ParameterKind::kNumber ? fmt::format("{}", axis.values[index[k]])
                                                 : axis.labels[index[k]]);
  }
  return text;
}

// The keys a model-file sweep refuses, checked before the model file is read; then the file.
model::ModelFile CheckedModelFile(const CellGrid& spec) {
  const std::string& src = spec.source;
  // The model file gives the bridge: the subsystem's dimensionless deck and substructure keys
  // have no meaning here (a_deg, eta0, xi, k_factor change the file's values instead).
  for (std::string_view key :
       {"spans", "W_over_L", "delta_over_L", "L_over_Le", "W0_over_w0", "w0_over_wg"}) {
    if (Mentions(spec, key)) {
      throw InputError::AtField(src, key,
                                "not a parameter of family 'model-file' (the model file gives "
                                "the bridge; allowed: record, pulse, a_g_g, w_g, T_g, scale, "
                                "a_deg, eta0, xi, eps_N, mu, Pi_delta, gap_m, k_factor, "
                                "seat_over_L, seat_m, incidence_deg, method)");
    }
  }
  const bool by_record = Mentions(spec, "record");
  if (by_record) {
    for (std::string_view key : {"pulse", "a_g_g", "w_g", "T_g"}) {
      if (Mentions(spec, key)) {
        throw InputError::AtField(src, key,
                                  "not a parameter of a record-driven sweep (a_g and w_g are "
                                  "each record's PGA and 2 pi / T_m; scale multiplies it)");
      }
    }
  }
  model::ModelFile file = model::ParseModelFile(spec.model_path);
  if (file.compliant && !file.compliant->Mixed() && Mentions(spec, "eps_N")) {
    // The compliant springs have no restitution; their backwall friction is the sweep's mu.
    throw InputError(KeyWhere(spec, "eps_N") + ": the abutments of " + spec.model_file +
                     " are compliant (law = \"compliant\"), whose springs have no restitution; "
                     "remove eps_N (mu, the backwall friction, and every other key of family "
                     "'model-file' are allowed)");
  }
  return file;
}

}  // namespace

struct ModelFileEvaluator::CellValues {
  const ModelFileCell& cell;
  const dynamics::RunResult& run;
  const dynamics::LawRun& law;  ///< the run with, if compliant, its joints' maxima
  double to_norm = 0.0;         ///< 1 / L_e (1/m)
  double t1_s = 0.0;            ///< the cell's fundamental period (with an intensity measure)
  double own_im = 0.0;          ///< the record's own intensity at it (axis unit)

  /// max |q| of deck d (m, m, rad).
  Eigen::Vector3d MaxOf(int d) const { return run.max_abs_q.segment<3>(3 * d); }
  /// q of deck d at the end of the run.
  Eigen::Vector3d EndOf(int d) const { return run.q_end.segment<3>(3 * d); }
  /// The radius of gyration of deck d (m).
  double RhoOf(int d) const {
    const model::Body& deck = cell.model->body(d);
    return std::sqrt(deck.inertia_kgm2 / deck.mass_kg);
  }
  /// theta_norm of deck d: max |theta| rho / L_e.
  double ThetaNormOf(int d) const { return MaxOf(d)(2) * RhoOf(d) * to_norm; }
};

std::uint64_t ModelFileEvaluator::CellIndex(std::span<const std::size_t> index) const {
  std::uint64_t cell = 0;
  for (std::size_t k = 0; k < spec_.axes.size(); ++k) cell = cell * spec_.axes[k].Size() + index[k];
  return cell;
}

std::size_t ModelFileEvaluator::RecordIndex(std::span<const std::size_t> index) const {
  for (std::size_t k = 0; k < spec_.axes.size(); ++k) {
    if (spec_.axes[k].key == "record") return index[k];
  }
  return 0;  // a fixed record: the one loaded
}

ModelFileEvaluator::ModelFileEvaluator(const CellGrid& spec)
    : CellEvaluator(spec.policies), spec_(spec), file_(CheckedModelFile(spec)), shared_(spec) {
  const std::string& src = spec.source;
  const bool by_record = Mentions(spec, "record");
  written_ = model::DecksAsWritten(spec.model_path);
  n_decks_ = file_.model.n_bodies();
  const model::ExcitationSpec& ex = file_.excitation;
  const bool by_pulse = Mentions(spec, "pulse") || Mentions(spec, "a_g_g") ||
                        Mentions(spec, "w_g") || Mentions(spec, "T_g");
  if (!by_record && ex.kind == model::ExcitationSpec::Kind::kSampled) {
    if (by_pulse &&
        !(Mentions(spec, "a_g_g") && (Mentions(spec, "w_g") || Mentions(spec, "T_g")))) {
      throw InputError::AtField(src, Mentions(spec, "a_g_g") ? "w_g" : "a_g_g",
                                "missing: the model file's excitation is sampled, so a pulse "
                                "needs a_g_g and w_g or T_g");
    }
    if (!by_pulse) {
      // The file's samples, read once as `skewbridge run` reads them, and their measures.
      if (ex.file.empty()) {
        samples_mps2_ = ex.values;
        samples_dt_s_ = *ex.dt_s;
      } else {
        records::ExcitationSamples samples =
            records::ReadExcitationSamples(ex.file, ex.dt_s, ex.to_mps2);
        samples_mps2_ = std::move(samples.values_mps2);
        samples_dt_s_ = samples.dt_s;
        double pga_mps2 = 0.0;
        for (double a : samples_mps2_) pga_mps2 = std::max(pga_mps2, std::abs(a));
        ex.CheckPga(pga_mps2, spec.model_path.string(), 0,
                    "excitation.file (" + ex.file.string() + ")");
      }
      records::GroundMotion motion;
      motion.file = ex.file.empty() ? spec.model_path.string() : ex.file.string();
      motion.dt_s = samples_dt_s_;
      motion.acc_mps2 = samples_mps2_;
      try {
        samples_measures_ = records::ComputeMeasures(motion);
      } catch (const InputError& e) {
        // Samples without a mean period (no content in its band) have no L_e: only a sweep
        // that needs it (Pi_delta) is refused; the scales are then NaN.
        if (Mentions(spec, "Pi_delta")) {
          throw InputError::AtField(src, "Pi_delta",
                                    std::string("needs L_e of the model file's samples, which "
                                                "have none: ") +
                                        e.what());
        }
        records::IntensityMeasures none;
        none.pga_mps2 = none.omega_g_radps = none.persistency_m = kNaN;
        samples_measures_ = none;
      }
    }
  }
  if (Mentions(spec, "xi")) {
    if (!file_.decks && file_.deck.C) {
      throw InputError::AtField(src, "xi",
                                "the model file gives substructure.C, so there is no xi to "
                                "change; remove xi or the file's C");
    }
    if (file_.decks) {
      for (const model::SupportSpec& s : file_.decks->supports) {
        if (s.other == model::kGround && s.damping) {
          throw InputError::AtField(src, "xi",
                                    "a [[support]] of the model file gives c_x, c_y, c_theta, so "
                                    "there is no xi to change; give xi there instead");
        }
      }
    }
  }
  seats_ = MentionsSeat(spec) || (file_.decks && file_.decks->seat_width_m);
  travel_ = !spec.limit_states.empty();
  // Cells under a record run as stripes of it (dynamics::RunScaledRecord) unless a gap follows
  // the factor (Pi_delta); they share one trace when the factor is the stripe's (scale_to).
  stripes_ = by_record && !Mentions(spec, "Pi_delta");
  if (stripes_ && spec.im.scale) {
    for (std::size_t k = 0; k < spec.axes.size(); ++k) {
      if (spec.axes[k].key == spec.im.AxisKey() && spec.axes[k].Size() > 1) stripe_axis_ = k;
    }
  }
  if (stripe_axis_) {
    for (std::size_t k = *stripe_axis_ + 1; k < spec.axes.size(); ++k) {
      if (!LimitOnlyAxis(spec.axes[k].key)) stripe_capacity_ *= spec.axes[k].Size();
    }
  }
  // A run's seat widths, or a record's stripes, differ only along the axes from the first
  // shared one on: a block of the cube from there to the last axis holds every cell of theirs.
  std::uint64_t block = 1;
  for (std::size_t k = spec.axes.size(); k-- > 0;) {
    block *= spec.axes[k].Size();
    if ((stripe_axis_ && k == *stripe_axis_) || LimitOnlyAxis(spec.axes[k].key)) {
      work_block_ = block;
    }
  }
  MakeResponseTable();
  if (by_record) records_ = LoadSweepRecords(spec);
  // Every cell's model is built and its run counted now, so a bad combination or a run that
  // `skewbridge run` would refuse (a pulse period of 1e7 s) fails before the file is touched;
  // with records, each cell's fundamental period is kept (a few distinct values: the axes that
  // change the modes are a_deg, eta0 and k_factor).
  const bool with_t1 = by_record;
  if (with_t1) t1_of_cell_.resize(spec.CellCount());
  // The fundamental periods outside the plausible range: how many cells, and the first.
  std::uint64_t implausible_t1 = 0;
  std::string first_implausible_t1;
  // Cells that differ only along the stripe axis (it sets the factor alone) or a limit-only
  // axis have one model, one run control and one record: the first of them, in cube order,
  // is checked and its T1 holds for the others.
  std::vector<std::uint8_t> same_model(spec.axes.size(), 0);
  for (std::size_t k = 0; k < spec.axes.size(); ++k) {
    same_model[k] = (stripe_axis_ && k == *stripe_axis_) || LimitOnlyAxis(spec.axes[k].key);
  }
  // Key: the cell with those axes at 0; value: its T1 and the index of T1 in t1_values_s_.
  std::unordered_map<std::uint64_t, std::pair<double, std::uint32_t>> checked_t1;
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    const std::vector<std::size_t> index = spec.AxisIndex(cell);
    std::uint64_t key = 0;
    for (std::size_t k = 0; k < spec.axes.size(); ++k) {
      key = key * spec.axes[k].Size() + (same_model[k] ? 0 : index[k]);
    }
    if (const auto seen = checked_t1.find(key); seen != checked_t1.end()) {
      const auto [t1, t1_index] = seen->second;
      if (t1 < model::kMinPeriod_s || t1 > model::kMaxPeriod_s) ++implausible_t1;
      if (with_t1) t1_of_cell_[cell] = t1_index;
      continue;
    }
    const ModelFileCell c = MakeCell(index, false);
    if (c.compliant && c.control.method != model::Method::kEventDriven) {
      throw InputError::AtField(src, "method",
                                "the model file's abutments are compliant (law = \"compliant\"), "
                                "which runs with the event-driven method only (cell " +
                                    CellText(spec, index) + ")");
    }
    try {
      model::CheckRunSize(
          c.control, c.excitation_duration_s, c.excitation_samples, spec.model_path.string(),
          by_record                                                    ? "record"
          : by_pulse || ex.kind == model::ExcitationSpec::Kind::kPulse ? "excitation"
                                                                       : "excitation.file");
    } catch (const InputError& e) {
      throw InputError(src + ": cell " + CellText(spec, index) + ": " + e.what());
    }
    const double t1 = model::FundamentalPeriod(*c.model);
    if (t1 < model::kMinPeriod_s || t1 > model::kMaxPeriod_s) {
      if (implausible_t1++ == 0) {
        first_implausible_t1 =
            model::PeriodWarning(
                "the fundamental period T1 of the cell (" + CellText(spec, index) + ")", t1)
                .value_or("");
      }
    }
    if (!with_t1) {
      checked_t1.emplace(key, std::pair<double, std::uint32_t>(t1, 0));
      continue;
    }
    auto it = std::find(t1_values_s_.begin(), t1_values_s_.end(), t1);
    if (it == t1_values_s_.end()) it = t1_values_s_.insert(t1_values_s_.end(), t1);
    t1_of_cell_[cell] = static_cast<std::uint32_t>(it - t1_values_s_.begin());
    checked_t1.emplace(key, std::pair<double, std::uint32_t>(t1, t1_of_cell_[cell]));
  }
  warnings_ = BridgeWarnings();
  if (implausible_t1 > 0) {
    warnings_.push_back(
        spec.model_path.string() + ": " + first_implausible_t1 +
        (implausible_t1 > 1
             ? fmt::format(" ({} of {} cells lie outside {:g}-{:g} s)", implausible_t1,
                           spec.CellCount(), model::kMinPeriod_s, model::kMaxPeriod_s)
             : ""));
  }
  if (!with_t1) return;

  // The records' spectral measures at T1 for the record table, when T1 is one for the sweep.
  const IntensityMeasureSpec& im = spec.im;
  if (t1_values_s_.size() == 1 && std::isfinite(t1_values_s_[0])) {
    for (SweepRecord& r : records_) {
      SetSpectralMeasuresAtT1(r, t1_values_s_[0], im.measure.empty() ? 0.05 : im.xi);
    }
  }
  if (im.measure.empty()) return;

  // Each record's measure once per distinct T1 (once when the period is given in s).
  const std::string field = im.scale ? "records.scale_to" : "records.im";
  if (im.at_t1) {
    for (const double t1 : t1_values_s_) {
      if (!std::isfinite(t1)) {
        throw InputError::AtField(src, field + ".period",
                                  "\"T1\" needs a model with stiffness in every direction: a "
                                  "cell's lowest natural frequency is 0 (see `skewbridge modes`)");
      }
    }
  }
  const std::size_t n_t1 = t1_values_s_.size();
  record_im_.resize(records_.size() * n_t1);
  const bool per_t1 = im.at_t1 && im.Spectral();
  for (std::size_t r = 0; r < records_.size(); ++r) {
    for (std::size_t t = 0; t < n_t1; ++t) {
      const SweepRecord& record = records_[r];
      // One T1: RecordIntensity takes the record table's values at T1 (same calls, computed
      // once by SetSpectralMeasuresAtT1).
      record_im_[r * n_t1 + t] =
          per_t1 || t == 0 ? RecordIntensity(record, im, t1_values_s_[t]) : record_im_[r * n_t1];
    }
  }
  // With [ida] the search chooses each run's factor: no stripes.
  if (!im.scale || spec.ida.enabled) return;

  // The scale factor of each cell: the stripe's value over the record's own measure.
  scale_of_cell_.resize(spec.CellCount());
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    const std::vector<std::size_t> index = spec.AxisIndex(cell);
    const std::size_t r = RecordIndex(index);
    const double own = record_im_[r * n_t1 + t1_of_cell_[cell]];
    if (!(own > 0.0) || !std::isfinite(own)) {
      throw InputError::AtField(src, field,
                                fmt::format("record '{}' has {} = {} {} at T1 = {} s: it cannot be "
                                            "scaled to a value",
                                            records_[r].label, im.measure, own, IntensityUnit(im),
                                            t1_values_s_[t1_of_cell_[cell]]));
    }
    const double factor = NumberOf(spec, index, im.AxisKey(), 0.0) / own;
    scale_of_cell_[cell] = factor;
    if (im.max_scale > 0.0 && factor > im.max_scale) ++scaled_too_far_;
  }
}

std::optional<CellScaling> ModelFileEvaluator::Scaling(
    std::span<const std::size_t> axis_index) const {
  if (scale_of_cell_.empty()) return std::nullopt;
  const std::uint64_t cell = CellIndex(axis_index);
  const std::size_t t = t1_of_cell_[cell];
  CellScaling s;
  s.t1_s = t1_values_s_[t];
  s.unscaled = record_im_[RecordIndex(axis_index) * t1_values_s_.size() + t];
  s.factor = scale_of_cell_[cell];
  s.target = NumberOf(spec_, axis_index, spec_.im.AxisKey(), 0.0);
  s.too_far = spec_.im.max_scale > 0.0 && s.factor > spec_.im.max_scale;
  return s;
}

records::SampledExcitation ScaledRecordExcitation(const records::GroundMotion& motion,
                                                  double factor, const Eigen::Vector2d& direction) {
  return records::ScaledExcitation(motion, factor, direction);
}

records::SampledExcitation ScaledPairExcitation(const records::GroundMotion& h1,
                                                const records::GroundMotion& h2, double factor,
                                                double incidence_deg) {
  return records::PairExcitation(h1, h2, incidence_deg, factor);
}

std::shared_ptr<const records::PeakPieces> ModelFileEvaluator::RecordPeakPieces(
    const SweepRecord& record) const {
  return peak_pieces_.Get(records_, record, policies().event.ramp_horizon_s);
}

ModelFileCell ModelFileEvaluator::MakeCell(std::span<const std::size_t> index, bool with_excitation,
                                           std::optional<double> factor) const {
  const std::string& src = spec_.source;
  const std::string model_source = spec_.model_path.string();
  const model::ExcitationSpec& ex = file_.excitation;
  ModelFileCell c;
  c.compliant = file_.compliant;
  c.control = file_.run;
  // A cell stores maxima, not histories nor the energy ledger (the maxima are the same bits).
  c.control.energy_ledger = false;
  c.control.output_interval_s = 0.0;
  c.control.method = MethodOf(spec_, index, file_.run.method);
  c.scale = NumberOf(spec_, index, "scale", 1.0);
  if (!scale_of_cell_.empty()) c.scale = scale_of_cell_[CellIndex(index)];
  if (factor) c.scale = *factor;

  // The excitation and its scales a_g, w_g, L_e [docs/theory.md §5], along the file's
  // direction or, with incidence_deg, along that angle from the bridge's x axis.
  bool turned = false;
  const double incidence_deg = NumberOf(spec_, index, "incidence_deg", 0.0, &turned);
  const Eigen::Vector2d direction = turned ? records::DirectionAt(incidence_deg) : ex.direction;
  const std::string label = LabelOf(spec_, index, "record");
  if (!label.empty()) {
    for (const SweepRecord& r : records_) {
      if (r.label == label) c.record = &r;
    }
    SB_DEMAND(c.record != nullptr, "a record label of the axis is not among the loaded records");
    c.a_g_mps2 = c.record->measures.pga_mps2 * c.scale;
    c.w_g_radps = c.record->measures.omega_g_radps;
    c.persistency_m = c.record->measures.persistency_m * c.scale;
    c.excitation_samples = c.record->motion.npts();
    c.excitation_duration_s = c.record->motion.dt_s * static_cast<double>(c.excitation_samples - 1);
    if (with_excitation) {
      c.excitation = std::make_unique<records::SampledExcitation>(
          c.record->IsPair()
              ? records::PairExcitation(c.record->motion, *c.record->motion_h2, direction, c.scale)
              : records::ScaledExcitation(c.record->motion, c.scale, direction,
                                          RecordPeakPieces(*c.record)));
    }
  } else if (samples_measures_) {
    c.a_g_mps2 = samples_measures_->pga_mps2 * c.scale;
    c.w_g_radps = samples_measures_->omega_g_radps;
    c.persistency_m = samples_measures_->persistency_m * c.scale;
    c.excitation_samples = samples_mps2_.size();
    c.excitation_duration_s = samples_dt_s_ * static_cast<double>(c.excitation_samples - 1);
    if (with_excitation) {
      // As `skewbridge run` makes it: the samples times the direction, both components.
      std::vector<double> ax(samples_mps2_.size()), ay(samples_mps2_.size());
      for (std::size_t i = 0; i < samples_mps2_.size(); ++i) {
        const double v = c.scale == 1.0 ? samples_mps2_[i] : samples_mps2_[i] * c.scale;
        ax[i] = v * direction.x();
        ay[i] = v * direction.y();
      }
      c.excitation =
          std::make_unique<records::SampledExcitation>(samples_dt_s_, std::move(ax), std::move(ay));
    }
  } else {
    const bool file_pulse = ex.kind == model::ExcitationSpec::Kind::kPulse;
    const std::string shape = LabelOf(spec_, index, "pulse");
    const bool sine = shape.empty()
                          ? file_pulse && ex.shape == model::ExcitationSpec::PulseShape::kSine
                          : shape == "sine";
    bool given = false;
    const double a_g_g = NumberOf(spec_, index, "a_g_g", 0.0, &given);
    c.a_g_mps2 = given ? a_g_g * model::kStandardGravity_mps2 : ex.amplitude_mps2;
    c.a_g_mps2 *= c.scale;
    const double w_g = NumberOf(spec_, index, "w_g", 0.0, &given);
    c.w_g_radps = given ? w_g : ex.omega_radps;
    const double T_g = NumberOf(spec_, index, "T_g", 0.0, &given);
    if (given) c.w_g_radps = 2.0 * std::numbers::pi / T_g;
    c.persistency_m = std::abs(c.a_g_mps2) / (c.w_g_radps * c.w_g_radps);
    c.excitation_duration_s = 2.0 * std::numbers::pi / c.w_g_radps;
    if (with_excitation) {
      c.excitation = std::make_unique<records::PulseExcitation>(
          sine ? records::PulseShape::kSine : records::PulseShape::kCosine, c.a_g_mps2, c.w_g_radps,
          direction);
    }
  }

  // The gaps: Pi_delta L_e of this cell's excitation, or metres; every joint and abutment.
  bool has_Pi = false, has_gap = false;
  const double Pi_delta = NumberOf(spec_, index, "Pi_delta", 0.0, &has_Pi);
  const double gap_m = NumberOf(spec_, index, "gap_m", 0.0, &has_gap);
  const bool set_gaps = has_Pi || has_gap;
  const double gap = has_Pi ? Pi_delta * c.persistency_m : gap_m;
  bool has_eps = false, has_mu = false, has_xi = false, has_a = false, has_eta0 = false,
       has_seat = false;
  const double eps_N = NumberOf(spec_, index, "eps_N", 0.0, &has_eps);
  const double mu = NumberOf(spec_, index, "mu", 0.0, &has_mu);
  const double xi = NumberOf(spec_, index, "xi", 0.0, &has_xi);
  const double a_deg = NumberOf(spec_, index, "a_deg", 0.0, &has_a);
  const double eta0 = NumberOf(spec_, index, "eta0", 0.0, &has_eta0);
  const double k_factor = NumberOf(spec_, index, "k_factor", 1.0);
  // seat_over_L scales with each deck's length; seat_m is the same for every deck.
  has_seat = MentionsSeat(spec_);
  const auto seat_of = [&](double length_m) { return SeatWidthOf(spec_, index, length_m); };

  // The deck re-derived as the file defines it: L kept, W kept or from eta0 at the new angle;
  // a uniform deck's I_m follows its geometry.
  auto reshape = [&](model::DeckGeometry& g, const model::DeckAsWritten& written) {
    if (has_a) g.skew_rad = a_deg * kDegToRad;
    const std::optional<double> ratio = has_eta0 ? std::optional<double>(eta0) : written.eta0;
    if ((has_a || has_eta0) && ratio) {
      if (!(g.skew_rad > 0.0)) {
        throw InputError::AtField(src, has_eta0 ? "eta0" : "a_deg",
                                  "needs a skew angle > 0 (the deck's W = L sin 2a / (2 eta0) " +
                                      std::string(has_eta0 ? "" : "of " + model_source) +
                                      " is 0 at a = 0); cell " + CellText(spec_, index));
      }
      g.width_m = model::WidthFromEta0(*ratio, g.skew_rad, g.length_m);
    }
  };

  try {
    if (!file_.decks) {
      model::DeckSpec d = file_.deck;
      reshape(d.geometry, written_.front());
      if (set_gaps) d.gap_plus_m = d.gap_minus_m = gap;
      for (model::ContactOverride& o : d.overrides) {
        if (has_eps) o.restitution.reset();
        if (has_mu) o.friction.reset();
      }
      if (has_eps) d.restitution = eps_N;
      // Compliant abutments: mu is the backwall friction (the contacts' mu is unused); with a law
      // per abutment, the rigid wall's corners' and the compliant wall's alike.
      if (has_mu && c.compliant) c.compliant->SetWallFriction(mu);
      if (has_mu && (!c.compliant || c.compliant->Mixed())) d.friction = mu;
      if (has_xi) d.xi = xi;
      c.model = model::BuildDeckModel(d, model_source);
      if (k_factor != 1.0) {
        // The stiffness the file describes (any kind), scaled; C from xi follows it.
        model::DeckSpec scaled = d;
        scaled.stiffness = model::DeckSpec::StiffnessKind::kMatrix;
        scaled.K = c.model->K() * k_factor;
        c.model = model::BuildDeckModel(scaled, model_source);
      }
      c.gap_m = d.gap_plus_m;
      if (has_seat) c.seat_width_m = {seat_of(d.geometry.length_m)};
    } else {
      model::MultiDeckSpec m = *file_.decks;
      for (std::size_t i = 0; i < m.decks.size(); ++i) {
        model::Body& b = m.decks[i];
        reshape(b.geometry, written_[i]);
        if (!written_[i].inertia_given) {
          b.inertia_kgm2 = model::UniformDeckInertia(b.mass_kg, b.geometry);
        }
      }
      if (set_gaps) {
        m.gap_plus_m = m.gap_minus_m = gap;
        for (model::JointSpec& j : m.joints) j.gap_m = gap;
      }
      if (has_eps) {
        m.restitution = eps_N;
        for (model::JointSpec& j : m.joints) j.restitution = eps_N;
      }
      // Compliant joints: mu is the backwalls' friction (the joints' springs carry none); with
      // rigid parts beside them (a mixed row), the rigid corners' friction too.
      if (has_mu && c.compliant) c.compliant->SetWallFriction(mu);
      if (has_mu && (!c.compliant || c.compliant->Mixed())) {
        m.friction = mu;
        for (model::JointSpec& j : m.joints) j.friction = mu;
      }
      for (model::SupportSpec& s : m.supports) {
        if (has_xi && s.other == model::kGround) s.xi = xi;
        s.stiffness *= k_factor;
      }
      c.model = model::BuildMultiDeckModel(m, model_source);
      c.gap_m = m.gap_plus_m;
      for (const model::Body& b : m.decks) {
        if (has_seat) {
          c.seat_width_m.push_back(seat_of(b.geometry.length_m));
        } else if (m.seat_width_m) {
          c.seat_width_m.push_back(*m.seat_width_m);
        }
      }
    }
  } catch (const InputError& e) {
    throw InputError(src + ": cell " + CellText(spec_, index) + ": " + e.what());
  }
  return c;
}

void ModelFileEvaluator::MakeResponseTable() {
  using V = const CellValues&;
  ResponseTable<CellValues>& t = table_;
  // Per deck (suffix _d<i>): the run's maxima, residuals and margins (NaN for a failed cell).
  for (int d = 0; d < n_decks_; ++d) {
    const std::string s = "_d" + std::to_string(d);
    const std::string of = " of deck " + std::to_string(d);
    t.Add({"x_m" + s, "m", "maximum |x|" + of + ", relative to the ground"},
          [d](V v) { return v.MaxOf(d)(0); });
    t.Add({"y_m" + s, "m", "maximum |y|" + of}, [d](V v) { return v.MaxOf(d)(1); });
    t.Add({"theta_m" + s, "rad", "maximum |theta|" + of}, [d](V v) { return v.MaxOf(d)(2); });
    t.Add({"x_end" + s, "m", "residual x" + of + " at the end of the run"},
          [d](V v) { return v.EndOf(d)(0); });
    t.Add({"y_end" + s, "m", "residual y" + of}, [d](V v) { return v.EndOf(d)(1); });
    t.Add({"theta_end" + s, "rad", "residual theta" + of}, [d](V v) { return v.EndOf(d)(2); });
    t.Add({"x_norm" + s, "1", "x_m / L_e" + of}, [d](V v) { return v.MaxOf(d)(0) * v.to_norm; });
    t.Add({"y_norm" + s, "1", "y_m / L_e" + of}, [d](V v) { return v.MaxOf(d)(1) * v.to_norm; });
    t.Add({"theta_norm" + s, "1", "theta_m rho / L_e" + of + ", rho its radius of gyration"},
          [d](V v) { return v.ThetaNormOf(d); });
    t.Add({"theta_end_norm" + s, "1", "theta_end rho / L_e" + of},
          [d](V v) { return v.EndOf(d)(2) * v.RhoOf(d) * v.to_norm; });
    if (seats_) {
      const auto margin = [d](V v) {
        return v.cell.seat_width_m[static_cast<std::size_t>(d)] - v.run.max_travel_m(d);
      };
      t.Add({"margin_m" + s, "m",
             "unseating margin" + of +
                 ": seat width - largest corner travel normal to the end line (travel_m)"},
            margin);
      t.Add({"margin_norm" + s, "1", "margin_m / L_e" + of},
            [margin](V v) { return margin(v) * v.to_norm; });
    }
    if (travel_) {
      t.Add({"travel_m" + s, "m",
             "largest corner travel" + of +
                 " normal to its end line over the run, exact (seat width - margin_m)"},
            [d](V v) { return v.run.max_travel_m(d); });
      t.Add({"travel_end_m" + s, "m",
             "residual corner travel" + of + " normal to its end line at the end (exact)"},
            [d](V v) { return model::CornerTravelAt(v.cell.model->body(d).geometry, v.EndOf(d)); });
      t.Add({"travel_bound_m" + s, "m",
             "upper bound of travel_m" + of +
                 " from the maxima of x, y and theta, each at its own time"},
            [d](V v) {
              return model::CornerTravelBound(v.cell.model->body(d).geometry, v.MaxOf(d));
            });
    }
  }
  // The cell: the run's counts, then its excitation and gaps (stored whatever the run did).
  t.Add({"theta_norm_max", "1", "largest theta_norm over the decks"}, [n = n_decks_](V v) {
    double theta_max = 0.0;
    for (int d = 0; d < n; ++d) theta_max = std::max(theta_max, v.ThetaNormOf(d));
    return theta_max;
  });
  t.Add({"impacts", "1", "number of impact events (a multi-contact impact counts once)"},
        [](V v) { return static_cast<double>(v.run.impacts); });
  t.Add({"min_impact_separation", "s",
         "smallest time between distinct impact instants (inf with fewer than two)"},
        [](V v) { return v.run.min_impact_separation_s; });
  if (file_.compliant) {
    // Per compliant wall, per deck-deck joint, then per abutment's shear keys
    // (dynamics::JointResponses).
    const bool both = file_.decks || file_.deck.abutments == model::AbutmentSet::kBoth;
    for (dynamics::JointResponse& r : dynamics::JointResponses(*file_.compliant, both)) {
      t.Add({r.name, r.unit, r.meaning}, [f = std::move(r.value)](V v) { return f(v.law); });
    }
  }
  t.AddAlways({"a_g", "m/s^2", "excitation amplitude: pulse a_g, or the record's PGA, x scale"},
              [](V v) { return v.cell.a_g_mps2; });
  t.AddAlways({"w_g", "rad/s", "excitation frequency: pulse w_g, or 2 pi / T_m of the record"},
              [](V v) { return v.cell.w_g_radps; });
  t.AddAlways({"L_e", "m", "persistency |a_g| / w_g^2"}, [](V v) { return v.cell.persistency_m; });
  t.AddAlways({"delta", "m", "gap of the +x abutment along x (Pi_delta L_e, gap_m or the file's)"},
              [](V v) { return v.cell.gap_m; });
  if (Mentions(spec_, "record")) {
    // The record's measures, of the excitation applied (record x scale).
    const auto measures = [](V v) -> const records::IntensityMeasures& {
      return v.cell.record->measures;
    };
    t.AddAlways({"pga", "m/s^2", "PGA of the record x scale"},
                [measures](V v) { return measures(v).pga_mps2 * v.cell.scale; });
    t.AddAlways({"pgv", "m/s", "PGV of the record x scale (no baseline correction)"},
                [measures](V v) { return measures(v).pgv_mps * v.cell.scale; });
    t.AddAlways({"pgd", "m", "PGD of the record x scale (no baseline correction)"},
                [measures](V v) { return measures(v).pgd_m * v.cell.scale; });
    t.AddAlways({"T_m", "s", "mean period of the record [Rathje et al. 1998]"},
                [measures](V v) { return measures(v).mean_period_s; });
    t.AddAlways({"arias", "m/s", "Arias intensity of the record x scale^2"},
                [measures](V v) { return measures(v).arias_mps * v.cell.scale * v.cell.scale; });
    t.AddAlways({"D5_95", "s", "significant duration D5-95 of the record"},
                [measures](V v) { return measures(v).significant_duration_s; });
  }
  if (!spec_.im.measure.empty()) {
    const std::string unit = IntensityUnit(spec_.im);
    const std::string what = IntensityDescription(spec_.im);
    // PGA, PGV, Sa and AvgSa are linear in the accelerations: the applied one is factor x own.
    t.AddAlways({"T1", "s", "fundamental period of the cell's model, 2 pi / w_1 without contacts"},
                [](V v) { return v.t1_s; });
    t.AddAlways({"im", unit, "intensity of the record as applied (x scale_factor): " + what},
                [](V v) { return v.own_im * v.cell.scale; });
    t.AddAlways({"im_unscaled", unit, "the record's own intensity: " + what},
                [](V v) { return v.own_im; });
    t.AddAlways({"scale_factor", "1",
                 spec_.im.scale ? "factor on the record's accelerations: im / im_unscaled"
                                : "1 (records.im: records unscaled, cloud analysis)"},
                [](V v) { return v.cell.scale; });
    t.AddAlways({"scaled_too_far", "1",
                 "1 when scale_factor > records.max_scale, else 0 (always 0 without it)"},
                [max_scale = spec_.im.max_scale](V v) {
                  return max_scale > 0.0 && v.cell.scale > max_scale ? 1.0 : 0.0;
                });
  }
}

std::vector<std::pair<std::int32_t, std::string>> ModelFileEvaluator::StatusNames() const {
  return SolverStatusNames();
}

double ModelFileEvaluator::UnscaledIntensity(std::span<const std::size_t> axis_index) const {
  SB_DEMAND(!record_im_.empty(), "the sweep scales no record to an intensity");
  const std::size_t t = t1_of_cell_[CellIndex(axis_index)];
  return record_im_[RecordIndex(axis_index) * t1_values_s_.size() + t];
}

CellOutcome ModelFileEvaluator::Evaluate(std::span<const std::size_t> axis_index) const {
  return EvaluateAt(axis_index, std::nullopt);
}

CellOutcome ModelFileEvaluator::EvaluateScaled(std::span<const std::size_t> axis_index,
                                               double factor) const {
  SB_DEMAND(!record_im_.empty(), "the sweep scales no record to an intensity");
  return EvaluateAt(axis_index, factor);
}

CellOutcome ModelFileEvaluator::EvaluateAt(std::span<const std::size_t> axis_index,
                                           std::optional<double> factor) const {
  const auto start = std::chrono::steady_clock::now();
  CellOutcome out;
  if (!factor && shared_.Active()) {
    // A seat width moves no deck: the run of a cell that differs only in it is this cell's.
    SeatRun& s = shared_.Get(axis_index, [&] {
      ModelFileCell c = MakeCell(axis_index, true, factor);
      // As `skewbridge run`: run.method picks the integrator, the file's [run] its controls.
      dynamics::LawRun run = CellRun(axis_index, c);
      return SeatRun{std::move(c), std::move(run)};
    });
    for (std::size_t d = 0; d < s.cell.seat_width_m.size(); ++d) {
      s.cell.seat_width_m[d] =
          SeatWidthOf(spec_, axis_index, s.cell.model->body(static_cast<int>(d)).geometry.length_m);
    }
    out = Outcome(axis_index, s.cell, s.run);
  } else {
    const ModelFileCell c = MakeCell(axis_index, true, factor);
    out = Outcome(
        axis_index, c,
        factor ? dynamics::RunUnderLaw(*c.model, c.compliant, *c.excitation, c.control, policies())
               : CellRun(axis_index, c));
  }
  out.stats.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::unique_ptr<Excitation> ModelFileEvaluator::StripeTraceExcitation(
    std::span<const std::size_t> axis_index) const {
  ModelFileCell trace = MakeCell(axis_index, true, dynamics::kStripeTraceFactor);
  const bool striped =
      stripes_ && !trace.compliant && trace.control.method == model::Method::kEventDriven;
  return striped ? std::move(trace.excitation) : nullptr;
}

dynamics::LawRun ModelFileEvaluator::CellRun(std::span<const std::size_t> axis_index,
                                             const ModelFileCell& c) const {
  if (!stripes_ || c.compliant || c.control.method != model::Method::kEventDriven) {
    // As `skewbridge run`: run.method, the file's [run] and [abutments] law decide.
    return dynamics::RunUnderLaw(*c.model, c.compliant, *c.excitation, c.control, policies());
  }
  if (!stripe_axis_) {  // a stripe of its own
    const ModelFileCell trace = MakeCell(axis_index, true, dynamics::kStripeTraceFactor);
    return dynamics::RigidLawRun(dynamics::RunScaledRecord(
        *c.model, *c.excitation, *trace.excitation, c.scale, c.control, policies()));
  }
  std::uint64_t key = 0;  // the cell with its stripe and limit-only axes at 0, row-major
  for (std::size_t k = 0; k < spec_.axes.size(); ++k) {
    const bool shared = k == *stripe_axis_ || LimitOnlyAxis(spec_.axes[k].key);
    key = key * spec_.axes[k].Size() + (shared ? 0 : axis_index[k]);
  }
  auto group = std::find_if(stripe_groups_.begin(), stripe_groups_.end(),
                            [key](const StripeGroup& g) { return g.key == key; });
  if (group == stripe_groups_.end()) {
    std::vector<std::size_t> index(axis_index.begin(), axis_index.end());
    std::vector<double> factors(spec_.axes[*stripe_axis_].Size());
    for (std::size_t v = 0; v < factors.size(); ++v) {
      index[*stripe_axis_] = v;
      factors[v] = scale_of_cell_[CellIndex(index)];
    }
    const ModelFileCell trace = MakeCell(axis_index, true, dynamics::kStripeTraceFactor);
    if (stripe_groups_.size() < stripe_capacity_) stripe_groups_.emplace_back();
    group = stripe_groups_.begin() + static_cast<std::ptrdiff_t>(next_stripe_group_);
    next_stripe_group_ = (next_stripe_group_ + 1) % stripe_capacity_;
    group->key = std::numeric_limits<std::uint64_t>::max();  // no group's key until traced
    group->starts =
        dynamics::TraceStripes(*trace.model, *trace.excitation, dynamics::kStripeTraceFactor,
                               trace.control, policies(), factors);
    group->key = key;
  }
  const dynamics::StripeStart& start = group->starts[axis_index[*stripe_axis_]];
  SB_DEMAND(start.factor == c.scale, "a stripe's factor is not its cell's");
  return dynamics::RigidLawRun(
      dynamics::RunStripe(*c.model, *c.excitation, c.control, policies(), start));
}

CellOutcome ModelFileEvaluator::Outcome(std::span<const std::size_t> axis_index,
                                        const ModelFileCell& c,
                                        const dynamics::LawRun& law_run) const {
  const dynamics::RunResult& run = law_run.run;
  CellOutcome out;
  out.status = CellStatusOf(run.status);
  out.status_text = run.message;
  CellValues values{c, run, law_run, 1.0 / c.persistency_m};
  if (!spec_.im.measure.empty()) {
    const std::size_t t = t1_of_cell_[CellIndex(axis_index)];
    values.t1_s = t1_values_s_[t];
    values.own_im = record_im_[RecordIndex(axis_index) * t1_values_s_.size() + t];
  }
  out.responses = table_.Values(values, out.status == kStatusOk);
  out.stats.events = static_cast<std::int64_t>(run.events.size());
  out.stats.steps = static_cast<std::int64_t>(run.free_steps + run.rk_steps);
  return out;
}

}  // namespace skewbridge::spectra
