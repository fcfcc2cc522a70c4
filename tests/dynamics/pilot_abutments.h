#pragma once
// The pilot bridge's model file (docs/examples/pilot-bridge.toml) with an [abutments] section of a
// test's own, parsed as if it stood beside the examples: the compliant model-file tests'
// common ground (abutment_springs_test.cpp, abutment_walls_test.cpp).

#include <gtest/gtest.h>

#include <cstddef>
#include <fstream>
#include <sstream>
#include <string>

#include "solver/common/error.h"
#include "solver/model/model_file.h"

namespace skewbridge::dynamics::testing {

/// The folder docs/examples of the source tree.
inline std::string Examples() {
  return std::string(SKEWBRIDGE_TEST_DATA_DIR) + "/../../docs/examples";
}

/// The whole text of the file at `path`.
inline std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// `text` with its [abutments] section (up to the next section) replaced by `abutments`.
inline std::string WithAbutments(const std::string& text, const std::string& abutments) {
  const std::size_t begin = text.find("[abutments]");
  const std::size_t end = text.find("\n[excitation]");
  EXPECT_NE(begin, std::string::npos);
  EXPECT_NE(end, std::string::npos);
  return text.substr(0, begin) + abutments + text.substr(end);
}

/// The pilot bridge's file with `abutments`, parsed as if it stood beside the examples.
inline model::ModelFile Pilot(const std::string& abutments, const std::string& name = "m.toml") {
  return model::ParseModelString(
      WithAbutments(ReadText(Examples() + "/pilot-bridge.toml"), abutments), name, Examples());
}

/// The message of the InputError that parsing `abutments` into the pilot bridge throws.
inline std::string Refusal(const std::string& abutments) {
  try {
    Pilot(abutments);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

/// [abutments] of the compliant example (Wilson and Elgamal's backfill, gaps 8 mm) with `keys`.
inline std::string CompliantWith(const std::string& keys) {
  return "[abutments]\nset = \"both\"\ngap_m = 0.008\nlaw = \"compliant\"\nsprings = 5\n"
         "[abutments.backfill]\nform = \"hyperbolic-gap\"\nk_max_Npm_per_m = 20.3e6\n"
         "r_f = 0.7\nf_ult_N_per_m = 326e3\n" +
         keys;
}

}  // namespace skewbridge::dynamics::testing
