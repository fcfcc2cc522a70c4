#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "jobs/app/commands.h"
#include "jobs/risk_command.h"
#include "solver/common/error.h"

namespace skewbridge::app {
namespace {

std::string Number(double v) { return std::isfinite(v) ? fmt::format("{:.3g}", v) : "-"; }

void PrintRun(const jobs::RiskRun& run) {
  const spectra::RiskTable& t = run.table;
  std::printf("sweep %s: lambda_LS over the hazard %s; fragility %s; rule %s, tail %s\n",
              run.sweep.c_str(), run.hazard_imt.c_str(), run.fragility_imt.c_str(),
              spectra::RiskRuleName(t.options.rule).c_str(),
              spectra::UpperTailName(t.options.tail).c_str());
  for (const std::string& note : t.notes) std::printf("  assumes: %s\n", note.c_str());
  std::printf("  %-16s %-32s %11s %11s %11s %10s %10s %11s %8s\n", "limit state", "combination",
              "lambda[1/yr]", "16%", "84%", "P(50 yr)", "T_R [yr]", "Cornell", "tail");
  for (const spectra::RiskRates& r : t.limit_states) {
    for (std::size_t c = 0; c < r.rate_per_yr.size(); ++c) {
      const std::string& label = run.combination_label[c];
      if (!r.reason[c].empty()) {
        std::printf("  %-16s %-32s  no rate: %s\n", r.name.c_str(), label.c_str(),
                    r.reason[c].c_str());
        continue;
      }
      std::printf("  %-16s %-32s %11s %11s %11s %10s %10s %11s %7s%%\n", r.name.c_str(),
                  label.c_str(), Number(r.rate_per_yr[c]).c_str(), Number(r.rate_p16[c]).c_str(),
                  Number(r.rate_p84[c]).c_str(), Number(r.p_50yr[c]).c_str(),
                  Number(r.return_period_yr[c]).c_str(), Number(r.cornell_rate[c]).c_str(),
                  Number(100.0 * r.share_beyond_hazard[c]).c_str());
      if (!r.flags[c].empty()) std::printf("      flags: %s\n", r.flags[c].c_str());
    }
  }
}

}  // namespace

void AddRiskCommand(CLI::App& app) {
  auto args = std::make_shared<jobs::RiskArgs>();
  auto rule = std::make_shared<std::string>("loglog");
  auto tail = std::make_shared<std::string>("power-law");
  auto damping = std::make_shared<double>(NAN);
  auto site = std::make_shared<int>(-1);
  CLI::App* cmd = app.add_subcommand(
      "risk",
      "Annual rate of each limit state of a final cube over a site's hazard curve, stored in "
      "the cube (risk/) and printed (docs/risk.md)");
  cmd->add_option("cube", args->cube, "Final cube FILE.h5 of a sweep with [limit_states]")
      ->required();
  cmd->add_option("--hazard", args->hazard,
                  "Hazard curve: an OpenQuake hazard-curve CSV or a two-column file (IM in g, "
                  "annual rate)")
      ->required();
  cmd->add_option("--hazard-imt", args->hazard_options.imt,
                  "The hazard's IMT (PGA or SA(T)) when the file names none; must agree if both");
  cmd->add_option("--hazard-component", args->hazard_options.component,
                  "The hazard's horizontal component: " + spectra::ComponentChoices());
  cmd->add_option("--hazard-damping", *damping, "The hazard's SA damping ratio (default 0.05)");
  cmd->add_option("--site", *site, "OpenQuake CSV of several sites: the row (from 0)");
  cmd->add_option("--sweep", args->sweep,
                  "Only this sweep (default: every sweep with a fragility)");
  cmd->add_option("--convert", args->conversion,
                  "Read the hazard's component as the fragility's by this named conversion");
  cmd->add_option("--period-tolerance", args->period_tolerance,
                  "Relative period gap accepted between hazard and fragility")
      ->capture_default_str();
  cmd->add_option("--rule", *rule, "Integral between the hazard's points")
      ->check(CLI::IsMember({"loglog", "discrete"}))
      ->capture_default_str();
  cmd->add_option("--tail", *tail, "What the integral takes beyond the hazard's last point")
      ->check(CLI::IsMember({"power-law", "lumped", "none"}))
      ->capture_default_str();
  cmd->add_flag("--records-selected-for-site", args->records_selected_for_site,
                "State that the cube's records were selected for this site's hazard");
  cmd->callback([args, rule, tail, damping, site] {
    args->options.rule =
        *rule == "discrete" ? spectra::RiskRule::kDiscrete : spectra::RiskRule::kLogLog;
    args->options.tail = *tail == "lumped" ? spectra::UpperTail::kLumped
                         : *tail == "none" ? spectra::UpperTail::kNone
                                           : spectra::UpperTail::kPowerLaw;
    if (!std::isnan(*damping)) args->hazard_options.damping = *damping;
    if (*site >= 0) args->hazard_options.site = *site;
    for (const jobs::RiskRun& run : jobs::RunRisk(*args)) PrintRun(run);
  });
}

}  // namespace skewbridge::app
