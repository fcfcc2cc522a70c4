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
    Id file = CreateMemoryFile(tmp);
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
    SaveFileImage(file.get(), tmp);
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
