// `skewbridge modes MODEL.toml`: the natural frequencies and mode shapes of a model file's
// substructure (without contacts), and for a single deck its stiffness about the mass centre,
// the centre of rigidity, the principal stiffness axes and the torsional stiffness about the
// centre. Nothing is integrated; the excitation is read only to validate the file. With --plan
// it prints instead the model's plan geometry as JSON, for drawing (scripts/report --model).
#include <fmt/core.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include "jobs/app/commands.h"
#include "jobs/app/json_text.h"
#include "solver/contact/kinematics.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"
#include "solver/model/plausibility.h"
#include "solver/model/substructure.h"

namespace skewbridge::app {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

const char* KindName(const model::ModelFile& file) {
  if (file.decks) {
    return "[[support]] tables";
  }
  switch (file.deck.stiffness) {
    case model::DeckSpec::StiffnessKind::kUncoupled:
      return "uncoupled";
    case model::DeckSpec::StiffnessKind::kPrincipal:
      return "principal";
    case model::DeckSpec::StiffnessKind::kElements:
      return "elements";
    case model::DeckSpec::StiffnessKind::kMatrix:
    default:
      return "matrix";
  }
}

// The stiffness analysis of deck b's own 3x3 block of K (its x, y, theta about its mass centre).
void PrintStiffnessCentre(const model::Model& model, int b) {
  const Eigen::Matrix3d K = model.K().block<3, 3>(3 * b, 3 * b);
  std::printf("stiffness about the mass centre (rows x, y, theta; N/m, N/rad, N m/rad):\n");
  for (int i = 0; i < 3; ++i) {
    std::printf("  %14.6e %14.6e %14.6e\n", K(i, 0), K(i, 1), K(i, 2));
  }
  const model::StiffnessCentre c = model::AnalyseStiffness(K);
  const double axis1_deg = c.axis1_rad * kRadToDeg;
  std::printf("principal axes: k1 = %.6e N/m at %.4f deg from x, k2 = %.6e N/m at %.4f deg\n",
              c.principal_Npm(0), axis1_deg, c.principal_Npm(1), axis1_deg + 90.0);
  if (c.has_centre) {
    std::printf("centre of rigidity: e_x = %.6g m, e_y = %.6g m from the mass centre\n",
                c.centre_of_rigidity_m.x() + 0.0, c.centre_of_rigidity_m.y() + 0.0);
    std::printf("torsion about the centre of rigidity: %.6e N m/rad\n",
                c.torsion_about_centre_Nmprad);
  } else {
    std::printf(
        "centre of rigidity: none (the translational stiffness is singular: a direction "
        "without stiffness)\n");
  }
}

std::string Json(const Eigen::Vector2d& v) { return fmt::format("[{}, {}]", v.x(), v.y()); }

std::string Json(const std::string& text) { return JsonString(text); }

// A number, or null when it is not finite (JSON has no NaN).
std::string Json(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

std::string JsonSpring(const model::PlanSpring& k) {
  return fmt::format("\"k_strong_Npm\": {}, \"k_weak_Npm\": {}, \"strong_axis_deg\": {}",
                     Json(k.k_strong_Npm), Json(k.k_weak_Npm), Json(k.strong_axis_rad * kRadToDeg));
}

// The plan of a model file at rest (q = 0) in the ground frame (m): each deck's outline,
// mass centre and stiffness analysis, each contact's corner and face with its gap, the bearings
// and piers of the elements form (deck frame = ground frame for one deck) and the supports of
// the [[deck]] form, as one JSON object (docs/model-format.md, `skewbridge modes --plan`).
void PrintPlanJson(const model::ModelFile& file, const std::string& path) {
  const model::Model& model = file.model;
  std::string out = fmt::format("{{\n  \"model\": {},\n  \"decks\": [", Json(path));
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(model.n_dof());
  for (int b = 0; b < model.n_bodies(); ++b) {
    const model::Body& body = model.body(b);
    const Eigen::Matrix3d K = model.K().block<3, 3>(3 * b, 3 * b);
    const model::StiffnessCentre c = model::AnalyseStiffness(K);
    std::string corners;
    for (int k = 1; k <= 4; ++k) {
      corners += (k > 1 ? ", " : "") + Json(body.rest_position_m + model::Corner(body.geometry, k));
    }
    out += fmt::format(
        "{}\n    {{\"name\": {}, \"mass_kg\": {}, \"inertia_kgm2\": {}, \"L_m\": {}, "
        "\"W_m\": {}, \"skew_deg\": {}, \"mass_centre_m\": {}, \"corners_m\": [{}], "
        "\"centre_of_rigidity_m\": {}, \"principal_Npm\": {}, \"axis1_deg\": {}, "
        "\"torsion_about_centre_Nmprad\": {}}}",
        b > 0 ? "," : "", Json(body.name), Json(body.mass_kg), Json(body.inertia_kgm2),
        Json(body.geometry.length_m), Json(body.geometry.width_m),
        Json(body.geometry.skew_rad * kRadToDeg), Json(body.rest_position_m), corners,
        c.has_centre ? Json(body.rest_position_m + c.centre_of_rigidity_m) : "null",
        Json(c.principal_Npm), Json(c.axis1_rad * kRadToDeg), Json(c.torsion_about_centre_Nmprad));
  }
  out += "\n  ],\n  \"contacts\": [";
  for (int i = 0; i < model.n_contacts(); ++i) {
    const model::Contact& k = model.contact(i);
    const Eigen::Vector2d shift = k.face.body == model::kGround
                                      ? Eigen::Vector2d::Zero()
                                      : Eigen::Vector2d(model.body(k.face.body).rest_position_m);
    out += fmt::format(
        "{}\n    {{\"name\": {}, \"deck\": {}, \"point_m\": {}, \"face_deck\": {}, "
        "\"face_point_m\": {}, \"normal\": {}, \"tangent\": {}, \"gap_m\": {}, "
        "\"eps_N\": {}, \"mu\": {}}}",
        i > 0 ? "," : "", Json(k.name), k.body,
        Json(model.body(k.body).rest_position_m + k.point_m),
        k.face.body == model::kGround ? "null" : fmt::format("{}", k.face.body),
        Json(shift + k.face.point_m), Json(k.face.normal), Json(k.face.tangent),
        Json(contact::Gap(model, i, q0)), Json(k.restitution), Json(k.friction));
  }
  out += "\n  ],\n  \"piers\": [";
  const bool elements =
      !file.decks && file.deck.stiffness == model::DeckSpec::StiffnessKind::kElements;
  if (elements) {
    for (std::size_t i = 0; i < file.deck.piers.size(); ++i) {
      const model::PierSpec& p = file.deck.piers[i];
      out += fmt::format("{}\n    {{\"position_m\": {}, {}}}", i > 0 ? "," : "", Json(p.position_m),
                         JsonSpring(p.spring));
    }
  }
  out += "\n  ],\n  \"bearings\": [";
  if (elements) {
    for (std::size_t i = 0; i < file.deck.bearings.size(); ++i) {
      const model::BearingSpec& bearing = file.deck.bearings[i];
      out += fmt::format("{}\n    {{\"position_m\": {}, \"pier\": {}, {}}}", i > 0 ? "," : "",
                         Json(bearing.position_m),
                         bearing.pier < 0 ? "null" : fmt::format("{}", bearing.pier),
                         JsonSpring(bearing.spring));
    }
  }
  out += "\n  ],\n  \"supports\": [";
  if (file.decks) {
    for (std::size_t i = 0; i < file.decks->supports.size(); ++i) {
      const model::SupportSpec& s = file.decks->supports[i];
      out += fmt::format(
          "{}\n    {{\"deck\": {}, \"other\": {}, \"k_x_Npm\": {}, \"k_y_Npm\": {}, "
          "\"k_theta_Nmprad\": {}}}",
          i > 0 ? "," : "", s.deck, s.other < 0 ? "null" : fmt::format("{}", s.other),
          Json(s.stiffness.x()), Json(s.stiffness.y()), Json(s.stiffness.z()));
    }
  }
  out += "\n  ]\n}\n";
  std::fputs(out.c_str(), stdout);
}

}  // namespace

void PrintWarnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings)
    std::fprintf(stderr, "skewbridge: warning: %s\n", w.c_str());
}

void PrintNaturalFrequencies(const model::Model& model) {
  const model::Modes modes = model::ComputeModes(model.M(), model.K());
  std::printf("natural frequencies (substructure without contacts):\n");
  for (Eigen::Index k = 0; k < modes.omega_radps.size(); ++k) {
    const double w = modes.omega_radps(k);
    std::printf("  mode %ld: w = %.6g rad/s, f = %.6g Hz", static_cast<long>(k + 1), w,
                w / (2.0 * std::numbers::pi));
    if (w > 0.0) {
      std::printf(", T = %.6g s", 2.0 * std::numbers::pi / w);
    }
    std::printf("\n");
  }
}

void PrintModes(const model::Model& model) {
  PrintNaturalFrequencies(model);
  const model::Modes modes = model::ComputeModes(model.M(), model.K());
  std::vector<model::Body> bodies;
  for (int b = 0; b < model.n_bodies(); ++b) {
    bodies.push_back(model.body(b));
  }
  const Eigen::MatrixXd shapes = model::DisplayModeShapes(modes, bodies);
  std::printf(
      "mode shapes (columns: modes; rho theta with rho the radius of gyration; "
      "largest entry +1):\n");
  for (Eigen::Index i = 0; i < shapes.rows(); ++i) {
    const int b = static_cast<int>(i / 3);
    const char* names[3] = {"x", "y", "rho theta"};
    std::printf("  %-9s deck %d:", names[i % 3], b);
    for (Eigen::Index k = 0; k < shapes.cols(); ++k) {
      std::printf(" %10.6f", shapes(i, k));
    }
    std::printf("\n");
  }
  if (model.n_bodies() == 1) {
    PrintStiffnessCentre(model, 0);
    return;
  }
  // Several decks: each deck's own centre of rigidity, when the substructure ties every deck to
  // the ground alone (K block-diagonal); a spring between decks leaves no per-deck centre.
  const Eigen::MatrixXd& K = model.K();
  Eigen::MatrixXd coupling = K;
  for (int b = 0; b < model.n_bodies(); ++b) {
    coupling.block<3, 3>(3 * b, 3 * b).setZero();
  }
  if (coupling.cwiseAbs().maxCoeff() > 0.0) {
    std::printf(
        "centre of rigidity and principal axes: none per deck (the substructure couples the "
        "decks)\n");
    return;
  }
  for (int b = 0; b < model.n_bodies(); ++b) {
    std::printf("deck %d:\n", b);
    PrintStiffnessCentre(model, b);
  }
}

void AddModesCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "modes",
      "Print a model file's natural frequencies, mode shapes, centre of rigidity and principal "
      "stiffness axes");
  auto model_path = std::make_shared<std::string>();
  auto plan = std::make_shared<bool>(false);
  cmd->add_option("MODEL", *model_path, "Model file (TOML, docs/model-format.md)")->required();
  cmd->add_flag("--plan", *plan,
                "Print instead the plan geometry at rest as JSON (decks, contacts with gaps, "
                "bearings, piers, centres of rigidity), as scripts/report --model draws it");
  cmd->callback([model_path, plan] {
    const model::ModelFile file = model::ParseModelFile(*model_path);
    PrintWarnings(model::PlausibilityWarnings(file));
    if (*plan) {
      PrintPlanJson(file, *model_path);
      return;
    }
    const model::Model& model = file.model;
    std::printf("model %s: %d deck%s, %d DOFs, substructure %s\n", model_path->c_str(),
                model.n_bodies(), model.n_bodies() == 1 ? "" : "s", model.n_dof(), KindName(file));
    PrintModes(model);
  });
}

}  // namespace skewbridge::app
