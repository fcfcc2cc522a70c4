#pragma once
/// @file
/// Strict text scanning shared by the record readers: line splitting that tolerates every line
/// ending found in the wild, header key look-up, and number parsing that splits Fortran fields
/// packed without blanks and rejects anything that is not a finite number.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "records/ground_motion.h"

namespace skewbridge::records::detail {

/// One physical line of a file, without its line ending; `number` is 1-based.
struct Line {
  std::string_view text;
  long number = 0;
};

/// Splits text into lines ending in LF, CR LF, CR CR LF or a lone CR; a missing final newline is
/// fine. The views point into `text`.
std::vector<Line> SplitLines(std::string_view text);

/// `text` without leading and trailing blanks (space, tab, CR, LF, FF, VT, NUL).
std::string_view Trim(std::string_view text);

/// Case-insensitive ASCII comparison helpers.
bool StartsWithNoCase(std::string_view text, std::string_view prefix);
/// Position of `key` in `text` (case-insensitive) or npos.
std::size_t FindNoCase(std::string_view text, std::string_view key);

/// True when the line holds only blanks.
bool IsBlank(std::string_view text);

/// True when every token of the line parses as a finite number (and there is at least one).
bool IsNumericLine(std::string_view text);

/// One token as a finite number (the rules of ParseNumber), or nullopt: for readers that word
/// their own message.
std::optional<double> TryParseNumber(std::string_view token);

/// The mean step of a time column [s] rounded to 1e-9 s, which no printed time column resolves
/// (67.74 s / 13548 = 0.005000000000000001 -> 0.005); the step itself where it rounds to zero or
/// is too large for the product with 1e9 to be finite.
double RoundedTimeStep(double step_s);

/// Parses one token as a finite number: optional sign, digits with optional '.', optional
/// exponent introduced by E, e, D or d.
/// @throws InputError "SOURCE:LINE: ..." for a non-numeric token, NaN, infinity or overflow.
double ParseNumber(std::string_view token, std::string_view source, long line);

/// Parses a token as a count (a non-negative integer, "5372" or "5372." allowed).
/// @throws InputError "SOURCE:LINE: ..." otherwise.
long ParseCount(std::string_view token, std::string_view source, long line);

/// Appends the numbers of one data line. Blanks and commas separate numbers; so does a sign
/// that follows a digit or a '.', which splits Fortran fields packed without blanks
/// (`-1.234E-02-5.678E-03`).
/// @throws InputError naming source and line for any token that is not a finite number.
void AppendNumbers(const Line& line, std::string_view source, std::vector<double>& out);

/// The tokens of a line (split at blanks and commas, no sign splitting).
std::vector<std::string_view> Tokens(std::string_view text);

/// The token after `key` (case-insensitive) in `text`, skipping blanks, '=' and ':'.
std::optional<std::string_view> TokenAfter(std::string_view text, std::string_view key);

/// Parses a unit spelling found in a header; trailing punctuation and parentheses are dropped.
/// @throws InputError "SOURCE:LINE: unknown units 'X' (allowed: g, m/s^2, cm/s^2)".
Units UnitsFromHeader(std::string_view spelling, std::string_view source, long line);

/// Reconciles the units a file states (if any) with the units the user gave (if any).
/// @throws InputError when neither states them, or when both do and they disagree.
Units ResolveUnits(std::optional<Units> in_file, const ReadOptions& options,
                   std::string_view source, long line);

/// Reconciles the dt a file states (if any) with the one the user gave (if any).
/// @throws InputError when neither gives one, when it is not > 0, or when both disagree.
double ResolveDt(std::optional<double> in_file, const ReadOptions& options, std::string_view source,
                 long line);

/// Builds a GroundMotion: converts to m/s^2 and checks there is at least one sample.
/// @throws InputError "SOURCE:LINE: no samples" when `values` is empty.
GroundMotion MakeMotion(std::string_view source, Format format, Units units, double dt_s,
                        std::vector<double> values, long last_line);

}  // namespace skewbridge::records::detail
