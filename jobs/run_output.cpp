#include "jobs/run_output.h"

#include <string>
#include <vector>

#include "jobs/h5/cube_file.h"
#include "jobs/h5/event_policy_attrs.h"
#include "jobs/h5/h5.h"
#include "solver/common/error.h"

namespace skewbridge::jobs {
namespace {

using h5::Id;

// Per-DOF names and units in the order of q: x, y, theta of body 0, then body 1, ...
struct DofLabels {
  std::vector<std::string> q_names, q_units, u_names, u_units;
};

DofLabels MakeDofLabels(int n_bodies) {
  DofLabels l;
  for (int b = 0; b < n_bodies; ++b) {
    const std::string s = std::to_string(b);
    l.q_names.insert(l.q_names.end(), {"x" + s, "y" + s, "theta" + s});
    l.q_units.insert(l.q_units.end(), {"m", "m", "rad"});
    l.u_names.insert(l.u_names.end(), {"vx" + s, "vy" + s, "omega" + s});
    l.u_units.insert(l.u_units.end(), {"m/s", "m/s", "rad/s"});
  }
  return l;
}

// A contiguous dataset of the given shape written whole, with its units and description.
Id WriteArray(hid_t parent, const std::string& name, hid_t mem_type, std::vector<hsize_t> shape,
              const void* data, const std::string& units, const std::string& description) {
  Id d = h5::CreateDataset(parent, name, mem_type, shape, {}, 0, nullptr);
  hsize_t count = 1;
  for (hsize_t s : shape) count *= s;
  // A zero-size selection has nothing to transfer and some HDF5 builds reject a null buffer.
  if (count > 0) {
    h5::WriteAll(d.get(), mem_type, data);
  }
  h5::SetAttr(d.get(), "units", units);
  h5::SetAttr(d.get(), "description", description);
  return d;
}

Id WriteDoubles(hid_t parent, const std::string& name, std::vector<hsize_t> shape,
                const double* data, const std::string& units, const std::string& description) {
  return WriteArray(parent, name, H5T_NATIVE_DOUBLE, std::move(shape), data, units, description);
}

Id WriteInts(hid_t parent, const std::string& name, std::vector<hsize_t> shape,
             const std::int32_t* data, const std::string& units, const std::string& description) {
  return WriteArray(parent, name, H5T_NATIVE_INT32, std::move(shape), data, units, description);
}

void SetColumns(hid_t dataset, const std::vector<std::string>& names,
                const std::vector<std::string>& units) {
  h5::SetAttr(dataset, "column_names", names);
  h5::SetAttr(dataset, "column_units", units);
}

void WriteSummary(hid_t file, const model::Model& model, const dynamics::RunResult& r,
                  const DofLabels& labels) {
  Id g = h5::CreateGroup(file, "summary");
  const hsize_t n = static_cast<hsize_t>(model.n_dof());
  SB_DEMAND(r.max_abs_q.size() == model.n_dof() && r.time_of_max_s.size() == model.n_dof() &&
                r.q_end.size() == model.n_dof() && r.u_end.size() == model.n_dof(),
            "run result sizes differ from the model's n_dof");
  Id d = WriteDoubles(g.get(), "max_abs_q", {n}, r.max_abs_q.data(), "m (x, y), rad (theta)",
                      "maximum over time of |q_i| per degree of freedom");
  SetColumns(d.get(), labels.q_names, labels.q_units);
  d = WriteDoubles(g.get(), "time_of_max_s", {n}, r.time_of_max_s.data(), "s",
                   "time at which each max_abs_q entry occurred");
  SetColumns(d.get(), labels.q_names, std::vector<std::string>(labels.q_names.size(), "s"));
  d = WriteDoubles(g.get(), "q_end", {n}, r.q_end.data(), "m (x, y), rad (theta)",
                   "residual displacements and rotations at the end time");
  SetColumns(d.get(), labels.q_names, labels.q_units);
  d = WriteDoubles(g.get(), "u_end", {n}, r.u_end.data(), "m/s (vx, vy), rad/s (omega)",
                   "velocities at the end time");
  SetColumns(d.get(), labels.u_names, labels.u_units);
  if (r.max_travel_m.size() == model.n_bodies()) {
    std::vector<std::string> decks;
    for (int b = 0; b < model.n_bodies(); ++b) decks.push_back("deck" + std::to_string(b));
    d = WriteDoubles(g.get(), "max_travel_m", {static_cast<hsize_t>(model.n_bodies())},
                     r.max_travel_m.data(), "m",
                     "largest travel of any corner of each deck normal to its end line over the "
                     "run, tracked by the integrator (the unseating demand travel_m of a cube)");
    SetColumns(d.get(), decks, std::vector<std::string>(decks.size(), "m"));
  }

  h5::SetAttr(g.get(), "end_time_s", r.end_time_s);
  h5::SetAttr(g.get(), "impacts", static_cast<std::int64_t>(r.impacts));
  h5::SetAttr(g.get(), "plastic_closures", static_cast<std::int64_t>(r.plastic_closures));
  h5::SetAttr(g.get(), "detachments", static_cast<std::int64_t>(r.detachments));
  h5::SetAttr(g.get(), "stick_transitions", static_cast<std::int64_t>(r.stick_transitions));
  h5::SetAttr(g.get(), "slip_transitions", static_cast<std::int64_t>(r.slip_transitions));
  h5::SetAttr(g.get(), "free_steps", static_cast<std::int64_t>(r.free_steps));
  h5::SetAttr(g.get(), "rk_steps", static_cast<std::int64_t>(r.rk_steps));
  h5::SetAttr(g.get(), "rk_rejected", static_cast<std::int64_t>(r.rk_rejected));
  // +inf (fewer than two impacts) is a valid IEEE value in HDF5 and reads back as inf.
  h5::SetAttr(g.get(), "min_impact_separation_s", r.min_impact_separation_s);
}

void WriteEnergy(hid_t file, const dynamics::EnergyLedger& e) {
  Id g = h5::CreateGroup(file, "energy");
  h5::SetAttr(g.get(), "units", std::string("J"));
  h5::SetAttr(g.get(), "balance",
              std::string("balance_error_J = (kinetic_J + strain_J) - (initial_J + input_J - "
                          "damping_J - impact_J - friction_J)"));
  h5::SetAttr(g.get(), "initial_J", e.initial_J);
  h5::SetAttr(g.get(), "input_J", e.input_J);
  h5::SetAttr(g.get(), "damping_J", e.damping_J);
  h5::SetAttr(g.get(), "impact_J", e.impact_J);
  h5::SetAttr(g.get(), "friction_J", e.friction_J);
  h5::SetAttr(g.get(), "kinetic_J", e.kinetic_J);
  h5::SetAttr(g.get(), "strain_J", e.strain_J);
  h5::SetAttr(g.get(), "balance_error_J", e.balance_error_J);
}

std::vector<std::string> ContactNames(const model::Model& model) {
  std::vector<std::string> names;
  for (const model::Contact& c : model.contacts()) names.push_back(c.name);
  return names;
}

void WriteEvents(hid_t file, const model::Model& model, const dynamics::RunResult& r) {
  Id g = h5::CreateGroup(file, "events");
  const std::size_t n = r.events.size();
  std::vector<double> t(n), in(n), it(n), before(n), after(n), loss(n);
  std::vector<std::int32_t> kind(n), contact(n);
  for (std::size_t i = 0; i < n; ++i) {
    const dynamics::EventRecord& e = r.events[i];
    t[i] = e.t_s;
    kind[i] = static_cast<std::int32_t>(e.kind);
    contact[i] = e.contact;
    in[i] = e.impulse_N_Ns;
    it[i] = e.impulse_T_Ns;
    before[i] = e.gamma_N_before_mps;
    after[i] = e.gamma_N_after_mps;
    loss[i] = e.kinetic_loss_J;
  }
  const std::vector<std::string> contacts = ContactNames(model);
  h5::SetAttr(g.get(), "contact_names", contacts);
  h5::SetAttr(g.get(), "count", static_cast<std::int64_t>(n));
  const hsize_t rows = static_cast<hsize_t>(n);
  WriteDoubles(g.get(), "t_s", {rows}, t.data(), "s", "time of the event");
  Id k = WriteInts(g.get(), "kind", {rows}, kind.data(), "1",
                   "event kind code; kind_names[code] names it");
  const dynamics::EventKind kinds[] = {
      dynamics::EventKind::kImpact, dynamics::EventKind::kPlasticClosure,
      dynamics::EventKind::kDetachment, dynamics::EventKind::kStick, dynamics::EventKind::kSlip};
  std::vector<std::string> kind_names;
  std::vector<std::int32_t> kind_codes;
  for (dynamics::EventKind kk : kinds) {
    kind_names.emplace_back(dynamics::ToString(kk));
    kind_codes.push_back(static_cast<std::int32_t>(kk));
  }
  h5::SetAttr(k.get(), "kind_names", kind_names);
  h5::SetAttr(k.get(), "kind_codes", kind_codes);
  Id c = WriteInts(g.get(), "contact", {rows}, contact.data(), "1",
                   "model contact index; the group's contact_names[index] names it");
  h5::SetAttr(c.get(), "contact_names", contacts);
  WriteDoubles(g.get(), "impulse_N", {rows}, in.data(), "N s",
               "normal impulse Lambda_N (impacts; 0 otherwise)");
  WriteDoubles(g.get(), "impulse_T", {rows}, it.data(), "N s",
               "tangential impulse Lambda_T (impacts; 0 otherwise)");
  WriteDoubles(g.get(), "gamma_N_before", {rows}, before.data(), "m/s",
               "normal relative velocity before the impact, gamma_N,A (impacts)");
  WriteDoubles(g.get(), "gamma_N_after", {rows}, after.data(), "m/s",
               "normal relative velocity after the impact, gamma_N,E (impacts)");
  WriteDoubles(g.get(), "kinetic_loss", {rows}, loss.data(), "J",
               "kinetic energy lost by the whole (multi-contact) impact; repeated on each "
               "contact's row of that impact");
}

void WriteHistories(hid_t file, const model::Model& model, const dynamics::Histories& h,
                    const DofLabels& labels) {
  const std::size_t n = h.t_s.size();
  const std::size_t nd = static_cast<std::size_t>(h.n_dof);
  const std::size_t nc = static_cast<std::size_t>(h.n_contacts);
  SB_DEMAND(h.n_dof == model.n_dof() && h.n_contacts == model.n_contacts(),
            "histories sized for a different model");
  SB_DEMAND(h.q.size() == n * nd && h.u.size() == n * nd && h.gap_m.size() == n * nc &&
                h.lambda_N.size() == n * nc && h.lambda_T.size() == n * nc &&
                h.state.size() == n * nc,
            "history arrays of inconsistent length");
  Id g = h5::CreateGroup(file, "histories");
  const hsize_t rows = static_cast<hsize_t>(n), dof = static_cast<hsize_t>(nd),
                cts = static_cast<hsize_t>(nc);
  h5::SetAttr(g.get(), "samples", static_cast<std::int64_t>(n));
  Id t = WriteDoubles(g.get(), "t_s", {rows}, h.t_s.data(), "s", "sample times");
  h5::SetScale(t.get(), "t_s");

  const std::vector<std::string> contacts = ContactNames(model);
  Id q = WriteDoubles(g.get(), "q", {rows, dof}, h.q.data(), "m (x, y), rad (theta)",
                      "displacements and rotations relative to the ground, [sample, dof]");
  SetColumns(q.get(), labels.q_names, labels.q_units);
  Id u = WriteDoubles(g.get(), "u", {rows, dof}, h.u.data(), "m/s (vx, vy), rad/s (omega)",
                      "velocities relative to the ground, [sample, dof]");
  SetColumns(u.get(), labels.u_names, labels.u_units);
  Id gap = WriteDoubles(g.get(), "gap", {rows, cts}, h.gap_m.data(), "m",
                        "normal gap g_N of each contact, [sample, contact]");
  Id ln = WriteDoubles(g.get(), "lambda_N", {rows, cts}, h.lambda_N.data(), "N",
                       "contact normal force, [sample, contact]");
  Id lt = WriteDoubles(g.get(), "lambda_T", {rows, cts}, h.lambda_T.data(), "N",
                       "contact tangential force, [sample, contact]");
  std::vector<std::int32_t> state(h.state.begin(), h.state.end());
  Id st = WriteInts(g.get(), "state", {rows, cts}, state.data(), "1",
                    "contact state code, [sample, contact]; state_names[code] names it");
  h5::SetAttr(st.get(), "state_names",
              std::vector<std::string>{"open", "stick", "slide-positive", "slide-negative"});
  h5::SetAttr(st.get(), "state_codes", std::vector<std::int32_t>{0, 1, 2, 3});
  for (const Id* d : {&gap, &ln, &lt, &st}) {
    h5::SetAttr(d->get(), "column_names", contacts);
  }
  for (const Id* d : {&q, &u, &gap, &ln, &lt, &st}) {
    h5::AttachScale(d->get(), t.get(), 0, "t_s");
  }
}

void WriteOrigin(hid_t file, const RunOrigin& origin) {
  Id g = h5::CreateGroup(file, "origin");
  for (const auto& [name, value] : origin.text) h5::SetAttr(g.get(), name, value);
  for (const auto& [name, value] : origin.numbers) h5::SetAttr(g.get(), name, value);
  if (origin.ground_ax_mps2.empty()) return;
  SB_DEMAND(origin.ground_ay_mps2.size() == origin.ground_ax_mps2.size(),
            "ground acceleration components of different lengths");
  const std::size_t n = origin.ground_ax_mps2.size();
  std::vector<double> a(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    a[2 * k] = origin.ground_ax_mps2[k];
    a[2 * k + 1] = origin.ground_ay_mps2[k];
  }
  Id d =
      WriteDoubles(g.get(), "ground_acceleration", {static_cast<hsize_t>(n), 2}, a.data(), "m/s^2",
                   "ground acceleration applied, sample k at t = k dt_s, linear between "
                   "samples, zero after the last; [sample, (x, y)]");
  SetColumns(d.get(), {"a_x", "a_y"}, {"m/s^2", "m/s^2"});
  h5::SetAttr(d.get(), "dt_s", origin.ground_dt_s);
}

void WriteJoints(hid_t file, const RunJoints& joints) {
  Id g = h5::CreateGroup(file, "joints");
  std::vector<std::string> names, units;
  for (const RunJoints::Response& r : joints.responses) {
    h5::SetAttr(g.get(), r.name, r.value);
    names.push_back(r.name);
    units.push_back(r.unit);
  }
  h5::SetAttr(g.get(), "response_names", names);
  h5::SetAttr(g.get(), "response_units", units);
  h5::SetAttr(g.get(), "joint_stored_J", joints.stored_J);
  h5::SetAttr(g.get(), "joint_dissipated_J", joints.dissipated_J);
  if (!joints.spring_names.empty()) {
    const hsize_t n = joints.spring_names.size();
    h5::SetAttr(g.get(), "spring_names", joints.spring_names);
    WriteDoubles(g.get(), "spring_force_N", {n}, joints.spring_force_N.data(), "N",
                 "largest force of each backfill or joint spring (spring_names)");
    WriteDoubles(g.get(), "spring_deformation_m", {n}, joints.spring_deformation_m.data(), "m",
                 "largest deformation of each spring beyond its face (the joint's gap)");
    WriteDoubles(g.get(), "spring_slip_m", {n}, joints.spring_slip_m.data(), "m",
                 "plastic slip of each spring along its wall over the run (0 without friction)");
  }
  if (joints.key_names.empty()) return;
  const hsize_t n = joints.key_names.size();
  h5::SetAttr(g.get(), "key_names", joints.key_names);
  WriteDoubles(g.get(), "key_force_N", {n}, joints.key_force_N.data(), "N",
               "largest force of each shear key (key_names)");
  WriteDoubles(g.get(), "key_deformation_m", {n}, joints.key_deformation_m.data(), "m",
               "largest deformation of each shear key beyond its transverse gap");
  WriteDoubles(g.get(), "key_break_time_s", {n}, joints.key_break_time_s.data(), "s",
               "time each shear key broke (deformation DD); inf for a key left intact");
}

}  // namespace

void WriteRunHdf5(const std::filesystem::path& path, const model::Model& model,
                  const dynamics::RunResult& result, std::string_view model_text,
                  std::string_view method, double time_step_s, const RunOrigin& origin,
                  const dynamics::RunPolicies& policies, const RunJoints& joints) {
  h5::SilenceErrorStack();
  Id file = h5::CreateFile(path.string());
  const hid_t f = file.get();
  h5::SetAttr(f, "format", std::string(kRunFormat));
  h5::SetAttr(f, "format_version", kRunFormatVersion);
  h5::SetAttr(f, "program_version", std::string(SKEWBRIDGE_VERSION));
  h5::SetAttr(f, "git_revision", std::string(SKEWBRIDGE_GIT_REVISION));
  h5::SetAttr(f, "created_utc", h5::UtcNow());
  h5::SetAttr(f, "model_text", std::string(model_text));
  h5::SetAttr(f, "status", std::string(dynamics::ToString(result.status)));
  h5::SetAttr(f, "status_message", result.message);
  h5::SetAttr(f, "method", std::string(method));
  h5::SetAttr(f, "time_step_s", time_step_s);
  h5::SetAttr(f, "n_bodies", static_cast<std::int64_t>(model.n_bodies()));
  h5::SetAttr(f, "n_dof", static_cast<std::int64_t>(model.n_dof()));
  h5::SetAttr(f, "contact_names", ContactNames(model));
  // The thresholds and rules of the integrator that ran.
  const std::optional<model::Method> ran = model::ParseMethod(method);
  SB_DEMAND(ran.has_value(), "WriteRunHdf5: unknown method");
  h5::WriteMethodPolicies(f, {*ran}, policies);

  const DofLabels labels = MakeDofLabels(model.n_bodies());
  WriteSummary(f, model, result, labels);
  WriteEnergy(f, result.energy);
  WriteEvents(f, model, result);
  if (!result.histories.t_s.empty()) {
    WriteHistories(f, model, result.histories, labels);
  }
  if (!origin.Empty()) WriteOrigin(f, origin);
  if (!joints.Empty()) WriteJoints(f, joints);
  h5::FlushToDisk(f);
}

}  // namespace skewbridge::jobs
