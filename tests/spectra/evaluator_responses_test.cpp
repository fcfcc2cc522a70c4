// The responses of the subsystem and multi-span evaluators by name: a subsystem cell's against
// the run of its point (spectra::EvaluatePoint) and the definitions of docs/sweep-format.md, a
// multi-span cell's against the relations its responses must satisfy (NaN for the decks a cell
// does not have). Cells that differ only in the seat width share one run: the subsystem,
// pilot-bridge and multi-span cubes are, bit for bit, the cells evaluated on their own.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/model/deck.h"
#include "spectra/grid.h"
#include "spectra/multispan_evaluator.h"
#include "spectra/point.h"
#include "spectra/spectra_evaluator.h"
#include "spectra/study.h"

namespace skewbridge::spectra::evaluator_responses_test {
namespace {

constexpr double kG = 9.80665;

// The value of the response `name` of `out`.
double ValueOf(const CellEvaluator& evaluator, const CellOutcome& out, const std::string& name) {
  const std::vector<ResponseInfo> names = evaluator.Responses();
  EXPECT_EQ(names.size(), out.responses.size());
  for (std::size_t k = 0; k < names.size() && k < out.responses.size(); ++k) {
    if (names[k].name == name) return out.responses[k];
  }
  ADD_FAILURE() << "no response " << name;
  return 0.0;
}

// Every cell of `grid` evaluated in cube order by one evaluator (the cells of one run but their
// seat widths follow each other, so they share it) against each cell evaluated by an evaluator
// of its own: every response's bits, the status and the counts. The margin `margin` must differ
// between the seat widths of one run (index `seat_axis`), so that a stale seat width fails.
template <typename Evaluator>
void ExpectSharedRunsAreTheCellsOwn(const CellGrid& grid, std::size_t seat_axis,
                                    const std::string& margin) {
  const Evaluator shared(grid);
  const std::vector<ResponseInfo> names = shared.Responses();
  std::vector<CellOutcome> in_order;
  for (std::uint64_t c = 0; c < grid.CellCount(); ++c) {
    in_order.push_back(shared.Evaluate(grid.AxisIndex(c)));
  }
  std::size_t differ = 0;
  for (std::uint64_t c = 0; c < grid.CellCount(); ++c) {
    SCOPED_TRACE("cell " + std::to_string(c));
    const std::vector<std::size_t> index = grid.AxisIndex(c);
    const Evaluator alone(grid);
    const CellOutcome own = alone.Evaluate(index);
    const CellOutcome& got = in_order[c];
    ASSERT_EQ(got.status, kStatusOk) << got.status_text;
    ASSERT_EQ(got.status, own.status);
    ASSERT_EQ(got.responses.size(), own.responses.size());
    for (std::size_t r = 0; r < own.responses.size(); ++r) {
      EXPECT_EQ(std::memcmp(&got.responses[r], &own.responses[r], sizeof(double)), 0)
          << names[r].name << ": " << got.responses[r] << " against " << own.responses[r];
    }
    EXPECT_EQ(got.stats.events, own.stats.events);
    EXPECT_EQ(got.stats.steps, own.stats.steps);
    if (index[seat_axis] > 0) {
      std::uint64_t stride = 1;  // cells between two seat widths (row-major)
      for (std::size_t k = seat_axis + 1; k < grid.axes.size(); ++k) stride *= grid.axes[k].Size();
      const CellOutcome& prior = in_order[c - stride];
      EXPECT_EQ(ValueOf(shared, got, "impacts"), ValueOf(shared, prior, "impacts"));
      if (ValueOf(shared, got, margin) != ValueOf(shared, prior, margin)) ++differ;
    }
  }
  EXPECT_GT(differ, 0u) << "no two seat widths of one run gave different margins";
}

TEST(SeatWidthsShareARun, SubsystemAndPilotBridgeCellsAreTheirOwn) {
  LimitState unseating;
  unseating.name = "unseating";
  unseating.kind = LimitStateKind::kUnseating;
  for (const char* family : {"subsystem", "pilot-bridge"}) {
    SCOPED_TRACE(family);
    CellGrid grid;
    grid.source = "spec.toml";
    grid.family = family;
    // The method axis after the seat widths: two runs kept at a time.
    grid.axes = {
        Axis{"Pi_delta", ParameterKind::kNumber, {0.3, 2.0}, {}, "list"},
        Axis{"seat_over_L", ParameterKind::kNumber, {0.0005, 0.002, 0.01}, {}, "list"},
        Axis{"method", ParameterKind::kLabel, {}, {"event-driven", "time-stepping"}, "list"}};
    grid.fixed = {{"a_deg", ParameterKind::kNumber, 30.0, ""},
                  {"w0_over_wg", ParameterKind::kNumber, 0.9, ""}};
    if (std::string(family) == "subsystem") {
      grid.fixed.push_back({"eta0", ParameterKind::kNumber, 1.2, ""});
      grid.fixed.push_back({"mu", ParameterKind::kNumber, 0.2, ""});
    }
    grid.limit_states = {unseating};
    ExpectSharedRunsAreTheCellsOwn<SpectraEvaluator>(grid, 1, "margin_m");
  }
}

TEST(SeatWidthsShareARun, MultiSpanCellsAreTheirOwn) {
  CellGrid grid;
  grid.source = "spec.toml";
  grid.family = "multi-span";
  grid.axes = {Axis{"spans", ParameterKind::kNumber, {1.0, 3.0}, {}, "list"},
               Axis{"seat_m", ParameterKind::kNumber, {0.05, 0.2, 1.0}, {}, "list"}};
  grid.fixed = {{"a_deg", ParameterKind::kNumber, 30.0, ""},
                {"W_over_L", ParameterKind::kNumber, 0.3, ""},
                {"Pi_delta", ParameterKind::kNumber, 1.0, ""},
                {"delta_over_L", ParameterKind::kNumber, 0.002, ""},
                {"mu", ParameterKind::kNumber, 0.1, ""}};
  LimitState unseating;
  unseating.name = "unseating";
  unseating.kind = LimitStateKind::kUnseating;
  grid.limit_states = {unseating};
  ExpectSharedRunsAreTheCellsOwn<MultiSpanEvaluator>(grid, 1, "margin_m_d0");
}

TEST(SubsystemResponses, EachNameHoldsWhatThePointsRunGives) {
  CellGrid grid;
  grid.source = "spec.toml";
  grid.family = "subsystem";
  grid.axes = {Axis{"Pi_delta", ParameterKind::kNumber, {0.3, 2.0}, {}, "list"},
               Axis{"w0_over_wg", ParameterKind::kNumber, {0.7, 1.9}, {}, "list"}};
  grid.fixed = {{"a_deg", ParameterKind::kNumber, 30.0, ""},
                {"eta0", ParameterKind::kNumber, 1.2, ""},
                {"mu", ParameterKind::kNumber, 0.2, ""},
                {"seat_over_L", ParameterKind::kNumber, 0.004, ""}};
  LimitState rotation;
  rotation.name = "rotation";
  rotation.kind = LimitStateKind::kRotation;
  rotation.threshold = 0.01;
  grid.limit_states = {rotation};  // the family then stores the travels too
  const SpectraEvaluator evaluator(grid);
  ASSERT_EQ(evaluator.Responses().size(), 16u + 2u + 3u);
  long impacts = 0;
  for (std::uint64_t c = 0; c < grid.CellCount(); ++c) {
    const std::vector<std::size_t> index = grid.AxisIndex(c);
    SCOPED_TRACE("cell " + std::to_string(c));
    const CellOutcome out = evaluator.Evaluate(index);
    ASSERT_EQ(out.status, kStatusOk) << out.status_text;
    const SweepRecord* record = nullptr;
    const PointParameters p = evaluator.Parameters(index, &record);
    const ExcitationScales scales = PulseScales(p);
    const DimensionalPoint point = ToDimensional(p, scales);
    const records::PulseExcitation pulse(p.pulse, scales.a_g_mps2, scales.w_g_radps);
    const PointResult r = EvaluatePoint(point, pulse);
    const auto at = [&](const std::string& name) { return ValueOf(evaluator, out, name); };
    EXPECT_EQ(at("x_m"), r.x_m);
    EXPECT_EQ(at("y_m"), r.y_m);
    EXPECT_EQ(at("theta_m"), r.theta_rad);
    EXPECT_EQ(at("theta_end"), r.theta_end_rad);
    const double L_e = scales.a_g_mps2 / (scales.w_g_radps * scales.w_g_radps);
    EXPECT_DOUBLE_EQ(at("x_norm"), r.x_m / L_e);
    EXPECT_DOUBLE_EQ(at("y_norm"), r.y_m / L_e);
    EXPECT_DOUBLE_EQ(at("theta_norm"), r.theta_rad * point.rho_m / L_e);
    EXPECT_DOUBLE_EQ(at("theta_end_norm"), r.theta_end_rad * point.rho_m / L_e);
    EXPECT_EQ(at("impacts"), static_cast<double>(r.impacts));
    EXPECT_EQ(at("min_impact_separation"), r.min_impact_separation_s);
    EXPECT_EQ(at("a_g"), 0.5 * kG);
    EXPECT_EQ(at("w_g"), scales.w_g_radps);
    EXPECT_DOUBLE_EQ(at("L_e"), L_e);
    EXPECT_DOUBLE_EQ(at("delta"), p.Pi_delta * L_e);
    EXPECT_DOUBLE_EQ(at("w0x_over_wg"), p.w0_over_wg);
    const std::vector<double> edges(kDefaultBandEdges.begin(), kDefaultBandEdges.end());
    EXPECT_EQ(at("band"),
              static_cast<double>(std::upper_bound(edges.begin(), edges.end(), p.w0_over_wg) -
                                  edges.begin()));
    const model::DeckGeometry& g = point.deck.geometry;
    const double travel_m = r.travel_m;
    EXPECT_EQ(at("travel_m"), travel_m);
    EXPECT_EQ(at("travel_bound_m"), model::CornerTravelBound(g, {r.x_m, r.y_m, r.theta_rad}));
    EXPECT_EQ(at("travel_end_m"),
              model::CornerTravelAt(g, {r.x_end_m, r.y_end_m, r.theta_end_rad}));
    EXPECT_DOUBLE_EQ(at("margin_m"), 0.004 * g.length_m - travel_m);
    EXPECT_DOUBLE_EQ(at("margin_norm"), (0.004 * g.length_m - travel_m) / L_e);
    impacts += r.impacts;
  }
  EXPECT_GT(impacts, 0);
}

TEST(MultiSpanResponses, EachNameSatisfiesItsDefinition) {
  CellGrid grid;
  grid.source = "spec.toml";
  grid.family = "multi-span";
  grid.axes = {Axis{"spans", ParameterKind::kNumber, {1.0, 3.0}, {}, "list"},
               Axis{"a_deg", ParameterKind::kNumber, {0.0, 30.0}, {}, "list"}};
  grid.fixed = {{"W_over_L", ParameterKind::kNumber, 0.3, ""},
                {"Pi_delta", ParameterKind::kNumber, 1.0, ""},
                {"delta_over_L", ParameterKind::kNumber, 0.002, ""},
                {"mu", ParameterKind::kNumber, 0.1, ""},
                {"seat_over_L", ParameterKind::kNumber, 0.02, ""}};
  LimitState rotation;
  rotation.name = "rotation";
  rotation.kind = LimitStateKind::kRotation;
  rotation.threshold = 0.01;
  grid.limit_states = {rotation};
  const MultiSpanEvaluator evaluator(grid);
  ASSERT_EQ(evaluator.Responses().size(), 3u * 9u + 6u);
  for (std::uint64_t c = 0; c < grid.CellCount(); ++c) {
    SCOPED_TRACE("cell " + std::to_string(c));
    const std::vector<std::size_t> index = grid.AxisIndex(c);
    const CellOutcome out = evaluator.Evaluate(index);
    ASSERT_EQ(out.status, kStatusOk) << out.status_text;
    const auto at = [&](const std::string& name) { return ValueOf(evaluator, out, name); };
    const int spans = index[0] == 0 ? 1 : 3;
    const bool skewed = index[1] == 1;
    const double L_e = at("L_e");
    const double w_g = 2.0 * std::numbers::pi;  // T_g = 1 s
    EXPECT_DOUBLE_EQ(L_e, 0.5 * kG / (w_g * w_g));
    EXPECT_EQ(at("a_g"), 0.5 * kG);
    EXPECT_DOUBLE_EQ(at("delta"), 1.0 * L_e);
    EXPECT_DOUBLE_EQ(at("L"), at("delta") / 0.002);
    double theta_norm_max = 0.0;
    for (int d = 0; d < 3; ++d) {
      const std::string s = "_d" + std::to_string(d);
      if (d >= spans) {
        for (const char* stem : {"x_norm", "y_norm", "theta_norm", "margin_norm", "theta_m",
                                 "travel_m", "travel_end_m", "margin_m", "travel_bound_m"}) {
          EXPECT_TRUE(std::isnan(at(stem + s))) << stem << s;
        }
        continue;
      }
      const double seat_m = 0.02 * at("L");
      EXPECT_DOUBLE_EQ(at("margin_m" + s), seat_m - at("travel_m" + s));
      EXPECT_DOUBLE_EQ(at("margin_norm" + s), at("margin_m" + s) / L_e);
      EXPECT_GE(at("travel_m" + s), at("travel_end_m" + s));
      // The bound from the maxima holds the exact travel (equal to rounding without rotation).
      EXPECT_GE(at("travel_bound_m" + s), at("travel_m" + s) * (1.0 - 1e-12));
      theta_norm_max = std::max(theta_norm_max, at("theta_norm" + s));
      // A deck without skew moves only along x [docs/theory.md §4 fact 3]; a skewed one turns.
      EXPECT_GT(at("x_norm" + s), 0.0);
      if (!skewed) {
        EXPECT_LT(std::abs(at("y_norm" + s)), 1e-9);
        EXPECT_LT(std::abs(at("theta_m" + s)), 1e-12);
        continue;
      }
      EXPECT_GT(at("theta_m" + s), 0.0);
      // Identical uniform spans: rho^2 = (L^2 + W^2 / cos^2 a) / 12, W = 0.3 L.
      const double L = at("L"), W = 0.3 * L, cos_a = std::cos(std::numbers::pi / 6.0);
      const double rho = std::sqrt((L * L + W * W / (cos_a * cos_a)) / 12.0);
      EXPECT_NEAR(at("theta_norm" + s), at("theta_m" + s) * rho / L_e,
                  1e-12 * at("theta_norm" + s));
    }
    EXPECT_EQ(at("theta_norm_max"), theta_norm_max);
    if (skewed) {
      EXPECT_GT(at("impacts"), 0.0);
    }
  }
}

}  // namespace
}  // namespace skewbridge::spectra::evaluator_responses_test
