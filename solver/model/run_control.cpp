#include "solver/model/run_control.h"

namespace skewbridge::model {

double RunControl::EndTime(double excitation_duration_s) const {
  return end_time_s ? *end_time_s : excitation_duration_s + tail_s;
}

}  // namespace skewbridge::model
