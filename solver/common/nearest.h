#pragma once
/// @file
/// Nearest names for error messages: "did you mean ...?" after a misspelt key, option,
/// sub-command or record label.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace skewbridge {

/// The edit distance of typing slips: the fewest one-character insertions, deletions,
/// substitutions and swaps of neighbours that turn `a` into `b` (optimal string alignment;
/// characters compared case-insensitively).
std::size_t EditDistance(std::string_view a, std::string_view b);

/// How far `word` is from `name` as a slip: the edit distance, or one more than the distance to
/// `name` without its last "_unit" or ".ext" part (`skew` is 1 from `skew_deg`, `RSN1` 1 from
/// `RSN1.AT2`), whichever is smaller.
std::size_t SlipDistance(std::string_view word, std::string_view name);

/// The `max_count` names of `names` nearest to `word` by SlipDistance, nearest first (ties in
/// the order given); with `plausible_only`, only those close enough to be a slip (a distance of
/// at most a third of the longer word, and at least 1 allowed).
std::vector<std::string> NearestNames(std::string_view word, const std::vector<std::string>& names,
                                      std::size_t max_count, bool plausible_only);

/// "; did you mean `NAME`?" for the plausible nearest name, or "" when none is close.
std::string DidYouMean(std::string_view word, const std::vector<std::string>& names);

}  // namespace skewbridge
