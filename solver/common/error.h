#pragma once
/// @file
/// The error categories of skewbridge (see docs/architecture.md, "Failures"):
/// bad input throws InputError; a broken invariant aborts through SB_DEMAND / SB_ASSERT;
/// an expected numerical outcome is a returned status, never an exception.

#include <stdexcept>
#include <string>
#include <string_view>

namespace skewbridge {

/// Bad user input (a file, a field, an option): the message names where and what is allowed.
/// Libraries throw it; the command-line program prints `what()` on one line and exits non-zero.
class InputError : public std::runtime_error {
 public:
  /// A message already naming its source, e.g. "model.toml: deck.W: must be > 0 (got -1)".
  explicit InputError(const std::string& message) : std::runtime_error(message) {}

  /// "FILE:LINE: problem" (line 0 is left out, for whole-file problems).
  static InputError AtLine(std::string_view file, long line, std::string_view problem);

  /// "SOURCE: FIELD: problem" for a named field of a structured input (TOML key, option).
  static InputError AtField(std::string_view source, std::string_view field,
                            std::string_view problem);
};

/// Aborts with a message: used only by SB_DEMAND / SB_ASSERT for broken invariants (bugs).
[[noreturn]] void AbortOnBrokenInvariant(const char* condition, const char* file, int line,
                                         const char* message);

}  // namespace skewbridge

/// Always-on invariant check: a failure is a bug in skewbridge, never a user error.
#define SB_DEMAND(condition, message)                                                \
  do {                                                                               \
    if (!(condition)) {                                                              \
      ::skewbridge::AbortOnBrokenInvariant(#condition, __FILE__, __LINE__, message); \
    }                                                                                \
  } while (false)

#ifdef NDEBUG
/// Debug-only invariant check, for the hot paths.
#define SB_ASSERT(condition, message) \
  do {                                \
  } while (false)
#else
#define SB_ASSERT(condition, message) SB_DEMAND(condition, message)
#endif
