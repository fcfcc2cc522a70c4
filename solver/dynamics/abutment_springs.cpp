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
  const int n_decks = rigid.n_bodies();
  SB_DEMAND(spec.joints.size() + 1 == static_cast<std::size_t>(n_decks),
            "AbutmentSprings: one compliant law per deck-deck joint");
  for (const model::CompliantWall& w : spec.walls) {
    if (w.shear_keys) joint::ValidateShearKey(w.shear_keys->key, rigid.source());
  }
  // A single deck's corners are P1..P4; a row's are D<i>.P<k>, the +x wall on the last deck.
  const auto corner = [&](int deck, int k) {
    // append() rather than operator+ on temporaries: g++ 12 reports a false -Wrestrict there.
    std::string name = n_decks == 1 ? "P" : "D";
    if (n_decks > 1) name.append(std::to_string(deck)).append(".P");
    return name.append(std::to_string(k));
  };
  // The walls in the order of spec.walls: +x, then -x.
  const struct {
    int deck;
    int first, last;
  } walls[] = {{n_decks - 1, 1, 2}, {0, 3, 4}};
  std::vector<CompliantSpring> springs;
  // The backfill of every wall first (each with its wall's friction), then every abutment's keys.
  for (const bool keys : {false, true}) {
    for (std::size_t i = 0; i < 2; ++i) {
      const auto& w = walls[i];
      const int first = ContactIndex(rigid, corner(w.deck, w.first));
      const int last = ContactIndex(rigid, corner(w.deck, w.last));
      if (first < 0 || last < 0) continue;  // set = "+x": no -x wall
      SB_DEMAND(i < spec.walls.size(), "AbutmentSprings: a compliant law per wall of the model");
      const model::CompliantWall& law = spec.walls[i];
      if (law.law == model::JointLaw::kImpact) continue;  // a law per abutment's rigid wall
      const std::string prefix(model::WallName(i));
      if (keys) {
        if (!law.shear_keys) continue;
        const std::vector<CompliantSpring> these =
            AbutmentShearKeys(rigid, first, last, law.shear_keys->key, prefix);
        springs.insert(springs.end(), these.begin(), these.end());
        continue;
      }
      const joint::HyperbolicGap wall =
          model::WallBackfill(law.backfill, rigid.body(w.deck).geometry, rigid.source());
      std::vector<CompliantSpring> these =
          WallSprings(rigid, first, last, wall, law.springs, prefix);
      for (CompliantSpring& s : these) {
        s.mu = law.friction;
        s.k_t_N_per_m = law.stick_stiffness_Npm / law.springs;  // 0: the spring's K_max
      }
      springs.insert(springs.end(), these.begin(), these.end());
    }
  }
  // Each deck-deck joint: its two contacts (the narrower deck's corners against the other's end
  // face), in the model's order.
  for (std::size_t i = 0; i < spec.joints.size(); ++i) {
    const model::CompliantJoint& law = spec.joints[i];
    if (law.law == model::JointLaw::kImpact) continue;  // a rigid joint of a mixed row
    std::vector<int> pair;
    for (int c = 0; c < rigid.n_contacts(); ++c) {
      const model::Contact& contact = rigid.contact(c);
      const int lo = std::min(contact.body, contact.face.body);
      if (contact.face.body != model::kGround && lo == static_cast<int>(i)) pair.push_back(c);
    }
    SB_DEMAND(pair.size() == 2, "AbutmentSprings: two contacts per deck-deck joint");
    const std::string prefix = std::string("J").append(std::to_string(i));
    const std::vector<CompliantSpring> these =
        law.spring_dashpot
            ? SpringDashpots(rigid, pair[0], pair[1], law.k_Npm, law.c_Nspm, law.springs, prefix)
            : WallSprings(rigid, pair[0], pair[1],
                          model::WallBackfill(law.backfill,
                                              rigid.body(rigid.contact(pair[0]).body).geometry,
                                              rigid.source()),
                          law.springs, prefix);
    springs.insert(springs.end(), these.begin(), these.end());
  }
  return springs;
}

model::Model LawModel(const model::Model& model, const model::CompliantAbutments& compliant) {
  if (!compliant.Mixed()) return WithoutContacts(model);
  const int n_decks = model.n_bodies();
  SB_DEMAND(compliant.joints.size() + 1 == static_cast<std::size_t>(n_decks),
            "LawModel: a law per deck-deck joint");
  // A contact's law: an abutment corner's is its wall's (+x: P1, P2, of the last deck; -x: P3, P4,
  // of deck 0), a deck-deck corner's its joint's (the lower of its two decks). The compliant
  // ones leave; the others stay in order.
  const auto law_of = [&](const model::Contact& c) {
    if (c.face.body != model::kGround) {
      return compliant.joints[static_cast<std::size_t>(std::min(c.body, c.face.body))].law;
    }
    const char k = c.name.back();
    const std::size_t wall = k == '1' || k == '2' ? 0 : 1;
    return wall < compliant.walls.size() ? compliant.walls[wall].law : model::JointLaw::kImpact;
  };
  std::vector<model::Contact> contacts;
  for (const model::Contact& c : model.contacts()) {
    if (law_of(c) == model::JointLaw::kCompliant) continue;
    contacts.push_back(c);
  }
  std::optional<model::Modes> modes;
  if (model.modes() != nullptr) modes = *model.modes();
  return model::Model(model.bodies(), model.K(), model.C(), model.r(), std::move(contacts),
                      model.source(), std::move(modes));
}

std::vector<JointResponse> JointResponses(const model::CompliantAbutments& compliant, bool both) {
  std::vector<JointResponse> out;
  const std::size_t n = both ? 2 : 1;
  // A wall's maxima in the run, found by its name (a law per abutment's run has the compliant
  // wall's only).
  const auto wall_of = [](const LawRun& r, const std::string& wall) -> const WallMaxima& {
    for (const WallMaxima& m : r.walls) {
      if (m.wall == wall) return m;
    }
    SB_DEMAND(false, "JointResponses: the run has the wall's maxima");
    return r.walls.front();
  };
  // The rigid wall of a law per abutment has no springs and no keys: no response of its own.
  const auto compliant_wall = [&](std::size_t w) {
    return w >= compliant.walls.size() || compliant.walls[w].law == model::JointLaw::kCompliant;
  };
  for (std::size_t w = 0; w < n; ++w) {
    if (!compliant_wall(w)) continue;
    const std::string side = w == 0 ? "px" : "mx", wall = w == 0 ? "+x" : "-x";
    out.push_back({"spring_force_" + side, "N",
                   "largest force of one backfill spring of the " + wall + " wall",
                   [wall, wall_of](const LawRun& r) { return wall_of(r, wall).spring_force_N; }});
    out.push_back({"backwall_def_" + side, "m",
                   "largest deformation of the " + wall +
                       " backfill beyond the gap (the largest of its springs)",
                   [wall, wall_of](const LawRun& r) { return wall_of(r, wall).deformation_m; }});
  }
  // A compliant joint's maxima in the run, found by its name "J<i>" (a mixed row's run has the
  // compliant joints' only).
  const auto joint_of = [](const LawRun& r, const std::string& name) -> const WallMaxima& {
    for (const WallMaxima& m : r.joints) {
      if (m.wall == name) return m;
    }
    SB_DEMAND(false, "JointResponses: the run has the joint's maxima");
    return r.joints.front();
  };
  for (std::size_t i = 0; i < compliant.joints.size(); ++i) {
    if (compliant.joints[i].law == model::JointLaw::kImpact) continue;  // a rigid joint
    const std::string id = std::to_string(i), name = "J" + id;
    out.push_back({"joint_force_j" + id, "N",
                   "largest force of one spring of deck-deck joint " + id,
                   [name, joint_of](const LawRun& r) { return joint_of(r, name).spring_force_N; }});
    out.push_back({"joint_def_j" + id, "m",
                   "largest deformation of deck-deck joint " + id +
                       " beyond its gap (the largest of its springs)",
                   [name, joint_of](const LawRun& r) { return joint_of(r, name).deformation_m; }});
  }
  // The keys' responses of both abutments when either has keys (an abutment without keys: 0, and
  // inf for the break), so that a cube's responses do not depend on which abutment has them.
  if (!compliant.HasShearKeys()) return out;
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
    if (!compliant_wall(w)) continue;
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
  // A law per abutment: the rigid integrator with the rigid wall's contacts, carrying the springs.
  CompliantRunResult r = compliant->Mixed()
                             ? SimulateMixed(LawModel(model, *compliant), springs, excitation,
                                             control, {}, policies.event)
                             : SimulateCompliant(WithoutContacts(model), springs, excitation,
                                                 control, {}, policies.event);
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
    out.springs.push_back({springs[j].name, r.max_spring_force_N(i), r.max_spring_deformation_m(i),
                           r.wall_slip_m(i)});
    std::vector<WallMaxima>& group = wall[0] == 'J' ? out.joints : out.walls;
    if (group.empty() || group.back().wall != wall) group.push_back({wall, 0.0, 0.0});
    WallMaxima& m = group.back();
    m.spring_force_N = std::max(m.spring_force_N, r.max_spring_force_N(i));
    m.deformation_m = std::max(m.deformation_m, r.max_spring_deformation_m(i));
  }
  out.run = std::move(r.run);
  out.joint_stored_J = r.joint_stored_J;
  out.joint_dissipated_J = r.joint_dissipated_J;
  return out;
}

}  // namespace skewbridge::dynamics
