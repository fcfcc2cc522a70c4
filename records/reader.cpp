#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "records/ground_motion.h"
#include "records/readers/readers.h"
#include "solver/common/error.h"
#include "solver/common/file_kind.h"

namespace skewbridge::records {
namespace {

using detail::FindNoCase;
using detail::Line;
using detail::StartsWithNoCase;
using detail::Trim;

constexpr std::size_t kEsmHeaderScan = 80;

std::string Lowered(std::string_view text) {
  std::string out;
  for (char c : Trim(text)) {
    if (c != ' ') out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

const std::pair<Format, std::string_view> kFormatNames[] = {
    {Format::kAuto, "auto"},       {Format::kAt2, "at2"},
    {Format::kEsm, "esm"},         {Format::kItsak, "itsak"},
    {Format::kCosmos, "cosmos"},   {Format::kCsmip, "csmip"},
    {Format::kSmc, "smc"},         {Format::kSmtk, "smtk"},
    {Format::kPlainText, "plain"}, {Format::kTimeSeries, "time-acc"},
};

bool LooksLikeTimeSeries(const std::vector<Line>& lines) {
  double previous = 0.0;
  std::size_t rows = 0;
  for (const Line& line : lines) {
    if (detail::IsBlank(line.text)) continue;
    const std::vector<std::string_view> tokens = detail::Tokens(line.text);
    if (tokens.size() != 2 || !detail::IsNumericLine(tokens[0])) return false;
    const double t = detail::ParseNumber(tokens[0], "", line.number);
    if (rows > 0 && !(t > previous)) return false;
    previous = t;
    ++rows;
  }
  return rows >= 2;
}

}  // namespace

std::string_view FormatName(Format format) {
  for (const auto& [f, name] : kFormatNames) {
    if (f == format) return name;
  }
  return "?";
}

std::optional<Format> ParseFormat(std::string_view text) {
  const std::string s = Lowered(text);
  for (const auto& [f, name] : kFormatNames) {
    if (s == name) return f;
  }
  return std::nullopt;
}

Format DetectFormat(std::string_view text, std::string_view source) {
  const std::vector<Line> lines = detail::SplitLines(text);
  std::size_t first = 0;
  while (first < lines.size() && detail::IsBlank(lines[first].text)) ++first;
  if (first == lines.size()) {
    throw InputError::AtLine(source, 1, "the file is empty (no header, no samples)");
  }
  const std::string_view head = Trim(lines[first].text);
  const auto any_line_starts = [&](std::size_t count, std::string_view prefix) {
    for (std::size_t i = first; i < lines.size() && i < first + count; ++i) {
      if (StartsWithNoCase(Trim(lines[i].text), prefix)) return true;
    }
    return false;
  };
  if (StartsWithNoCase(head, "EVENT_NAME:") ||
      any_line_starts(kEsmHeaderScan, "SAMPLING_INTERVAL_S:")) {
    return Format::kEsm;
  }
  if (FindNoCase(head, "(Format v") != std::string_view::npos) return Format::kCosmos;
  if (head.size() > 2 && std::isdigit(static_cast<unsigned char>(head[0])) && head[1] == ' ' &&
      FindNoCase(head, "ACCELEROGRAM") != std::string_view::npos) {
    return Format::kSmc;
  }
  if (StartsWithNoCase(head, "CORRECTED ACCELEROGRAM") ||
      StartsWithNoCase(head, "UNCORRECTED ACCELEROGRAM")) {
    return Format::kCsmip;
  }
  if (StartsWithNoCase(head, "Event Date") || any_line_starts(16, "Time Increment")) {
    return Format::kSmtk;
  }
  const std::vector<std::string_view> head_tokens = detail::Tokens(head);
  if (head_tokens.size() >= 3 && StartsWithNoCase(head_tokens.back(), "Values") &&
      first + 1 < lines.size() && StartsWithNoCase(Trim(lines[first + 1].text), "(")) {
    return Format::kItsak;
  }
  for (std::size_t i = first; i < lines.size() && i < first + 12; ++i) {
    if (FindNoCase(lines[i].text, "NPTS") != std::string_view::npos) return Format::kAt2;
  }
  for (std::size_t i = first; i < lines.size(); ++i) {
    if (!detail::IsBlank(lines[i].text) && !detail::IsNumericLine(lines[i].text)) {
      throw InputError::AtLine(
          source, lines[i].number,
          "unrecognised record format: line is neither a known header nor numbers (formats: "
          "at2, esm, itsak, cosmos, csmip, smc, smtk, plain, time-acc)");
    }
  }
  return LooksLikeTimeSeries(lines) ? Format::kTimeSeries : Format::kPlainText;
}

namespace {

GroundMotion ParseAnyFormat(std::string_view text, std::string_view source,
                            const ReadOptions& options) {
  const Format format =
      options.format == Format::kAuto ? DetectFormat(text, source) : options.format;
  const std::vector<Line> lines = detail::SplitLines(text);
  if (std::all_of(lines.begin(), lines.end(),
                  [](const Line& line) { return detail::IsBlank(line.text); })) {
    throw InputError::AtLine(source, 1, "the file is empty (no header, no samples)");
  }
  switch (format) {
    case Format::kAt2:
      return detail::ParseAt2(lines, source, options);
    case Format::kEsm:
      return detail::ParseEsm(lines, source, options);
    case Format::kItsak:
      return detail::ParseItsak(lines, source, options);
    case Format::kCosmos:
      return detail::ParseCosmos(lines, source, options);
    case Format::kCsmip:
      return detail::ParseCsmip(lines, source, options);
    case Format::kSmc:
      return detail::ParseSmc(lines, source, options);
    case Format::kSmtk:
      return detail::ParseSmtk(lines, source, options);
    case Format::kPlainText:
      return detail::ParsePlainText(lines, source, options);
    case Format::kTimeSeries:
      return detail::ParseTimeSeries(lines, source, options);
    case Format::kAuto:
      break;
  }
  throw InputError::AtLine(source, 0, "no reader for the requested format");
}

std::string Shown(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

}  // namespace

GroundMotion ParseRecord(std::string_view text, std::string_view source,
                         const ReadOptions& options) {
  GroundMotion motion = ParseAnyFormat(text, source, options);
  double pga_mps2 = 0.0;
  for (double a : motion.acc_mps2) pga_mps2 = std::max(pga_mps2, std::abs(a));
  if (pga_mps2 > options.max_pga_g * kStandardGravity_mps2) {
    throw InputError::AtLine(
        source, 0,
        "PGA " + Shown(pga_mps2) + " m/s^2 (" + Shown(pga_mps2 / kStandardGravity_mps2) +
            " g) read in " + motion.original_units +
            (options.units ? " as given" : " as the file states") + " is above " +
            Shown(options.max_pga_g) +
            " g, beyond any recorded ground motion; allowed: the record's true units (--units "
            "of records info, units of a record set), or a larger max_pga_g (--max-pga-g) if "
            "the record means it");
  }
  return motion;
}

GroundMotion ReadRecord(const std::filesystem::path& path, const ReadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError::AtLine(path.string(), 0, "record file: " + WhyUnreadable(path));
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) {
    throw InputError::AtLine(path.string(), 0, "error while reading the record file");
  }
  return ParseRecord(buffer.view(), path.string(), options);
}

}  // namespace skewbridge::records
