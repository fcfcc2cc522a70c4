#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <sstream>

#include "jobs/sweep_spec.h"
#include "spectra/limit_states.h"

namespace skewbridge::jobs {
namespace {

// A number in its shortest round-trip form.
std::string Fmt(double v) { return fmt::format("{}", v); }

// 16 hex digits of the 64-bit FNV-1a hash of `bytes`.
std::string Fnv1a(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64 offset basis
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return fmt::format("{:016x}", h);
}

}  // namespace

std::string SweepSpec::CanonicalText() const {
  std::ostringstream out;
  auto str = [](const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') {
        q += '\\';
      }
      q += c;
    }
    return q + "\"";
  };
  out << "sweep.name = " << str(name) << "\n";
  out << "sweep.family = " << str(family) << "\n";
  if (!model_file.empty()) {
    out << "sweep.model = " << str(model_file) << "\n";
  }
  if (!record_set.empty()) {
    out << "records.set = " << str(record_set) << "\n";
  }
  if (!record_folder.empty()) {
    out << "records.folder = " << str(record_folder) << "\n";
    out << "records.pattern = " << str(record_pattern) << "\n";
    // Written only when given, so that a folder of single records keeps its identity.
    if (record_pairs_by_name) out << "records.pairs = true\n";
    if (!record_pairs_table.empty()) out << "records.pairs = " << str(record_pairs_table) << "\n";
    if (!record_units.empty()) out << "records.units = " << str(record_units) << "\n";
    if (record_dt_s > 0.0) out << "records.dt = " << Fmt(record_dt_s) << "\n";
  }
  if (synthetic_count > 0) {
    out << "records.synthetic = {count = " << synthetic_count << ", seed = " << synthetic_seed
        << "}\n";
  }
  if (!im.measure.empty()) {
    out << (im.scale ? "records.scale_to" : "records.im") << " = {measure = " << str(im.measure);
    if (im.Spectral()) {
      out << ", period = " << (im.at_t1 ? std::string("\"T1\"") : Fmt(im.period_s))
          << ", xi = " << Fmt(im.xi);
    }
    out << "}\n";
  }
  if (im.max_scale > 0.0) out << "records.max_scale = " << Fmt(im.max_scale) << "\n";
  // Written only when chosen, so that the identity of a sweep that keeps them stays as it was.
  if (im.exclude_beyond_max_scale) out << "records.beyond_max_scale = \"exclude\"\n";
  if (ida.enabled) {
    out << "ida = {start = " << Fmt(ida.start) << ", step = " << Fmt(ida.step)
        << ", step_increase = " << Fmt(ida.step_increase) << ", tolerance = " << Fmt(ida.tolerance)
        << ", max_im = " << Fmt(ida.max_im) << ", max_runs = " << ida.max_runs << "}\n";
  }
  if (!study_bands.empty()) {
    out << "study.bands = [";
    for (std::size_t i = 0; i < study_bands.size(); ++i) {
      out << (i ? ", " : "") << Fmt(study_bands[i]);
    }
    out << "]\n";
  }
  // The policy members the sweep sets away from the integrators' defaults (none: no line, so a
  // sweep without [event_policy] or [time_stepping_policy] keeps its identity).
  const auto changed = [&](const char* table, const std::vector<schema::Entry>& set,
                           const std::vector<schema::Entry>& defaults) {
    for (std::size_t i = 0; i < set.size(); ++i) {
      if (set[i].value != defaults[i].value) {
        out << table << "." << set[i].name << " = " << Fmt(set[i].value) << "\n";
      }
    }
  };
  changed("event_policy", schema::Entries(policies.event),
          schema::Entries(dynamics::EventPolicy{}));
  changed("time_stepping_policy", schema::Entries(policies.time_stepping),
          schema::Entries(dynamics::TimeSteppingPolicy{}));
  for (const Axis& axis : axes) {
    out << "axes." << axis.key << " = [";
    for (std::size_t i = 0; i < axis.Size(); ++i) {
      out << (i ? ", " : "")
          << (axis.kind == ParameterKind::kNumber ? Fmt(axis.values[i]) : str(axis.labels[i]));
    }
    out << "]\n";
  }
  for (const FixedValue& f : fixed) {
    out << "fixed." << f.key << " = "
        << (f.kind == ParameterKind::kNumber ? Fmt(f.value) : str(f.label)) << "\n";
  }
  for (const spectra::LimitState& ls : limit_states) {
    out << "limit_states." << spectra::LimitStateKindName(ls.kind);
    if (ls.kind == spectra::LimitStateKind::kResponse) out << "." << ls.response;
    out << " = {threshold = " << Fmt(ls.threshold) << ", seat_m = [";
    for (std::size_t i = 0; i < ls.seat_m.size(); ++i) out << (i ? ", " : "") << Fmt(ls.seat_m[i]);
    out << "]}\n";
  }
  out << "sweep.responses = [";
  for (std::size_t i = 0; i < responses.size(); ++i) {
    out << (i ? ", " : "") << str(responses[i]);
  }
  out << "]\n";
  return out.str();
}

std::string SweepSpec::InputsText() const {
  std::string out = fmt::format("program.version = \"{}\"\n", SKEWBRIDGE_VERSION);
  for (const InputFile& input : inputs) {
    if (input.role == "spec") continue;
    out += fmt::format("{} \"{}\" = {}\n", input.role, input.file, input.sha256);
  }
  return out;
}

std::string SweepSpec::Hash() const { return Fnv1a(CanonicalText() + InputsText()); }

namespace {

// The lines of a canonical or input text as key -> value, in order. Keys of the specification
// hold no space and end at the first " = "; a value of the input manifest (a hex checksum or a
// quoted version) holds none, so an input's key ends at the last one.
std::vector<std::pair<std::string, std::string>> KeyedLines(const std::string& text, bool inputs) {
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t at = inputs ? line.rfind(" = ") : line.find(" = ");
    if (at == std::string::npos) {
      out.emplace_back(line, "");
    } else {
      out.emplace_back(line.substr(0, at), line.substr(at + 3));
    }
  }
  return out;
}

// The first key whose value differs between the two texts, present in either: {key, old, new}
// with "(absent)" for a key that one side lacks; all empty when the texts agree.
std::array<std::string, 3> FirstDifference(const std::string& before, const std::string& now,
                                           bool inputs) {
  const auto old_lines = KeyedLines(before, inputs);
  const auto new_lines = KeyedLines(now, inputs);
  auto find = [](const auto& lines, const std::string& key) -> const std::string* {
    for (const auto& [k, v] : lines) {
      if (k == key) return &v;
    }
    return nullptr;
  };
  for (const auto& [key, value] : new_lines) {
    const std::string* was = find(old_lines, key);
    if (was == nullptr) return {key, "(absent)", value};
    if (*was != value) return {key, *was, value};
  }
  for (const auto& [key, value] : old_lines) {
    if (find(new_lines, key) == nullptr) return {key, value, "(absent)"};
  }
  return {};
}

// A value for a message: whole when short, else its start and length.
std::string Shortened(const std::string& value) {
  constexpr std::size_t kMax = 72;
  if (value.size() <= kMax) return value;
  return value.substr(0, kMax) + fmt::format("... ({} characters)", value.size());
}

}  // namespace

std::string DescribeIdentityChange(const std::string& stored_canonical,
                                   const std::string& stored_inputs, const SweepSpec& spec) {
  const auto spec_change = FirstDifference(stored_canonical, spec.CanonicalText(), false);
  if (!spec_change[0].empty()) {
    return fmt::format(
        "{}: key {} differs from the specification the cube was computed with "
        "(cube: {}; now: {})",
        spec.source, spec_change[0], Shortened(spec_change[1]), Shortened(spec_change[2]));
  }
  const auto input_change = FirstDifference(stored_inputs, spec.InputsText(), true);
  if (input_change[0].empty()) return "";
  const std::string& key = input_change[0];
  if (key == "program.version") {
    if (input_change[1] == "(absent)") {
      return "the cube holds no input manifest (it was written before the checksums of its "
             "input files were stored), so its inputs cannot be checked";
    }
    auto bare = [](std::string v) {
      v.erase(std::remove(v.begin(), v.end(), '"'), v.end());
      return v;
    };
    return fmt::format(
        "the cube was computed by skewbridge {}, this is {} (its results may "
        "differ)",
        bare(input_change[1]), bare(input_change[2]));
  }
  // `ROLE "FILE"`: name the file where this run reads it.
  const std::size_t quote = key.find('"');
  const std::string role = key.substr(0, quote == std::string::npos ? key.size() : quote - 1);
  const std::string file =
      quote == std::string::npos ? key : key.substr(quote + 1, key.size() - quote - 2);
  std::string where = file;
  for (const InputFile& input : spec.inputs) {
    if (input.file == file) where = input.path.string();
  }
  if (input_change[1] == "(absent)") {
    return fmt::format("{} ({}) is an input the cube was not computed from", where, role);
  }
  if (input_change[2] == "(absent)") {
    return fmt::format("{} ({}) was an input of the cube and is no longer one", where, role);
  }
  return fmt::format("{} ({}) has changed since the cube was computed from it (sha256 {}, now {})",
                     where, role, input_change[1], input_change[2]);
}

}  // namespace skewbridge::jobs
