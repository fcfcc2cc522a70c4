// The pilot bridge with compliant abutments run by the C++ API alone, for the command-line test
// of a model file's law = "compliant" (tests/app/compliant_model_test.sh): the rigid model of
// docs/examples/pilot-bridge.toml, Wilson and Elgamal's per-metre backfill over W / cos a built
// here into five springs per wall (WallSprings), SimulateCompliant under the two-column signal
// read here, times a factor, along x. Prints the maxima as `name value` lines (%.17g).
// usage: compliant_direct SIGNAL.txt FACTOR
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/compliant_run.h"
#include "tests/dynamics/benchmark_cases.h"

int main(int argc, char** argv) {
  using namespace skewbridge;
  if (argc != 3) {
    std::fprintf(stderr, "usage: compliant_direct SIGNAL.txt FACTOR\n");
    return 2;
  }
  const double factor = std::strtod(argv[2], nullptr);
  std::ifstream in(argv[1]);
  std::vector<double> ax, ay;
  double t = 0.0, a = 0.0;
  while (in >> t >> a) {
    ax.push_back(factor == 1.0 ? a : a * factor);
    ay.push_back(0.0);
  }
  const records::SampledExcitation ex(0.01, ax, ay);
  const model::Model rigid = dynamics::bench::PilotBridge(true, 0.008);
  const double wall_m = 19.36 / std::cos(20.0 * std::numbers::pi / 180.0);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  std::vector<dynamics::CompliantSpring> springs =
      dynamics::WallSprings(rigid, 0, 1, wall, 5, "+x");
  const std::vector<dynamics::CompliantSpring> minus =
      dynamics::WallSprings(rigid, 2, 3, wall, 5, "-x");
  springs.insert(springs.end(), minus.begin(), minus.end());
  model::RunControl control;
  control.tail_s = 2.0;
  const dynamics::CompliantRunResult r =
      dynamics::SimulateCompliant(dynamics::WithoutContacts(rigid), springs, ex, control);
  const char* names[3] = {"x", "y", "theta"};
  for (int i = 0; i < 3; ++i) {
    std::printf("%s_m %.17g\n%s_end %.17g\n", names[i], r.run.max_abs_q(i), names[i],
                r.run.q_end(i));
  }
  std::printf("impacts %ld\ntravel_m %.17g\n", r.run.impacts, r.run.max_travel_m(0));
  std::printf("min_impact_separation %.17g\n", r.run.min_impact_separation_s);
  for (int w = 0; w < 2; ++w) {
    double force = 0.0, deformation = 0.0;
    for (int j = 5 * w; j < 5 * w + 5; ++j) {
      force = std::max(force, r.max_spring_force_N(j));
      deformation = std::max(deformation, r.max_spring_deformation_m(j));
    }
    std::printf("spring_force_%s %.17g\nbackwall_def_%s %.17g\n", w == 0 ? "px" : "mx", force,
                w == 0 ? "px" : "mx", deformation);
  }
  for (int j = 0; j < 10; ++j) {
    std::printf("spring_force_%d %.17g\nspring_def_%d %.17g\n", j, r.max_spring_force_N(j), j,
                r.max_spring_deformation_m(j));
  }
  std::printf("status %s\n", dynamics::ToString(r.run.status));
  return 0;
}
