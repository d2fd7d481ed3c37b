// `kelvin run case.yaml`: runs a CFD case file (see cfd/run/run_case.h).
#include <fmt/format.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "cfd/campaign/maneuver_campaign.h"
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

// The maneuvers of -m as a resumable campaign; exits 3 if a run failed and
// 128 + the signal if a stop was requested.
void RunManeuvers(const std::string& case_file, const std::vector<std::string>& maneuvers, int jobs,
                  const cfd::RunOptions& run, const std::string& output) {
  cfd::ManeuverCampaignOptions o;
  o.maneuvers = maneuvers;
  o.jobs = jobs;
  o.executable = SelfExecutable();
  o.output = output;
  o.run = run;
  const cfd::ManeuverCampaignSummary s = cfd::RunManeuverCampaign(case_file, o);
  std::printf("%s", s.table.c_str());
  std::fflush(stdout);
  if (s.interrupted) {
    std::fprintf(stderr, "kelvin: run stopped; rerun the same command to resume each maneuver from its checkpoint\n");
    std::exit(128 + static_cast<int>(g_stop_signal != 0 ? g_stop_signal : SIGTERM));
  }
  if (s.failed > 0) {
    std::fprintf(stderr, "kelvin: run: %d of %zu maneuvers failed (see the table)\n", s.failed, s.runs.size());
    std::exit(3);
  }
}

}  // namespace

Command AddRunCommand(CLI::App& app) {
  struct Args {
    std::string case_file;
    std::string restart;
    std::string output;
    std::vector<std::string> maneuvers;
    int jobs = 1;
    bool no_progress = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("run", "Run a CFD case file (mesh/physics/schemes/solution/time/boundary/output)");
  sub->add_option("case", args->case_file, "Case file (YAML)")->required();
  sub->add_option("--restart", args->restart, "Continue from this HDF5 checkpoint");
  sub->add_option("-o,--output", args->output, "Output directory (overrides output.directory)");
  sub->add_option("-m,--maneuver", args->maneuvers,
                  "Fly this maneuver instead of maneuver.kind (repeatable: turning:35:stbd, zigzag:10/10:port, ...); "
                  "each in <output>/<maneuver>/, resumed from its checkpoint and skipped once finished");
  sub->add_option("-j,--jobs", args->jobs, "With -m: maneuvers at the same time (default 1)");
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
    if (!args->maneuvers.empty()) {
      if (!args->restart.empty()) {
        throw ArgumentError("--restart: not with -m (each maneuver resumes from its own checkpoint in "
                            "<output>/<maneuver>/)");
      }
      options.output_override.clear();
      RunManeuvers(args->case_file, args->maneuvers, args->jobs, options, args->output);
      return;
    }
    if (args->jobs != 1) throw ArgumentError(fmt::format("--jobs {}: only with -m (several maneuvers)", args->jobs));
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
