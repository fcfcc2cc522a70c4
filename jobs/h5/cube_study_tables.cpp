#include "jobs/h5/cube_study_tables.h"

#include <algorithm>
#include <limits>
#include <string_view>
#include <type_traits>

#include "spectra/limit_states.h"
#include "spectra/round_off.h"

namespace skewbridge::jobs::h5 {
namespace {

void SetDoublesAttr(hid_t obj, const std::string& name, const std::vector<double>& values) {
  const hsize_t n = values.size();
  Id space = Dataspace(std::span<const hsize_t>(&n, 1));
  Id attr(H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
          H5Aclose, "create attribute " + name);
  Check(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, values.data()), "write attribute " + name);
}

// A contiguous dataset of the given shape, written whole, with units and description.
template <typename T>
Id WriteArray(hid_t parent, const std::string& name, const std::vector<hsize_t>& shape,
              const std::vector<T>& values, const std::string& units,
              const std::string& description) {
  const bool is_double = std::is_same_v<T, double>;
  Id ds = CreateDataset(parent, name, is_double ? H5T_IEEE_F64LE : H5T_STD_I64LE, shape, {}, 0,
                        nullptr);
  WriteAll(ds.get(), is_double ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64, values.data());
  SetAttr(ds.get(), "units", units);
  SetAttr(ds.get(), "description", description);
  return ds;
}

// The columns of record pairs, only when the table holds one (a table of single records keeps
// its layout): which rows are pairs, the H2 file and component, the zeros that made the two
// components one length, and the H2 peaks (the columns above are H1's).
void WritePairColumns(hid_t table, const StudyTables& study) {
  const bool any_pair = std::any_of(study.records.begin(), study.records.end(),
                                    [](const SweepRecord& r) { return r.IsPair(); });
  if (!any_pair) return;
  const std::vector<hsize_t> shape{study.records.size()};
  std::vector<std::int64_t> pair, padded_h1, padded_h2;
  std::vector<std::string> file_h2, component_h2;
  std::vector<double> pga_h2, pgv_h2, tm_h2, rotd50, rotd100, gm, angle;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  for (const SweepRecord& r : study.records) {
    pair.push_back(r.IsPair() ? 1 : 0);
    file_h2.push_back(r.file_h2);
    component_h2.push_back(r.IsPair() ? r.motion_h2->component : "");
    padded_h1.push_back(static_cast<std::int64_t>(r.padded_samples[0]));
    padded_h2.push_back(static_cast<std::int64_t>(r.padded_samples[1]));
    pga_h2.push_back(r.measures_h2 ? r.measures_h2->pga_mps2 : kNaN);
    pgv_h2.push_back(r.measures_h2 ? r.measures_h2->pgv_mps : kNaN);
    tm_h2.push_back(r.measures_h2 ? r.measures_h2->mean_period_s : kNaN);
    rotd50.push_back(r.rotd50_t1_mps2);
    rotd100.push_back(r.rotd100_t1_mps2);
    gm.push_back(r.gm_t1_mps2);
    angle.push_back(r.rotd100_angle_t1_deg);
  }
  WriteArray(table, "pair", shape, pair, "1",
             "1: a pair of horizontal components (the other columns are of H1, the *_h2 of H2); "
             "0: a single record");
  WriteStrings(table, "file_h2", file_h2);
  WriteStrings(table, "component_h2", component_h2);
  WriteArray(table, "padded_samples_h1", shape, padded_h1, "1",
             "zero samples appended at the end of H1 to reach the pair's npts");
  WriteArray(table, "padded_samples_h2", shape, padded_h2, "1",
             "zero samples appended at the end of H2 to reach the pair's npts");
  WriteArray(table, "pga_h2_mps2", shape, pga_h2, "m/s^2", "peak ground acceleration of H2");
  WriteArray(table, "pgv_h2_mps", shape, pgv_h2, "m/s", "peak ground velocity of H2");
  WriteArray(table, "T_m_h2_s", shape, tm_h2, "s", "mean period of H2 [Rathje et al. 1998]");
  const std::string at_t1 =
      " at T1 (attribute T1_s) and spectral_xi, of the pair as given (unscaled) [Boore 2010]; "
      "NaN for a single record or when the cells' T1 differ";
  WriteArray(table, "RotD50_T1_mps2", shape, rotd50, "m/s^2",
             "median over the angles 0-179 deg of the peak oscillator response" + at_t1);
  WriteArray(table, "RotD100_T1_mps2", shape, rotd100, "m/s^2",
             "largest over the angles 0-179 deg of the peak oscillator response" + at_t1);
  WriteArray(table, "RotD100_angle_T1_deg", shape, angle, "deg",
             "angle of RotD100 from H1 towards H2" + at_t1);
  WriteArray(table, "GM_T1_mps2", shape, gm, "m/s^2", "geometric mean sqrt(Sa_H1 Sa_H2)" + at_t1);
}

void WriteRecordTable(hid_t sweep_group, const StudyTables& study) {
  Id g = CreateGroup(sweep_group, "records");
  SetAttr(g.get(), "source", study.records_source);
  SetAttr(g.get(), "set", study.records_set);
  SetAttr(g.get(), "count", static_cast<std::int64_t>(study.records.size()));
  const std::vector<hsize_t> shape{study.records.size()};
  std::vector<std::string> label;
  std::vector<std::string> file;
  std::vector<std::string> component;
  std::vector<std::int64_t> npts;
  std::vector<double> scale, dt, pga, pgv, pgd, tm, wg, le, arias, d595, cav, sa_t1, avgsa;
  for (const SweepRecord& r : study.records) {
    label.push_back(r.label);
    file.push_back(r.file);
    component.push_back(r.motion.component);
    npts.push_back(static_cast<std::int64_t>(r.motion.npts()));
    scale.push_back(r.scale);
    dt.push_back(r.motion.dt_s);
    pga.push_back(r.measures.pga_mps2);
    pgv.push_back(r.measures.pgv_mps);
    pgd.push_back(r.measures.pgd_m);
    tm.push_back(r.measures.mean_period_s);
    wg.push_back(r.measures.omega_g_radps);
    le.push_back(r.measures.persistency_m);
    arias.push_back(r.measures.arias_mps);
    d595.push_back(r.measures.significant_duration_s);
    cav.push_back(r.measures.cav_mps);
    sa_t1.push_back(r.sa_t1_mps2);
    avgsa.push_back(r.avgsa_mps2);
  }
  // T1 is one for the sweep (else NaN and the cells hold theirs): the group says which.
  const SweepRecord& first = study.records.front();
  SetAttr(g.get(), "T1_s", first.t1_s);
  SetAttr(g.get(), "spectral_xi", first.spectral_xi);
  WriteStrings(g.get(), "label", label);
  WriteStrings(g.get(), "file", file);
  WriteStrings(g.get(), "component", component);
  WriteArray(g.get(), "scale", shape, scale, "1", "the manifest's factor on the accelerations");
  WriteArray(g.get(), "dt_s", shape, dt, "s", "sample interval");
  WriteArray(g.get(), "npts", shape, npts, "1", "number of samples");
  WriteArray(g.get(), "pga_mps2", shape, pga, "m/s^2", "peak ground acceleration = a_g");
  WriteArray(g.get(), "pgv_mps", shape, pgv, "m/s", "peak ground velocity");
  WriteArray(g.get(), "pgd_m", shape, pgd, "m", "peak ground displacement");
  WriteArray(g.get(), "T_m_s", shape, tm, "s", "mean period [Rathje et al. 1998]");
  WriteArray(g.get(), "w_g_radps", shape, wg, "rad/s", "w_g = 2 pi / T_m");
  WriteArray(g.get(), "L_e_m", shape, le, "m", "persistency PGA / w_g^2");
  WriteArray(g.get(), "arias_mps", shape, arias, "m/s", "Arias intensity");
  WriteArray(g.get(), "D5_95_s", shape, d595, "s", "significant duration 5-95 % of Arias");
  WriteArray(g.get(), "CAV_mps", shape, cav, "m/s",
             "cumulative absolute velocity int |a| dt over the record [EPRI 1988]");
  const std::string where_t1 =
      " at the sweep's fundamental period T1 (attribute T1_s) and damping spectral_xi; NaN "
      "when the cells' T1 differ (the cells store T1 and im) or the family has no model";
  WriteArray(g.get(), "Sa_T1_mps2", shape, sa_t1, "m/s^2",
             "pseudo-spectral acceleration Sa(T1)" + where_t1);
  WriteArray(g.get(), "AvgSa_mps2", shape, avgsa, "m/s^2",
             "AvgSa(T1): geometric mean of Sa over " + std::to_string(records::kAvgSaPeriodCount) +
                 " periods equally spaced in 0.2-3 T1 [Eads et al. 2015]" + where_t1);
  WritePairColumns(g.get(), study);
  // The table's rows are the record axis: attach its scale to every column (select by label).
  if (Exists(sweep_group, "axes/record")) {
    Id record_axis = OpenDataset(sweep_group, "axes/record");
    for (const std::string& column : ListChildren(g.get())) {
      Id ds = OpenDataset(g.get(), column);
      AttachScale(ds.get(), record_axis.get(), 0, "record");
    }
  }
}

void WriteCorrelation(hid_t sweep_group, const CorrelationTable& table,
                      const std::vector<double>& band_edges) {
  Id g = CreateGroup(sweep_group, "correlation");
  SetAttr(g.get(), "x", std::string("L_e"));
  SetAttr(g.get(), "y", table.y);
  SetAttr(g.get(), "over", std::string("record"));
  SetAttr(g.get(), "axis_order", table.axis_order);
  // Without the response band (not stored, or a family without it) there are no groups.
  if (!band_edges.empty()) SetDoublesAttr(g.get(), "band_edges", band_edges);
  SetAttr(g.get(), "min_band_records", kMinBandRecords);
  SetAttr(g.get(), "loglog",
          std::string("log10(theta_m) = intercept + slope log10(L_e), least squares; "
                      "r2 = 1 - SS_res/SS_tot"));
  std::vector<hsize_t> shape(table.shape.begin(), table.shape.end());
  std::vector<hsize_t> band_shape = shape;
  band_shape.push_back(table.bands);
  std::vector<Id> scales;
  for (const std::string& key : table.axis_order) {
    scales.push_back(OpenDataset(sweep_group, "axes/" + key));
  }
  auto attach = [&](const Id& ds) {
    for (std::size_t k = 0; k < scales.size(); ++k) {
      AttachScale(ds.get(), scales[k].get(), static_cast<unsigned>(k), table.axis_order[k]);
    }
  };
  attach(WriteArray(g.get(), "n", shape, table.n, "1",
                    "cells used: status ok, theta_m and L_e finite"));
  attach(WriteArray(g.get(), "pearson_theta_Le", shape, table.pearson, "1",
                    "Pearson r of (L_e, theta_m) over the records"));
  attach(WriteArray(g.get(), "spearman_theta_Le", shape, table.spearman, "1",
                    "Spearman rho of (L_e, theta_m), ties given their average rank"));
  attach(WriteArray(g.get(), "loglog_n", shape, table.loglog_n, "1",
                    "cells with theta_m > 0 and L_e > 0"));
  attach(WriteArray(g.get(), "loglog_slope", shape, table.loglog_slope, "1",
                    "slope of log10 theta_m against log10 L_e (least squares)"));
  attach(WriteArray(g.get(), "loglog_intercept", shape, table.loglog_intercept, "1",
                    "intercept of log10 theta_m = intercept + slope log10 L_e (L_e in m)"));
  attach(WriteArray(g.get(), "loglog_r2", shape, table.loglog_r2, "1",
                    "R^2 of the log-log fit, 1 - SS_res / SS_tot"));
  WriteStrings(g.get(), "reason", table.reason);
  if (table.bands == 0) return;
  const std::string per_band = " per w0x/w_g group (last dimension), NaN below min_band_records";
  attach(WriteArray(g.get(), "band_n", band_shape, table.band_n, "1",
                    "cells used per w0x/w_g group (last dimension)"));
  attach(WriteArray(g.get(), "band_pearson_theta_Le", band_shape, table.band_pearson, "1",
                    "Pearson r" + per_band));
  attach(WriteArray(g.get(), "band_spearman_theta_Le", band_shape, table.band_spearman, "1",
                    "Spearman rho" + per_band));
  attach(WriteArray(g.get(), "band_loglog_slope", band_shape, table.band_loglog_slope, "1",
                    "log-log slope" + per_band));
  attach(WriteArray(g.get(), "band_loglog_intercept", band_shape, table.band_loglog_intercept, "1",
                    "log-log intercept" + per_band));
  attach(WriteArray(g.get(), "band_loglog_r2", band_shape, table.band_loglog_r2, "1",
                    "log-log R^2" + per_band));
}

// The fragility/ group, or with `angles` the fragility_worst_incidence/ group: the same fits over
// the grid without the incidence_deg axis, at the worst of those angles.
void WriteFragility(hid_t sweep_group, const std::vector<FragilityStudy>& studies,
                    const std::vector<double>* angles = nullptr) {
  Id g = CreateGroup(sweep_group, angles == nullptr ? "fragility" : "fragility_worst_incidence");
  const FragilityStudy& first = studies.front();
  if (angles != nullptr) {
    SetAttr(g.get(), "reduces", std::string("incidence_deg"));
    SetDoublesAttr(g.get(), "incidence_deg", *angles);
    SetAttr(g.get(), "reduction",
            std::string("worst incidence angle: a cell of the grid without incidence_deg (a "
                        "record at a stripe and the other axes) exceeds when its cell exceeds "
                        "at some angle (the largest ls_<name> over incidence_deg); its D / C is "
                        "the largest over the angles; it is used when the cells of every angle "
                        "are done with status ok; its IM is the record's at the stripe (the "
                        "same at every angle). The fits, bootstrap and cloud are those of "
                        "fragility/, over these cells; fragility/ holds the fits per angle"));
  }
  std::vector<std::string> names;
  for (const FragilityStudy& f : studies) names.push_back(f.ls.name);
  SetAttr(g.get(), "limit_states", names);
  SetAttr(g.get(), "method", std::string(first.table.stripe_axis.empty() ? "cloud" : "stripes"));
  SetAttr(g.get(), "im", first.im);
  SetAttr(g.get(), "im_units", first.im_units);
  SetAttr(g.get(), "im_description", first.im_description);
  SetAttr(g.get(), "stripe_axis", first.table.stripe_axis);
  SetAttr(g.get(), "axis_order", first.table.axis_order);
  SetAttr(g.get(), "model",
          std::string("P(exceeded | IM = x) = Phi(ln(x / theta) / beta), lognormal"));
  SetAttr(g.get(), "likelihood",
          std::string("binomial over the cells, maximised by Newton's method; standard errors "
                      "from the observed information [Baker 2015, Earthquake Spectra "
                      "31(1):579-599]"));
  SetAttr(g.get(), "cloud",
          std::string("ln(D / C) = cloud_intercept + cloud_slope ln(IM), least squares; "
                      "cloud_theta = exp(-intercept / slope), cloud_beta = sigma / slope "
                      "[Cornell et al. 2002]"));
  SetAttr(g.get(), "bootstrap",
          std::string("records drawn with replacement (std::mt19937_64, seed per combination "
                      "seeded from bootstrap_seed and its index), percentiles 2.5 and 97.5"));
  SetAttr(g.get(), "bootstrap_resamples",
          static_cast<std::int64_t>(first.table.bootstrap_resamples));
  SetAttr(g.get(), "bootstrap_seed", static_cast<std::int64_t>(first.table.bootstrap_seed));
  SetAttr(g.get(), "confidence", 0.95);
  std::vector<Id> scales;
  for (const std::string& key : first.table.axis_order) {
    scales.push_back(OpenDataset(sweep_group, "axes/" + key));
  }
  for (const FragilityStudy& f : studies) {
    const FragilityTable& t = f.table;
    Id ls = CreateGroup(g.get(), f.ls.name);
    SetAttr(ls.get(), "kind", spectra::LimitStateKindName(f.ls.kind));
    SetAttr(ls.get(), "threshold", f.ls.threshold);
    SetAttr(ls.get(), "demand_units", f.demand_unit);
    if (const double floor = spectra::RoundOffFloor(f.demand_unit); floor > 0.0) {
      SetAttr(ls.get(), "round_off_floor", floor);
    }
    if (!f.ls.seat_m.empty()) SetDoublesAttr(ls.get(), "seat_m", f.ls.seat_m);
    if (f.ls.kind == spectra::LimitStateKind::kResponse)
      SetAttr(ls.get(), "response", f.ls.response);
    std::vector<hsize_t> shape;
    for (const std::size_t n : t.shape) shape.push_back(n);
    if (shape.empty()) shape.push_back(1);
    auto attach = [&](const Id& ds) {
      for (std::size_t k = 0; k < scales.size(); ++k) {
        AttachScale(ds.get(), scales[k].get(), static_cast<unsigned>(k), t.axis_order[k]);
      }
    };
    auto put = [&](const std::string& name, const auto& values, std::string units,
                   const std::string& description) {
      if (units == "g") units = f.im_units;  // the unit of the IM
      attach(WriteArray(ls.get(), name, shape, values, units, description));
    };
    put("theta", t.theta, "g", "maximum-likelihood median IM of exceedance");
    put("beta", t.beta, "1", "maximum-likelihood dispersion (log standard deviation)");
    put("se_ln_theta", t.se_ln_theta, "1", "standard error of ln theta (observed information)");
    put("se_beta", t.se_beta, "1", "standard error of beta (observed information)");
    put("cov_ln_theta_beta", t.cov_ln_theta_beta, "1", "covariance of (ln theta, beta)");
    put("theta_lo", t.theta_lo, "g", "95 % interval of theta: exp(ln theta - 1.96 se_ln_theta)");
    put("theta_hi", t.theta_hi, "g", "95 % interval of theta: exp(ln theta + 1.96 se_ln_theta)");
    put("beta_lo", t.beta_lo, "1", "95 % interval of beta: beta - 1.96 se_beta");
    put("beta_hi", t.beta_hi, "1", "95 % interval of beta: beta + 1.96 se_beta");
    put("boot_theta_lo", t.boot_theta_lo, "g", "2.5 % of theta over the bootstrap resamples");
    put("boot_theta_hi", t.boot_theta_hi, "g", "97.5 % of theta over the bootstrap resamples");
    put("boot_beta_lo", t.boot_beta_lo, "1", "2.5 % of beta over the bootstrap resamples");
    put("boot_beta_hi", t.boot_beta_hi, "1", "97.5 % of beta over the bootstrap resamples");
    put("boot_used", t.boot_used, "1", "bootstrap resamples that gave a fit (NaN bounds below 20)");
    put("n_cells", t.n_cells, "1", "cells used: done, status ok");
    put("n_exceeded", t.n_exceeded, "1", "cells among them that exceeded the limit state");
    put("cloud_n", t.cloud_n, "1", "cells of the cloud fit: D / C > 0 and IM > 0, finite");
    put("cloud_excluded", t.cloud_excluded, "1", "cells left out of the cloud fit");
    put("cloud_intercept", t.cloud_intercept, "1",
        "intercept of ln(D / C) on ln(IM) (IM in im_units)");
    put("cloud_slope", t.cloud_slope, "1", "slope of ln(D / C) on ln(IM)");
    put("cloud_sigma", t.cloud_sigma, "1", "residual standard deviation of ln(D / C)");
    put("cloud_theta", t.cloud_theta, "g", "cloud median IM of D = C");
    put("cloud_beta", t.cloud_beta, "1", "cloud dispersion sigma / slope");
    WriteStrings(ls.get(), "reason", t.reason);
    WriteStrings(ls.get(), "cloud_reason", t.cloud_reason);
    if (!t.n_excluded.empty()) {
      put("n_excluded_beyond_max_scale", t.n_excluded, "1",
          "cells done with status ok left out of every fit: scaled beyond records.max_scale "
          "(records.beyond_max_scale = \"exclude\")");
    }
    if (t.stripes == 0) continue;
    // [1, S] without combination axes, as the per-combination datasets are [1].
    std::vector<hsize_t> stripe_shape = shape;
    stripe_shape.push_back(t.stripes);
    Id stripe_scale = OpenDataset(sweep_group, "axes/" + t.stripe_axis);
    auto put_stripes = [&](const std::string& name, const auto& values, std::string units,
                           const std::string& description) {
      if (units == "g") units = f.im_units;
      Id ds = WriteArray(ls.get(), name, stripe_shape, values, units, description);
      attach(ds);
      AttachScale(ds.get(), stripe_scale.get(), static_cast<unsigned>(shape.size()), t.stripe_axis);
    };
    put_stripes("stripe_im", t.stripe_im, "g", "geometric mean IM of the stripe's cells");
    put_stripes("stripe_n", t.stripe_n, "1", "cells of the stripe used");
    put_stripes("stripe_exceeded", t.stripe_exceeded, "1", "cells of the stripe that exceeded");
    if (!t.stripe_excluded.empty()) {
      put_stripes("stripe_excluded", t.stripe_excluded, "1",
                  "cells of the stripe left out: scaled beyond records.max_scale");
    }
  }
}

// over_incidence/max, median and angle_of_max_deg: one dataset per response of the bridge over
// the grid without the incidence_deg axis, its remaining axis scales attached.
void WriteOverIncidence(hid_t sweep_group, const OverIncidence& over) {
  Id g = CreateGroup(sweep_group, "over_incidence");
  SetAttr(g.get(), "reduces", std::string("incidence_deg"));
  SetDoublesAttr(g.get(), "incidence_deg", over.angles_deg);
  SetAttr(g.get(), "axis_order", over.axis_order);
  std::vector<std::string> names;
  for (const ResponseInfo& r : over.responses) names.push_back(r.name);
  SetAttr(g.get(), "responses", names);
  SetAttr(g.get(), "statistics",
          std::string("max: the largest value over the incidence angles; median: numpy's "
                      "median over them (the mean of the two middle values for an even "
                      "count); angle_of_max_deg: the angle of the largest (the first in axis "
                      "order on ties); NaN where the cell of some angle is not done with "
                      "status ok or holds NaN"));
  const std::vector<hsize_t> shape =
      over.shape.empty() ? std::vector<hsize_t>{1}
                         : std::vector<hsize_t>(over.shape.begin(), over.shape.end());
  std::vector<Id> scales;
  for (const std::string& key : over.axis_order) {
    scales.push_back(OpenDataset(sweep_group, "axes/" + key));
  }
  struct Statistic {
    const char* group;
    const char* what;
    std::vector<double> spectra::AxisStatistics::*values;
  };
  const Statistic statistics[] = {
      {"max", "largest over the incidence angles of ", &spectra::AxisStatistics::max},
      {"median", "median over the incidence angles of ", &spectra::AxisStatistics::median},
      {"angle_of_max_deg", "incidence angle [deg] of the largest ",
       &spectra::AxisStatistics::coordinate_of_max}};
  for (const Statistic& st : statistics) {
    Id sg = CreateGroup(g.get(), st.group);
    SetAttr(sg.get(), "reduces", std::string("incidence_deg"));
    SetAttr(sg.get(), "statistic", std::string(st.group));
    // The remaining axes linked into the group, as in the sweep group: a netCDF reader (xarray)
    // opening the group alone then has their coordinates.
    for (const std::string& key : over.axis_order) {
      if (std::find(names.begin(), names.end(), key) != names.end()) continue;
      Check(H5Lcreate_hard(sweep_group, ("axes/" + key).c_str(), sg.get(), key.c_str(), H5P_DEFAULT,
                           H5P_DEFAULT),
            "link axes/" + key + " into over_incidence/" + st.group);
    }
    for (std::size_t r = 0; r < over.responses.size(); ++r) {
      const ResponseInfo& info = over.responses[r];
      const bool angle = std::string_view(st.group) == "angle_of_max_deg";
      Id ds = WriteArray(sg.get(), info.name, shape, over.statistics[r].*st.values,
                         angle ? std::string("deg") : info.unit,
                         st.what + info.name + ": " + info.description);
      SetAttr(ds.get(), "reduces", std::string("incidence_deg"));
      SetAttr(ds.get(), "statistic", std::string(st.group));
      SetAttr(ds.get(), "response", info.name);
      for (std::size_t k = 0; k < scales.size(); ++k) {
        AttachScale(ds.get(), scales[k].get(), static_cast<unsigned>(k), over.axis_order[k]);
      }
    }
  }
}

// `exclude`: records.beyond_max_scale = "exclude" (capacities beyond max_scale left out). With
// `angles`, the fragility_worst_incidence/ group: the fits of each record's capacity at its
// worst angle of those, over the combinations without the incidence_deg axis.
void WriteIdaFragility(hid_t sweep_group, const std::vector<IdaFragilityStudy>& studies,
                       bool exclude, const std::vector<double>* angles = nullptr) {
  Id g = CreateGroup(sweep_group, angles == nullptr ? "fragility" : "fragility_worst_incidence");
  const IdaFragilityStudy& first = studies.front();
  if (angles != nullptr) {
    SetAttr(g.get(), "reduces", std::string("incidence_deg"));
    SetDoublesAttr(g.get(), "incidence_deg", *angles);
    SetAttr(g.get(), "reduction",
            std::string("worst incidence angle: a record's capacity is the lowest of its "
                        "capacities over incidence_deg (the lowest intensity at which it "
                        "exceeds the limit state at some angle); a record exceeding it at no "
                        "angle is censored at the lowest of its angles' censoring intensities; "
                        "a capacity beyond records.max_scale is treated at each angle as in "
                        "fragility/ first; a record enters when its cells of every angle are "
                        "done with status ok. fragility/ holds the fits per angle"));
  }
  std::vector<std::string> names;
  for (const IdaFragilityStudy& f : studies) names.push_back(f.ls.name);
  SetAttr(g.get(), "limit_states", names);
  SetAttr(g.get(), "method", std::string("ida"));
  SetAttr(g.get(), "im", std::string("ida_capacity"));
  SetAttr(g.get(), "im_units", first.im_units);
  SetAttr(g.get(), "im_description",
          std::string("each record's capacity: the lowest intensity of its hunt-and-fill "
                      "search at which the limit state is exceeded [Vamvatsikos and Cornell "
                      "2002, 2004]"));
  SetAttr(g.get(), "axis_order", first.axis_order);
  SetAttr(g.get(), "model",
          std::string("P(exceeded | IM = x) = Phi(ln(x / theta) / beta), lognormal"));
  SetAttr(
      g.get(), "fit",
      std::string("every capacity finite: theta = exp(mean of ln IM_c), beta = standard "
                  "deviation of ln IM_c with n - 1, over the records' capacities [Baker "
                  "2015, Earthquake Spectra 31(1):579-599]; n_censored > 0: the "
                  "maximum-likelihood theta and beta (n) of the lognormal with the records "
                  "that never reach the limit state right-censored at their highest run "
                  "(note), a capacity beyond records.max_scale censored at it (n_scaled_too_far); "
                  "NaN (with the reason) when fewer than 2 capacities are finite"));
  std::vector<Id> scales;
  for (const std::string& key : first.axis_order) {
    scales.push_back(OpenDataset(sweep_group, "axes/" + key));
  }
  for (const IdaFragilityStudy& f : studies) {
    Id ls = CreateGroup(g.get(), f.ls.name);
    SetAttr(ls.get(), "kind", spectra::LimitStateKindName(f.ls.kind));
    SetAttr(ls.get(), "threshold", f.ls.threshold);
    if (!f.ls.seat_m.empty()) SetDoublesAttr(ls.get(), "seat_m", f.ls.seat_m);
    if (f.ls.kind == spectra::LimitStateKind::kResponse)
      SetAttr(ls.get(), "response", f.ls.response);
    std::vector<hsize_t> shape;
    for (const std::size_t n : f.shape) shape.push_back(n);
    if (shape.empty()) shape.push_back(1);
    auto put = [&](const std::string& name, const auto& values, const std::string& units,
                   const std::string& description) {
      Id ds = WriteArray(ls.get(), name, shape, values, units, description);
      for (std::size_t k = 0; k < scales.size(); ++k) {
        AttachScale(ds.get(), scales[k].get(), static_cast<unsigned>(k), f.axis_order[k]);
      }
    };
    put("theta", f.theta, f.im_units,
        "median capacity: exp(mean ln IM_c), or the censored maximum likelihood's");
    put("beta", f.beta, "1",
        "dispersion: standard deviation of ln IM_c (n - 1), or the censored maximum "
        "likelihood's");
    put("n_records", f.n, "1", "records with a finite capacity (cells done, status ok)");
    put("n_censored", f.censored, "1",
        "records not reaching the limit state up to ida.max_im (censored in the fit)");
    WriteStrings(ls.get(), "reason", f.reason);
    if (exclude) {
      put("n_scaled_too_far", f.too_far, "1",
          "capacities reached at a scale factor above records.max_scale: left out of the fit");
      put("n_excluded_beyond_max_scale", f.too_far, "1",
          "records left out of the fit: capacity beyond records.max_scale "
          "(records.beyond_max_scale = \"exclude\")");
    } else {
      put("n_scaled_too_far", f.too_far, "1",
          "capacities reached at a scale factor above records.max_scale: censored at max_scale "
          "(in n_censored)");
    }
    WriteStrings(ls.get(), "note", f.note);
  }
}

}  // namespace

void WriteStudyTables(const Datasets& d, const CubeLayout& layout, const StudyTables& study) {
  // Below it a stored rotation is round-off, zero for every fit and figure.
  SetAttr(d.group.get(), "round_off_floor_rad", spectra::kRotationRoundOffFloor_rad);
  for (std::size_t r = 0; r < layout.responses.size(); ++r) {
    if (layout.responses[r].name == "band" && !study.band_edges.empty()) {
      SetDoublesAttr(d.responses[r].get(), "band_edges", study.band_edges);
    }
  }
  if (!study.records.empty()) WriteRecordTable(d.group.get(), study);
  if (!study.im.measure.empty()) {
    SetAttr(d.group.get(), "im_measure", study.im.measure);
    SetAttr(d.group.get(), "im_description", spectra::IntensityDescription(study.im));
    SetAttr(d.group.get(), "im_units", spectra::IntensityUnit(study.im));
    SetAttr(d.group.get(), "im_scaled", static_cast<std::int64_t>(study.im.scale ? 1 : 0));
    SetAttr(
        d.group.get(), "max_scale",
        study.im.max_scale > 0.0 ? study.im.max_scale : std::numeric_limits<double>::infinity());
    if (study.scaled_too_far >= 0)
      SetAttr(d.group.get(), "scaled_too_far_count", study.scaled_too_far);
    if (study.im.max_scale > 0.0) {
      SetAttr(d.group.get(), "beyond_max_scale",
              std::string(study.im.exclude_beyond_max_scale ? "exclude" : "keep"));
    }
  }
  if (study.correlation) WriteCorrelation(d.group.get(), *study.correlation, study.band_edges);
  if (!study.fragility.empty()) WriteFragility(d.group.get(), study.fragility);
  if (!study.fragility_worst_incidence.empty() && study.over_incidence) {
    WriteFragility(d.group.get(), study.fragility_worst_incidence,
                   &study.over_incidence->angles_deg);
  }
  if (study.over_incidence) WriteOverIncidence(d.group.get(), *study.over_incidence);
  if (!study.ida_fragility.empty())
    WriteIdaFragility(d.group.get(), study.ida_fragility, study.im.exclude_beyond_max_scale);
  if (!study.ida_fragility_worst_incidence.empty() && study.over_incidence) {
    WriteIdaFragility(d.group.get(), study.ida_fragility_worst_incidence,
                      study.im.exclude_beyond_max_scale, &study.over_incidence->angles_deg);
  }
}

}  // namespace skewbridge::jobs::h5
