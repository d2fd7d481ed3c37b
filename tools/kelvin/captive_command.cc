// kelvin captive: runs a captive test campaign (static drift, pure sway, pure
// yaw, yaw with drift, circular motion) and writes the force histories in the
// captive HDF5 schema that `kelvin identify` reads. Solver mmg: virtual tests
// from the ship's MMG model; solver cfd: resumable CFD runs (cfd/campaign).
#include <fmt/format.h>
#include <mpi.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "cfd/campaign/cfd_campaign.h"
#include "cfd/parallel/petsc_context.h"
#include "data/schema/campaign_file.h"
#include "data/schema/captive_io.h"
#include "data/schema/errors.h"
#include "identification/virtual_captive.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct CaptiveArgs {
  std::string campaign_file;
  std::string output;
  int jobs = 0;
  int np = 0;
  long stop_after_steps = 0;
  std::string run;
  bool no_progress = false;
};

void RunCfd(const data::CampaignFile& file, const CaptiveArgs& a) {
  cfd::CampaignRunOptions o;
  o.jobs = a.jobs;
  if (a.np > 1) {
    o.ranks_per_run = a.np;
    o.launcher = FindLauncher(a.np);
  }
  // A worker that an MPI launcher started (by --np): its run is decomposed
  // over the launch's ranks, and rank 0 reports.
  int rank = 0;
  if (LauncherRanks() > 1) {
    cfd::EnsurePetsc();
    o.ranks = MPI_COMM_WORLD;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) spdlog::set_level(spdlog::level::err);
  }
  o.stop_after_steps = a.stop_after_steps;
  o.only_run = a.run;
  o.executable = SelfExecutable();
  o.output = a.output;
  o.progress = !a.no_progress;
  const cfd::CampaignRunSummary s = cfd::RunCfdCampaign(file, o);
  if (!a.run.empty()) {
    if (rank == 0) {
      fmt::print("run '{}': {} ({} steps computed)\n", a.run, s.runs_done == 1 ? "done" : "stopped",
                 s.steps_computed);
    }
    return;
  }
  if (!s.complete) {
    fmt::print("campaign '{}' stopped after {} steps; run the same command again to resume\n",
               file.name, s.steps_computed);
    std::exit(4);
  }
  fmt::print("campaign '{}' ({} runs, solver cfd, {} steps computed now)\n  written: {}\n",
             file.name, s.runs_total, s.steps_computed, s.output.string());
}

void RunCaptive(const CaptiveArgs& a) {
  // Under a launcher only a CFD run's worker decomposes; every rank of a
  // whole campaign would compute every run and write the same files.
  if (const int launched = LauncherRanks(); launched > 1 && (a.run.empty() || a.np > 1)) {
    throw ArgumentError(fmt::format(
        "kelvin captive was started by an MPI launcher on {} ranks; only the workers of a CFD "
        "campaign (--run NAME, started by --np) run on ranks; expected one process, with --np N "
        "for runs on N ranks",
        launched));
  }
  const data::CampaignFile file = data::LoadCampaignFile(a.campaign_file);
  if (file.solver == data::CampaignFile::Solver::kCfd) {
    RunCfd(file, a);
    return;
  }
  if (a.jobs > 0 || a.np > 0 || a.stop_after_steps > 0 || !a.run.empty()) {
    throw ArgumentError(
        "--jobs, --np, --stop-after-steps and --run are for campaigns with solver: cfd");
  }
  const data::CaptiveCampaign campaign = ident::RunCampaign(file);
  const std::string out = a.output.empty() ? "results/" + file.name + ".h5" : a.output;
  data::WriteCampaignH5(campaign, out);
  fmt::print("campaign '{}' ({} runs, solver mmg: virtual captive tests of {})\n", file.name,
             campaign.runs.size(), file.ship_file.string());
  for (const auto& run : campaign.runs) {
    fmt::print("  {:<24} {:<16} {} samples\n", run.name, data::MotionKindName(run.motion.kind),
               run.time.size());
  }
  fmt::print("  written: {}\n", out);
}

}  // namespace

Command AddCaptiveCommand(CLI::App& app) {
  auto args = std::make_shared<CaptiveArgs>();
  CLI::App* cmd =
      app.add_subcommand("captive", "Run a captive test campaign and write its force histories");
  cmd->add_option("campaign", args->campaign_file, "Campaign file (data/cases/<campaign>.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output,
                  "Campaign HDF5 (default results/<name>.h5; cfd: <cfd.directory>/<name>.h5)");
  cmd->add_option("-j,--jobs", args->jobs,
                  "cfd: runs at the same time (default: cfd.jobs of the file)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--np", args->np,
                  "cfd: each run on N MPI ranks (its worker starts under mpiexec -n N; with "
                  "--jobs J, J runs of N ranks at a time)")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--stop-after-steps", args->stop_after_steps,
                  "cfd: stop as if killed after this many time steps (resume by running again)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--run", args->run, "cfd: run only this run (what --jobs starts for each run)");
  cmd->add_flag("--no-progress", args->no_progress, "cfd: no progress table");
  return {cmd, [args] { RunCaptive(*args); }};
}

}  // namespace kelvin::cli
