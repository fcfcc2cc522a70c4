#pragma once
// The four runs that measure the event-driven integrator's speed (simulate_benchmark and
// simulate_one_run): the single-abutment subsystem under a 3 s cosine pulse and the pilot bridge
// under a 40 s record-like signal, each with contacts and with gaps too wide to close; the pilot
// bridge with contacts at two gaps (a pounding stress case and the study's Pi_delta = 0.5).

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"

namespace skewbridge::dynamics::bench {

/// One benchmark run: model, excitation and run control.
struct Case {
  model::Model model;
  std::unique_ptr<Excitation> excitation;
  model::RunControl control;
};

/// The subsystem (eta0 = 2, a = 30 deg, w0 = W0 = pi rad/s) under a cosine pulse a_g = 5 m/s^2,
/// w_g = 2 pi rad/s; with contacts the gap is Pi_delta = 0.5, without it is 1 km.
inline Case SubsystemCosinePulse(bool contacts) {
  constexpr double kPi = std::numbers::pi;
  model::DeckSpec spec;
  spec.mass_kg = 1.0e5;
  spec.geometry = {30.0, model::WidthFromEta0(2.0, 30.0 * kPi / 180.0, 30.0), 30.0 * kPi / 180.0};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = kPi;
  spec.gap_plus_m = contacts ? 0.5 * 5.0 / (4.0 * kPi * kPi) : 1e3;
  spec.restitution = 0.5;
  spec.friction = 0.2;
  Case c{model::BuildDeckModel(spec),
         std::make_unique<records::PulseExcitation>(records::PulseShape::kCosine, 5.0, 2.0 * kPi),
         {}};
  c.control.end_time_s = 3.0;
  return c;
}

/// Both gaps of the pilot bridge's stress case (m): Pi_delta ~ 0.1 of the signal's persistency
/// PGA / (4 pi)^2 = 19 mm, so the deck pounds 655 times in 40 s.
inline constexpr double kPilotStressGap_m = 0.002;
/// Both gaps at Pi_delta = 0.5 of that persistency, the smallest of the pilot study (docs/theory.md
/// §6).
inline constexpr double kPilotStudyGap_m = 0.0095;

/// A record-like signal: white noise of seed `seed` through a 2 Hz resonator under a sine
/// envelope, 40 s at 0.01 s (4001 samples), PGA 3 m/s^2.
inline std::vector<double> RecordLikeSignal(unsigned seed = 12345) {
  constexpr double kPi = std::numbers::pi;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> a(4001);
  double x = 0.0, v = 0.0, peak = 0.0;
  const double w = 4.0 * kPi, dt = 0.01;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double envelope = std::sin(kPi * static_cast<double>(i) / 4000.0);
    v += dt * (-w * w * x - 2.0 * 0.3 * w * v + 30.0 * noise(rng));
    x += dt * v;
    a[i] = envelope * w * w * x;
    peak = std::max(peak, std::abs(a[i]));
  }
  for (double& ai : a) ai *= 3.0 / peak;
  return a;
}

/// The pilot bridge of docs/examples/pilot-bridge.toml with both gaps `gap_m` (or 1 km).
inline model::Model PilotBridge(bool contacts, double gap_m) {
  const model::ModelFile file = model::ParseModelFile(std::string(SKEWBRIDGE_TEST_DATA_DIR) +
                                                      "/../../docs/examples/pilot-bridge.toml");
  model::DeckSpec spec = file.deck;
  spec.gap_plus_m = spec.gap_minus_m = contacts ? gap_m : 1e3;
  return model::BuildDeckModel(spec);
}

/// The pilot bridge with both gaps `gap_m` (or 1 km) under RecordLikeSignal() along x.
inline Case PilotBridgeRecord(bool contacts, double gap_m = kPilotStressGap_m) {
  Case c{PilotBridge(contacts, gap_m),
         std::make_unique<records::SampledExcitation>(0.01, RecordLikeSignal()),
         {}};
  c.control.end_time_s = 40.0;
  return c;
}

}  // namespace skewbridge::dynamics::bench
