// `skewbridge modes MODEL.toml`: the natural frequencies and mode shapes of a model file's
// substructure (without contacts), and for a single deck its stiffness about the mass centre,
// the centre of rigidity, the principal stiffness axes and the torsional stiffness about the
// centre. Nothing is integrated; the excitation is read only to validate the file.
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include "jobs/app/commands.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"
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

}  // namespace

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
  cmd->add_option("MODEL", *model_path, "Model file (TOML, docs/model-format.md)")->required();
  cmd->callback([model_path] {
    const model::ModelFile file = model::ParseModelFile(*model_path);
    const model::Model& model = file.model;
    std::printf("model %s: %d deck%s, %d DOFs, substructure %s\n", model_path->c_str(),
                model.n_bodies(), model.n_bodies() == 1 ? "" : "s", model.n_dof(), KindName(file));
    PrintModes(model);
  });
}

}  // namespace skewbridge::app
