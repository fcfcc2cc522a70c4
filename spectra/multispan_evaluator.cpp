#include "spectra/multispan_evaluator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "records/excitations.h"
#include "records/incidence.h"
#include "solver/common/error.h"
#include "solver/dynamics/run.h"
#include "solver/model/multispan.h"

namespace skewbridge::spectra {
namespace {

constexpr double kStandardGravity_mps2 = 9.80665;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDeckMass_kg = 1.0e6;  // cancels out of every dimensionless response

// One cell made dimensional: the bridge, the pulse scales and the run controls.
struct Cell {
  model::MultiSpanSpec bridge;
  double a_g_mps2 = 0.0;
  double w_g_radps = 2.0 * std::numbers::pi;  // T_g = 1 s; cancels out
  double persistency_m = 0.0;                 // L_e = a_g / w_g^2
  records::PulseShape shape = records::PulseShape::kCosine;
  model::Method method = model::Method::kEventDriven;
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // incidence_deg, else x
};

Cell MakeCell(const CellGrid& spec, std::span<const std::size_t> index) {
  Cell c;
  const std::string& source = spec.source;
  c.a_g_mps2 = NumberOf(spec, index, "a_g_g", 0.5) * kStandardGravity_mps2;
  c.persistency_m = c.a_g_mps2 / (c.w_g_radps * c.w_g_radps);
  c.shape = LabelOf(spec, index, "pulse", "cosine") == "sine" ? records::PulseShape::kSine
                                                              : records::PulseShape::kCosine;
  c.method = MethodOf(spec, index, model::Method::kEventDriven);
  bool turned = false;
  const double incidence_deg = NumberOf(spec, index, "incidence_deg", 0.0, &turned);
  if (turned) c.direction = records::DirectionAt(incidence_deg);
  model::MultiSpanSpec& b = c.bridge;
  b.n_spans = static_cast<int>(NumberOf(spec, index, "spans", 1.0));
  const double Pi_delta = NumberOf(spec, index, "Pi_delta", 1.0);
  const double delta_m = Pi_delta * c.persistency_m;
  bool has_delta_over_L = false;
  const double delta_over_L = NumberOf(spec, index, "delta_over_L", 0.0, &has_delta_over_L);
  double L_m = 0.0;
  if (has_delta_over_L) {
    if (!(delta_over_L > 0.0) || !(Pi_delta > 0.0)) {
      throw InputError::AtField(source, "delta_over_L",
                                "needs delta_over_L > 0 and Pi_delta > 0 (the gap sets the span "
                                "length); use L_over_Le");
    }
    L_m = delta_m / delta_over_L;
  } else {
    L_m = NumberOf(spec, index, "L_over_Le", 250.0) * c.persistency_m;
  }
  const double a_deg = NumberOf(spec, index, "a_deg", 30.0);
  b.skew_rad = a_deg * std::numbers::pi / 180.0;
  bool has_eta0 = false;
  const double eta0 = NumberOf(spec, index, "eta0", 0.0, &has_eta0);
  if (has_eta0) {
    if (!(a_deg > 0.0)) {
      throw InputError::AtField(source, "eta0",
                                "needs a skew angle > 0 (eta0 = sin 2a / (2 W/L) is 0 at a = 0); "
                                "give W_over_L");
    }
    b.width_m = model::WidthFromEta0(eta0, b.skew_rad, L_m);
  } else {
    bool has_ratio = false;
    b.width_m = NumberOf(spec, index, "W_over_L", 0.0, &has_ratio) * L_m;
    if (!has_ratio) {
      throw InputError::AtField(source, "eta0", "missing: give eta0 or W_over_L");
    }
  }
  b.span_lengths_m = {L_m};
  b.mass_per_length_kgpm = kDeckMass_kg / L_m;
  const double w0 = NumberOf(spec, index, "w0_over_wg", 1.0) * c.w_g_radps;
  b.w0x_radps = w0;
  b.w0y_radps = w0;
  b.W0_radps = NumberOf(spec, index, "W0_over_w0", 1.0) * w0;
  b.xi = NumberOf(spec, index, "xi", 0.05);
  b.abutment_gap_m = delta_m;
  b.joint_gap_m = delta_m;
  b.restitution = NumberOf(spec, index, "eps_N", 0.5);
  b.friction = NumberOf(spec, index, "mu", 0.0);
  bool has_seat = false;
  const double seat_m = SeatWidthOf(spec, index, L_m, &has_seat);
  if (has_seat) {
    b.seat_width_m = seat_m;
  }
  return c;
}

int MaxSpans(const CellGrid& spec) {
  if (const Axis* axis = spec.FindAxis("spans")) {
    return static_cast<int>(*std::max_element(axis->values.begin(), axis->values.end()));
  }
  if (const FixedValue* fixed = spec.FindFixed("spans")) {
    return static_cast<int>(fixed->value);
  }
  return 1;
}

}  // namespace

struct MultiSpanEvaluator::CellValues {
  const Cell& cell;
  const model::Model& model;
  const dynamics::RunResult& run;
  double to_norm = 0.0;  ///< 1 / L_e (1/m)

  /// Whether the cell's bridge has deck d.
  bool Has(int d) const { return d < model.n_bodies(); }
  /// max |q| of deck d (m, m, rad).
  Eigen::Vector3d MaxOf(int d) const { return run.max_abs_q.segment<3>(3 * d); }
  /// theta_norm of deck d: max |theta| rho w_g^2 / a_g.
  double ThetaNormOf(int d) const {
    const model::Body& deck = model.body(d);
    return MaxOf(d)(2) * std::sqrt(deck.inertia_kgm2 / deck.mass_kg) * to_norm;
  }
  /// Deck d's largest corner travel normal to its end line over the run, exact (m).
  double TravelOf(int d) const { return run.max_travel_m(d); }
};

MultiSpanEvaluator::MultiSpanEvaluator(const CellGrid& spec)
    : CellEvaluator(spec.policies), spec_(spec), shared_(spec) {
  for (std::string_view key : {"record"}) {
    if (Mentions(spec, key)) {
      throw InputError::AtField(spec.source, key,
                                "not a parameter of family 'multi-span' (pulses only)");
    }
  }
  if (Mentions(spec, "delta_over_L") && Mentions(spec, "L_over_Le")) {
    throw InputError::AtField(spec.source, "L_over_Le",
                              "give either delta_over_L or L_over_Le, not both");
  }
  max_spans_ = MaxSpans(spec);
  travel_ = !spec.limit_states.empty();
  MakeResponseTable();
  // Every cell is mapped and its model built now, so a bad combination fails before any output.
  for (std::uint64_t cell = 0; cell < spec.CellCount(); ++cell) {
    const std::vector<std::size_t> index = spec.AxisIndex(cell);
    const Cell c = MakeCell(spec, index);
    try {
      model::BuildMultiSpanBridge(c.bridge, spec.source);
    } catch (const InputError& e) {
      throw InputError(spec.source + ": " + e.what());
    }
  }
}

void MultiSpanEvaluator::MakeResponseTable() {
  using V = const CellValues&;
  constexpr double kNoDeck = kNaN;
  ResponseTable<CellValues>& t = table_;
  const bool seat = MentionsSeat(spec_);
  // Per deck (suffix _d<i>): NaN for a failed cell and for a deck the cell's bridge lacks.
  const auto deck = [](int d, double (*read)(V, int)) {
    return [d, read](V v) { return v.Has(d) ? read(v, d) : kNoDeck; };
  };
  for (int d = 0; d < max_spans_; ++d) {
    const std::string s = "_d" + std::to_string(d);
    const std::string of = " of deck " + std::to_string(d) + " (NaN when the cell has fewer decks)";
    t.Add({"x_norm" + s, "1", "max |x| w_g^2 / a_g" + of},
          deck(d, [](V v, int i) { return v.MaxOf(i)(0) * v.to_norm; }));
    t.Add({"y_norm" + s, "1", "max |y| w_g^2 / a_g" + of},
          deck(d, [](V v, int i) { return v.MaxOf(i)(1) * v.to_norm; }));
    t.Add({"theta_norm" + s, "1", "max |theta| rho w_g^2 / a_g" + of},
          deck(d, [](V v, int i) { return v.ThetaNormOf(i); }));
    if (seat) {
      t.Add(
          {"margin_norm" + s, "1",
           "unseating margin (seat width - corner travel normal to the end line) w_g^2 / a_g" + of},
          deck(d, [](V v, int i) {
            return (*v.cell.bridge.seat_width_m - v.TravelOf(i)) * v.to_norm;
          }));
    }
    if (travel_) {
      t.Add({"theta_m" + s, "rad", "max |theta|" + of},
            deck(d, [](V v, int i) { return v.MaxOf(i)(2); }));
      t.Add({"travel_m" + s, "m",
             "largest corner travel normal to the end line over the run, exact" + of},
            deck(d, [](V v, int i) { return v.TravelOf(i); }));
      t.Add({"travel_end_m" + s, "m",
             "corner travel normal to the end line at the end of the run" + of},
            deck(d, [](V v, int i) {
              return model::CornerTravelAt(v.model.body(i).geometry,
                                           v.run.q_end.segment<3>(3 * i).eval());
            }));
      if (seat) {
        t.Add({"margin_m" + s, "m", "unseating margin: seat width - travel_m" + of},
              deck(d, [](V v, int i) { return *v.cell.bridge.seat_width_m - v.TravelOf(i); }));
      }
      t.Add(
          {"travel_bound_m" + s, "m",
           "upper bound of travel_m from the maxima of x, y and theta, each at its own time" + of},
          deck(d, [](V v, int i) {
            return model::CornerTravelBound(v.model.body(i).geometry, v.MaxOf(i));
          }));
    }
  }
  // The cell: the run's counts, then its geometry (stored whatever the run did).
  t.Add({"theta_norm_max", "1", "largest theta_norm over the decks"}, [](V v) {
    double theta_max = 0.0;
    for (int d = 0; d < v.model.n_bodies(); ++d) theta_max = std::max(theta_max, v.ThetaNormOf(d));
    return theta_max;
  });
  t.Add({"impacts", "1", "number of impact events (a multi-contact impact counts once)"},
        [](V v) { return static_cast<double>(v.run.impacts); });
  t.AddAlways({"L_e", "m", "persistency a_g / w_g^2"}, [](V v) { return v.cell.persistency_m; });
  t.AddAlways({"L", "m", "span length"}, [](V v) { return v.cell.bridge.span_lengths_m[0]; });
  t.AddAlways({"delta", "m", "gap of every joint and abutment, along x: Pi_delta L_e"},
              [](V v) { return v.cell.bridge.joint_gap_m; });
  if (travel_) {
    // The intensity of the fragility functions (jobs/study.cpp takes a_g / g without stripes).
    t.AddAlways({"a_g", "m/s^2", "pulse amplitude a_g = a_g_g g"},
                [](V v) { return v.cell.a_g_mps2; });
  }
}

std::vector<std::pair<std::int32_t, std::string>> MultiSpanEvaluator::StatusNames() const {
  return SolverStatusNames();
}

MultiSpanEvaluator::SeatRun MultiSpanEvaluator::RunOf(
    std::span<const std::size_t> axis_index) const {
  const Cell c = MakeCell(spec_, axis_index);
  SeatRun out;
  const model::Model& model =
      out.model.emplace(model::BuildMultiSpanBridge(c.bridge, spec_.source));
  const records::PulseExcitation pulse(c.shape, c.a_g_mps2, c.w_g_radps, c.direction);
  const double excitation_period_s = 2.0 * std::numbers::pi / c.w_g_radps;
  const double w_min = std::min({c.bridge.w0x_radps, c.bridge.W0_radps});
  const double natural_period_s = w_min > 0.0 ? 2.0 * std::numbers::pi / w_min : 0.0;
  model::RunControl control;
  // Tolerances in state units follow the persistency, as for the single deck, so that the run
  // is self-similar in a_g [docs/theory.md §4 fact 4].
  control.absolute_tolerance = 1e-11 * c.persistency_m;
  // A cell stores maxima, not the energy ledger: its work integrals are not computed.
  control.energy_ledger = false;
  control.end_time_s = pulse.Duration() + 2.0 * std::max(excitation_period_s, natural_period_s);
  control.method = c.method;
  if (c.method == model::Method::kTimeStepping) control.time_step_s = 1e-4 * excitation_period_s;
  out.run = dynamics::Run(model, pulse, control, policies());
  return out;
}

CellOutcome MultiSpanEvaluator::Evaluate(std::span<const std::size_t> axis_index) const {
  const auto start = std::chrono::steady_clock::now();
  const Cell c = MakeCell(spec_, axis_index);
  // A seat width moves no deck: the run of a cell that differs only in it is this cell's.
  std::optional<SeatRun> own;
  const SeatRun& s = shared_.Active() ? shared_.Get(axis_index, [&] { return RunOf(axis_index); })
                                      : own.emplace(RunOf(axis_index));
  const model::Model& model = *s.model;
  const dynamics::RunResult& run = s.run;

  CellOutcome out;
  out.status = CellStatusOf(run.status);
  out.status_text = run.message;
  out.responses = table_.Values({c, model, run, 1.0 / c.persistency_m}, out.status == kStatusOk);
  out.stats.events = static_cast<std::int64_t>(run.events.size());
  out.stats.steps = static_cast<std::int64_t>(run.free_steps + run.rk_steps);
  out.stats.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace skewbridge::spectra
