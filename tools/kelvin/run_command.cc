// `kelvin run case.yaml`: runs a CFD case file (see cfd/run/run_case.h).
#include <fmt/format.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "cfd/run/run_case.h"
#include "data/schema/errors.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {
namespace {

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void RequestStop(int signal) { g_stop_signal = signal; }

// SIGINT and SIGTERM ask the run to stop after the step in progress with a
// checkpoint; the previous handlers come back when the run returns.
class StopSignals {
 public:
  StopSignals() {
    struct sigaction sa {};
    sa.sa_handler = RequestStop;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~StopSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

}  // namespace

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
    options.stop_requested = [] { return static_cast<int>(g_stop_signal); };
    const StopSignals signals;
    const cfd::RunSummary s = cfd::RunCase(args->case_file, options);
    if (s.status == cfd::RunSummary::Status::kDiverged) {
      std::fprintf(stderr, "kelvin: run %s\n", s.message.c_str());
      std::exit(3);
    }
    if (s.status == cfd::RunSummary::Status::kInterrupted) {
      std::fprintf(stderr, "kelvin: run %s\n", s.message.c_str());
      std::exit(128 + static_cast<int>(g_stop_signal));  // the shell's convention for a signal
    }
    std::printf("%s\n", s.message.c_str());
  };
  return cmd;
}

}  // namespace kelvin::cli
