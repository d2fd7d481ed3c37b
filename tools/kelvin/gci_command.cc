// `kelvin gci case.yaml --family 3 --grids DIR`: grid-convergence study of a
// case on a grid family (see cfd/verification/gci_study.h);
// `kelvin gci --grids DIR --values FILE`: the same for values computed on each
// grid elsewhere (cfd/verification/gci_values.h).
#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cfd/verification/gci_study.h"
#include "cfd/verification/gci_values.h"
#include "data/schema/errors.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {


Command AddGciCommand(CLI::App& app) {
  struct Args {
    std::string case_file;
    std::string values;
    std::string grids;
    int family = 3;
    std::vector<std::string> outputs = {"C_T"};
    std::string runs;
    std::string report;
    int average = 1;
    double ratio_tolerance = 0.05;
    bool rerun = false;
    bool no_progress = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "gci", "Grid-convergence study: run a case on each grid of a family (kelvin mesh --family) and report R, "
             "observed order, Richardson extrapolation and GCI of chosen outputs");
  CLI::Option* case_opt =
      sub->add_option("case", args->case_file, "Case file (YAML) whose mesh.poly_mesh is replaced by each grid")
          ->check(CLI::ExistingFile);
  CLI::Option* values_opt = sub->add_option("--values", args->values,
                  "Instead of a case: a YAML file of values already computed on grids 1-3 (outputs: {name: [g1, g2, "
                  "g3]}, optional settled: [..]); needs --report")
      ->check(CLI::ExistingFile)
      ->excludes(case_opt);
  sub->add_option("--grids", args->grids, "Family directory written by kelvin mesh --family (family.txt, gridN/)")
      ->required();
  CLI::Option* family_opt = sub->add_option("--family", args->family, "Number of grids (grid 1 finest; the GCI uses three)")
      ->capture_default_str();
  CLI::Option* outputs_opt = sub->add_option("--outputs", args->outputs,
                  "Outputs: C_T, C_F, C_P, X, Y, N, X_prime, Y_prime, N_prime or a history.h5 dataset "
                  "(name or name:column); comma-separated or repeated")
      ->capture_default_str();
  CLI::Option* runs_opt = sub->add_option("--runs", args->runs, "Directory of the runs (default: <output.directory>/gci)");
  sub->add_option("--report", args->report, "Report path without extension (writes .h5 and .yaml; default <runs>/gci)");
  CLI::Option* average_opt = sub->add_option("--average", args->average, "Mean of each output over the last N steps")->capture_default_str();
  sub->add_option("--ratio-tolerance", args->ratio_tolerance,
                  "Largest relative difference between the refinement ratios h2/h1 and h3/h2")
      ->capture_default_str();
  CLI::Option* rerun_opt = sub->add_flag("--rerun", args->rerun, "Run every grid again, even if a finished run is there");
  // The values file carries its own outputs and its three grids; these only steer runs.
  for (CLI::Option* o : {family_opt, outputs_opt, runs_opt, average_opt, rerun_opt}) values_opt->excludes(o);
  sub->add_flag("--no-progress", args->no_progress, "No progress line");
  Command cmd;
  cmd.app = sub;
  cmd.run = [args]() {
    if (!(args->ratio_tolerance > 0.0)) {
      throw ArgumentError(fmt::format("--ratio-tolerance {}: expected a positive fraction", args->ratio_tolerance));
    }
    if (args->case_file.empty() == args->values.empty()) {
      throw ArgumentError("kelvin gci: expected either a case file or --values FILE");
    }
    if (!args->values.empty()) {
      if (args->report.empty()) throw ArgumentError("--values: expected --report PATH (the report's .h5 and .yaml)");
      const cfd::GciStudy study =
          cfd::GciStudyFromValues(cfd::ReadGridFamily(args->grids, 3, args->ratio_tolerance), args->values);
      cfd::WriteGciReport(study, args->report, args->values);
      std::printf("%s\nreport: %s.h5, %s.yaml\n", cfd::GciTable(study).c_str(), args->report.c_str(),
                  args->report.c_str());
      return;
    }
    cfd::GciStudyOptions o;
    o.case_file = args->case_file;
    o.grids = args->grids;
    o.family = args->family;
    o.outputs = cfd::SplitOutputNames(args->outputs);
    o.runs = args->runs;
    o.average = args->average;
    o.ratio_tolerance = args->ratio_tolerance;
    o.rerun = args->rerun;
    o.progress = !args->no_progress;
    const cfd::GciStudy study = cfd::RunGciStudy(o);
    std::filesystem::path report = args->report;
    if (report.empty()) report = study.grids.front().directory.parent_path() / "gci";
    cfd::WriteGciReport(study, report, args->case_file);
    std::printf("%s\nreport: %s.h5, %s.yaml\n", cfd::GciTable(study).c_str(), report.string().c_str(),
                report.string().c_str());
  };
  return cmd;
}

}  // namespace kelvin::cli
