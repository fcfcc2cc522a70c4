#include "spectra/spectra_evaluator.h"

#include <chrono>
#include <cmath>

#include "records/incidence.h"
#include "solver/common/error.h"
#include "solver/model/deck.h"

namespace skewbridge::spectra {
namespace {

constexpr double kStandardGravity_mps2 = 9.80665;

}  // namespace

struct SpectraEvaluator::CellValues {
  const spectra::PointResult& run;
  const spectra::DimensionalPoint& point;
  double seat_m = 0.0;  ///< seat width: seat_over_L L, or seat_m (with seats)
};

SpectraEvaluator::SpectraEvaluator(const CellGrid& spec)
    : CellEvaluator(spec.policies), spec_(spec), shared_(spec) {
  sources_ = {SourceOf("w0_over_wg"),
              SourceOf("Pi_delta"),
              SourceOf("a_deg"),
              SourceOf("eta0"),
              SourceOf("W_over_L"),
              SourceOf("W0_over_w0"),
              SourceOf("xi"),
              SourceOf("eps_N"),
              SourceOf("mu"),
              SourceOf("delta_over_L"),
              SourceOf("L_over_Le"),
              SourceOf("a_g_g"),
              SourceOf("incidence_deg"),
              LabelSourceOf("pulse"),
              LabelSourceOf("record"),
              Mentions(spec, "method")};
  if (spec.family == "subsystem") {
    family_ = spectra::Family::kSubsystem;
  } else if (spec.family == "pilot-bridge") {
    family_ = spectra::Family::kPilotBridge;
    // The pilot bridge's mass, inertia and substructure are the published ones
    // [docs/theory.md §6]; only its skew (a_deg, eta0) may vary (spectra::PilotBridgeDeck).
    for (std::string_view key : {"W_over_L", "W0_over_w0", "delta_over_L", "L_over_Le", "spans"}) {
      if (Mentions(spec, key)) {
        throw InputError::AtField(spec.source, key,
                                  "not a parameter of family 'pilot-bridge' (its deck is the "
                                  "published one; a_deg and eta0 may vary its skew)");
      }
    }
  } else {
    throw InputError::AtField(spec.source, "sweep.family",
                              "family '" + spec.family +
                                  "' cannot be swept by this build (allowed: subsystem, "
                                  "pilot-bridge)");
  }
  if (family_ == spectra::Family::kSubsystem && Mentions(spec, "incidence_deg")) {
    throw InputError::AtField(spec.source, "incidence_deg",
                              "not a parameter of family 'subsystem' (its responses are "
                              "normalised by one component along x, docs/theory.md §5; the "
                              "pilot-bridge, multi-span and model-file families take it)");
  }
  if (Mentions(spec, "spans") && NumberOf(spec, {}, "spans", 1.0) != 1.0) {
    throw InputError::AtField(spec.source, "spans", "only single-span decks are supported (1)");
  }
  if (Mentions(spec, "record") && Mentions(spec, "pulse")) {
    throw InputError::AtField(spec.source, "pulse",
                              "a sweep is driven by pulses or by records, not both");
  }
  if (Mentions(spec, "record")) {
    // A record fixes a_g (its PGA) and w_g (2 pi / T_m); a swept value that the mapping would
    // ignore would only repeat cells.
    if (Mentions(spec, "a_g_g")) {
      throw InputError::AtField(spec.source, "a_g_g",
                                "not a parameter of a record-driven sweep (a_g is each record's "
                                "PGA)");
    }
    if (family_ == spectra::Family::kPilotBridge && Mentions(spec, "w0_over_wg")) {
      throw InputError::AtField(spec.source, "w0_over_wg",
                                "not a parameter of the pilot bridge under records (its w0x is "
                                "fixed and w_g is each record's; see the response w0x_over_wg)");
    }
    records_ = LoadSweepRecords(spec);
  }
  band_edges_ = BandEdges(spec);
  seats_ = MentionsSeat(spec);
  travel_ = !spec.limit_states.empty();

  // The responses [docs/theory.md §5]: the run's maxima (NaN for a failed cell), then the
  // cell's excitation and geometry (stored whatever the run did).
  using V = const CellValues&;
  ResponseTable<CellValues>& t = table_;
  t.Add({"x_m", "m", "maximum |x|, longitudinal deck displacement relative to the ground"},
        [](V v) { return v.run.x_m; });
  t.Add({"y_m", "m", "maximum |y|, transverse deck displacement relative to the ground"},
        [](V v) { return v.run.y_m; });
  t.Add({"theta_m", "rad", "maximum |theta|, deck rotation in plan"},
        [](V v) { return v.run.theta_rad; });
  t.Add({"theta_end", "rad", "residual rotation theta at the end of the run"},
        [](V v) { return v.run.theta_end_rad; });
  t.Add({"x_norm", "1", "x_m w_g^2 / a_g"}, [](V v) { return v.run.x_norm; });
  t.Add({"y_norm", "1", "y_m w_g^2 / a_g"}, [](V v) { return v.run.y_norm; });
  t.Add({"theta_norm", "1", "theta_m rho w_g^2 / a_g, rho the radius of gyration"},
        [](V v) { return v.run.theta_norm; });
  t.Add({"theta_end_norm", "1", "theta_end rho w_g^2 / a_g"},
        [](V v) { return v.run.theta_end_norm; });
  t.Add({"impacts", "1", "number of impact events (a multi-contact impact counts once)"},
        [](V v) { return static_cast<double>(v.run.impacts); });
  t.Add({"min_impact_separation", "s",
         "smallest time between distinct impact instants (inf with fewer than two)"},
        [](V v) { return v.run.min_impact_separation_s; });
  t.AddAlways({"a_g", "m/s^2", "excitation amplitude a_g (pulse) or PGA (record)"},
              [](V v) { return v.point.scales.a_g_mps2; });
  t.AddAlways({"w_g", "rad/s", "excitation frequency w_g (pulse) or 2 pi / T_m (record)"},
              [](V v) { return v.point.scales.w_g_radps; });
  t.AddAlways({"L_e", "m", "persistency a_g / w_g^2"}, [](V v) { return v.point.persistency_m; });
  t.AddAlways({"delta", "m", "joint gap along x, Pi_delta L_e"},
              [](V v) { return v.point.delta_m; });
  t.AddAlways({"w0x_over_wg", "1", "sqrt(K_xx / m) / w_g"},
              [](V v) { return v.point.w0x_radps / v.point.scales.w_g_radps; });
  t.AddAlways(
      {"band", "1",
       "w0x/w_g group: k for band_edges[k-1] <= w0x_over_wg < band_edges[k] ([study] bands)"},
      [edges = band_edges_](V v) {
        return BandOf(v.point.w0x_radps / v.point.scales.w_g_radps, edges);
      });
  if (seats_) {
    t.Add({"margin_m", "m",
           "unseating margin: seat width (seat_over_L L or seat_m) - largest corner travel normal "
           "to the end "
           "line (travel_m)"},
          [](V v) { return v.seat_m - v.run.travel_m; });
    t.Add({"margin_norm", "1", "margin_m w_g^2 / a_g"},
          [](V v) { return (v.seat_m - v.run.travel_m) / v.point.persistency_m; });
  }
  if (travel_) {
    t.Add({"travel_m", "m",
           "largest corner travel normal to the end line over the run, exact (tracked by the "
           "integrator)"},
          [](V v) { return v.run.travel_m; });
    t.Add({"travel_end_m", "m",
           "corner travel normal to the end line at the end of the run (residual)"},
          [](V v) {
            return model::CornerTravelAt(v.point.deck.geometry,
                                         {v.run.x_end_m, v.run.y_end_m, v.run.theta_end_rad});
          });
    t.Add({"travel_bound_m", "m",
           "upper bound of travel_m from the maxima of x, y and theta, each at its own time"},
          [](V v) {
            return model::CornerTravelBound(v.point.deck.geometry,
                                            {v.run.x_m, v.run.y_m, v.run.theta_rad});
          });
  }
  // Every cell's mapping is checked now, so a bad combination fails before the file is touched.
  std::vector<std::size_t> index(spec.axes.size(), 0);
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    index = spec.AxisIndex(cell);
    const SweepRecord* record = nullptr;
    const spectra::PointParameters p = Parameters(index, &record);
    try {
      spectra::ToDimensional(
          p, record != nullptr ? spectra::ExcitationScales{1.0, 1.0} : spectra::PulseScales(p));
    } catch (const InputError& e) {
      throw InputError(spec.source + ": " + e.what());
    }
  }
}

SpectraEvaluator::NumberSource SpectraEvaluator::SourceOf(std::string_view key) const {
  NumberSource source;
  for (std::size_t k = 0; k < spec_.axes.size(); ++k) {
    if (spec_.axes[k].key == key) {
      source.axis = static_cast<int>(k);
      return source;
    }
  }
  if (const FixedValue* fixed = spec_.FindFixed(key)) {
    source.fixed = true;
    source.value = fixed->value;
  }
  return source;
}

SpectraEvaluator::LabelSource SpectraEvaluator::LabelSourceOf(std::string_view key) const {
  LabelSource source;
  for (std::size_t k = 0; k < spec_.axes.size(); ++k) {
    if (spec_.axes[k].key == key) {
      source.axis = static_cast<int>(k);
      return source;
    }
  }
  if (const FixedValue* fixed = spec_.FindFixed(key)) {
    source.label = fixed->label;
  }
  return source;
}

spectra::PointParameters SpectraEvaluator::Parameters(std::span<const std::size_t> index,
                                                      const SweepRecord** record) const {
  spectra::PointParameters p;
  p.family = family_;
  if (family_ == spectra::Family::kPilotBridge) {
    p.mu = 0.3;  // the published pilot bridge [docs/theory.md §6]
  }
  p.w0_over_wg = Number(sources_.w0_over_wg, index, p.w0_over_wg);
  p.Pi_delta = Number(sources_.Pi_delta, index, p.Pi_delta);
  bool given = false;
  const double a_deg = Number(sources_.a_deg, index, p.skew_deg, &given);
  if (family_ == spectra::Family::kPilotBridge) {
    if (given) p.pilot_skew_deg = a_deg;
  } else {
    p.skew_deg = a_deg;
  }
  const double eta0 = Number(sources_.eta0, index, 0.0, &given);
  if (given) p.eta0 = eta0;
  const double w_over_l = Number(sources_.W_over_L, index, 0.0, &given);
  if (given) p.W_over_L = w_over_l;
  if (family_ == spectra::Family::kSubsystem && !p.eta0 && !p.W_over_L) p.eta0 = 1.0;
  p.W0_over_w0 = Number(sources_.W0_over_w0, index, p.W0_over_w0);
  p.xi = Number(sources_.xi, index, p.xi);
  p.eps_N = Number(sources_.eps_N, index, p.eps_N);
  p.mu = Number(sources_.mu, index, p.mu);
  const double delta_over_l = Number(sources_.delta_over_L, index, 0.0, &given);
  if (given) p.delta_over_L = delta_over_l;
  p.L_over_Le = Number(sources_.L_over_Le, index, p.L_over_Le);
  p.pulse_a_g_mps2 = Number(sources_.a_g_g, index, 0.5) * kStandardGravity_mps2;
  p.pulse = Label(sources_.pulse, index) == "sine" ? records::PulseShape::kSine
                                                   : records::PulseShape::kCosine;
  // Without a method key MethodOf gives its fallback.
  p.method = sources_.method ? MethodOf(spec_, index, spectra::Method::kEventDriven)
                             : spectra::Method::kEventDriven;
  *record = nullptr;
  if (!records_.empty()) {
    const std::string& label = Label(sources_.record, index);
    for (const SweepRecord& r : records_) {
      if (r.label == label) *record = &r;
    }
  }
  return p;
}

std::vector<std::pair<std::int32_t, std::string>> SpectraEvaluator::StatusNames() const {
  return SolverStatusNames();
}

SpectraEvaluator::CellRun SpectraEvaluator::MakeRun(std::span<const std::size_t> axis_index) const {
  CellRun out;
  const spectra::PointParameters p = Parameters(axis_index, &out.record);
  // As Evaluate: the record's PGA and 2 pi / T_m, or the pulse's scales.
  const spectra::ExcitationScales scales =
      out.record != nullptr ? spectra::ExcitationScales{out.record->measures.pga_mps2,
                                                        out.record->measures.omega_g_radps}
                            : spectra::PulseScales(p);
  out.excitation = MakeExcitation(axis_index, p, out.record, scales);
  out.run = spectra::MakePointRun(spectra::ToDimensional(p, scales), *out.excitation);
  return out;
}

std::unique_ptr<Excitation> SpectraEvaluator::MakeExcitation(
    std::span<const std::size_t> axis_index, const spectra::PointParameters& p,
    const SweepRecord* record, const spectra::ExcitationScales& scales) const {
  const Eigen::Vector2d direction = DirectionOf(axis_index);
  if (record != nullptr && record->IsPair()) {
    return std::make_unique<records::SampledExcitation>(
        records::PairExcitation(record->motion, *record->motion_h2, direction));
  }
  if (record != nullptr) {
    // ToExcitation's samples (a factor of 1 leaves them as read), with the pieces that hold
    // their peak: the run's scale has the bits of the walk over every piece.
    return std::make_unique<records::SampledExcitation>(
        records::ScaledExcitation(record->motion, 1.0, direction, RecordPeakPieces(*record)));
  }
  return std::make_unique<records::PulseExcitation>(p.pulse, scales.a_g_mps2, scales.w_g_radps,
                                                    direction);
}

Eigen::Vector2d SpectraEvaluator::DirectionOf(std::span<const std::size_t> axis_index) const {
  bool turned = false;
  const double incidence_deg = Number(sources_.incidence_deg, axis_index, 0.0, &turned);
  // Without incidence_deg the default direction x, as the excitations make it.
  return turned ? records::DirectionAt(incidence_deg) : Eigen::Vector2d::UnitX();
}

std::shared_ptr<const records::PeakPieces> SpectraEvaluator::RecordPeakPieces(
    const SweepRecord& record) const {
  return peak_pieces_.Get(records_, record, policies().event.ramp_horizon_s);
}

SpectraEvaluator::SeatRun SpectraEvaluator::RunOf(std::span<const std::size_t> axis_index) const {
  const SweepRecord* record = nullptr;
  const spectra::PointParameters p = Parameters(axis_index, &record);
  const spectra::ExcitationScales scales =
      record != nullptr
          ? spectra::ExcitationScales{record->measures.pga_mps2, record->measures.omega_g_radps}
          : spectra::PulseScales(p);
  SeatRun out;
  out.point = spectra::ToDimensional(p, scales);
  if (record == nullptr) {
    // MakeExcitation's pulse, on the stack.
    const records::PulseExcitation pulse(p.pulse, scales.a_g_mps2, scales.w_g_radps,
                                         DirectionOf(axis_index));
    out.result = spectra::EvaluatePoint(out.point, pulse, policies());
  } else {
    out.result = spectra::EvaluatePoint(out.point, *MakeExcitation(axis_index, p, record, scales),
                                        policies());
  }
  return out;
}

CellOutcome SpectraEvaluator::Evaluate(std::span<const std::size_t> axis_index) const {
  const auto start = std::chrono::steady_clock::now();
  // A seat width moves no deck: the run of a cell that differs only in it is this cell's.
  std::optional<SeatRun> own;
  const SeatRun& s = shared_.Active() ? shared_.Get(axis_index, [&] { return RunOf(axis_index); })
                                      : own.emplace(RunOf(axis_index));
  const spectra::PointResult& r = s.result;
  const spectra::DimensionalPoint& point = s.point;

  CellOutcome out;
  out.status = CellStatusOf(r.status);
  out.status_text = r.message;
  CellValues values{r, point};
  if (seats_) {
    values.seat_m = SeatWidthOf(spec_, axis_index, point.deck.geometry.length_m);
  }
  out.responses = table_.Values(values, out.status == kStatusOk);
  out.stats.events = r.events;
  out.stats.steps = r.steps;
  out.stats.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace skewbridge::spectra
