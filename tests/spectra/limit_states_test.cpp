// The limit states of a single-deck family evaluated in process (no MPI, so the sanitizer
// build runs them too): a subsystem deck at zero skew neither moves transversally nor rotates
// [docs/theory.md §4 fact 3], so its corner travel is its longitudinal maximum (to rounding);
// an inner cell without its responses stays an internal error.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "spectra/grid.h"
#include "spectra/limit_states.h"
#include "spectra/spectra_evaluator.h"

namespace skewbridge::spectra::limit_states_test {
namespace {

std::size_t ColumnOf(const std::vector<ResponseInfo>& responses, const std::string& name) {
  for (std::size_t c = 0; c < responses.size(); ++c) {
    if (responses[c].name == name) return c;
  }
  ADD_FAILURE() << "no response " << name;
  return 0;
}

TEST(LimitStates, SubsystemAtZeroSkewTravelsAsFarAsItsLongitudinalMaximum) {
  CellGrid grid;
  grid.source = "spec.toml";
  grid.family = "subsystem";
  grid.axes = {Axis{"Pi_delta", ParameterKind::kNumber, {0.25, 4.0}, {}, "list"}};
  grid.fixed = {{"a_deg", ParameterKind::kNumber, 0.0, ""},
                {"W_over_L", ParameterKind::kNumber, 0.3, ""},
                {"seat_over_L", ParameterKind::kNumber, 0.004, ""}};
  LimitState unseating;
  unseating.name = "unseating";
  unseating.kind = LimitStateKind::kUnseating;
  LimitState displacement;
  displacement.name = "seat_displacement";
  displacement.kind = LimitStateKind::kSeatDisplacement;
  displacement.threshold = 0.5;
  grid.limit_states = {unseating, displacement};
  const LimitStateEvaluator evaluator(std::make_unique<SpectraEvaluator>(grid), grid);
  const std::vector<ResponseInfo> r = evaluator.Responses();
  int exceeded = 0;
  for (std::size_t i = 0; i < 2; ++i) {
    const CellOutcome out = evaluator.Evaluate(std::vector<std::size_t>{i});
    ASSERT_EQ(out.status, kStatusOk);
    const std::vector<double>& v = out.responses;
    const double x_m = v[ColumnOf(r, "x_m")];
    ASSERT_GT(x_m, 0.0);
    // Rounding leaves a rotation of order 1e-18 rad: a travel of 1e-17 L beside x_m.
    EXPECT_LT(v[ColumnOf(r, "y_m")], 1e-12 * x_m);
    EXPECT_LT(v[ColumnOf(r, "theta_m")], 1e-15);
    EXPECT_NEAR(v[ColumnOf(r, "travel_m")], x_m, 1e-12 * x_m);
    EXPECT_LE(v[ColumnOf(r, "travel_end_m")], v[ColumnOf(r, "travel_m")]);
    const double seat_m = 0.004 * 250.0 * v[ColumnOf(r, "L_e")];  // L = L_over_Le L_e
    EXPECT_NEAR(v[ColumnOf(r, "margin_m")], seat_m - x_m, 1e-12 * seat_m);
    EXPECT_NEAR(v[ColumnOf(r, "ls_unseating_demand")], x_m / seat_m, 1e-12 * x_m / seat_m);
    EXPECT_EQ(v[ColumnOf(r, "ls_unseating")], x_m > seat_m ? 1.0 : 0.0);
    EXPECT_EQ(v[ColumnOf(r, "ls_seat_displacement_demand")], v[ColumnOf(r, "travel_m")]);
    EXPECT_EQ(v[ColumnOf(r, "ls_seat_displacement")], x_m > 0.5 ? 1.0 : 0.0);
    exceeded += x_m > seat_m ? 1 : 0;
  }
  // A gap of 0.25 L_e lets the deck travel past a seat of L_e; one of 4 L_e does not.
  EXPECT_EQ(exceeded, 1);
}

// An inner evaluator that declares one response and returns none.
class Silent final : public CellEvaluator {
 public:
  std::vector<ResponseInfo> Responses() const override { return {{"x", "m", "a response"}}; }
  CellOutcome Evaluate(std::span<const std::size_t>) const override { return {}; }
};

TEST(LimitStates, AnInnerCellWithoutItsResponsesIsAnInternalErrorNotPadded) {
  CellGrid grid;
  grid.source = "spec.toml";
  grid.family = "subsystem";
  grid.axes = {Axis{"Pi_delta", ParameterKind::kNumber, {1.0}, {}, "list"}};
  LimitState over;
  over.name = "over";
  over.kind = LimitStateKind::kResponse;
  over.response = "x";
  over.threshold = 1.0;
  grid.limit_states = {over};
  const LimitStateEvaluator evaluator(std::make_unique<Silent>(), grid);
  ASSERT_EQ(evaluator.Responses().size(), 3u);  // x, ls_over_demand, ls_over
  const CellOutcome out = evaluator.Evaluate(std::vector<std::size_t>{0});
  EXPECT_EQ(out.status, kStatusResponseCount);
  EXPECT_EQ(out.status_text,
            "internal error: the evaluator returned 0 responses for the 1 it declares");
  EXPECT_TRUE(out.responses.empty());
}

}  // namespace
}  // namespace skewbridge::spectra::limit_states_test
