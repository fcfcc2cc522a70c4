#include "solver/dynamics/abutment_springs.h"

#include <algorithm>
#include <string_view>

#include "solver/common/error.h"
#include "solver/dynamics/run.h"

namespace skewbridge::dynamics {
namespace {

// The index of the contact named `name` (a deck corner), or -1.
int ContactIndex(const model::Model& model, std::string_view name) {
  for (int c = 0; c < model.n_contacts(); ++c) {
    if (model.contact(c).name == name) return c;
  }
  return -1;
}

}  // namespace

std::vector<CompliantSpring> AbutmentSprings(const model::Model& rigid,
                                             const model::CompliantAbutments& spec) {
  SB_DEMAND(rigid.n_bodies() == 1, "AbutmentSprings: a single deck");
  const joint::HyperbolicGap wall =
      model::WallBackfill(spec.backfill, rigid.body(0).geometry, rigid.source());
  std::vector<CompliantSpring> springs;
  const struct {
    const char* first;
    const char* last;
    const char* prefix;
  } walls[] = {{"P1", "P2", "+x"}, {"P3", "P4", "-x"}};
  for (const auto& w : walls) {
    const int first = ContactIndex(rigid, w.first);
    const int last = ContactIndex(rigid, w.last);
    if (first < 0 || last < 0) continue;  // set = "+x": no -x wall
    std::vector<CompliantSpring> these =
        WallSprings(rigid, first, last, wall, spec.springs, w.prefix);
    for (CompliantSpring& s : these) {
      s.mu = spec.wall_friction;
      s.k_t_N_per_m = spec.stick_stiffness_Npm / spec.springs;  // 0: the spring's K_max
    }
    springs.insert(springs.end(), these.begin(), these.end());
  }
  return springs;
}

LawRun RunUnderLaw(const model::Model& model,
                   const std::optional<model::CompliantAbutments>& compliant,
                   const Excitation& excitation, const model::RunControl& control,
                   const RunPolicies& policies) {
  LawRun out;
  if (!compliant) {
    out.run = Run(model, excitation, control, policies);
    return out;
  }
  if (control.method != model::Method::kEventDriven) {
    throw InputError::AtField(model.source(), "run.method",
                              "the compliant abutments run with the event-driven method only "
                              "(allowed: \"event-driven\")");
  }
  const std::vector<CompliantSpring> springs = AbutmentSprings(model, *compliant);
  CompliantRunResult r =
      SimulateCompliant(WithoutContacts(model), springs, excitation, control, {}, policies.event);
  for (std::size_t j = 0; j < springs.size(); ++j) {
    const std::string wall = springs[j].name.substr(0, springs[j].name.find('.'));
    if (out.walls.empty() || out.walls.back().wall != wall) out.walls.push_back({wall, 0.0, 0.0});
    WallMaxima& m = out.walls.back();
    m.spring_force_N = std::max(m.spring_force_N, r.max_spring_force_N(static_cast<int>(j)));
    m.deformation_m = std::max(m.deformation_m, r.max_spring_deformation_m(static_cast<int>(j)));
  }
  out.run = std::move(r.run);
  out.joint_stored_J = r.joint_stored_J;
  out.joint_dissipated_J = r.joint_dissipated_J;
  return out;
}

}  // namespace skewbridge::dynamics
