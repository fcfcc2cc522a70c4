#pragma once
// A deterministic stand-in for the physics, used only by the tests of the sweep machinery:
// a pure function of the cell index with deliberately uneven cost (a hash decides how much
// real arithmetic a cell does) and some cells that fail with a status or throw.

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <stdexcept>
#include <thread>

#include "jobs/cell.h"
#include "jobs/sweep_spec.h"

namespace skewbridge::jobs::testing {

/// SplitMix64 finaliser: a well-mixed hash of the cell index.
inline std::uint64_t Mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// Status 1 ("ray") for cells whose hash is 3 mod 17; an exception for 5 mod 23.
class TestEvaluator final : public CellEvaluator {
 public:
  /// work: arithmetic iterations per cost unit (a cell costs 1..4 units, 1 in 50 costs 40);
  /// sleep_ms: added wall time per cell (kill tests), which never changes the results.
  TestEvaluator(const SweepSpec& spec, std::int64_t work, double sleep_ms)
      : shape_(spec.Shape()), work_(work), sleep_ms_(sleep_ms) {}

  std::vector<ResponseInfo> Responses() const override {
    return {{"x_peak", "1", "test response: iterated map of the cell coordinates"},
            {"theta_peak", "1", "test response: second iterated value"},
            {"cell_echo", "1", "the linear cell index, as a double"}};
  }

  std::vector<std::pair<std::int32_t, std::string>> StatusNames() const override {
    return {{1, "ray"}};
  }

  std::uint64_t Linear(std::span<const std::size_t> index) const {
    std::uint64_t cell = 0;
    for (std::size_t k = 0; k < shape_.size(); ++k) {
      cell = cell * shape_[k] + index[k];
    }
    return cell;
  }

  static bool Throws(std::uint64_t cell) { return Mix(cell) % 23 == 5; }
  static bool Fails(std::uint64_t cell) { return !Throws(cell) && Mix(cell) % 17 == 3; }

  CellOutcome Evaluate(std::span<const std::size_t> index) const override {
    const std::uint64_t cell = Linear(index);
    const std::uint64_t h = Mix(cell);
    if (sleep_ms_ > 0) {
      std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(sleep_ms_));
    }
    if (Throws(cell)) {
      throw std::runtime_error("test evaluator: injected exception");
    }
    const std::int64_t units = h % 50 == 0 ? 40 : 1 + static_cast<std::int64_t>(h % 4);
    const std::int64_t iterations = work_ * units;
    double x = 0.1 + static_cast<double>(h % 1000) * 1e-3;
    double y = 0.0;
    for (std::int64_t i = 0; i < iterations; ++i) {
      x = 3.9 * x * (1.0 - x);
      y += std::sin(x) * 1e-3;
    }
    CellOutcome out;
    out.status = Fails(cell) ? 1 : kStatusOk;
    out.status_text = out.status ? "test evaluator: injected ray" : "";
    out.responses = {x, y, static_cast<double>(cell)};
    out.stats.events = static_cast<std::int64_t>(h % 100);
    out.stats.steps = iterations;
    return out;
  }

 private:
  std::vector<std::size_t> shape_;
  std::int64_t work_;
  double sleep_ms_;
};

/// Wraps an evaluator and sets a stop flag after a given number of evaluations, as a signal
/// would.
class StoppingEvaluator final : public CellEvaluator {
 public:
  StoppingEvaluator(const CellEvaluator& inner, int stop_after, volatile std::sig_atomic_t* flag)
      : inner_(inner), stop_after_(stop_after), flag_(flag) {}
  std::vector<ResponseInfo> Responses() const override { return inner_.Responses(); }
  std::vector<std::pair<std::int32_t, std::string>> StatusNames() const override {
    return inner_.StatusNames();
  }
  CellOutcome Evaluate(std::span<const std::size_t> index) const override {
    if (++count_ >= stop_after_) {
      *flag_ = 15;
    }
    return inner_.Evaluate(index);
  }

 private:
  const CellEvaluator& inner_;
  int stop_after_;
  volatile std::sig_atomic_t* flag_;
  mutable int count_ = 0;
};

}  // namespace skewbridge::jobs::testing
