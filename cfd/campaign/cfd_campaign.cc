#include "cfd/campaign/cfd_campaign.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <span>
#include <thread>

#include "cfd/campaign/appendage_run.h"
#include "cfd/campaign/campaign_jobs.h"
#include "cfd/campaign/run_samples.h"
#include "cfd/campaign/worker_process.h"
#include "cfd/parallel/domain_part.h"
#include "cfd/run/captive_sampler.h"
#include "cfd/run/run_driver.h"
#include "data/schema/atomic_file.h"
#include "data/schema/captive_io.h"
#include "data/schema/config.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "simulator/mmg/ship_parameters.h"

namespace kelvin::cfd {
namespace {

// A run whose flow diverged: it fails alone in a serial campaign.
class RunDivergedError : public InputError {
 public:
  using InputError::InputError;
};


namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// --- one run in this process -------------------------------------------------

struct Context {
  const data::CampaignFile& file;
  const CaseSettings& settings;  // of the campaign's case file
  const data::CaptiveShip& ship;
  long budget = 0;    // > 0: steps allowed in this call
  long computed = 0;  // steps computed in this call
  std::function<void()> report;
  MPI_Comm ranks = MPI_COMM_NULL;  // a worker's ranks (the run is decomposed over them)
};

std::vector<int> HullPatches(const Context& ctx, const Case& c) {
  std::vector<std::string> names =
      ctx.file.cfd.hull_patches.empty() ? c.settings.output.force_patches : ctx.file.cfd.hull_patches;
  if (names.empty()) {
    throw ConfigError(fmt::format(
        "{}: cfd.hull_patches is empty and the case {} has no output.forces; expected the "
        "hull patch names",
        ctx.file.path.string(), ctx.file.cfd.case_file.string()));
  }
  std::vector<int> out;
  for (const std::string& n : names) {
    const int p = c.mesh->FindPatch(n);
    if (p < 0) {
      std::vector<std::string> all;
      for (const Patch& patch : c.mesh->patches()) all.push_back(patch.name);
      throw ConfigError(
          fmt::format("{}: cfd.hull_patches: '{}' is not a patch of the case mesh ({})",
                      ctx.file.path.string(), n, fmt::join(all, ", ")));
    }
    out.push_back(p);
  }
  return out;
}

// The run's own files beside the driver's checkpoint: the samples (written
// before the state, so that a checkpoint never runs ahead of them), the
// cost so far and the progress file; the progress table after each step.
class JobFiles final : public Monitor {
 public:
  // `sampler`: null for a run with the propeller and rudder (its samples are
  // in its checkpoints).
  // On ranks (`part`) rank 0 writes them; the cost is of all ranks.
  JobFiles(Context& ctx, CampaignJob& job, const CaptiveSampler* sampler, RunCost cost,
           const DomainPart* part)
      : ctx_(ctx), job_(job), sampler_(sampler), cost_(cost), part_(part) {}
  void AfterStep(const PimpleSolver& solver, const StepRecord& record, History&) override {
    cost_.cpu_seconds += part_ ? part_->Sum(record.step_cpu_seconds) : record.step_cpu_seconds;
    cost_.courant_max = std::max(cost_.courant_max, record.step.courant_max);
    ++ctx_.computed;
    job_.step = solver.step();
    if (ctx_.report) ctx_.report();
  }
  void BeforeCheckpoint(const PimpleSolver&) override {
    OnFirstRank(part_, [&] {
      if (sampler_) WriteSamples(job_.dir / "samples.h5", sampler_->samples(), job_.step, job_.steps, cost_);
      WriteProgressFile(job_, seconds());
    });
  }
  void WriteResult(const Settle& settle) const {
    OnFirstRank(part_, [&] {
      WriteSamples(job_.dir / "result.h5", sampler_->samples(), job_.step, job_.steps, cost_,
                   settle);
      WriteProgressFile(job_, seconds());
    });
  }
  // A run with the propeller and rudder: its means and cost.
  void WriteAppendageResult(const data::AppendageRun& run) const {
    OnFirstRank(part_, [&] { WriteAppendageFile(run); });
  }

 private:
  void WriteAppendageFile(const data::AppendageRun& run) const {
    data::H5Writer w(job_.dir / "result.h5");
    w.SetAttribute("/", "kind", "kelvin captive CFD run with propeller and rudder");
    w.SetAttribute("/", "cpu_seconds", cost_.cpu_seconds);
    w.SetAttribute("/", "courant_max", cost_.courant_max);
    w.SetAttribute("/", "cells", cost_.cells);
    data::AppendageCampaign one;
    one.runs.push_back(run);
    data::WriteAppendageRuns(one, w);
    w.Commit();
    WriteProgressFile(job_, seconds());
  }
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  Context& ctx_;
  CampaignJob& job_;
  const CaptiveSampler* sampler_;
  RunCost cost_;
  const DomainPart* part_;
  Clock::time_point start_ = Clock::now();
};

// The samples and cost a resumed run starts from: those of samples.h5 up
// to the checkpoint's step, or none (and no restart) when the pair does not
// match (the samples run ahead of a checkpoint that was not written; fewer
// samples than steps: start again).
struct Resume {
  bool restart = false;
  std::vector<CaptiveSample> samples;
  RunCost cost;
};

Resume ReadResume(const CampaignJob& job) {
  const fs::path checkpoint = job.dir / "checkpoint.h5", samples_file = job.dir / "samples.h5";
  Resume r;
  if (!fs::exists(checkpoint) || !fs::exists(samples_file)) return r;
  const auto step = static_cast<std::size_t>(data::H5Reader(checkpoint).NumberAttribute("/", "step"));
  std::vector<CaptiveSample> samples = ReadSamples(samples_file, RigidMotion(job.cfd_motion));
  if (samples.size() < step) return r;
  samples.resize(step);
  r.restart = true;
  r.samples = std::move(samples);
  const data::H5Reader previous(samples_file);
  if (previous.HasAttribute("/", "cpu_seconds")) {
    r.cost.cpu_seconds = previous.NumberAttribute("/", "cpu_seconds");
    r.cost.courant_max = previous.NumberAttribute("/", "courant_max");
  }
  return r;
}

// Runs (or resumes) one job through the run driver; false when the step
// budget ran out first.
bool ExecuteAppendageJob(Context& ctx, CampaignJob& job);

// Creates the run's directory, locks it against a second process and removes
// what a killed earlier attempt left half-written; on ranks rank 0 does this
// and holds the lock (in `lock`).
void ClaimRunDirectory(const Context& ctx, const CampaignJob& job, std::optional<RunLock>& lock) {
  OnFirstRank(ctx.ranks, [&] {
    fs::create_directories(job.dir);
    lock.emplace(job.dir, job.name);
    data::RemoveStaleTemporaries(job.dir);
  });
}

// The cells of the run's (whole) mesh.
double CellCount(const Case& c) {
  return c.part && c.part->parallel() ? static_cast<double>(c.part->n_global_cells)
                                      : c.mesh->n_cells();
}

// Runs a job's case through the driver with the campaign's checkpoints
// (<dir>/checkpoint.h5) and step budget, restarting from `restart` if set;
// sets job.step. Empty when the budget ran out first; a diverged run throws.
std::optional<RunDriverSummary> DriveJob(const Context& ctx, CampaignJob& job, Case& c, std::span<Monitor* const> monitors,
                                         const fs::path& restart) {
  RunDriverOptions o;
  o.restart = restart;
  o.checkpoint = job.dir / "checkpoint.h5";
  o.checkpoint_interval = ctx.file.cfd.checkpoint_interval;
  o.checkpoint_at_end = false;
  o.step_budget = ctx.budget > 0 ? ctx.budget - ctx.computed : 0;
  o.progress = false;
  const RunDriverSummary d = RunDriver(c, monitors, o);
  if (d.status == RunDriverSummary::Status::kDiverged) {
    throw RunDivergedError(fmt::format("run '{}' {}", job.name, d.message));
  }
  if (d.status == RunDriverSummary::Status::kStopped) return std::nullopt;
  job.step = c.solver->step();
  return d;
}

bool ExecuteJob(Context& ctx, CampaignJob& job) {
  if (ctx.budget > 0 && ctx.computed >= ctx.budget) return false;  // as if killed here
  if (job.appendage) return ExecuteAppendageJob(ctx, job);
  CaseOverrides overrides;
  overrides.motion = job.cfd_motion;
  overrides.dt = job.dt;
  overrides.end_time = job.dt * job.steps;
  overrides.steady = job.settle;
  overrides.ranks = ctx.ranks;
  std::optional<RunLock> lock;
  ClaimRunDirectory(ctx, job, lock);
  const fs::path checkpoint = job.dir / "checkpoint.h5";
  Case c = LoadCaseFile(ctx.file.cfd.case_file, overrides);
  const PrimeScales scales{c.settings.rho, ctx.ship.Lpp,
                           ctx.file.cfd.draft > 0 ? ctx.file.cfd.draft : ctx.ship.d,
                           job.cfd_motion.speed};
  // The steady criterion measures the loads the run samples (the hull
  // patches); its window goes into the run's checkpoints.
  c.force_patches = HullPatches(ctx, c);
  CaptiveSampler sampler(c, c.force_patches, scales);
  Resume resume = ReadResume(job);
  resume.cost.cells = CellCount(c);
  sampler.Restore(std::move(resume.samples));
  JobFiles files(ctx, job, &sampler, resume.cost, c.part.get());
  Monitor* monitors[] = {&sampler, &files};
  const std::optional<RunDriverSummary> driven =
      DriveJob(ctx, job, c, monitors, resume.restart ? checkpoint : fs::path());
  if (!driven) return false;
  const RunDriverSummary& d = *driven;
  Settle settle;
  if (job.settle) {
    settle.settled = d.steady.settled ? 1 : 0;
    settle.change = d.steady.force_change;
    // The criterion's window holds the newest sample at least `window` back;
    // half a step earlier keeps that sample in the analysis despite round-off.
    settle.t_settle = c.solver->time() - job.settle->criterion.window - 0.5 * job.dt;
    job.steps = job.step;  // a settled run ends early
  }
  files.WriteResult(settle);
  OnFirstRank(ctx.ranks, [&] {
    std::error_code ec;
    fs::remove(checkpoint, ec);
    fs::remove(job.dir / "samples.h5", ec);
  });
  return true;
}

// A run with the propeller and rudder: the free-running coupler holds the
// body, the sampler keeps its samples in the checkpoints; the means over the
// second half of the steady duration go into result.h5.
bool ExecuteAppendageJob(Context& ctx, CampaignJob& job) {
  CaseOverrides overrides;
  overrides.dt = job.dt;
  overrides.end_time = job.dt * job.steps;
  overrides.output = job.dir;
  overrides.ranks = ctx.ranks;
  std::optional<RunLock> lock;
  ClaimRunDirectory(ctx, job, lock);
  const fs::path checkpoint = job.dir / "checkpoint.h5";
  Case c = LoadAppendageCase(ctx.file, *job.appendage, overrides);
  c.force_patches = HullPatches(ctx, c);
  FreeRunningCoupler coupler(c);
  AppendageSampler sampler(c, coupler);
  RunCost cost;
  cost.cells = CellCount(c);
  JobFiles files(ctx, job, nullptr, cost, c.part.get());
  Monitor* monitors[] = {&coupler, &sampler, &files};
  if (!DriveJob(ctx, job, c, monitors, fs::exists(checkpoint) ? checkpoint : fs::path())) return false;
  const double from = ctx.file.cfd.steady_ramp + 0.5 * ctx.file.cfd.steady_duration - 0.5 * job.dt;
  files.WriteAppendageResult(sampler.Mean(*job.appendage, from));
  OnFirstRank(ctx.ranks, [&] {
    std::error_code ec;
    fs::remove(checkpoint, ec);
  });
  return true;
}

// --- several runs as worker processes ---------------------------------------

pid_t StartWorker(const data::CampaignFile& f, const WorkerProgram& program, CampaignJob& job) {
  return SpawnWorker(program, {"--quiet", "captive", f.path.string(), "--run", job.name, "--no-progress"},
                     job.dir / "log.txt", job.name);
}

// --- the campaign ------------------------------------------------------------

// The ship of a campaign, after checking that the campaign runs in CFD at a
// given carriage speed.
data::CaptiveShip CampaignShip(const data::CampaignFile& f) {
  if (f.solver != data::CampaignFile::Solver::kCfd) {
    throw ConfigError(f.path.string() + ": campaign.solver is not 'cfd'");
  }
  const data::CaptiveShip ship = data::LoadCaptiveShip(f.ship_file);
  if (!(f.speed > 0))
    throw ConfigError(f.path.string() + ": campaign.speed: expected the carriage speed in m/s");
  return ship;
}

// The settings of the campaign's case, whose density must be the ship's.
CaseSettings CampaignCaseSettings(const data::CampaignFile& f, const data::CaptiveShip& ship) {
  CaseSettings settings =
      ReadCaseSettings(data::ConfigNode::LoadFile(f.cfd.case_file), f.cfd.case_file.parent_path());
  const double case_rho = settings.rho;
  if (std::abs(case_rho - ship.rho) > 1e-9 * ship.rho) {
    throw ConfigError(
        fmt::format("{}: physics.rho = {} differs from the ship's rho = {} ({}); the prime system "
                    "needs one density",
                    f.cfd.case_file.string(), case_rho, ship.rho, f.ship_file.string()));
  }
  return settings;
}

// Worker mode (--run): runs just the named job in this process and writes
// its result; the campaign file is left to the parent.
CampaignRunSummary RunOnly(Context& ctx, const std::string& name, std::vector<CampaignJob>& jobs,
                           CampaignRunSummary summary) {
  auto it = std::find_if(jobs.begin(), jobs.end(), [&](const CampaignJob& j) { return j.name == name; });
  if (it == jobs.end()) {
    std::vector<std::string> names;
    for (const CampaignJob& j : jobs) names.push_back(j.name);
    throw ArgumentError(fmt::format("--run {}: no such run in {} (runs: {})", name,
                                    ctx.file.path.string(), fmt::join(names, ", ")));
  }
  if (it->state != CampaignJob::State::kDone) {
    it->state = CampaignJob::State::kRunning;
    if (ExecuteJob(ctx, *it)) it->state = CampaignJob::State::kDone;
  }
  summary.steps_computed = ctx.computed;
  summary.runs_done = it->state == CampaignJob::State::kDone ? 1 : 0;
  summary.complete = false;
  return summary;
}

// Runs the jobs left one after the other in this process; false when the
// step budget ran out first (the campaign resumes later).
bool RunSerial(Context& ctx, std::vector<CampaignJob>& jobs, CampaignRunSummary& summary,
               ProgressTable& progress) {
  ctx.report = [&] {
    summary.steps_computed = ctx.computed;
    progress.Print(false);
  };
  progress.Print(true);
  for (CampaignJob& j : jobs) {
    if (j.state == CampaignJob::State::kDone) continue;
    j.state = CampaignJob::State::kRunning;
    bool finished = false;
    try {
      finished = ExecuteJob(ctx, j);
    } catch (const RunDivergedError& e) {
      // A run that diverges fails alone: the others run, and the campaign
      // names it at the end (ThrowIfRunsFailed). Bad input stops it all.
      j.state = CampaignJob::State::kFailed;
      j.message = e.what();
      const std::string prefix = "run '" + j.name + "' ";
      if (j.message.rfind(prefix, 0) == 0) j.message.erase(0, prefix.size());
      summary.steps_computed = ctx.computed;
      progress.Print(true);
      continue;
    }
    summary.steps_computed = ctx.computed;
    if (!finished) {
      j.state = CampaignJob::State::kLeft;
      progress.Print(true);
      return false;
    }
    j.state = CampaignJob::State::kDone;
    progress.Print(true);
  }
  return true;
}

// The steps a job has computed since its progress file was last read.
int AdvanceProgress(CampaignJob& job) {
  const int before = job.step;
  ReadProgressFile(job);
  return job.step - before;
}

// Starts worker processes for up to `slots` jobs left; returns how many.
int StartWorkers(const data::CampaignFile& f, const WorkerProgram& program, int slots,
                 std::vector<CampaignJob>& jobs) {
  int started = 0;
  for (CampaignJob& j : jobs) {
    if (started >= slots) break;
    if (j.state != CampaignJob::State::kLeft) continue;
    j.pid = StartWorker(f, program, j);
    j.state = CampaignJob::State::kRunning;
    ++j.starts;
    ++started;
  }
  return started;
}

// Records the end of worker `pid` (exit status `status`): its job is done
// when it exited with 0 and wrote result.h5, failed otherwise with the error
// line of its log. Returns the number of workers that ended (0 or 1).
int FinishWorker(pid_t pid, int status, std::vector<CampaignJob>& jobs, CampaignRunSummary& summary) {
  int finished = 0;
  for (CampaignJob& j : jobs) {
    if (j.pid != pid) continue;
    j.pid = -1;
    ++finished;
    summary.steps_computed += AdvanceProgress(j);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(j.dir / "result.h5")) {
      j.state = CampaignJob::State::kDone;
      j.step = j.steps;
    } else if (j.starts < kWorkerStartAttempts && DiedStartingMpi(j.dir / "log.txt")) {
      spdlog::warn("run '{}': its worker died while MPI started up; starting it again", j.name);
      j.state = CampaignJob::State::kLeft;
    } else {
      j.state = CampaignJob::State::kFailed;
      j.message = ErrorLine(j.dir / "log.txt");
    }
  }
  return finished;
}

// Throws InputError naming every failed run and the error line of its log.
void ThrowIfRunsFailed(const data::CampaignFile& f, const std::vector<CampaignJob>& jobs) {
  std::string failures;
  for (const CampaignJob& j : jobs) {
    if (j.state == CampaignJob::State::kFailed)
      failures += fmt::format("\n  run '{}': {}", j.name, j.message);
  }
  if (!failures.empty())
    throw InputError("captive campaign '" + f.name + "': runs failed:" + failures);
}

// Runs the jobs left as `kelvin captive --run` worker processes, at most
// `n_jobs` at a time, polling their progress files for the table.
void RunWorkers(const data::CampaignFile& f, const CampaignRunOptions& options, int n_jobs,
                std::vector<CampaignJob>& jobs, CampaignRunSummary& summary, ProgressTable& progress) {
  if (options.executable.empty())
    throw ArgumentError("--jobs > 1 needs the path of the kelvin program");
  const WorkerProgram program{options.executable, options.launcher, options.ranks_per_run};
  progress.Print(true);
  int running = 0;
  for (;;) {
    running += StartWorkers(f, program, n_jobs - running, jobs);
    if (running == 0) break;
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0) {
      running -= FinishWorker(pid, status, jobs, summary);
      progress.Print(true);
      continue;
    }
    for (CampaignJob& j : jobs) {
      if (j.state == CampaignJob::State::kRunning) summary.steps_computed += AdvanceProgress(j);
    }
    progress.Print(false);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ThrowIfRunsFailed(f, jobs);
}

// --- the campaign file -------------------------------------------------------

// The captive run of a finished job: the total hull loads, without the
// rigid-body inertia (CFD gives the hydrodynamic force alone).
data::CaptiveRun CaptiveRunOf(const CampaignJob& job, const std::vector<CaptiveSample>& samples) {
  data::CaptiveRun run;
  run.name = job.name;
  run.motion = job.motion;
  run.includes_rigid_body_inertia = false;
  const data::H5Reader result(job.dir / "result.h5");
  if (result.HasAttribute("/", "settled")) {
    run.settled = static_cast<int>(result.NumberAttribute("/", "settled"));
    run.settle_change = result.NumberAttribute("/", "settle_change");
    run.t_settle = result.NumberAttribute("/", "t_settle");
  }
  for (const CaptiveSample& s : samples) {
    const PlanarLoad total = s.loads.Total();
    run.time.push_back(s.time);
    run.force[0].push_back(total.X);
    run.force[1].push_back(total.Y);
    run.force[2].push_back(total.N);
  }
  return run;
}

// The ship file's propeller and rudder, for the fit of the interaction coefficients.
data::AppendageGeometry AppendageGeometryOf(const data::AppendageDesign& d) {
  const sim::ShipParameters ship = sim::LoadShip(d.ship_file);
  data::AppendageGeometry g;
  g.Lpp = ship.principal.Lpp;
  g.D_p = ship.propeller.D_p;
  g.A_R = ship.rudder.A_R;
  g.H_R = ship.rudder.H_R;
  g.rho = ship.principal.rho;
  g.x_R_prime = ship.rudder.x_R_prime;
  g.x_P_prime = ship.propeller.x_P_prime;
  g.ship_file = fs::absolute(d.ship_file).lexically_normal().string();
  return g;
}

// Every run is done: the campaign file in the captive schema, with the
// solver, the case and the prime draft as attributes and the extra channels.
void WriteCampaignFile(const data::CampaignFile& f, const data::CaptiveShip& ship,
                       const CaseSettings& settings, const std::vector<CampaignJob>& jobs,
                       const fs::path& output) {
  data::CaptiveCampaign campaign;
  const bool free_surface = settings.free_surface;
  campaign.description = fmt::format(
      "CFD captive campaign '{}' of {}: case {}, {}, hull loads on the moving mesh", f.name,
      ship.name, f.cfd.case_file.filename().string(),
      free_surface ? "linearized free surface" : "double body (no free surface)");
  campaign.ship = ship;
  std::vector<std::vector<CaptiveSample>> all;
  std::vector<const CampaignJob*> bare;
  data::AppendageCampaign appendages;
  for (const CampaignJob& j : jobs) {
    if (j.appendage) {
      appendages.runs.push_back(data::ReadAppendageRuns(j.dir / "result.h5", /*geometry=*/false).runs.at(0));
      continue;
    }
    all.push_back(ReadSamples(j.dir / "result.h5", RigidMotion(j.cfd_motion)));
    campaign.runs.push_back(CaptiveRunOf(j, all.back()));
    bare.push_back(&j);
  }
  // One writer and one Commit(): a kill between two commits would leave the
  // file under its name without the attributes and channels below. A kill
  // during an earlier attempt's write left its temporary beside it.
  data::RemoveStaleTemporaries(output.has_parent_path() ? output.parent_path() : fs::path("."));
  data::H5Writer w(output);
  data::WriteCampaignH5(campaign, w);
  w.SetAttribute("/", "solver", "cfd");
  w.SetAttribute("/", "case", f.cfd.case_file.string());
  w.SetAttribute("/", "prime_draft", f.cfd.draft > 0 ? f.cfd.draft : ship.d);
  for (std::size_t r = 0; r < bare.size(); ++r) WriteExtraChannels(w, bare[r]->name, all[r]);
  if (f.appendages) {
    appendages.geometry = AppendageGeometryOf(*f.appendages);
    data::WriteAppendageRuns(appendages, w);
  }
  w.Commit();
}

}  // namespace

CampaignRunSummary RunCfdCampaign(const data::CampaignFile& f, const CampaignRunOptions& options) {
  const data::CaptiveShip ship = CampaignShip(f);
  const CaseSettings settings = CampaignCaseSettings(f, ship);
  std::vector<CampaignJob> jobs = PlanCampaignJobs(f, ship, settings.time.dt);
  const int n_jobs = options.jobs > 0 ? options.jobs : f.cfd.jobs;
  const bool workers = n_jobs > 1 || options.ranks_per_run > 1;
  if (workers && options.stop_after_steps > 0) {
    throw ArgumentError(
        "--stop-after-steps runs the campaign in one process; use it with --jobs 1 and no --np");
  }
  if (options.ranks_per_run > 1 && options.launcher.empty()) {
    throw ArgumentError(
        fmt::format("--np {}: no MPI launcher to start the runs with", options.ranks_per_run));
  }
  CampaignRunSummary summary;
  summary.output = options.output.empty() ? f.cfd.directory / (f.name + ".h5") : options.output;
  summary.runs_total = static_cast<int>(jobs.size());
  ReadJobStates(jobs);
  ProgressTable progress(f, options, jobs, summary);
  Context ctx{f, settings, ship, options.stop_after_steps, 0, {}, options.ranks};
  if (!options.only_run.empty()) return RunOnly(ctx, options.only_run, jobs, summary);
  if (!workers) {
    if (!RunSerial(ctx, jobs, summary, progress)) return summary;  // stopped by the step budget
    ThrowIfRunsFailed(f, jobs);
  } else {
    RunWorkers(f, options, n_jobs, jobs, summary, progress);
  }
  WriteCampaignFile(f, ship, settings, jobs, summary.output);
  summary.runs_done = summary.runs_total;
  summary.complete = true;
  summary.table = ProgressTableText(jobs, progress.elapsed(), summary.steps_computed);
  return summary;
}

}  // namespace kelvin::cfd
