// libFuzzer target of the excitation-file reader of model files (ParseExcitationSamples). The
// first byte chooses whether the model file gives dt_s and which factor units x scale it
// applies, so that one- and two-column files, the dt check and the overflow check are all
// explored. Malformed input must end in InputError; anything else (crash, sanitizer report,
// other exception, hang) is a finding. What loads must keep the reader's promises.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "records/excitations.h"
#include "solver/common/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace skewbridge::records;
  if (size == 0) return 0;
  const std::uint8_t flags = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  std::optional<double> dt_s;
  if (flags & 1) dt_s = (flags & 2) ? 0.01 : 0.005;
  const double factors[4] = {1.0, kStandardGravity_mps2, 0.01, 1e300};
  const double to_mps2 = factors[(flags >> 2) & 3];
  try {
    const ExcitationSamples s = ParseExcitationSamples(text, "fuzz-input", dt_s, to_mps2);
    if (s.values_mps2.size() < 2 || !(s.dt_s > 0.0) || !std::isfinite(s.dt_s)) __builtin_trap();
    for (double v : s.values_mps2) {
      if (!std::isfinite(v)) __builtin_trap();
    }
    if (dt_s && std::abs(s.dt_s - *dt_s) > 1e-9 * *dt_s) __builtin_trap();
  } catch (const skewbridge::InputError&) {
  }
  return 0;
}
