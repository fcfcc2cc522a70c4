// libFuzzer target of one record reader: the format is fixed at build time (SB_FUZZ_FORMAT, a
// FormatName or "auto" for detection by content). The first byte chooses which of dt and units
// the "user" gives, so that both the header paths and the user-option paths are explored.
// Malformed input must end in InputError; anything else (crash, sanitizer report, other
// exception, hang) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "records/ground_motion.h"
#include "records/measures.h"
#include "solver/common/error.h"

#ifndef SB_FUZZ_FORMAT
#error "SB_FUZZ_FORMAT must name the reader under test"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skewbridge::records;
  if (size == 0) return 0;
  const std::uint8_t flags = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  ReadOptions options;
  options.format = ParseFormat(SB_FUZZ_FORMAT).value();
  if (flags & 1) options.dt_s = 0.01;
  if (flags & 2) options.units = (flags & 4) ? Units::kG : Units::kCentimetresPerSecond2;
  options.channel = 1 + ((flags >> 3) & 3);
  try {
    const GroundMotion motion = ParseRecord(text, "fuzz-input", options);
    // Records that load must also have measures (or a clean InputError for no energy).
    if (motion.npts() <= 1 << 16) ComputeMeasures(motion);
  } catch (const skewbridge::InputError&) {
  }
  return 0;
}
