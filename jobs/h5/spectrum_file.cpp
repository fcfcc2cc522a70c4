#include "jobs/h5/spectrum_file.h"

#include <system_error>

#include "jobs/h5/h5.h"
#include "solver/common/error.h"

namespace skewbridge::jobs::h5 {
namespace {

Id WriteDoubles(hid_t parent, const std::string& name, const std::vector<hsize_t>& shape,
                const std::vector<double>& values, const std::string& units,
                const std::string& description) {
  Id ds = CreateDataset(parent, name, H5T_IEEE_F64LE, shape, {}, 0, nullptr);
  WriteAll(ds.get(), H5T_NATIVE_DOUBLE, values.data());
  SetAttr(ds.get(), "units", units);
  SetAttr(ds.get(), "description", description);
  return ds;
}

}  // namespace

void WriteSpectrumFile(const std::filesystem::path& path, const SpectrumTable& t) {
  const hsize_t r = t.label.size();
  const hsize_t x = t.xi.size();
  const hsize_t p = t.periods_s.size();
  SB_DEMAND(t.file.size() == r && t.set.size() == r && t.pga_mps2.size() == r &&
                t.dt_s.size() == r && t.sd_m.size() == r * x * p && t.psv_mps.size() == r * x * p &&
                t.psa_mps2.size() == r * x * p,
            "spectrum table arrays of inconsistent sizes");
  SilenceErrorStack();
  const std::string tmp = path.string() + ".tmp";
  try {
    MemoryFile image = CreateMemoryFile(tmp);
    const Id& file = image.file;
    Id g = CreateGroup(file.get(), "spectra");
    SetAttr(g.get(), "command", t.command);
    SetAttr(g.get(), "method",
            std::string("u'' + 2 xi w u' + w^2 u = -a(t), u(0) = u'(0) = 0, a linear between "
                        "samples, solved exactly at the samples [Nigam and Jennings 1969]; "
                        "Sd = max|u|, PSv = w Sd, PSa = w^2 Sd"));
    SetAttr(g.get(), "dims", std::vector<std::string>{"record", "xi", "period"});
    WriteStrings(g.get(), "label", t.label);
    WriteStrings(g.get(), "file", t.file);
    WriteStrings(g.get(), "set", t.set);
    const std::vector<hsize_t> records{r};
    WriteDoubles(g.get(), "dt_s", records, t.dt_s, "s", "sample interval");
    WriteDoubles(g.get(), "pga_mps2", records, t.pga_mps2, "m/s^2", "peak ground acceleration");
    Id period = WriteDoubles(g.get(), "period_s", {p}, t.periods_s, "s", "oscillator period T");
    Id xi = WriteDoubles(g.get(), "xi", {x}, t.xi, "1", "damping ratio");
    SetScale(period.get(), "period_s");
    SetScale(xi.get(), "xi");
    const std::vector<hsize_t> cube{r, x, p};
    for (auto [name, values, units, what] :
         {std::tuple{"Sd_m", &t.sd_m, "m", "spectral displacement max|u|"},
          std::tuple{"PSv_mps", &t.psv_mps, "m/s", "pseudo-spectral velocity w Sd"},
          std::tuple{"PSa_mps2", &t.psa_mps2, "m/s^2", "pseudo-spectral acceleration w^2 Sd"}}) {
      Id ds = WriteDoubles(g.get(), name, cube, *values, units, what);
      AttachScale(ds.get(), xi.get(), 1, "xi");
      AttachScale(ds.get(), period.get(), 2, "period_s");
    }
    const hsize_t q = t.pair_label.size();
    if (q > 0) {
      for (const std::vector<double>* values :
           {&t.sa_h1_mps2, &t.sa_h2_mps2, &t.gm_mps2, &t.rotd0_mps2, &t.rotd50_mps2,
            &t.rotd100_mps2, &t.rotd100_angle_deg}) {
        SB_DEMAND(values->size() == q * x * p, "pair spectrum arrays of inconsistent sizes");
      }
      Id pairs = CreateGroup(file.get(), "pairs");
      SetAttr(pairs.get(), "method",
              std::string("the oscillator of /spectra under each horizontal component; at every "
                          "angle theta = 0, 1, ..., 179 deg the peak over time of |u1 cos theta + "
                          "u2 sin theta|, its median (mean of the 90th and 91st of the 180 sorted "
                          "peaks) RotD50, maximum RotD100, minimum RotD00 [Boore 2010, BSSA "
                          "100:1830]; GM = sqrt(Sa_H1 Sa_H2); all w^2 times a displacement"));
      SetAttr(pairs.get(), "dims", std::vector<std::string>{"pair", "xi", "period"});
      WriteStrings(pairs.get(), "label", t.pair_label);
      WriteStrings(pairs.get(), "set", t.pair_set);
      const std::vector<hsize_t> shape{q, x, p};
      for (auto [name, values, units, what] :
           {std::tuple{"Sa_H1_mps2", &t.sa_h1_mps2, "m/s^2", "PSa of H1 (= the record H1's)"},
            std::tuple{"Sa_H2_mps2", &t.sa_h2_mps2, "m/s^2", "PSa of H2"},
            std::tuple{"GM_mps2", &t.gm_mps2, "m/s^2", "geometric mean sqrt(Sa_H1 Sa_H2)"},
            std::tuple{"RotD00_mps2", &t.rotd0_mps2, "m/s^2", "smallest peak over the angles"},
            std::tuple{"RotD50_mps2", &t.rotd50_mps2, "m/s^2", "median peak over the angles"},
            std::tuple{"RotD100_mps2", &t.rotd100_mps2, "m/s^2", "largest peak over the angles"},
            std::tuple{"RotD100_angle_deg", &t.rotd100_angle_deg, "deg",
                       "angle of RotD100 from H1 towards H2 (the first of ties), 0-179"}}) {
        Id ds = WriteDoubles(pairs.get(), name, shape, *values, units, what);
        AttachScale(ds.get(), xi.get(), 1, "xi");
        AttachScale(ds.get(), period.get(), 2, "period_s");
      }
    }
    SaveFileImage(file.get(), *image.memory, tmp);
  } catch (const H5Error& e) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw H5Error(tmp + ": " + e.what());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw H5Error("rename " + tmp + " to " + path.string() + ": " + ec.message());
  }
}

}  // namespace skewbridge::jobs::h5
