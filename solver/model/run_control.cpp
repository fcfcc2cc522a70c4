#include "solver/model/run_control.h"

namespace skewbridge::model {

const char* ToString(Method method) {
  return method == Method::kTimeStepping ? "time-stepping" : "event-driven";
}

std::optional<Method> ParseMethod(std::string_view name) {
  if (name == "event-driven") return Method::kEventDriven;
  if (name == "time-stepping") return Method::kTimeStepping;
  return std::nullopt;
}

double RunControl::EndTime(double excitation_duration_s) const {
  return end_time_s ? *end_time_s : excitation_duration_s + tail_s;
}

}  // namespace skewbridge::model
