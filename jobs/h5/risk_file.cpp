#include "jobs/h5/risk_file.h"

#include <fmt/format.h>
#include <hdf5.h>

#include <cmath>
#include <limits>
#include <span>

#include "jobs/h5/cube_file.h"
#include "jobs/h5/h5.h"
#include "jobs/h5/h5_error.h"
#include "solver/common/error.h"

namespace skewbridge::jobs::h5 {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kPartial = "risk_partial";

std::vector<double> ReadDoubles(hid_t parent, const std::string& name) {
  Id ds = OpenDataset(parent, name);
  std::size_t n = 1;
  for (hsize_t extent : Shape(ds.get())) n *= extent;
  std::vector<double> out(n);
  ReadAll(ds.get(), H5T_NATIVE_DOUBLE, out.data());
  return out;
}

std::vector<std::int64_t> ReadInts(hid_t parent, const std::string& name) {
  Id ds = OpenDataset(parent, name);
  std::size_t n = 1;
  for (hsize_t extent : Shape(ds.get())) n *= extent;
  std::vector<std::int64_t> out(n);
  ReadAll(ds.get(), H5T_NATIVE_INT64, out.data());
  return out;
}

// A dataset of doubles with its units and description.
void PutDoubles(hid_t parent, const std::string& name, const std::vector<hsize_t>& shape,
                const std::vector<double>& values, const std::string& units,
                const std::string& description) {
  Id ds = CreateDataset(parent, name, H5T_IEEE_F64LE, shape, {}, 0, nullptr);
  WriteAll(ds.get(), H5T_NATIVE_DOUBLE, values.data());
  SetAttr(ds.get(), "units", units);
  SetAttr(ds.get(), "description", description);
}

void Delete(hid_t parent, const std::string& name) {
  Check(H5Ldelete(parent, name.c_str(), H5P_DEFAULT), "H5Ldelete " + name);
}

// Replaces the "hazard" rows of inputs/ by one row for this hazard file.
void ReplaceHazardInput(hid_t sweep_group, const RiskHazardInfo& hazard) {
  Id inputs = Exists(sweep_group, "inputs") ? OpenGroup(sweep_group, "inputs")
                                            : CreateGroup(sweep_group, "inputs");
  std::vector<std::string> roles, files, sums;
  std::vector<std::int64_t> sizes;
  if (Exists(inputs.get(), "role")) {
    const std::vector<std::string> r = ReadStrings(OpenDataset(inputs.get(), "role").get());
    const std::vector<std::string> f = ReadStrings(OpenDataset(inputs.get(), "file").get());
    const std::vector<std::string> s = ReadStrings(OpenDataset(inputs.get(), "sha256").get());
    const std::vector<std::int64_t> b = ReadInts(inputs.get(), "bytes");
    for (std::size_t i = 0; i < r.size() && i < f.size() && i < s.size() && i < b.size(); ++i) {
      if (r[i] == "hazard") continue;
      roles.push_back(r[i]);
      files.push_back(f[i]);
      sums.push_back(s[i]);
      sizes.push_back(b[i]);
    }
    for (const char* name : {"role", "file", "sha256", "bytes"}) Delete(inputs.get(), name);
  }
  roles.push_back("hazard");
  files.push_back(hazard.file);
  sums.push_back(hazard.sha256);
  sizes.push_back(static_cast<std::int64_t>(hazard.bytes));
  WriteStrings(inputs.get(), "role", roles);
  WriteStrings(inputs.get(), "file", files);
  WriteStrings(inputs.get(), "sha256", sums);
  const hsize_t n = sizes.size();
  Id bytes = CreateDataset(inputs.get(), "bytes", H5T_STD_I64LE, std::span<const hsize_t>(&n, 1),
                           {}, 0, nullptr);
  WriteAll(bytes.get(), H5T_NATIVE_INT64, sizes.data());
  SetAttr(bytes.get(), "units", std::string("byte"));
}

}  // namespace

RiskSource ReadRiskSource(const std::filesystem::path& path, const std::string& sweep) {
  const std::string name = path.string();
  try {
    Id file = OpenFile(name, false);
    if (!HasAttr(file.get(), "format") || GetStringAttr(file.get(), "format") != kCubeFormat) {
      throw InputError::AtLine(name, 0, "not a skewbridge cube (root attribute format)");
    }
    if (!Exists(file.get(), "sweeps") || !Exists(OpenGroup(file.get(), "sweeps").get(), sweep)) {
      throw InputError::AtLine(name, 0, "holds no sweep named '" + sweep + "'");
    }
    Id g = OpenGroup(file.get(), "sweeps/" + sweep);
    if (GetIntAttr(g.get(), "complete") == 0) {
      throw InputError::AtLine(name, 0,
                               "sweep '" + sweep +
                                   "' is not complete: its fragility is fitted "
                                   "into the final cube only");
    }
    if (!Exists(g.get(), "fragility")) {
      throw InputError::AtLine(name, 0,
                               "sweep '" + sweep +
                                   "' has no fragility/ (a sweep with "
                                   "[limit_states] fits one into its final cube)");
    }
    RiskSource s;
    s.sweep = sweep;
    s.im_measure = HasAttr(g.get(), "im_measure") ? GetStringAttr(g.get(), "im_measure") : "";
    s.im_description =
        HasAttr(g.get(), "im_description") ? GetStringAttr(g.get(), "im_description") : "";
    const double max_scale =
        HasAttr(g.get(), "max_scale") ? GetDoubleAttr(g.get(), "max_scale") : 0.0;
    s.max_scale = std::isfinite(max_scale) ? max_scale : 0.0;
    s.cube_axes = GetStringListAttr(g.get(), "axis_order");
    Id axes = OpenGroup(g.get(), "axes");
    for (const std::string& key : s.cube_axes) {
      s.cube_shape.push_back(
          static_cast<std::size_t>(Shape(OpenDataset(axes.get(), key).get()).at(0)));
    }
    Id f = OpenGroup(g.get(), "fragility");
    s.method = HasAttr(f.get(), "method") ? GetStringAttr(f.get(), "method") : "stripes";
    s.im = HasAttr(f.get(), "im") ? GetStringAttr(f.get(), "im") : "";
    s.im_units = HasAttr(f.get(), "im_units") ? GetStringAttr(f.get(), "im_units") : "g";
    if (HasAttr(f.get(), "axis_order")) s.axis_order = GetStringListAttr(f.get(), "axis_order");
    const std::string stripe_axis =
        HasAttr(f.get(), "stripe_axis") ? GetStringAttr(f.get(), "stripe_axis") : "";
    for (std::size_t k = 0; k < s.cube_axes.size(); ++k) {
      if (!stripe_axis.empty() && s.cube_axes[k] == stripe_axis) s.stripes = s.cube_shape[k];
    }
    for (const std::string& ls_name : GetStringListAttr(f.get(), "limit_states")) {
      Id ls = OpenGroup(f.get(), ls_name);
      StoredFragility fr;
      fr.name = ls_name;
      fr.theta = ReadDoubles(ls.get(), "theta");
      fr.beta = ReadDoubles(ls.get(), "beta");
      const std::size_t combos = fr.theta.size();
      auto optional = [&](const char* key) {
        return Exists(ls.get(), key) ? ReadDoubles(ls.get(), key)
                                     : std::vector<double>(combos, kNaN);
      };
      fr.se_ln_theta = optional("se_ln_theta");
      fr.se_beta = optional("se_beta");
      fr.cov_ln_theta_beta = optional("cov_ln_theta_beta");
      fr.reason = ReadStrings(OpenDataset(ls.get(), "reason").get());
      if (s.stripes > 0 && Exists(ls.get(), "stripe_im")) {
        fr.stripe_im = ReadDoubles(ls.get(), "stripe_im");
        fr.stripe_n = ReadInts(ls.get(), "stripe_n");
      }
      s.limit_states.push_back(std::move(fr));
    }
    Id responses = OpenGroup(g.get(), "responses");
    if (Exists(responses.get(), "T1")) s.t1_s = ReadDoubles(responses.get(), "T1");
    if (Exists(responses.get(), "scale_factor")) {
      s.scale_factor = ReadDoubles(responses.get(), "scale_factor");
    }
    s.status = ReadDoubles(g.get(), "status");
    return s;
  } catch (const H5Error& e) {
    throw InputError::AtLine(name, 0, std::string("cannot read the cube: ") + e.what());
  }
}

void WriteRisk(const std::filesystem::path& path, const std::string& sweep,
               const spectra::RiskTable& table, const RiskHazardInfo& hazard,
               const std::vector<std::string>& axis_order, const std::vector<std::size_t>& shape) {
  const std::string name = path.string();
  try {
    Id file = OpenFile(name, true);
    Id g = OpenGroup(file.get(), "sweeps/" + sweep);
    if (Exists(g.get(), kPartial)) Delete(g.get(), kPartial);
    Id r = CreateGroup(g.get(), kPartial);
    SetAttr(r.get(), "hazard_file", hazard.file);
    SetAttr(r.get(), "hazard_bytes", static_cast<std::int64_t>(hazard.bytes));
    SetAttr(r.get(), "hazard_sha256", hazard.sha256);
    SetAttr(r.get(), "hazard_format", hazard.format);
    SetAttr(r.get(), "hazard_imt", hazard.imt);
    SetAttr(r.get(), "fragility_imt", hazard.fragility_imt);
    SetAttr(r.get(), "hazard_kind", hazard.kind);
    SetAttr(r.get(), "hazard_investigation_time_yr", hazard.investigation_time_yr);
    SetAttr(r.get(), "hazard_site", hazard.site);
    SetAttr(r.get(), "hazard_lon_deg", hazard.lon_deg);
    SetAttr(r.get(), "hazard_lat_deg", hazard.lat_deg);
    SetAttr(r.get(), "conversion", hazard.conversion);
    SetAttr(r.get(), "period_tolerance", hazard.period_tolerance);
    SetAttr(r.get(), "rule", spectra::RiskRuleName(table.options.rule));
    SetAttr(r.get(), "tail", spectra::UpperTailName(table.options.tail));
    SetAttr(r.get(), "spread_draws", static_cast<std::int64_t>(spectra::kRiskDraws));
    SetAttr(r.get(), "spread_seed", static_cast<std::int64_t>(spectra::kRiskSeed));
    SetAttr(r.get(), "created_utc", hazard.created_utc);
    SetAttr(r.get(), "model",
            std::string("lambda_LS = int Phi(ln(x / theta) / beta) |d lambda_IM(x)| over the "
                        "hazard's points (docs/risk.md); P(t) = 1 - exp(-lambda_LS t)"));
    if (!table.notes.empty()) SetAttr(r.get(), "notes", table.notes);
    if (!axis_order.empty()) SetAttr(r.get(), "axis_order", axis_order);
    std::vector<std::string> names;
    for (const spectra::RiskRates& ls : table.limit_states) names.push_back(ls.name);
    if (!names.empty()) SetAttr(r.get(), "limit_states", names);
    const hsize_t n = table.hazard.im.size();
    PutDoubles(r.get(), "hazard_im", {n}, table.hazard.im, "g",
               "the hazard's levels integrated, in the fragility's measure");
    PutDoubles(r.get(), "hazard_rate", {n}, table.hazard.rate_per_yr, "1/yr",
               "the annual rate of exceedance at each level");
    std::vector<hsize_t> combo_shape(shape.begin(), shape.end());
    if (combo_shape.empty()) combo_shape.push_back(1);
    std::vector<hsize_t> deagg_shape = combo_shape;
    deagg_shape.push_back(n);
    for (const spectra::RiskRates& ls : table.limit_states) {
      Id lg = CreateGroup(r.get(), ls.name);
      auto put = [&](const std::string& key, const std::vector<double>& v, const std::string& u,
                     const std::string& d) { PutDoubles(lg.get(), key, combo_shape, v, u, d); };
      put("rate_per_yr", ls.rate_per_yr, "1/yr", "lambda_LS, the annual rate of the limit state");
      put("rate_p16", ls.rate_p16, "1/yr", "16 % of lambda_LS from the fit's covariance");
      put("rate_p84", ls.rate_p84, "1/yr", "84 % of lambda_LS from the fit's covariance");
      put("p_1yr", ls.p_1yr, "1", "1 - exp(-lambda_LS): probability in 1 year");
      put("p_50yr", ls.p_50yr, "1", "1 - exp(-50 lambda_LS): probability in 50 years");
      put("return_period_yr", ls.return_period_yr, "yr", "1 / lambda_LS");
      put("cornell_rate", ls.cornell_rate, "1/yr",
          "k0 theta^-k exp(k^2 beta^2 / 2) with the local power-law fit [Cornell et al. 2002]");
      put("cornell_k", ls.cornell_k, "1", "slope k of the local power law");
      put("cornell_k0", ls.cornell_k0, "1/yr", "k0 of the local power law (x in g)");
      put("share_beyond_hazard", ls.share_beyond_hazard, "1",
          "share of lambda_LS from IM beyond the hazard's last point (the tail)");
      put("share_above_stripes", ls.share_above_stripes, "1",
          "share of lambda_LS from IM above the largest stripe");
      put("share_above_stripes_movable", ls.share_above_stripes_movable, "1",
          "(1 - P(LS | largest stripe)) lambda_IM(largest stripe) / lambda_LS");
      put("share_below_stripes", ls.share_below_stripes, "1",
          "share of lambda_LS from IM below the smallest stripe");
      put("p_at_first_level", ls.p_at_first_level, "1", "P(LS | the hazard's first level)");
      PutDoubles(lg.get(), "deaggregation", deagg_shape, ls.deaggregation, "1",
                 "share of lambda_LS from each hazard interval [x_i, x_i+1); the last entry: "
                 "beyond x_n");
      WriteStrings(lg.get(), "reason", ls.reason);
      WriteStrings(lg.get(), "flags", ls.flags);
    }
    ReplaceHazardInput(g.get(), hazard);
    if (Exists(g.get(), "risk")) Delete(g.get(), "risk");
    Check(H5Lmove(g.get(), kPartial, g.get(), "risk", H5P_DEFAULT, H5P_DEFAULT), "H5Lmove risk");
    FlushToDisk(file.get());
  } catch (const H5Error& e) {
    throw InputError::AtLine(name, 0, std::string("cannot write the risk group: ") + e.what());
  }
}

RiskSummary ReadRiskSummary(const std::filesystem::path& path, const std::string& sweep) {
  const std::string name = path.string();
  RiskSummary s;
  try {
    Id file = OpenFile(name, false);
    Id g = OpenGroup(file.get(), "sweeps/" + sweep);
    if (!Exists(g.get(), "risk")) return s;
    s.present = true;
    Id r = OpenGroup(g.get(), "risk");
    s.attrs.push_back(
        fmt::format("hazard {} ({} bytes, sha256 {}), {}", GetStringAttr(r.get(), "hazard_file"),
                    GetIntAttr(r.get(), "hazard_bytes"), GetStringAttr(r.get(), "hazard_sha256"),
                    GetStringAttr(r.get(), "hazard_format")));
    s.attrs.push_back("hazard measure " + GetStringAttr(r.get(), "hazard_imt") + "; fragility " +
                      GetStringAttr(r.get(), "fragility_imt"));
    const std::string conversion = GetStringAttr(r.get(), "conversion");
    s.attrs.push_back(fmt::format("rule {}, tail {}, period tolerance {:g} %{}",
                                  GetStringAttr(r.get(), "rule"), GetStringAttr(r.get(), "tail"),
                                  100.0 * GetDoubleAttr(r.get(), "period_tolerance"),
                                  conversion.empty() ? "" : ", --convert " + conversion));
    if (HasAttr(r.get(), "notes")) s.notes = GetStringListAttr(r.get(), "notes");
    if (HasAttr(r.get(), "axis_order")) s.axis_order = GetStringListAttr(r.get(), "axis_order");
    if (!HasAttr(r.get(), "limit_states")) return s;
    for (const std::string& ls_name : GetStringListAttr(r.get(), "limit_states")) {
      Id lg = OpenGroup(r.get(), ls_name);
      StoredRisk ls;
      ls.name = ls_name;
      ls.rate_per_yr = ReadDoubles(lg.get(), "rate_per_yr");
      ls.rate_p16 = ReadDoubles(lg.get(), "rate_p16");
      ls.rate_p84 = ReadDoubles(lg.get(), "rate_p84");
      ls.p_50yr = ReadDoubles(lg.get(), "p_50yr");
      ls.return_period_yr = ReadDoubles(lg.get(), "return_period_yr");
      ls.cornell_rate = ReadDoubles(lg.get(), "cornell_rate");
      ls.share_beyond_hazard = ReadDoubles(lg.get(), "share_beyond_hazard");
      ls.reason = ReadStrings(OpenDataset(lg.get(), "reason").get());
      ls.flags = ReadStrings(OpenDataset(lg.get(), "flags").get());
      s.limit_states.push_back(std::move(ls));
    }
  } catch (const H5Error& e) {
    throw InputError::AtLine(name, 0, std::string("cannot read risk/: ") + e.what());
  }
  return s;
}

}  // namespace skewbridge::jobs::h5
