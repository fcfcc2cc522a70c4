#include "solver/common/error.h"

#include <cstdio>
#include <cstdlib>

namespace skewbridge {

InputError InputError::AtLine(std::string_view file, long line, std::string_view problem) {
  // Appends one piece at a time: g++ 12 warns falsely (-Wrestrict) on chained operator+.
  std::string message(file);
  if (line > 0) {
    message.push_back(':');
    message.append(std::to_string(line));
  }
  message.append(": ");
  message.append(problem);
  return InputError(message);
}

InputError InputError::AtField(std::string_view source, std::string_view field,
                               std::string_view problem) {
  std::string message(source);
  message += ": ";
  message += field;
  message += ": ";
  message += problem;
  return InputError(message);
}

void AbortOnBrokenInvariant(const char* condition, const char* file, int line,
                            const char* message) {
  std::fprintf(stderr, "skewbridge: internal error at %s:%d: %s (%s)\n", file, line, message,
               condition);
  std::abort();
}

}  // namespace skewbridge
