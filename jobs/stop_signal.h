#pragma once
/// @file
/// SIGTERM / SIGINT as a stop request for a running sweep: the handler only sets a flag that
/// the sweep runner polls between cells (SweepOptions::stop).

#include <csignal>

namespace skewbridge::jobs {

/// Installs handlers for SIGTERM and SIGINT on construction and restores the previous ones on
/// destruction. @pre at most one alive per process.
class StopSignal {
 public:
  StopSignal();
  StopSignal(const StopSignal&) = delete;
  StopSignal& operator=(const StopSignal&) = delete;
  ~StopSignal();
  /// The flag, non-zero once a signal arrived (the signal number).
  const volatile std::sig_atomic_t* Flag() const;
  /// The signal that arrived, or 0.
  int Received() const;
};

}  // namespace skewbridge::jobs
