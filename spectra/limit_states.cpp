#include "spectra/limit_states.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>

#include "solver/common/error.h"

namespace skewbridge::spectra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::optional<std::size_t> Column(std::span<const ResponseInfo> responses, std::string_view name) {
  for (std::size_t r = 0; r < responses.size(); ++r) {
    if (responses[r].name == name) return r;
  }
  return std::nullopt;
}

// The column `<stem>` of a single-deck family, else the columns `<stem>_d0`, `<stem>_d1`, ... in
// deck order (none when both are absent).
std::vector<std::size_t> DeckColumns(std::span<const ResponseInfo> responses,
                                     const std::string& stem) {
  if (const std::optional<std::size_t> c = Column(responses, stem)) return {*c};
  std::vector<std::size_t> out;
  for (int d = 0;; ++d) {
    const std::optional<std::size_t> c = Column(responses, stem + "_d" + std::to_string(d));
    if (!c) break;
    out.push_back(*c);
  }
  return out;
}

std::string Field(const LimitState& ls) {
  return "limit_states." +
         (ls.kind == LimitStateKind::kResponse ? "response." + ls.response : ls.name);
}

}  // namespace

std::string LimitStateKindName(LimitStateKind kind) {
  switch (kind) {
    case LimitStateKind::kUnseating:
      return "unseating";
    case LimitStateKind::kRotation:
      return "rotation";
    case LimitStateKind::kSeatDisplacement:
      return "seat_displacement";
    case LimitStateKind::kResidual:
      return "residual";
    case LimitStateKind::kJointClosing:
      return "joint_closing";
    case LimitStateKind::kResponse:
      return "response";
  }
  return "response";
}

std::pair<std::string, std::string> LimitStateResponseNames(const LimitState& ls) {
  return {"ls_" + ls.name + "_demand", "ls_" + ls.name};
}

std::string LimitStateDemandUnit(const LimitState& ls, std::span<const ResponseInfo> inner) {
  switch (ls.kind) {
    case LimitStateKind::kUnseating:
    case LimitStateKind::kJointClosing:
      return "1";
    case LimitStateKind::kRotation:
      return "rad";
    case LimitStateKind::kSeatDisplacement:
    case LimitStateKind::kResidual:
      return "m";
    case LimitStateKind::kResponse:
      break;
  }
  const std::optional<std::size_t> c = Column(inner, ls.response);
  return c ? inner[*c].unit : "1";
}

LimitStateEvaluator::LimitStateEvaluator(std::unique_ptr<CellEvaluator> inner, const CellGrid& grid)
    : CellEvaluator(inner->policies()),
      inner_(std::move(inner)),
      inner_responses_(inner_->Responses()) {
  const std::span<const ResponseInfo> r(inner_responses_);
  const std::string family = "family '" + grid.family + "'";
  for (const LimitState& ls : grid.limit_states) {
    Plan plan;
    plan.ls = ls;
    const std::string field = Field(ls);
    switch (ls.kind) {
      case LimitStateKind::kRotation:
        plan.columns = DeckColumns(r, "theta_m");
        if (plan.columns.empty()) {
          throw InputError::AtField(ls.at, field,
                                    family +
                                        " stores no rotation in rad (theta_m); use "
                                        "[limit_states.response] on a response it stores");
        }
        break;
      case LimitStateKind::kSeatDisplacement:
      case LimitStateKind::kResidual:
      case LimitStateKind::kUnseating: {
        const bool end = ls.kind == LimitStateKind::kResidual;
        plan.columns = DeckColumns(r, end ? "travel_end_m" : "travel_m");
        if (plan.columns.empty()) {
          throw InputError::AtField(ls.at, field,
                                    "needs the corner travel of each deck relative to its "
                                    "seat, which " +
                                        family +
                                        " does not store; allowed here: rotation, "
                                        "joint_closing, response");
        }
        if (ls.kind != LimitStateKind::kUnseating) break;
        const std::size_t decks = plan.columns.size();
        if (ls.seat_m.empty()) {
          plan.margins = DeckColumns(r, "margin_m");
          if (plan.margins.size() != decks) {
            throw InputError::AtField(
                ls.at, field,
                "needs seat widths: give seat_over_L or seat_m (axis or fixed), or unseating = "
                "{seat_m = [...]} (m, one or one per support line)");
          }
        } else if (ls.seat_m.size() == 1) {
          plan.seats_m.assign(decks, ls.seat_m.front());
        } else if (grid.FindAxis("spans") != nullptr) {
          // The last abutment is line 1, 2, ... as the cell has 1, 2, ... spans.
          throw InputError::AtField(ls.at, field + ".seat_m",
                                    "one seat width per support line needs a fixed number of "
                                    "spans (spans is an axis); give one seat width, "
                                    "seat_over_L or seat_m");
        } else if (ls.seat_m.size() == decks + 1) {
          // Deck i rests on support lines i and i + 1; its corners are all bounded by the same
          // travel, so the narrower seat governs.
          for (std::size_t d = 0; d < decks; ++d) {
            plan.seats_m.push_back(std::min(ls.seat_m[d], ls.seat_m[d + 1]));
          }
        } else {
          throw InputError::AtField(
              ls.at, field + ".seat_m",
              fmt::format("give one seat width or one per support line ({} for {} deck{}: "
                          "abutment, pier lines, abutment); got {}",
                          decks + 1, decks, decks == 1 ? "" : "s", ls.seat_m.size()));
        }
        break;
      }
      case LimitStateKind::kJointClosing:
        if (const std::optional<std::size_t> c = Column(r, "impacts")) {
          plan.columns = {*c};
        } else {
          throw InputError::AtField(ls.at, field, family + " stores no impact count");
        }
        break;
      case LimitStateKind::kResponse:
        if (const std::optional<std::size_t> c = Column(r, ls.response)) {
          plan.columns = {*c};
        } else {
          std::string allowed;
          for (const ResponseInfo& info : inner_responses_) {
            allowed += (allowed.empty() ? "" : ", ") + info.name;
          }
          throw InputError::AtField(ls.at, field, "unknown response; allowed: " + allowed);
        }
        break;
    }
    plans_.push_back(std::move(plan));
  }
  // The inner responses as they are (a failed cell's are already NaN), then each limit state's
  // demand and exceedance (NaN for a failed cell).
  using V = const CellValues&;
  for (std::size_t i = 0; i < inner_responses_.size(); ++i) {
    table_.AddAlways(inner_responses_[i], [i](V v) { return v.inner[i]; });
  }
  for (const Plan& p : plans_) {
    const LimitState& ls = p.ls;
    const auto [demand, exceeded] = LimitStateResponseNames(ls);
    std::string what, when;
    switch (ls.kind) {
      case LimitStateKind::kUnseating:
        what = "largest corner travel normal to the end line over the seat width, over the decks";
        when = "a corner travels beyond its seat (margin < 0)";
        break;
      case LimitStateKind::kRotation:
        what = "largest |theta| over the decks";
        when = fmt::format("the rotation exceeds {} rad", ls.threshold);
        break;
      case LimitStateKind::kSeatDisplacement:
        what = "largest corner travel normal to the end line, over the decks";
        when = fmt::format("a corner travels more than {} m relative to its seat", ls.threshold);
        break;
      case LimitStateKind::kResidual:
        what = "largest residual corner travel normal to the end line, over the decks";
        when = fmt::format("the residual travel exceeds {} m", ls.threshold);
        break;
      case LimitStateKind::kJointClosing:
        what = "number of impacts";
        when = "a gap closes (at least one impact)";
        break;
      case LimitStateKind::kResponse:
        what = ls.response;
        when = fmt::format("{} exceeds {}", ls.response, ls.threshold);
        break;
    }
    table_.Add({demand, LimitStateDemandUnit(ls, inner_responses_),
                "limit state " + ls.name + ": demand, " + what},
               [p](V v) { return Assess(p, v.inner).first; });
    table_.Add({exceeded, "1",
                "limit state " + ls.name + ": 1 when " + when + ", else 0; NaN if the cell failed"},
               [p](V v) { return Assess(p, v.inner).second; });
  }
}

CellOutcome LimitStateEvaluator::Evaluate(std::span<const std::size_t> axis_index) const {
  return WithLimitStates(inner_->Evaluate(axis_index));
}

CellOutcome LimitStateEvaluator::EvaluateScaled(std::span<const std::size_t> axis_index,
                                                double factor) const {
  const RecordScaling* scaling = inner_->record_scaling();
  SB_DEMAND(scaling != nullptr, "the sweep scales no record to an intensity");
  return WithLimitStates(scaling->EvaluateScaled(axis_index, factor));
}

std::pair<double, double> LimitStateEvaluator::Assess(const Plan& p, const std::vector<double>& v) {
  double demand = kNaN, exceeded = kNaN;
  switch (p.ls.kind) {
    case LimitStateKind::kUnseating: {
      demand = 0.0;
      bool off = false;
      for (std::size_t d = 0; d < p.columns.size(); ++d) {
        const double travel = v[p.columns[d]];
        double seat = 0.0;
        if (p.margins.empty()) {
          seat = p.seats_m[d];
          off = off || travel > seat;
        } else {
          const double margin = v[p.margins[d]];
          seat = margin + travel;
          off = off || margin < 0.0;
        }
        // A zero seat: any travel is beyond it (ratio inf); none is 0.
        demand = std::max(demand, travel > 0.0 ? travel / seat : 0.0);
      }
      exceeded = off ? 1.0 : 0.0;
      break;
    }
    case LimitStateKind::kRotation:
    case LimitStateKind::kSeatDisplacement:
    case LimitStateKind::kResidual:
    case LimitStateKind::kResponse:
      demand = -std::numeric_limits<double>::infinity();
      for (std::size_t c : p.columns) demand = std::max(demand, v[c]);
      exceeded = demand > p.ls.threshold ? 1.0 : 0.0;
      break;
    case LimitStateKind::kJointClosing:
      demand = v[p.columns.front()];
      exceeded = demand >= 1.0 ? 1.0 : 0.0;
      break;
  }
  if (std::isnan(demand)) exceeded = kNaN;
  return {demand, exceeded};
}

CellOutcome LimitStateEvaluator::WithLimitStates(CellOutcome out) const {
  if (!CheckResponseCount(out, inner_responses_.size())) return out;
  out.responses = table_.Values({out.responses}, out.status == kStatusOk);
  return out;
}

}  // namespace skewbridge::spectra
