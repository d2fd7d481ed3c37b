// `kelvin run case.yaml`: runs a CFD case file (see cfd/run/run_case.h).
#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "cfd/run/run_case.h"
#include "data/schema/errors.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

Command AddRunCommand(CLI::App& app) {
  struct Args {
    std::string case_file;
    std::string restart;
    std::string output;
    bool no_progress = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("run", "Run a CFD case file (mesh/physics/schemes/solution/time/boundary/output)");
  sub->add_option("case", args->case_file, "Case file (YAML)")->required();
  sub->add_option("--restart", args->restart, "Continue from this HDF5 checkpoint");
  sub->add_option("-o,--output", args->output, "Output directory (overrides output.directory)");
  sub->add_flag("--no-progress", args->no_progress, "No progress line");
  Command cmd;
  cmd.app = sub;
  cmd.run = [args]() {
    cfd::RunOptions options;
    options.restart = args->restart;
    options.output_override = args->output;
    options.progress = !args->no_progress;
    const cfd::RunSummary s = cfd::RunCase(args->case_file, options);
    if (s.status == cfd::RunSummary::Status::kDiverged) {
      std::fprintf(stderr, "kelvin: run %s\n", s.message.c_str());
      std::exit(3);
    }
    std::printf("%s\n", s.message.c_str());
  };
  return cmd;
}

}  // namespace kelvin::cli
