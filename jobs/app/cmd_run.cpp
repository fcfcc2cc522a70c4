// `skewbridge run MODEL.toml [--csv run.csv] [--out run.h5]`: one run of a model file by the
// method of run.method (event-driven or time-stepping); prints a summary, writes the time
// histories as CSV and the whole run as HDF5 (docs/run-output.md), each to a temporary name
// renamed on success. A run that stops with a status other than ok exits with status 3.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "jobs/app/commands.h"
#include "jobs/h5/h5_error.h"
#include "jobs/run_output.h"
#include "records/excitations.h"
#include "solver/common/error.h"
#include "solver/dynamics/simulate.h"
#include "solver/dynamics/time_stepping.h"
#include "solver/model/model_file.h"
#include "solver/model/plausibility.h"

namespace skewbridge::app {
namespace {

// Exit status of a run that ended before its end time with a status other than ok.
constexpr int kRunStoppedExitCode = 3;

std::unique_ptr<Excitation> MakeExcitation(const model::ExcitationSpec& spec,
                                           const std::string& model_path) {
  if (spec.kind == model::ExcitationSpec::Kind::kPulse) {
    const auto shape = spec.shape == model::ExcitationSpec::PulseShape::kCosine
                           ? records::PulseShape::kCosine
                           : records::PulseShape::kSine;
    return std::make_unique<records::PulseExcitation>(shape, spec.amplitude_mps2, spec.omega_radps,
                                                      spec.direction);
  }
  double dt = spec.dt_s.value_or(0.0);
  std::vector<double> values = spec.values;
  if (!spec.file.empty()) {
    records::ExcitationSamples samples =
        records::ReadExcitationSamples(spec.file, spec.dt_s, spec.to_mps2);
    values = std::move(samples.values_mps2);
    dt = samples.dt_s;
    double pga_mps2 = 0.0;
    for (double a : values) pga_mps2 = std::max(pga_mps2, std::abs(a));
    spec.CheckPga(pga_mps2, model_path, 0, "excitation.file (" + spec.file.string() + ")");
  }
  std::vector<double> ax(values.size()), ay(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    ax[i] = values[i] * spec.direction.x();
    ay[i] = values[i] * spec.direction.y();
  }
  return std::make_unique<records::SampledExcitation>(dt, std::move(ax), std::move(ay));
}

void WriteCsv(const std::filesystem::path& path, const model::Model& model,
              const dynamics::Histories& h) {
  const std::filesystem::path temporary = path.string() + ".partial";
  {
    std::ofstream out(temporary);
    if (!out) {
      throw InputError::AtField("--csv", path.string(), "cannot write");
    }
    out << "t_s";
    for (int b = 0; b < model.n_bodies(); ++b) {
      out << ",x" << b << "_m,y" << b << "_m,theta" << b << "_rad";
    }
    for (int b = 0; b < model.n_bodies(); ++b) {
      out << ",vx" << b << "_mps,vy" << b << "_mps,omega" << b << "_radps";
    }
    for (const model::Contact& c : model.contacts()) {
      out << ",gap_" << c.name << "_m,lambdaN_" << c.name << "_N,lambdaT_" << c.name << "_N,state_"
          << c.name;
    }
    out << "\n";
    out.precision(12);
    const std::size_t n = static_cast<std::size_t>(h.n_dof),
                      nc = static_cast<std::size_t>(h.n_contacts);
    for (std::size_t s = 0; s < h.t_s.size(); ++s) {
      out << h.t_s[s];
      for (std::size_t i = 0; i < n; ++i) out << "," << h.q[s * n + i];
      for (std::size_t i = 0; i < n; ++i) out << "," << h.u[s * n + i];
      for (std::size_t c = 0; c < nc; ++c) {
        out << "," << h.gap_m[s * nc + c] << "," << h.lambda_N[s * nc + c] << ","
            << h.lambda_T[s * nc + c] << "," << h.state[s * nc + c];
      }
      out << "\n";
    }
  }
  std::filesystem::rename(temporary, path);
}

// The whole run as HDF5; a failed write removes the temporary file and names --out.
void WriteHdf5(const std::filesystem::path& path, const model::ModelFile& file,
               const model::RunControl& control, const dynamics::RunResult& r) {
  std::ifstream in(file.path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  const std::filesystem::path temporary = path.string() + ".partial";
  try {
    // The step h means nothing to the event-driven integrator: NaN says so in the file.
    const double time_step_s = control.method == "time-stepping"
                                   ? control.time_step_s
                                   : std::numeric_limits<double>::quiet_NaN();
    jobs::WriteRunHdf5(temporary, file.model, r, text.str(), control.method, time_step_s);
  } catch (const jobs::h5::H5Error& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw InputError::AtField("--out", path.string(), std::string("cannot write: ") + e.what());
  }
  std::filesystem::rename(temporary, path);
}

// A number of the summary: printf's `format` when finite, else "not-finite" (a run that stops
// with status non-finite keeps its last state; the summary never prints nan or inf).
std::string Number(const char* format, double value) {
  if (!std::isfinite(value)) {
    return "not-finite";
  }
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace

void AddRunCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("run", "Integrate one model file and summarise the response");
  auto model_path = std::make_shared<std::string>();
  auto csv_path = std::make_shared<std::string>();
  auto out_path = std::make_shared<std::string>();
  auto output_interval_s = std::make_shared<double>(0.0);
  cmd->add_option("MODEL", *model_path, "Model file (TOML, docs/model-format.md)")->required();
  cmd->add_option("--csv", *csv_path, "Write the time histories as CSV");
  cmd->add_option("--out", *out_path, "Write the run as HDF5 (docs/run-output.md)");
  cmd->add_option("--output-interval", *output_interval_s,
                  "History sample interval in s (> 0), overriding run.output_interval_s");
  cmd->callback([model_path, csv_path, out_path, output_interval_s] {
    const model::ModelFile file = model::ParseModelFile(*model_path);
    PrintWarnings(model::PlausibilityWarnings(file));
    const std::unique_ptr<Excitation> excitation = MakeExcitation(file.excitation, *model_path);
    model::RunControl control = file.run;
    if (*output_interval_s < 0.0) {
      throw InputError::AtField("--output-interval", fmt::format("{}", *output_interval_s),
                                "must be > 0 s");
    }
    if (*output_interval_s > 0.0) {
      control.output_interval_s = *output_interval_s;
    }
    if (!csv_path->empty() && control.output_interval_s <= 0.0) {
      control.output_interval_s = 0.01;
    }
    // The run counted again with what is known now: the samples of an excitation file and the
    // history interval of the command line.
    const auto* sampled = dynamic_cast<const records::SampledExcitation*>(excitation.get());
    model::CheckRunSize(control, excitation->Duration(), sampled ? sampled->ax_mps2().size() : 0,
                        *model_path,
                        file.excitation.file.empty() ? "excitation" : "excitation.file");
    // run.method: the event-driven integrator, or the Moreau-Jean scheme with run.time_step_s.
    const bool time_stepping = control.method == "time-stepping";
    dynamics::RunResult r;
    if (time_stepping) {
      dynamics::TimeSteppingWorkspace workspace(file.model);
      r = dynamics::SimulateTimeStepping(file.model, *excitation, control, workspace);
    } else {
      dynamics::SimulationWorkspace workspace(file.model);
      r = dynamics::Simulate(file.model, *excitation, control, workspace);
    }
    std::printf("model %s: method %s", model_path->c_str(), control.method.c_str());
    if (time_stepping) {
      std::printf(" (h = %.6g s)", control.time_step_s);
    }
    std::printf(", status %s%s%s, t_end %s s\n", dynamics::ToString(r.status),
                r.message.empty() ? "" : " - ", r.message.c_str(),
                Number("%.6g", r.end_time_s).c_str());
    // Stiffness assembled from bearings and piers: its modes are a result worth seeing.
    if (!file.decks && file.deck.stiffness == model::DeckSpec::StiffnessKind::kElements) {
      PrintModes(file.model);
    }
    const char* names[3] = {"x", "y", "theta"};
    const char* units[3] = {"m", "m", "rad"};
    for (int i = 0; i < file.model.n_dof(); ++i) {
      std::printf("  max|%s%d| = %s at %s s, residual %s (%s)\n", names[i % 3], i / 3,
                  Number("%.6e", r.max_abs_q[i]).c_str(),
                  Number("%.6f", r.time_of_max_s[i]).c_str(), Number("%.6e", r.q_end[i]).c_str(),
                  units[i % 3]);
    }
    std::printf("  impacts %ld, plastic closures %ld, detachments %ld, stick %ld, slip %ld\n",
                r.impacts, r.plastic_closures, r.detachments, r.stick_transitions,
                r.slip_transitions);
    std::printf(
        "  steps: exact %ld, Runge-Kutta %ld (+%ld rejected); smallest impact separation %s\n",
        r.free_steps, r.rk_steps, r.rk_rejected,
        r.impacts < 2 ? "none (fewer than two impacts)"
                      : (Number("%.3e", r.min_impact_separation_s) + " s").c_str());
    const dynamics::EnergyLedger& e = r.energy;
    std::printf(
        "  energy (J): input %s, damping %s, impacts %s, friction %s, now %s, balance error %s\n",
        Number("%.6e", e.input_J).c_str(), Number("%.6e", e.damping_J).c_str(),
        Number("%.6e", e.impact_J).c_str(), Number("%.6e", e.friction_J).c_str(),
        Number("%.6e", e.kinetic_J + e.strain_J).c_str(),
        Number("%.3e", e.balance_error_J).c_str());
    if (!csv_path->empty()) {
      WriteCsv(*csv_path, file.model, r.histories);
    }
    if (!out_path->empty()) {
      WriteHdf5(*out_path, file, control, r);
    }
    if (r.status != dynamics::RunStatus::kOk) {
      // An expected numerical outcome (Painleve, LCP failure, step limit, a state no longer
      // finite): the summary and the
      // files hold the run up to where it stopped; the exit status tells scripts it stopped.
      std::fprintf(stderr, "skewbridge: run stopped: %s: %s\n", dynamics::ToString(r.status),
                   r.message.c_str());
      throw CLI::RuntimeError(kRunStoppedExitCode);
    }
  });
}

}  // namespace skewbridge::app
