#include "solver/dynamics/abutment_springs.h"

#include <algorithm>
#include <cmath>
#include <limits>
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
  if (spec.shear_keys) joint::ValidateShearKey(spec.shear_keys->key, rigid.source());
  std::vector<CompliantSpring> springs;
  const struct {
    const char* first;
    const char* last;
    const char* prefix;
  } walls[] = {{"P1", "P2", "+x"}, {"P3", "P4", "-x"}};
  // The backfill of every wall first (with the wall's friction), then the keys of every abutment.
  for (const bool keys : {false, true}) {
    if (keys && !spec.shear_keys) break;
    for (const auto& w : walls) {
      const int first = ContactIndex(rigid, w.first);
      const int last = ContactIndex(rigid, w.last);
      if (first < 0 || last < 0) continue;  // set = "+x": no -x wall
      if (keys) {
        const std::vector<CompliantSpring> these =
            AbutmentShearKeys(rigid, first, last, spec.shear_keys->key, w.prefix);
        springs.insert(springs.end(), these.begin(), these.end());
        continue;
      }
      std::vector<CompliantSpring> these =
          WallSprings(rigid, first, last, wall, spec.springs, w.prefix);
      for (CompliantSpring& s : these) {
        s.mu = spec.wall_friction;
        s.k_t_N_per_m = spec.stick_stiffness_Npm / spec.springs;  // 0: the spring's K_max
      }
      springs.insert(springs.end(), these.begin(), these.end());
    }
  }
  return springs;
}

std::vector<JointResponse> JointResponses(const model::CompliantAbutments& compliant, bool both) {
  std::vector<JointResponse> out;
  const std::size_t n = both ? 2 : 1;
  for (std::size_t w = 0; w < n; ++w) {
    const std::string side = w == 0 ? "px" : "mx", wall = w == 0 ? "+x" : "-x";
    out.push_back({"spring_force_" + side, "N",
                   "largest force of one backfill spring of the " + wall + " wall",
                   [w](const LawRun& r) { return r.walls[w].spring_force_N; }});
    out.push_back({"backwall_def_" + side, "m",
                   "largest deformation of the " + wall +
                       " backfill beyond the gap (the largest of its springs)",
                   [w](const LawRun& r) { return r.walls[w].deformation_m; }});
  }
  if (!compliant.shear_keys) return out;
  // The keys of one abutment: the largest of `of` over them, or the earliest break.
  const auto over = [](std::string wall, double KeyMaxima::*of, bool earliest) {
    return [wall, of, earliest](const LawRun& r) {
      double v = earliest ? std::numeric_limits<double>::infinity() : 0.0;
      for (const KeyMaxima& k : r.keys) {
        if (k.wall == wall) v = earliest ? std::min(v, k.*of) : std::max(v, k.*of);
      }
      return v;
    };
  };
  for (std::size_t w = 0; w < n; ++w) {
    const std::string side = w == 0 ? "px" : "mx", wall = w == 0 ? "+x" : "-x";
    out.push_back({"key_force_" + side, "N",
                   "largest force of the " + wall + " abutment's two shear keys",
                   over(wall, &KeyMaxima::force_N, false)});
    out.push_back({"key_def_" + side, "m",
                   "largest deformation of the " + wall +
                       " abutment's shear keys beyond their transverse gap",
                   over(wall, &KeyMaxima::deformation_m, false)});
    out.push_back({"key_break_time_" + side, "s",
                   "earliest time one of the " + wall +
                       " abutment's shear keys broke (deformation DD); inf when neither broke",
                   over(wall, &KeyMaxima::break_time_s, true)});
  }
  out.push_back(
      {"keys_broken", "1", "number of shear keys broken over the run", [](const LawRun& r) {
         return static_cast<double>(
             std::count_if(r.keys.begin(), r.keys.end(),
                           [](const KeyMaxima& k) { return !std::isinf(k.break_time_s); }));
       }});
  return out;
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
    const int i = static_cast<int>(j);
    const std::string wall = springs[j].name.substr(0, springs[j].name.find('.'));
    if (springs[j].law == SpringLaw::kShearKey) {
      const double broke = r.key_break_time_s(i);
      out.keys.push_back({springs[j].name, wall, r.max_spring_force_N(i),
                          r.max_spring_deformation_m(i),
                          std::isnan(broke) ? std::numeric_limits<double>::infinity() : broke});
      continue;
    }
    if (out.walls.empty() || out.walls.back().wall != wall) out.walls.push_back({wall, 0.0, 0.0});
    WallMaxima& m = out.walls.back();
    m.spring_force_N = std::max(m.spring_force_N, r.max_spring_force_N(i));
    m.deformation_m = std::max(m.deformation_m, r.max_spring_deformation_m(i));
  }
  out.run = std::move(r.run);
  out.joint_stored_J = r.joint_stored_J;
  out.joint_dissipated_J = r.joint_dissipated_J;
  return out;
}

}  // namespace skewbridge::dynamics
