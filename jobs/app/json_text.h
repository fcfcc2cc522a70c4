#pragma once
/// @file
/// Text as a JSON string literal, for the sub-commands that print JSON (`modes --plan`,
/// `records info --json`).

#include <fmt/core.h>

#include <string>
#include <string_view>

namespace skewbridge::app {

/// `text` quoted as a JSON string: '"' and '\\' escaped, control characters as \u00XX (RFC 8259,
/// section 7); other bytes, UTF-8 included, pass through unchanged.
inline std::string JsonString(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<int>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace skewbridge::app
