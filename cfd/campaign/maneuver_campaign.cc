#include "cfd/campaign/maneuver_campaign.h"

#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <thread>

#include "cfd/campaign/worker_process.h"
#include "cfd/run/case_loader.h"
#include "cfd/run/maneuver_pilot.h"
#include "data/schema/config.h"
#include "data/schema/errors.h"
#include "simulator/maneuvers/maneuver.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using State = ManeuverRun::State;

constexpr int kDivergedExit = 3;  // kelvin run's exit status for a diverged run

std::string RunName(const std::string& maneuver) {
  std::string s = maneuver;
  std::replace_if(s.begin(), s.end(), [](char c) { return c == ':' || c == '/'; }, '_');
  return s;
}

// The planned runs: each definition parsed (one ArgumentError naming a bad
// one), none twice, in the order given.
std::vector<ManeuverRun> PlanRuns(const std::vector<std::string>& maneuvers, const fs::path& output) {
  std::vector<ManeuverRun> runs;
  for (const std::string& text : maneuvers) {
    std::string canonical;
    try {
      canonical = sim::ManeuverSpec::Parse(text).ToString();
    } catch (const ArgumentError& e) {
      throw ArgumentError(fmt::format("--maneuver {}: {}", text, e.what()));
    }
    for (const ManeuverRun& r : runs) {
      if (r.maneuver == canonical) throw ArgumentError(fmt::format("--maneuver {}: given twice", text));
    }
    ManeuverRun r;
    r.maneuver = canonical;
    r.name = RunName(canonical);
    r.directory = output / r.name;
    if (fs::exists(r.directory / "maneuver.h5")) r.state = State::kFinishedBefore;
    runs.push_back(std::move(r));
  }
  return runs;
}

std::string StateName(const ManeuverRun& r) {
  switch (r.state) {
    case State::kLeft: return "not run";
    case State::kRunning: return "running";
    case State::kDone: return "done";
    case State::kFinishedBefore: return "done (finished before)";
    case State::kFailed: return "FAILED: " + r.message;
    case State::kInterrupted: return "stopped: " + r.message;
  }
  return "?";
}

std::string Table(const std::vector<ManeuverRun>& runs) {
  std::size_t width = 8;
  for (const ManeuverRun& r : runs) width = std::max(width, r.maneuver.size());
  std::string s = fmt::format("{:<{}}  {}\n", "maneuver", width, "state (results in <run>/maneuver.h5)");
  for (const ManeuverRun& r : runs) s += fmt::format("{:<{}}  {}\n", r.maneuver, width, StateName(r));
  return s;
}

// One run in this process: from its checkpoint when it has one.
void RunHere(const fs::path& case_file, const ManeuverCampaignOptions& options, ManeuverRun& run) {
  fs::create_directories(run.directory);
  const RunLock lock(run.directory, run.name);
  RunOptions o = options.run;
  o.maneuver = run.maneuver;
  o.output_override = run.directory;
  const fs::path checkpoint = run.directory / "checkpoint.h5";
  o.restart = fs::exists(checkpoint) ? checkpoint : fs::path();
  if (!o.restart.empty()) std::fprintf(options.stream, "%s: resuming from %s\n", run.maneuver.c_str(), checkpoint.c_str());
  const RunSummary s = RunCase(case_file, o);
  switch (s.status) {
    case RunSummary::Status::kCompleted:
      run.state = State::kDone;
      std::fprintf(options.stream, "%s: %s\n", run.maneuver.c_str(), s.message.c_str());
      break;
    case RunSummary::Status::kDiverged:
      run.state = State::kFailed;
      run.message = s.message;
      break;
    case RunSummary::Status::kInterrupted:
      run.state = State::kInterrupted;
      run.message = s.message;
      break;
  }
}

void RunSerial(const fs::path& case_file, const ManeuverCampaignOptions& options, ManeuverCampaignSummary& summary) {
  for (ManeuverRun& r : summary.runs) {
    if (r.state != State::kLeft) continue;
    RunHere(case_file, options, r);
    if (r.state == State::kInterrupted) {
      summary.interrupted = true;
      return;
    }
  }
}

pid_t StartWorker(const fs::path& case_file, const ManeuverCampaignOptions& options, const fs::path& output,
                  ManeuverRun& r) {
  return SpawnWorker(WorkerProgram{options.executable, {}, 1},
                     {"--quiet", "run", fs::absolute(case_file).string(), "-m", r.maneuver, "-o",
                      fs::absolute(output).string(), "--jobs", "1", "--no-progress"},
                     r.directory / "log.txt", r.name);
}

// The end of a worker: done when it exited with 0 and wrote maneuver.h5.
void FinishWorker(ManeuverRun& r, int status, std::FILE* stream) {
  r.pid = -1;
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (code == 0 && fs::exists(r.directory / "maneuver.h5")) {
    r.state = State::kDone;
  } else if (code <= 128 && r.starts < kWorkerStartAttempts && DiedStartingMpi(r.directory / "log.txt")) {
    std::fprintf(stream, "%s: its worker died while MPI started up; starting it again\n", r.maneuver.c_str());
    std::fflush(stream);
    r.state = State::kLeft;
    return;
  } else {
    r.state = code > 128 ? State::kInterrupted : State::kFailed;
    r.message = ErrorLine(r.directory / "log.txt");
    if (code != kDivergedExit && code <= 128) r.message = fmt::format("exit {}: {}", code, r.message);
  }
  std::fprintf(stream, "%s: %s\n", r.maneuver.c_str(), StateName(r).c_str());
  std::fflush(stream);
}

void RunWorkers(const fs::path& case_file, const ManeuverCampaignOptions& options, const fs::path& output,
                ManeuverCampaignSummary& summary) {
  if (options.executable.empty()) throw ArgumentError("--jobs > 1 needs the path of the kelvin program");
  int running = 0;
  bool stopping = false;
  for (;;) {
    for (ManeuverRun& r : summary.runs) {
      if (stopping || running >= options.jobs || r.state != State::kLeft) continue;
      r.pid = StartWorker(case_file, options, output, r);
      r.state = State::kRunning;
      ++r.starts;
      ++running;
    }
    if (running == 0) break;
    if (!stopping && options.run.stop_requested && options.run.stop_requested() != 0) {
      stopping = summary.interrupted = true;  // each worker checkpoints and stops
      for (const ManeuverRun& r : summary.runs) {
        if (r.pid > 0) ::kill(r.pid, SIGTERM);
      }
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      continue;
    }
    for (ManeuverRun& r : summary.runs) {
      if (r.pid != pid) continue;
      FinishWorker(r, status, options.stream);
      --running;
    }
  }
}

// The campaign's output directory: the option, else the case's (`root`).
fs::path OutputDirectory(const data::ConfigNode& root, const fs::path& case_file,
                         const ManeuverCampaignOptions& options) {
  if (!options.output.empty()) return options.output;
  return ReadCaseSettings(root, case_file.parent_path()).output.directory;
}

}  // namespace

ManeuverCampaignSummary RunManeuverCampaign(const fs::path& case_file, const ManeuverCampaignOptions& options) {
  if (options.maneuvers.empty()) throw ArgumentError("--maneuver: expected at least one maneuver definition");
  if (options.jobs < 1) throw ArgumentError(fmt::format("--jobs {}: expected at least 1", options.jobs));
  const data::ConfigNode root = data::ConfigNode::LoadFile(case_file);
  RequireManeuverSection(root, options.maneuvers.front());
  const fs::path output = OutputDirectory(root, case_file, options);
  ManeuverCampaignSummary summary;
  summary.runs = PlanRuns(options.maneuvers, output);
  if (options.jobs > 1 && summary.runs.size() > 1) {
    RunWorkers(case_file, options, output, summary);
  } else {
    RunSerial(case_file, options, summary);
  }
  summary.complete = true;
  for (const ManeuverRun& r : summary.runs) {
    summary.failed += r.state == State::kFailed;
    summary.complete = summary.complete && (r.state == State::kDone || r.state == State::kFinishedBefore);
  }
  summary.table = Table(summary.runs);
  return summary;
}

}  // namespace kelvin::cfd
