#pragma once
// The canonical single-abutment cases of docs/examples/subsystem.toml (docs/theory.md §6) varied in
// friction, eta0 and pulse shape, and the pilot bridge, shared by the time-stepping tests and
// the convergence study.

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/run_result.h"
#include "solver/model/model_file.h"

namespace skewbridge::timestepping_test {

inline std::string ExamplesDir() {
  return std::string(SKEWBRIDGE_TEST_DATA_DIR) + "/../../docs/examples";
}

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void Replace(std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at != std::string::npos) {
    text.replace(at, from.size(), to);
  }
}

struct Case {
  std::string name;
  model::ModelFile file;
  std::unique_ptr<Excitation> excitation;
};

/// The subsystem of subsystem.toml with mu, eta0 and the pulse shape set.
inline Case SubsystemCase(double mu, double eta0, bool cosine) {
  std::string text = ReadText(ExamplesDir() + "/subsystem.toml");
  Replace(text, "eta0 = 2.0", "eta0 = " + std::to_string(eta0));
  Replace(text, "mu = 0.0", "mu = " + std::to_string(mu));
  if (!cosine) {
    Replace(text, "shape = \"cosine\"", "shape = \"sine\"");
  }
  Case c{std::string(cosine ? "cos" : "sin") + " mu=" + std::to_string(mu).substr(0, 3) +
             " eta0=" + std::to_string(eta0).substr(0, 3),
         model::ParseModelString(text, "subsystem.toml", ExamplesDir()), nullptr};
  const model::ExcitationSpec& spec = c.file.excitation;
  c.excitation = std::make_unique<records::PulseExcitation>(
      spec.shape == model::ExcitationSpec::PulseShape::kCosine ? records::PulseShape::kCosine
                                                               : records::PulseShape::kSine,
      spec.amplitude_mps2, spec.omega_radps, spec.direction);
  return c;
}

/// The eight canonical cases: mu in {0, 0.3} x eta0 in {0.8, 2} x {cosine, sine}.
inline std::vector<Case> CanonicalCases() {
  std::vector<Case> cases;
  for (double mu : {0.0, 0.3}) {
    for (double eta0 : {0.8, 2.0}) {
      for (bool cosine : {true, false}) {
        cases.push_back(SubsystemCase(mu, eta0, cosine));
      }
    }
  }
  return cases;
}

/// The pilot bridge of pilot-bridge.toml with its sampled signal (two columns: t, a) times
/// `scale` (the signal as given does not close the 0.03 m gaps).
inline Case PilotCase(double scale) {
  Case c{"pilot bridge, signal x " + std::to_string(scale).substr(0, 3),
         model::ParseModelFile(ExamplesDir() + "/pilot-bridge.toml"), nullptr};
  std::ifstream in(c.file.excitation.file);
  std::vector<double> t, a;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double ti = 0.0, ai = 0.0;
    if (fields >> ti >> ai) {
      t.push_back(ti);
      a.push_back(ai * c.file.excitation.to_mps2 * scale);
    }
  }
  const Eigen::Vector2d d = c.file.excitation.direction;
  std::vector<double> ax(a.size()), ay(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ax[i] = a[i] * d.x();
    ay[i] = a[i] * d.y();
  }
  c.excitation = std::make_unique<records::SampledExcitation>(t[1] - t[0], ax, ay);
  return c;
}

/// Error of the maxima of `trial` against `reference`, relative per DOF to the reference
/// maximum with a floor (the translational floor 1e-3 of the largest translation, the
/// rotational one that divided by the radius of gyration rho), so a zero rotation does not
/// divide by zero.
inline double MaximaError(const dynamics::RunResult& reference, const dynamics::RunResult& trial,
                          double rho_m) {
  double floor_m = 0.0;
  for (int i = 0; i < reference.max_abs_q.size(); ++i) {
    if (i % 3 != 2) floor_m = std::max(floor_m, reference.max_abs_q[i]);
  }
  floor_m *= 1e-3;
  double error = 0.0;
  for (int i = 0; i < reference.max_abs_q.size(); ++i) {
    const double floor = i % 3 == 2 ? floor_m / rho_m : floor_m;
    error = std::max(error, std::abs(trial.max_abs_q[i] - reference.max_abs_q[i]) /
                                std::max(reference.max_abs_q[i], floor));
  }
  return error;
}

/// Max norm of the displacement histories' difference over the common output samples, relative
/// to the largest reference translation (rotations times rho).
inline double HistoryError(const dynamics::RunResult& reference, const dynamics::RunResult& trial,
                           double rho_m) {
  const dynamics::Histories& a = reference.histories;
  const dynamics::Histories& b = trial.histories;
  const std::size_t n = static_cast<std::size_t>(a.n_dof);
  const std::size_t samples = std::min(a.t_s.size(), b.t_s.size());
  double scale = 0.0, error = 0.0;
  for (std::size_t s = 0; s < samples; ++s) {
    for (std::size_t i = 0; i < n; ++i) {
      const double w = i % 3 == 2 ? rho_m : 1.0;
      scale = std::max(scale, w * std::abs(a.q[s * n + i]));
      error = std::max(error, w * std::abs(a.q[s * n + i] - b.q[s * n + i]));
    }
  }
  return scale > 0.0 ? error / scale : error;
}

inline double Rho(const model::Model& m) {
  return std::sqrt(m.body(0).inertia_kgm2 / m.body(0).mass_kg);
}

}  // namespace skewbridge::timestepping_test
