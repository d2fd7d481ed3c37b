// `kelvin run case.yaml`: runs a CFD case file (see cfd/run/run_case.h).
#include <fmt/format.h>

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cfd/campaign/maneuver_campaign.h"
#include "cfd/campaign/worker_process.h"
#include "cfd/parallel/petsc_context.h"
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

// `--np N`: this command again under `mpiexec -n N` (replaces the process).
[[noreturn]] void RelaunchOnRanks(int np, const std::vector<std::string>& run_args) {
  const cfd::WorkerProgram program{SelfExecutable(), FindLauncher(np), np};
  std::vector<std::string> args = {"run"};
  args.insert(args.end(), run_args.begin(), run_args.end());
  std::vector<std::string> command = cfd::WorkerCommand(program, args);
  std::vector<char*> c_argv = cfd::ExecArgv(command);
  const std::filesystem::path& launcher = program.launcher;
  std::fflush(nullptr);
  std::vector<char*> env = cfd::LauncherEnvironment();
  execve(launcher.c_str(), c_argv.data(), env.data());
  throw ArgumentError(fmt::format("--np {}: could not start {}: {}", np, launcher.string(), std::strerror(errno)));
}

}  // namespace

Command AddRunCommand(CLI::App& app) {
  struct Args {
    std::string case_file;
    std::string restart;
    std::string output;
    std::vector<std::string> maneuvers;
    int jobs = 1;
    int np = 0;
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
  sub->add_option("--np", args->np,
                  "Run on N MPI ranks: starts itself under mpiexec -n N (the same as 'mpiexec -n N kelvin run ...'; "
                  "on a cluster use its launcher instead)")
      ->check(CLI::Range(1, 1 << 20));
  Command cmd;
  cmd.app = sub;
  cmd.run = [args]() {
    const int launched = LauncherRanks();
    if (args->np > 1 && launched == 1) {
      if (!args->maneuvers.empty()) {
        throw ArgumentError(fmt::format("--np {}: not with -m (the maneuvers run as separate processes: --jobs)",
                                        args->np));
      }
      std::vector<std::string> run_args = {args->case_file};
      if (!args->restart.empty()) run_args.insert(run_args.end(), {"--restart", args->restart});
      if (!args->output.empty()) run_args.insert(run_args.end(), {"-o", args->output});
      if (args->no_progress) run_args.push_back("--no-progress");
      RelaunchOnRanks(args->np, run_args);
    }
    cfd::RunOptions options;
    options.restart = args->restart;
    options.output_override = args->output;
    options.progress = !args->no_progress;
    // Under a launcher the case is decomposed over its ranks; rank 0 reports.
    int rank = 0;
    if (launched > 1) {
      if (!args->maneuvers.empty()) {
        throw ArgumentError(fmt::format("-m: the maneuvers of -m run as separate processes (--jobs), not on the {} "
                                        "MPI ranks of this launch; expected one process",
                                        launched));
      }
      cfd::EnsurePetsc();
      options.ranks = MPI_COMM_WORLD;
      MPI_Comm_rank(MPI_COMM_WORLD, &rank);
      if (rank != 0) {
        spdlog::set_level(spdlog::level::err);
        options.progress = false;
      }
    }
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
      if (rank == 0) std::fprintf(stderr, "kelvin: run %s\n", s.message.c_str());
      std::exit(3);
    }
    if (s.status == cfd::RunSummary::Status::kInterrupted) {
      if (rank == 0) std::fprintf(stderr, "kelvin: run %s\n", s.message.c_str());
      std::exit(128 + static_cast<int>(g_stop_signal));  // the shell's convention for a signal
    }
    if (rank == 0) std::printf("%s\n", s.message.c_str());
  };
  return cmd;
}

}  // namespace kelvin::cli
