// `skewbridge run MODEL.toml [--record FILE | --record-set SET --label L] [--scale S |
// --target-sa-g X | --target-pga-g X | --target-rotd50-g X] [--incidence-deg A] [--csv run.csv]
// [--out run.h5]`: one run of a model file by the method of run.method (event-driven or
// time-stepping), under its own excitation, a record of any format the readers know or a record
// pair of a set (H1 along the direction, H2 at +90 deg); and `skewbridge run --from-cube CUBE.h5
// --cell AXIS=VALUE,...` (or --cell-index N): one cell of a model-file, subsystem or pilot-bridge
// sweep run again as the sweep ran it, with histories. Prints a summary, writes the time histories
// as CSV and the whole run as HDF5 (docs/run-output.md), each to a temporary name renamed on
// success. A run that stops with a status other than ok exits with status 3.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "jobs/app/commands.h"
#include "jobs/cell_rerun.h"
#include "jobs/h5/h5_error.h"
#include "jobs/run_output.h"
#include "records/excitations.h"
#include "records/incidence.h"
#include "records/measures.h"
#include "records/record_set.h"
#include "solver/common/error.h"
#include "solver/dynamics/abutment_springs.h"
#include "solver/dynamics/run.h"
#include "solver/dynamics/simulate.h"
#include "solver/dynamics/stripes.h"
#include "solver/model/model_file.h"
#include "solver/model/plausibility.h"
#include "spectra/model_file_evaluator.h"
#include "spectra/solver_status.h"
#include "spectra/study.h"

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
void WriteHdf5(const std::filesystem::path& path, const std::string& model_text,
               const model::Model& model, const model::RunControl& control,
               const dynamics::RunResult& r, const jobs::RunOrigin& origin,
               const dynamics::RunPolicies& policies, const jobs::RunJoints& joints) {
  const std::filesystem::path temporary = path.string() + ".partial";
  try {
    // The step h means nothing to the event-driven integrator: NaN says so in the file.
    const double time_step_s = control.method == model::Method::kTimeStepping
                                   ? control.time_step_s
                                   : std::numeric_limits<double>::quiet_NaN();
    jobs::WriteRunHdf5(temporary, model, r, model_text, model::ToString(control.method),
                       time_step_s, origin, policies, joints);
  } catch (const jobs::h5::H5Error& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw InputError::AtField("--out", path.string(), std::string("cannot write: ") + e.what());
  }
  std::filesystem::rename(temporary, path);
}

// The compliant walls of a run in words: "5 springs per wall and two shear keys per abutment"
// when every wall has the same number of springs and every abutment keys, else wall by wall. With
// a law per abutment, the compliant wall's: "-x (the +x abutment rigid), 5 springs".
std::string WallsText(const model::CompliantAbutments& compliant) {
  std::vector<model::CompliantWall> walls;
  std::string mixed;
  for (std::size_t w = 0; w < compliant.walls.size(); ++w) {
    if (compliant.walls[w].law == model::JointLaw::kCompliant) {
      walls.push_back(compliant.walls[w]);
    } else {
      mixed = std::string(model::WallName(1 - w)) + " (the " + std::string(model::WallName(w)) +
              " abutment rigid), ";
    }
  }
  if (!mixed.empty()) {
    return mixed + std::to_string(walls.front().springs) + " springs" +
           (walls.front().shear_keys ? " and two shear keys" : "");
  }
  bool same_springs = true;
  bool all_keys = true;
  for (const model::CompliantWall& w : walls) {
    same_springs = same_springs && w.springs == walls.front().springs;
    all_keys = all_keys && w.shear_keys.has_value();
  }
  std::string text;
  if (same_springs) {
    text = std::to_string(walls.front().springs) + " springs per wall";
  } else {
    for (std::size_t w = 0; w < walls.size(); ++w) {
      text.append(w == 0 ? "" : ", ")
          .append(std::to_string(walls[w].springs))
          .append(w == 0 ? " springs on the " : " on the ")
          .append(model::WallName(w))
          .append(" wall");
    }
  }
  if (all_keys) return text + " and two shear keys per abutment";
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (walls[w].shear_keys) {
      text.append(" and two shear keys at the ").append(model::WallName(w)).append(" abutment");
    }
  }
  return text;
}

// A row of decks with rigid and compliant parts in words: "-x wall (5 springs), J1 (5 springs);
// rigid: +x wall, J0".
std::string RowText(const model::CompliantAbutments& c) {
  std::string compliant, rigid;
  const auto add = [](std::string& text, const std::string& part) {
    text.append(text.empty() ? "" : ", ").append(part);
  };
  for (std::size_t w = 0; w < c.walls.size(); ++w) {
    const std::string wall = std::string(model::WallName(w)) + " wall";
    if (c.walls[w].law == model::JointLaw::kImpact) {
      add(rigid, wall);
      continue;
    }
    add(compliant, wall + " (" + std::to_string(c.walls[w].springs) + " springs" +
                       (c.walls[w].shear_keys ? " and two shear keys)" : ")"));
  }
  for (std::size_t i = 0; i < c.joints.size(); ++i) {
    const std::string joint = "J" + std::to_string(i);
    if (c.joints[i].law == model::JointLaw::kImpact) {
      add(rigid, joint);
      continue;
    }
    add(compliant, joint + " (" + std::to_string(c.joints[i].springs) + " springs)");
  }
  return compliant + "; rigid: " + rigid;
}

// The compliant joints' responses of a run for its file, as a sweep's cell stores them.
jobs::RunJoints Joints(const model::CompliantAbutments& compliant, const dynamics::LawRun& run) {
  jobs::RunJoints j;
  // The -x wall exists when the model has its contacts (P3, P4): the walls' maxima say so (with a
  // law per abutment, both walls exist and one has springs).
  for (const dynamics::JointResponse& r :
       dynamics::JointResponses(compliant, run.walls.size() == 2 || compliant.Mixed())) {
    j.responses.push_back({r.name, r.unit, r.value(run)});
  }
  j.stored_J = run.joint_stored_J;
  j.dissipated_J = run.joint_dissipated_J;
  for (const dynamics::KeyMaxima& k : run.keys) {
    j.key_names.push_back(k.name);
    j.key_force_N.push_back(k.force_N);
    j.key_deformation_m.push_back(k.deformation_m);
    j.key_break_time_s.push_back(k.break_time_s);
  }
  for (const dynamics::SpringMaxima& s : run.springs) {
    j.spring_names.push_back(s.name);
    j.spring_force_N.push_back(s.force_N);
    j.spring_deformation_m.push_back(s.deformation_m);
    j.spring_slip_m.push_back(s.wall_slip_m);
  }
  return j;
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
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

// The command line of `run`.
struct RunOptions {
  std::string model;
  std::string csv, out;
  double output_interval_s = 0.0;
  std::string record, format, units, record_set, label;
  std::optional<double> dt_s, scale, target_sa_g, target_pga_g, target_rotd50_g;  // when given
  std::optional<double> incidence_deg;  // the ground motion's angle from x (deg), when given
  std::string from_cube, sweep, cell;
  long long cell_index = -1;
};

// What is run: the model, its ground motion and controls, and where they came from.
struct RunInput {
  std::string title;       // the summary's first words ("model M.toml", "cube C.h5 ...")
  std::string model_text;  // stored in the run file
  const model::Model* model = nullptr;
  /// The model file's compliant abutments ([abutments] law = "compliant"), else empty.
  std::optional<model::CompliantAbutments> compliant;
  const Excitation* excitation = nullptr;
  // The record at dynamics::kStripeTraceFactor when the run is a record's at `factor` taken as a
  // stripe of it (dynamics::RunScaledRecord, as a sweep's cell), else nullptr.
  const Excitation* trace_excitation = nullptr;
  double factor = 1.0;
  model::RunControl control;
  dynamics::RunPolicies policies;  // the integrators' defaults, or a cube cell's sweep's
  bool print_modes = false;
  jobs::RunOrigin origin;
};

// Samples a smooth ground motion (a pulse) is drawn with: enough that straight lines between
// them follow one cycle to the eye.
constexpr int kPulseDrawSamples = 2000;

// The ground acceleration of the run for the run file's origin group: a sampled excitation's
// samples, or a pulse sampled kPulseDrawSamples times over its duration.
void KeepGround(const Excitation& excitation, jobs::RunOrigin& origin) {
  const auto* sampled = dynamic_cast<const records::SampledExcitation*>(&excitation);
  if (sampled == nullptr) {
    const double duration_s = excitation.Duration();
    if (!(duration_s > 0.0) || !std::isfinite(duration_s)) return;
    origin.ground_dt_s = duration_s / kPulseDrawSamples;
    for (int k = 0; k <= kPulseDrawSamples; ++k) {
      const Eigen::Vector2d a = excitation.At(k * origin.ground_dt_s);
      origin.ground_ax_mps2.push_back(a.x());
      origin.ground_ay_mps2.push_back(a.y());
    }
    return;
  }
  origin.ground_ax_mps2 = sampled->ax_mps2();
  origin.ground_ay_mps2 = sampled->ay_mps2().empty()
                              ? std::vector<double>(sampled->ax_mps2().size(), 0.0)
                              : sampled->ay_mps2();
  origin.ground_dt_s = sampled->dt_s();
}

// The record of --record (any format the readers know) or of --record-set and --label: one
// component, or both of a pair of the set (one dt and one length, as a sweep reads them).
records::RecordComponents LoadRunRecord(const RunOptions& o, jobs::RunOrigin& origin) {
  if (!o.record.empty()) {
    records::ReadOptions read;
    if (!o.format.empty()) {
      const std::optional<records::Format> format = records::ParseFormat(o.format);
      if (!format) {
        throw InputError::AtField("--format", o.format,
                                  "unknown format; allowed: auto, at2, esm, itsak, cosmos, csmip, "
                                  "smc, smtk, plain, time-acc");
      }
      read.format = *format;
    }
    if (!o.units.empty()) {
      read.units = records::ParseUnits(o.units);
      if (!read.units) {
        throw InputError::AtField("--units", o.units, "unknown units; allowed: g, m/s^2, cm/s^2");
      }
    }
    if (o.dt_s) {
      if (!(*o.dt_s > 0.0) || !std::isfinite(*o.dt_s)) {
        throw InputError::AtField("--dt", fmt::format("{}", *o.dt_s), "must be a time > 0 s");
      }
      read.dt_s = *o.dt_s;
    }
    records::RecordComponents one;
    one.motions.push_back(records::ReadRecord(o.record, read));
    origin.text.push_back({"record_file", o.record});
    origin.text.push_back({"record_format", one.motions[0].format});
    return one;
  }
  const records::RecordSet set = records::LoadRecordSet(o.record_set);
  std::string labels;
  for (const records::RecordEntry& entry : set.records) {
    const std::string label = records::RecordLabel(entry);
    if (label == o.label) {
      records::RecordComponents components = records::LoadComponents(entry);
      origin.text.push_back({"record_set", o.record_set});
      origin.text.push_back({"record_label", label});
      origin.text.push_back({"record_file", entry.file.string()});
      origin.text.push_back({"record_format", components.motions[0].format});
      if (components.IsPair()) {
        origin.text.push_back({"record_file_h2", entry.file_h2.string()});
        origin.numbers.push_back(
            {"padded_samples_h1", static_cast<double>(components.padded_samples[0])});
        origin.numbers.push_back(
            {"padded_samples_h2", static_cast<double>(components.padded_samples[1])});
      }
      origin.numbers.push_back({"record_set_scale", entry.scale});
      return components;
    }
    labels += (labels.empty() ? "" : ", ") + label;
  }
  throw InputError::AtField("--label", o.label,
                            "not a record of " + o.record_set + "; its labels: " + labels);
}

// The factor on the record's accelerations (both components of a pair alike): --scale, or a
// target intensity over the record's own (Sa(T1, 5 %) at the model's fundamental period T1, or
// PGA, of one component; RotD50(T1, 5 %) of a pair), computed as a sweep's stripes are.
double RecordFactor(const RunOptions& o, const model::Model& model,
                    const records::RecordComponents& components, jobs::RunOrigin& origin) {
  const int given = o.scale.has_value() + o.target_sa_g.has_value() + o.target_pga_g.has_value() +
                    o.target_rotd50_g.has_value();
  if (given > 1) {
    throw InputError(
        "--scale: give one of --scale, --target-sa-g, --target-pga-g, --target-rotd50-g");
  }
  if (components.IsPair() && (o.target_sa_g || o.target_pga_g)) {
    throw InputError::AtField(
        o.target_sa_g ? "--target-sa-g" : "--target-pga-g", o.label,
        "is a measure of one component and '" + o.label +
            "' is a pair of horizontal components; allowed for a pair: --scale, "
            "--target-rotd50-g");
  }
  if (!components.IsPair() && o.target_rotd50_g) {
    throw InputError::AtField("--target-rotd50-g", fmt::format("{}", *o.target_rotd50_g),
                              "RotD50 is a measure of a pair of horizontal components (h1, h2 "
                              "of a record set); allowed for one record: --scale, "
                              "--target-sa-g, --target-pga-g");
  }
  const records::GroundMotion& motion = components.motions[0];
  auto positive = [](const char* option, double v) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw InputError::AtField(option, fmt::format("{}", v), "must be a number > 0");
    }
  };
  if (!o.target_sa_g && !o.target_pga_g && !o.target_rotd50_g) {
    const double factor = o.scale.value_or(1.0);
    positive("--scale", factor);
    origin.numbers.push_back({"scale_factor", factor});
    return factor;
  }
  spectra::SweepRecord record;
  record.motion = motion;
  spectra::IntensityMeasureSpec im;
  double target = 0.0, t1_s = std::numeric_limits<double>::quiet_NaN();
  const char* option = o.target_sa_g       ? "--target-sa-g"
                       : o.target_rotd50_g ? "--target-rotd50-g"
                                           : "--target-pga-g";
  if (o.target_sa_g || o.target_rotd50_g) {
    target = o.target_sa_g ? *o.target_sa_g : *o.target_rotd50_g;
    positive(option, target);
    t1_s = model::FundamentalPeriod(model);
    if (!(t1_s > 0.0) || !std::isfinite(t1_s)) {
      throw InputError::AtField(option, fmt::format("{}", target),
                                "needs a model with stiffness in every direction: its lowest "
                                "natural frequency is 0 (see `skewbridge modes`)");
    }
    im.measure = o.target_sa_g ? "Sa" : "RotD50";
    im.at_t1 = true;
    im.xi = 0.05;
    if (components.IsPair()) record.motion_h2 = components.motions[1];
  } else {
    positive("--target-pga-g", *o.target_pga_g);
    record.measures = records::ComputeMeasures(motion);
    im.measure = "PGA";
    target = *o.target_pga_g;
  }
  const double own = spectra::RecordIntensity(record, im, t1_s);
  if (!(own > 0.0) || !std::isfinite(own)) {
    throw InputError::AtField(option, fmt::format("{}", target),
                              fmt::format("the record's own {} is {} g: it cannot be scaled to "
                                          "a value",
                                          im.measure, own));
  }
  const double factor = target / own;
  origin.text.push_back({"scaled_to", spectra::IntensityDescription(im)});
  origin.numbers.push_back({"target_g", target});
  origin.numbers.push_back({"unscaled_g", own});
  if (im.at_t1) origin.numbers.push_back({"T1_s", t1_s});
  origin.numbers.push_back({"scale_factor", factor});
  return factor;
}

// The run's model, excitation and controls, and the summary of what was run.
void Execute(const RunInput& in, const RunOptions& o) {
  model::RunControl control = in.control;
  if (o.output_interval_s < 0.0) {
    throw InputError::AtField("--output-interval", fmt::format("{}", o.output_interval_s),
                              "must be > 0 s");
  }
  if (o.output_interval_s > 0.0) {
    control.output_interval_s = o.output_interval_s;
  }
  if (!o.csv.empty() && control.output_interval_s <= 0.0) {
    control.output_interval_s = 0.01;
  }
  const bool time_stepping = control.method == model::Method::kTimeStepping;
  // A record's event-driven run under the rigid law goes as a sweep's cell of it goes.
  const dynamics::LawRun law_run =
      in.trace_excitation != nullptr && !in.compliant &&
              control.method == model::Method::kEventDriven
          ? dynamics::RigidLawRun(dynamics::RunScaledRecord(
                *in.model, *in.excitation, *in.trace_excitation, in.factor, control, in.policies))
          : dynamics::RunUnderLaw(*in.model, in.compliant, *in.excitation, control, in.policies);
  const dynamics::RunResult& r = law_run.run;
  // A compliant run's histories and files describe the deck without its rigid contacts (with a
  // law per abutment, with the rigid wall's only): the model it integrated.
  const std::optional<model::Model> contactless =
      in.compliant ? std::optional<model::Model>(dynamics::LawModel(*in.model, *in.compliant))
                   : std::nullopt;
  const model::Model& model = contactless ? *contactless : *in.model;
  std::printf("%s: method %s", in.title.c_str(), model::ToString(control.method));
  if (time_stepping) {
    std::printf(" (h = %.6g s)", control.time_step_s);
  }
  std::printf(", status %s%s%s, t_end %s s\n", dynamics::ToString(r.status),
              r.message.empty() ? "" : " - ", r.message.c_str(),
              Number("%.6g", r.end_time_s).c_str());
  // Stiffness assembled from bearings and piers: its modes are a result worth seeing.
  if (in.print_modes) {
    PrintModes(model);
  }
  const char* names[3] = {"x", "y", "theta"};
  const char* units[3] = {"m", "m", "rad"};
  for (int i = 0; i < model.n_dof(); ++i) {
    std::printf("  max|%s%d| = %s at %s s, residual %s (%s)\n", names[i % 3], i / 3,
                Number("%.6e", r.max_abs_q[i]).c_str(), Number("%.6f", r.time_of_max_s[i]).c_str(),
                Number("%.6e", r.q_end[i]).c_str(), units[i % 3]);
  }
  std::printf("  impacts %ld, plastic closures %ld, detachments %ld, stick %ld, slip %ld\n",
              r.impacts, r.plastic_closures, r.detachments, r.stick_transitions,
              r.slip_transitions);
  // A compliant run's events are strikes; with a law per abutment impacts and strikes both count.
  const char* strikes_are = !in.compliant           ? "impact"
                            : in.compliant->Mixed() ? "impact or strike"
                                                    : "strike";
  const char* strikes_are_plural = !in.compliant           ? "impacts"
                                   : in.compliant->Mixed() ? "impacts or strikes"
                                                           : "strikes";
  std::printf("  steps: exact %ld, Runge-Kutta %ld (+%ld rejected); smallest %s separation %s\n",
              r.free_steps, r.rk_steps, r.rk_rejected, strikes_are,
              r.impacts < 2
                  ? (std::string("none (fewer than two ") + strikes_are_plural + ")").c_str()
                  : (Number("%.3e", r.min_impact_separation_s) + " s").c_str());
  const dynamics::EnergyLedger& e = r.energy;
  std::printf(
      "  energy (J): input %s, damping %s, impacts %s, friction %s, now %s, balance error %s\n",
      Number("%.6e", e.input_J).c_str(), Number("%.6e", e.damping_J).c_str(),
      Number("%.6e", e.impact_J).c_str(), Number("%.6e", e.friction_J).c_str(),
      Number("%.6e", e.kinetic_J + e.strain_J).c_str(), Number("%.3e", e.balance_error_J).c_str());
  if (in.compliant) {
    const bool row = in.compliant->Mixed() && !in.compliant->joints.empty();
    std::printf("  compliant %s%s; %s energy (J): stored %s, dissipated %s\n",
                row                     ? "parts "
                : in.compliant->Mixed() ? "abutment "
                                        : "abutments, ",
                (row ? RowText(*in.compliant) : WallsText(*in.compliant)).c_str(),
                in.compliant->HasShearKeys() ? "backfill and keys'" : "backfill",
                Number("%.6e", law_run.joint_stored_J).c_str(),
                Number("%.6e", law_run.joint_dissipated_J).c_str());
    for (const dynamics::WallMaxima& w : law_run.walls) {
      std::printf("  %s wall: largest spring force %s N, largest deformation %s m\n",
                  w.wall.c_str(), Number("%.6e", w.spring_force_N).c_str(),
                  Number("%.6e", w.deformation_m).c_str());
    }
    for (const dynamics::WallMaxima& j : law_run.joints) {
      std::printf("  deck-deck joint %s: largest spring force %s N, largest deformation %s m\n",
                  j.wall.c_str(), Number("%.6e", j.spring_force_N).c_str(),
                  Number("%.6e", j.deformation_m).c_str());
    }
    for (const dynamics::KeyMaxima& k : law_run.keys) {
      std::printf("  shear key %s: largest force %s N, largest deformation %s m, %s\n",
                  k.name.c_str(), Number("%.6e", k.force_N).c_str(),
                  Number("%.6e", k.deformation_m).c_str(),
                  std::isinf(k.break_time_s)
                      ? "intact"
                      : ("broke at " + Number("%.6f", k.break_time_s) + " s").c_str());
    }
  }
  if (!o.csv.empty()) {
    WriteCsv(o.csv, model, r.histories);
  }
  if (!o.out.empty()) {
    WriteHdf5(o.out, in.model_text, model, control, r, in.origin, in.policies,
              in.compliant ? Joints(*in.compliant, law_run) : jobs::RunJoints{});
  }
  if (r.status != dynamics::RunStatus::kOk) {
    // An expected numerical outcome (Painleve, LCP failure, step limit, a state no longer
    // finite): the summary and the files hold the run up to where it stopped; the exit status
    // tells scripts it stopped.
    std::fprintf(stderr, "skewbridge: run stopped: %s: %s\n", dynamics::ToString(r.status),
                 r.message.c_str());
    throw CLI::RuntimeError(kRunStoppedExitCode);
  }
}

// `run MODEL [--record ... | --record-set ...]`.
void RunModelFile(const RunOptions& o) {
  const model::ModelFile file = model::ParseModelFile(o.model);
  PrintWarnings(model::PlausibilityWarnings(file));
  RunInput in;
  in.model_text = ReadText(file.path);
  in.model = &file.model;
  in.compliant = file.compliant;
  in.control = file.run;
  in.print_modes = !file.decks && file.deck.stiffness == model::DeckSpec::StiffnessKind::kElements;
  std::unique_ptr<Excitation> excitation, trace_excitation;
  // The ground motion's direction: the file's, or --incidence-deg from the bridge's x axis (as a
  // sweep's incidence_deg, the same bits).
  model::ExcitationSpec excitation_spec = file.excitation;
  if (o.incidence_deg) {
    if (!std::isfinite(*o.incidence_deg) || std::abs(*o.incidence_deg) > 360.0) {
      throw InputError::AtField("--incidence-deg", fmt::format("{}", *o.incidence_deg),
                                "must be an angle in [-360, 360] deg from the bridge's x axis");
    }
    excitation_spec.direction = records::DirectionAt(*o.incidence_deg);
    in.origin.numbers.push_back({"incidence_deg", *o.incidence_deg});
  }
  const bool by_record = !o.record.empty() || !o.record_set.empty();
  if (by_record) {
    const records::RecordComponents components = LoadRunRecord(o, in.origin);
    const double factor = RecordFactor(o, file.model, components, in.origin);
    in.origin.text.insert(in.origin.text.begin(),
                          {"kind", components.IsPair() ? "record-pair" : "record"});
    excitation = std::make_unique<records::SampledExcitation>(
        components.IsPair() ? records::PairExcitation(components.motions[0], components.motions[1],
                                                      excitation_spec.direction, factor)
                            : spectra::ScaledRecordExcitation(components.motions[0], factor,
                                                              excitation_spec.direction));
    // The record at the stripes' trace factor, built alike: the run goes as a sweep's cell of
    // the record at this factor goes (spectra::ModelFileEvaluator), and gives its bits.
    trace_excitation = std::make_unique<records::SampledExcitation>(
        components.IsPair()
            ? records::PairExcitation(components.motions[0], components.motions[1],
                                      excitation_spec.direction, dynamics::kStripeTraceFactor)
            : spectra::ScaledRecordExcitation(components.motions[0], dynamics::kStripeTraceFactor,
                                              excitation_spec.direction));
    in.trace_excitation = trace_excitation.get();
    in.factor = factor;
    in.title = fmt::format(
        "model {}, record {}{} x {:.6g}", o.model, o.record.empty() ? o.label : o.record,
        components.IsPair() ? " (pair: H1 along the direction, H2 at +90 deg)" : "", factor);
  } else {
    if (o.scale || o.target_sa_g || o.target_pga_g || o.target_rotd50_g) {
      const char* option = o.scale          ? "--scale"
                           : o.target_sa_g  ? "--target-sa-g"
                           : o.target_pga_g ? "--target-pga-g"
                                            : "--target-rotd50-g";
      throw InputError(std::string(option) +
                       ": scales a record: give --record FILE or --record-set SET --label L");
    }
    excitation = MakeExcitation(excitation_spec, o.model);
    in.title = "model " + o.model;
    if (o.incidence_deg) in.origin.text.insert(in.origin.text.begin(), {"kind", "excitation"});
  }
  if (o.incidence_deg) in.title += fmt::format(", incidence {:g} deg", *o.incidence_deg);
  // The run counted again with what is known now: the samples of an excitation file or record
  // and the history interval of the command line.
  model::RunControl counted = in.control;
  if (o.output_interval_s > 0.0) counted.output_interval_s = o.output_interval_s;
  if (!o.csv.empty() && counted.output_interval_s <= 0.0) counted.output_interval_s = 0.01;
  const auto* sampled = dynamic_cast<const records::SampledExcitation*>(excitation.get());
  model::CheckRunSize(counted, excitation->Duration(), sampled ? sampled->ax_mps2().size() : 0,
                      o.model,
                      by_record                      ? "record"
                      : file.excitation.file.empty() ? "excitation"
                                                     : "excitation.file");
  if (by_record || o.incidence_deg) KeepGround(*excitation, in.origin);
  in.excitation = excitation.get();
  Execute(in, o);
}

// `run --from-cube CUBE --cell ...`: the cell as its sweep ran it, with histories.
void RunCubeCell(const RunOptions& o) {
  if (!o.model.empty() || !o.record.empty() || !o.record_set.empty() || o.scale || o.target_sa_g ||
      o.target_pga_g || o.target_rotd50_g || o.incidence_deg) {
    throw InputError::AtField("--from-cube", o.from_cube,
                              "takes the model, record, scale and incidence from the cube: give "
                              "no MODEL, --record, --record-set, --scale, --target-* or "
                              "--incidence-deg");
  }
  jobs::CellChoice choice;
  choice.sweep = o.sweep;
  choice.coordinates = o.cell;
  if (o.cell_index >= 0) choice.index = static_cast<std::uint64_t>(o.cell_index);
  const jobs::CellRerun rerun = jobs::PrepareCellRerun(o.from_cube, choice);
  PrintWarnings(rerun.evaluator->Warnings());
  RunInput in;
  in.model_text = rerun.model_text;
  in.model = &*rerun.model;
  in.compliant = rerun.compliant;
  in.excitation = rerun.excitation.get();
  in.control = rerun.control;
  in.trace_excitation = rerun.trace_excitation.get();
  in.factor = rerun.scale;
  // The cell's runs used its sweep's policies ([event_policy], [time_stepping_policy]).
  in.policies = rerun.evaluator->policies();
  // Histories and the energy ledger are what a re-run is for; the sweep leaves both out because
  // the maxima are the same bits with or without them (tests/app/rerun_cell_test.sh).
  if (in.control.output_interval_s <= 0.0) in.control.output_interval_s = 0.01;
  in.control.energy_ledger = true;
  in.title = fmt::format("cube {}, sweep {}, cell {} ({})", o.from_cube, rerun.spec.name,
                         rerun.index, rerun.coordinates);
  jobs::RunOrigin& origin = in.origin;
  origin.text = {{"kind", "cube-cell"},
                 {"cube", o.from_cube},
                 {"sweep", rerun.spec.name},
                 {"family", rerun.spec.family},
                 {"coordinates", rerun.coordinates},
                 {"specification", rerun.spec.source},
                 {"cube_status", rerun.done ? rerun.status_name : "not_done"}};
  if (rerun.record != nullptr) {
    origin.text.push_back({"record_label", rerun.record->label});
    origin.text.push_back({"record_file", rerun.record->file});
  }
  origin.numbers = {{"cell_index", static_cast<double>(rerun.index)},
                    {"scale_factor", rerun.scale}};
  KeepGround(*rerun.excitation, origin);
  if (!rerun.done) {
    PrintWarnings({o.from_cube + ": cell " + std::to_string(rerun.index) +
                   " is not done in the cube: there is nothing stored to compare the run with"});
  }
  Execute(in, o);
}

}  // namespace

void AddRunCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "run", "Integrate one model file (or re-run one cell of a cube) and summarise the response");
  auto o = std::make_shared<RunOptions>();
  cmd->add_option("MODEL", o->model, "Model file (TOML, docs/model-format.md)");
  cmd->add_option("--csv", o->csv, "Write the time histories as CSV");
  cmd->add_option("--out", o->out, "Write the run as HDF5 (docs/run-output.md)");
  cmd->add_option("--output-interval", o->output_interval_s,
                  "History sample interval in s (> 0), overriding run.output_interval_s");
  cmd->add_option("--record", o->record,
                  "A record file of any format the readers know (docs/records.md) in place of the "
                  "model file's excitation, along its direction");
  cmd->add_option("--format", o->format, "The record file's format (default: detected)");
  cmd->add_option("--units", o->units, "Units of a record file that states none (g, m/s^2, ...)");
  cmd->add_option("--dt", o->dt_s, "Sample interval in s of a headerless record file");
  cmd->add_option("--record-set", o->record_set,
                  "A record set (TOML manifest) to take --label from");
  cmd->add_option("--label", o->label, "The label of the record in --record-set");
  cmd->add_option("--scale", o->scale, "Factor on the record's accelerations (> 0)");
  cmd->add_option("--target-sa-g", o->target_sa_g,
                  "Scale the record to Sa(T1, 5 %) = X g at the model's fundamental period T1");
  cmd->add_option("--target-pga-g", o->target_pga_g, "Scale the record to PGA = X g");
  cmd->add_option("--target-rotd50-g", o->target_rotd50_g,
                  "Scale a record pair to RotD50(T1, 5 %) = X g at the model's fundamental period");
  cmd->add_option("--incidence-deg", o->incidence_deg,
                  "The ground motion's angle from the bridge's x axis in deg (a pair: H1 along "
                  "it, H2 at +90 deg), in place of the model file's direction");
  cmd->add_option("--from-cube", o->from_cube,
                  "Re-run one cell of a sweep's cube (model-file, subsystem, pilot-bridge) as the "
                  "sweep ran it");
  cmd->add_option("--sweep", o->sweep, "The sweep of --from-cube (when the cube holds several)");
  cmd->add_option("--cell", o->cell,
                  "The cell of --from-cube by its coordinates: AXIS=VALUE,AXIS=VALUE,...");
  cmd->add_option("--cell-index", o->cell_index,
                  "The cell of --from-cube by its row-major index (docs/hdf5-layout.md)");
  cmd->callback([o] {
    if (!o->from_cube.empty()) {
      RunCubeCell(*o);
      return;
    }
    if (o->model.empty()) {
      throw InputError(
          "run: MODEL is required (Model file (TOML, docs/model-format.md)), or --from-cube "
          "CUBE.h5 with --cell AXIS=VALUE,... or --cell-index N");
    }
    if (!o->sweep.empty() || !o->cell.empty() || o->cell_index >= 0) {
      throw InputError(std::string(!o->cell.empty()   ? "--cell"
                                   : o->sweep.empty() ? "--cell-index"
                                                      : "--sweep") +
                       ": chooses a cell of --from-cube CUBE.h5");
    }
    if (!o->record.empty() && !o->record_set.empty()) {
      throw InputError::AtField("--record", o->record, "give --record or --record-set, not both");
    }
    if (o->record_set.empty() != o->label.empty()) {
      throw InputError::AtField(o->label.empty() ? "--record-set" : "--label",
                                o->label.empty() ? o->record_set : o->label,
                                "--record-set and --label go together");
    }
    if (o->record.empty() && (!o->format.empty() || !o->units.empty() || o->dt_s)) {
      throw InputError("--format, --units, --dt: describe --record FILE");
    }
    RunModelFile(*o);
  });
}

}  // namespace skewbridge::app
