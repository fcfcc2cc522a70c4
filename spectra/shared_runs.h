#pragma once
/// @file
/// One dynamic run for the cells that differ only along an axis of the limit states alone: a
/// seat width (seat_over_L, seat_m) enters the margins and the limit-state outcomes and moves no
/// deck. An evaluator keeps the last runs here, keyed by the cell with those axes at index 0,
/// and a cell whose run is kept takes its responses from it with its own seat widths. Cells are
/// evaluated in cube order (row-major), so with the seat axes last but `method` a grid of three
/// seat widths costs one run per three cells; a group split between two chunks runs twice,
/// never differently.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "spectra/grid.h"

namespace skewbridge::spectra {

/// Whether axis `key` enters the limit states alone (seat_over_L, seat_m).
inline bool LimitOnlyAxis(const std::string& key) {
  return key == "seat_over_L" || key == "seat_m";
}

/// The last dynamic runs of an evaluator (`Run`: whatever the cell's responses read besides its
/// seat widths), for the cells that differ from them only along limit-only axes. Not safe for
/// concurrent use: a sweep evaluates its cells one after the other on each rank.
template <typename Run>
class SharedRuns {
 public:
  /// Finds the limit-only axes of `grid`; keeps as many runs as there are cells between two
  /// values of the first limit-only axis (the sizes of the non-limit-only axes after it).
  explicit SharedRuns(const CellGrid& grid) {
    for (std::size_t k = 0; k < grid.axes.size(); ++k) {
      sizes_.push_back(grid.axes[k].Size());
      limit_only_.push_back(LimitOnlyAxis(grid.axes[k].key) ? 1 : 0);
      if (limit_only_.back()) {
        any_ = true;
      } else if (any_) {
        capacity_ *= grid.axes[k].Size();
      }
    }
  }

  /// Whether the grid has a limit-only axis (else every cell runs on its own).
  bool Active() const { return any_; }

  /// The run of the cell at `index`: a kept one when a cell with the same key ran last, else
  /// make() (whose result replaces the oldest kept run). @pre Active()
  template <typename Make>
  Run& Get(std::span<const std::size_t> index, Make&& make) {
    const std::uint64_t key = Key(index);
    for (Slot& s : slots_) {
      if (s.key == key && s.run) return *s.run;
    }
    if (slots_.size() < capacity_) slots_.emplace_back();
    Slot& s = slots_[next_];
    next_ = (next_ + 1) % capacity_;
    s.key = kNoKey;  // no cell's key until its run is made
    s.run.reset();
    s.run.emplace(make());
    s.key = key;
    return *s.run;
  }

 private:
  static constexpr std::uint64_t kNoKey = std::numeric_limits<std::uint64_t>::max();
  struct Slot {
    std::uint64_t key = kNoKey;
    std::optional<Run> run;
  };
  // The row-major index of the cell with its limit-only axes at 0.
  std::uint64_t Key(std::span<const std::size_t> index) const {
    std::uint64_t cell = 0;
    for (std::size_t k = 0; k < sizes_.size(); ++k) {
      cell = cell * sizes_[k] + (limit_only_[k] ? 0 : index[k]);
    }
    return cell;
  }
  std::vector<std::uint64_t> sizes_;      // [axis] values
  std::vector<std::uint8_t> limit_only_;  // [axis] 1 for a limit-only axis
  bool any_ = false;
  std::size_t capacity_ = 1;
  std::vector<Slot> slots_;
  std::size_t next_ = 0;
};

}  // namespace skewbridge::spectra
