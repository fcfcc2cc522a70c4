#pragma once
/// @file
/// The mode of every contact of a run and the closed set those modes make [docs/theory.md §3.1,
/// §3.7]: one owner, so the closed contacts' list and count can never disagree with the modes.

#include <cstdint>
#include <vector>

#include "solver/dynamics/run_result.h"

namespace skewbridge::dynamics {

/// The mode of one contact: open, or closed and sticking, sliding with a sign of the slip
/// velocity gamma_T, or frictionless (mu = 0: no tangential row).
enum class ContactMode : std::uint8_t {
  kOpen,
  kStick,
  kSlidePositive,  ///< gamma_T > 0: friction lambda_T = -mu lambda_N
  kSlideNegative,  ///< gamma_T < 0: friction lambda_T = +mu lambda_N
  kFrictionless,
};

/// True for every mode but kOpen.
constexpr bool IsClosed(ContactMode mode) { return mode != ContactMode::kOpen; }

/// True for the two sliding modes.
constexpr bool IsSliding(ContactMode mode) {
  return mode == ContactMode::kSlidePositive || mode == ContactMode::kSlideNegative;
}

/// The sliding mode of a slip sign s (s > 0: kSlidePositive, s < 0: kSlideNegative, 0: kStick).
constexpr ContactMode SlideOrStick(int slip_sign) {
  return slip_sign > 0   ? ContactMode::kSlidePositive
         : slip_sign < 0 ? ContactMode::kSlideNegative
                         : ContactMode::kStick;
}

/// The slip sign of a mode: +1 or -1 while sliding, 0 otherwise.
constexpr int SlipSign(ContactMode mode) {
  return mode == ContactMode::kSlidePositive ? 1 : mode == ContactMode::kSlideNegative ? -1 : 0;
}

/// The state code a history stores for a mode (a frictionless contact counts as sliding).
constexpr ContactState HistoryState(ContactMode mode) {
  switch (mode) {
    case ContactMode::kOpen:
      return ContactState::kOpen;
    case ContactMode::kStick:
      return ContactState::kStick;
    case ContactMode::kSlidePositive:
    case ContactMode::kFrictionless:
      return ContactState::kSlidePositive;
    case ContactMode::kSlideNegative:
      return ContactState::kSlideNegative;
  }
  return ContactState::kOpen;
}

/// The modes of the n contacts of a model (all open at first) and their closed set: the closed
/// contacts' ids in ascending order and their count, updated with every change of a mode.
class ContactModes {
 public:
  /// n_contacts open contacts.
  explicit ContactModes(int n_contacts)
      : modes_(static_cast<std::size_t>(n_contacts), ContactMode::kOpen) {
    closed_ids_.reserve(modes_.size());
  }

  /// Number of contacts.
  int size() const { return static_cast<int>(modes_.size()); }
  /// The mode of contact c.
  ContactMode operator[](int c) const { return modes_[static_cast<std::size_t>(c)]; }
  /// True when contact c is closed.
  bool closed(int c) const { return IsClosed((*this)[c]); }
  /// Sets the mode of contact c (and the closed set with it).
  void Set(int c, ContactMode mode) {
    ContactMode& m = modes_[static_cast<std::size_t>(c)];
    const bool was_closed = IsClosed(m);
    m = mode;
    if (was_closed != IsClosed(mode)) {
      closed_ids_.clear();
      for (int i = 0; i < size(); ++i) {
        if (closed(i)) {
          closed_ids_.push_back(i);
        }
      }
    }
  }
  /// The closed contacts, ascending.
  const std::vector<int>& closed_ids() const { return closed_ids_; }
  /// Number of closed contacts.
  int closed_count() const { return static_cast<int>(closed_ids_.size()); }
  /// True when any contact is closed.
  bool any_closed() const { return !closed_ids_.empty(); }
  /// True when some contact sticks.
  bool any_stick() const {
    for (ContactMode m : modes_) {
      if (m == ContactMode::kStick) {
        return true;
      }
    }
    return false;
  }

 private:
  std::vector<ContactMode> modes_;
  std::vector<int> closed_ids_;  // the contacts with a closed mode, ascending
};

}  // namespace skewbridge::dynamics
