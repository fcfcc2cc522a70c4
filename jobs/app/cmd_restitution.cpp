// `skewbridge restitution`: the equivalent restitution of a compliant abutment. A point mass (the
// deck's share striking the abutment) arrives at the closing point of the backfill spring with a
// given speed; the strike is integrated against the hyperbolic law (solver/dynamics/
// compliant_strike.h) and reported as exit over approach speed, contact duration, permanent set,
// largest deformation and force, and the energy the backfill absorbed (docs/compliant.md §3). The
// law is given by its OpenSees constants, by Shamsabadi's K50 form, or by the Caltrans SDC 2.0
// rules of the backwall; a linear spring-dashpot that pulls on nothing (the Kelvin-Voigt pounding
// element) is the fourth form, for comparison.
#include <fmt/core.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <system_error>
#include <vector>

#include "jobs/app/commands.h"
#include "solver/common/error.h"
#include "solver/dynamics/compliant_strike.h"
#include "solver/joint/backfill.h"

namespace skewbridge::app {
namespace {

constexpr std::string_view kCommand = "restitution";

struct RestitutionArgs {
  double mass_kg = 0.0;
  double k_max_Npm = 0.0;  ///< OpenSees form (with --r-f, --f-ult-N)
  double k_ur_Npm = 0.0;   ///< 0: K_ur = K_max
  double r_f = 0.0;
  double f_ult_N = 0.0;
  double k50_Npm = 0.0;  ///< Shamsabadi form (with --f-ult-N and --height-m or --y-max-m)
  double height_m = 0.0;
  double y_max_m = 0.0;
  bool caltrans = false;  ///< Caltrans SDC 2.0 (with --width-m, --height-m, --skew-deg)
  double width_m = 0.0;
  double skew_deg = 0.0;
  bool no_skew_reduction = false;
  double spring_Npm = 0.0;     ///< linear spring-dashpot form: stiffness k (N/m)
  double damping_ratio = 0.0;  ///< its dashpot as zeta = c / (2 sqrt(k m)), in [0, 1)
  std::vector<double> velocities_mps;
  std::string range;  ///< --velocities-mps A:B:N
  bool csv = false;
};

double Number(std::string_view text, std::string_view field) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v) || !(v > 0.0)) {
    throw InputError::AtField(kCommand, field,
                              "'" + std::string(text) +
                                  "' is not a number > 0 (allowed: A:B:N, "
                                  "N speeds in m/s evenly from A to B)");
  }
  return v;
}

// --velocities-mps A:B:N: N approach speeds spaced evenly from A to B (m/s).
std::vector<double> ParseRange(const std::string& token) {
  const std::size_t c1 = token.find(':');
  const std::size_t c2 = c1 == std::string::npos ? c1 : token.find(':', c1 + 1);
  if (c2 == std::string::npos) {
    throw InputError::AtField(kCommand, "--velocities-mps", "'" + token + "': give A:B:N");
  }
  const std::string_view t(token);
  const double a = Number(t.substr(0, c1), "--velocities-mps");
  const double b = Number(t.substr(c1 + 1, c2 - c1 - 1), "--velocities-mps");
  const double n_value = Number(t.substr(c2 + 1), "--velocities-mps");
  if (n_value != std::floor(n_value) || n_value < 2 || n_value > 10000 || !(a < b)) {
    throw InputError::AtField(kCommand, "--velocities-mps",
                              "'" + token + "': A:B:N needs A < B and N a whole number 2..10000");
  }
  const int n = static_cast<int>(n_value);
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(i + 1 == n ? b : a + (b - a) * i / (n - 1));
  return out;
}

// The law from exactly one of the three forms; its description for the header.
joint::HyperbolicGap LawOf(const RestitutionArgs& a, std::string& description) {
  const int forms =
      (a.k_max_Npm > 0.0) + (a.k50_Npm > 0.0) + (a.caltrans ? 1 : 0) + (a.spring_Npm > 0.0);
  if (forms != 1) {
    throw InputError::AtField(
        kCommand, "law",
        "give exactly one of --k-max-Npm (OpenSees constants with --r-f "
        "and --f-ult-N), --k50-Npm (Shamsabadi, with --f-ult-N and "
        "--height-m or --y-max-m), --caltrans (with --width-m and --height-m), "
        "--spring-Npm (linear spring-dashpot, with --damping-ratio)");
  }
  auto y_max = [&]() {
    if (a.y_max_m > 0.0) return a.y_max_m;
    if (a.height_m > 0.0) return joint::ShamsabadiYMax_m(a.height_m);
    throw InputError::AtField(kCommand, "--height-m",
                              "needed (> 0, m) for y_max = 0.05 H, or give --y-max-m");
  };
  joint::HyperbolicGap law;
  if (a.k_max_Npm > 0.0) {
    law.k_max_N_per_m = a.k_max_Npm;
    law.k_ur_N_per_m = a.k_ur_Npm > 0.0 ? a.k_ur_Npm : a.k_max_Npm;
    law.r_f = a.r_f;
    law.f_ult_N = a.f_ult_N;
    // The options by their own names; the law's check below names its constants.
    if (!(a.r_f > 0.0 && a.r_f <= 1.0)) {
      throw InputError::AtField(kCommand, "--r-f",
                                fmt::format("needed, in (0, 1] (got {})", a.r_f));
    }
    if (!(a.f_ult_N > 0.0)) {
      throw InputError::AtField(kCommand, "--f-ult-N",
                                fmt::format("needed, > 0 N (got {})", a.f_ult_N));
    }
    joint::ValidateHyperbolicGap(law, kCommand);
    description = "OpenSees HyperbolicGap constants";
  } else if (a.k50_Npm > 0.0) {
    law = joint::FromShamsabadi(a.k50_Npm, a.f_ult_N, y_max(), 0.0, kCommand);
    description = fmt::format("Shamsabadi K50 = {:.6g} N/m, F_ult = {:.6g} N, y_max = {:.6g} m",
                              a.k50_Npm, a.f_ult_N, y_max());
  } else {
    if (!(a.width_m > 0.0)) {
      throw InputError::AtField(kCommand, "--width-m", "needed with --caltrans (> 0, m)");
    }
    if (!(a.height_m > 0.0)) {
      throw InputError::AtField(kCommand, "--height-m", "needed with --caltrans (> 0, m)");
    }
    if (!(std::isfinite(a.skew_deg) && std::abs(a.skew_deg) < 90.0)) {
      throw InputError::AtField(kCommand, "--skew-deg",
                                fmt::format("must be in (-90, 90) deg (got {})", a.skew_deg));
    }
    const double r_sk = a.no_skew_reduction
                            ? 1.0
                            : joint::CaltransSkewFactor(a.skew_deg * std::numbers::pi / 180.0);
    const joint::CaltransAbutment c = joint::CaltransSdc2(a.width_m, a.height_m, r_sk);
    law = joint::FromInitialStiffness(c.k_initial_N_per_m, c.p_bw_N, y_max(), 0.0, kCommand);
    description = fmt::format(
        "Caltrans SDC 2.0, backwall {:.6g} m x {:.6g} m, R_sk = {:.6g}: K = {:.6g} N/m, "
        "P_bw = {:.6g} N reached at y_max = {:.6g} m",
        a.width_m, a.height_m, r_sk, c.k_initial_N_per_m, c.p_bw_N, y_max());
  }
  return law;
}

void Run(const RestitutionArgs& a) {
  if (!(std::isfinite(a.mass_kg) && a.mass_kg > 0.0)) {
    throw InputError::AtField(kCommand, "--mass-kg", "needed: the striking mass (> 0, kg)");
  }
  const bool linear = a.spring_Npm > 0.0 && a.k_max_Npm <= 0.0 && a.k50_Npm <= 0.0 && !a.caltrans;
  if (linear &&
      !(std::isfinite(a.damping_ratio) && a.damping_ratio >= 0.0 && a.damping_ratio < 1.0)) {
    throw InputError::AtField(kCommand, "--damping-ratio",
                              fmt::format("must be in [0, 1) (got {})", a.damping_ratio));
  }
  std::string description;
  joint::HyperbolicGap law;
  double dashpot_Nspm = 0.0;
  if (linear) {
    dashpot_Nspm = 2.0 * a.damping_ratio * std::sqrt(a.spring_Npm * a.mass_kg);
    description = fmt::format(
        "linear spring-dashpot that pulls on nothing, k = {:.6g} N/m, c = {:.6g} N s/m "
        "(zeta = {:.6g})",
        a.spring_Npm, dashpot_Nspm, a.damping_ratio);
  } else {
    law = LawOf(a, description);
    if (a.damping_ratio != 0.0) {
      throw InputError::AtField(kCommand, "--damping-ratio", "only with --spring-Npm");
    }
  }
  std::vector<double> speeds = a.velocities_mps;
  if (!a.range.empty()) {
    const std::vector<double> more = ParseRange(a.range);
    speeds.insert(speeds.end(), more.begin(), more.end());
  }
  if (speeds.empty()) {
    throw InputError::AtField(kCommand, "--velocity-mps",
                              "give approach speeds (m/s, > 0) or --velocities-mps A:B:N");
  }
  for (const double v : speeds) {
    if (!(std::isfinite(v) && v > 0.0)) {
      throw InputError::AtField(kCommand, "--velocity-mps",
                                fmt::format("speeds must be > 0 m/s (got {})", v));
    }
  }
  // Strike every speed before printing anything: a failure leaves no half table.
  std::vector<dynamics::StrikeResult> results;
  for (const double v : speeds) {
    results.push_back(linear
                          ? dynamics::StrikeSpringDashpot(a.spring_Npm, dashpot_Nspm, a.mass_kg, v)
                          : dynamics::StrikeBackfill(law, joint::BackfillState{}, a.mass_kg, v));
  }
  if (!a.csv && linear) {
    std::printf("joint: %s\n", description.c_str());
    std::printf("  mass %.6g kg (T = 2 pi sqrt(m / k) = %.6g s)\n", a.mass_kg,
                2.0 * std::numbers::pi * std::sqrt(a.mass_kg / a.spring_Npm));
  } else if (!a.csv) {
    std::printf("backfill: %s\n", description.c_str());
    std::printf(
        "  K_max = %.6g N/m, K_ur = %.6g N/m, R_f = %.6g, F_ult = %.6g N; mass %.6g kg "
        "(T = 2 pi sqrt(m / K_max) = %.6g s)\n",
        law.k_max_N_per_m, law.k_ur_N_per_m, law.r_f, law.f_ult_N, a.mass_kg,
        2.0 * std::numbers::pi * std::sqrt(a.mass_kg / law.k_max_N_per_m));
  }
  std::printf(a.csv ? "%s\n" : "%s\n",
              a.csv ? "approach_mps,restitution,contact_duration_s,permanent_set_m,"
                      "max_deformation_m,max_force_N,dissipated_J,energy_residual,status"
                    : "  v0 (m/s)  eps_N      contact (s)  set (mm)   d_max (mm)  F_max (N)    "
                      "absorbed  ledger");
  for (const dynamics::StrikeResult& r : results) {
    const double input_J = 0.5 * a.mass_kg * r.approach_speed_mps * r.approach_speed_mps;
    const char* status =
        r.status == dynamics::StrikeStatus::kSeparated ? "separated" : "no-separation";
    if (a.csv) {
      std::printf("%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.3e,%s\n", r.approach_speed_mps,
                  r.restitution, r.contact_duration_s, r.permanent_set_m, r.max_deformation_m,
                  r.max_force_N, r.dissipated_J, r.energy_residual, status);
    } else {
      std::printf("  %8.4g  %-9.5f  %-11.5g  %-9.4g  %-10.4g  %-11.5g  %5.1f %%  %.1e%s\n",
                  r.approach_speed_mps, r.restitution, r.contact_duration_s,
                  1e3 * r.permanent_set_m, 1e3 * r.max_deformation_m, r.max_force_N,
                  100.0 * r.dissipated_J / input_J, r.energy_residual,
                  r.status == dynamics::StrikeStatus::kSeparated ? "" : "  (no separation)");
    }
  }
}

}  // namespace

void AddRestitutionCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "restitution",
      "The equivalent restitution, contact duration and permanent set of a compliant abutment "
      "struck by a mass (docs/compliant.md)");
  auto a = std::make_shared<RestitutionArgs>();
  cmd->add_option("--mass-kg", a->mass_kg, "Striking mass (kg), e.g. the deck's mass");
  cmd->add_option("--velocity-mps", a->velocities_mps,
                  "Approach speeds at the closing of the joint (m/s), one or more");
  cmd->add_option("--velocities-mps", a->range, "A:B:N: N approach speeds from A to B (m/s)");
  cmd->add_option("--k-max-Npm", a->k_max_Npm, "OpenSees form: initial stiffness K_max (N/m)");
  cmd->add_option("--k-ur-Npm", a->k_ur_Npm, "Unloading-reloading stiffness K_ur (N/m; K_max)");
  cmd->add_option("--r-f", a->r_f, "OpenSees form: failure ratio R_f in (0, 1]");
  cmd->add_option("--f-ult-N", a->f_ult_N, "Ultimate passive resistance F_ult (N)");
  cmd->add_option("--k50-Npm", a->k50_Npm,
                  "Shamsabadi form: secant stiffness K50 at F_ult/2 (N/m)");
  cmd->add_option("--height-m", a->height_m, "Backwall height H (m): y_max = 0.05 H");
  cmd->add_option("--y-max-m", a->y_max_m, "Deformation at F_ult (m), instead of 0.05 H");
  cmd->add_flag("--caltrans", a->caltrans,
                "Caltrans SDC 2.0 rules from --width-m and --height-m (and --skew-deg)");
  cmd->add_option("--width-m", a->width_m, "Backwall width w (m), for --caltrans");
  cmd->add_option("--skew-deg", a->skew_deg,
                  "Skew angle (deg): R_sk = exp(-theta / 45 deg), for --caltrans");
  cmd->add_flag("--no-skew-reduction", a->no_skew_reduction, "R_sk = 1 with --caltrans");
  cmd->add_option("--spring-Npm", a->spring_Npm,
                  "Linear spring-dashpot form: spring stiffness k (N/m); it pulls on nothing");
  cmd->add_option("--damping-ratio", a->damping_ratio,
                  "Its dashpot c = 2 zeta sqrt(k m) as zeta in [0, 1) (0)");
  cmd->add_flag("--csv", a->csv, "Print CSV rows (with a header) instead of the table");
  cmd->callback([a] { Run(*a); });
}

}  // namespace skewbridge::app
