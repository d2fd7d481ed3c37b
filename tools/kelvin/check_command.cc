// kelvin check: the surrogate check of a derivative set against reference
// maneuver runs (simulator/maneuvers/surrogate_check.h). Writes the report
// and the set's `check` section; a failed check exits with code 3 after
// printing its table.
#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "simulator/maneuvers/surrogate_check.h"
#include "simulator/mmg/derivative_check_io.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct CheckArgs {
  std::string derivatives;
  std::string ship_file;
  std::vector<std::string> references;
  std::vector<std::string> tolerances;
  std::vector<std::string> maneuvers;
  std::string output_dir;
};

void RunCheck(const CheckArgs& a) {
  sim::SurrogateCheckOptions o;
  o.derivatives = a.derivatives;
  o.ship = a.ship_file;
  o.references.assign(a.references.begin(), a.references.end());
  o.maneuvers = a.maneuvers;
  for (const std::string& t : a.tolerances) o.tolerances = sim::ParseCheckTolerances(t, o.tolerances);
  const sim::SurrogateCheck check = sim::RunSurrogateCheck(o);

  const std::filesystem::path dir =
      a.output_dir.empty() ? std::filesystem::path("results/check") / std::filesystem::path(a.derivatives).stem()
                           : std::filesystem::path(a.output_dir);
  sim::WriteCheckReport(check, dir);
  sim::WriteDerivativeCheck(a.derivatives, check.section);
  fmt::print("{}", sim::FormatCheckTable(check));
  fmt::print("  written: {} (report), {} (track errors), check section of {}\n", (dir / "check_report.md").string(),
             (dir / "track_errors.h5").string(), a.derivatives);
  std::fflush(stdout);
  if (!check.passed) {
    std::fprintf(stderr, "kelvin: check FAILED: derivative set %s does not reproduce its references\n",
                 a.derivatives.c_str());
    std::exit(3);
  }
}

}  // namespace

Command AddCheckCommand(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Check a derivative set's surrogate against reference maneuver runs and record the verdict in the set");
  cmd->add_option("derivatives", args->derivatives, "Derivative set (YAML, from kelvin identify)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--ship", args->ship_file, "Ship file the set's hull goes into (data/ships/<ship>.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--against", args->references,
                  "Reference maneuver results (HDF5, the schema of kelvin simulate; free-running CFD runs)")
      ->required()
      ->expected(1, -1)
      ->check(CLI::ExistingFile);
  cmd->add_option("--tolerances", args->tolerances,
                  "metric=5%, metric=2deg, metric=0.1m, metric=none, comma-separated ('overshoot' = both overshoot "
                  "angles); default advance=5%,tactical_diameter=5%,overshoot=2deg");
  cmd->add_option("-m,--maneuver", args->maneuvers,
                  "Require every reference to be this maneuver (repeatable, e.g. turning:35:stbd)");
  cmd->add_option("-o,--output", args->output_dir, "Report directory (default results/check/<set>)");
  return {cmd, [args] { RunCheck(*args); }};
}

}  // namespace kelvin::cli
