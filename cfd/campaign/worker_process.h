// What the campaigns (captive: cfd_campaign.h; maneuvers:
// maneuver_campaign.h) share to run their jobs: a worker process per run (a
// kelvin subcommand, its output into the run's log), the last line of that
// log for the failure report, and an exclusive lock on a run directory.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace kelvin::cfd {

// Starts `exe args...` with stdout and stderr into `log` (created or
// truncated); returns its pid. Throws InputError naming `run` if it cannot
// start.
pid_t SpawnWorker(const std::filesystem::path& exe, const std::vector<std::string>& args,
                  const std::filesystem::path& log, const std::string& run);

// The last non-empty line of a text file ("" if there is none).
std::string LastLine(const std::filesystem::path& path);

// True when a worker's log shows it died while MPI started up (Open MPI's
// "before MPI_INIT completed"): a transient failure of the MPI singleton
// under load that leaves nothing behind, seen once in the CI campaign tests.
// The campaigns start such a worker again, up to kWorkerStartAttempts times
// in all, and report it as failed after that.
bool DiedStartingMpi(const std::filesystem::path& log);
inline constexpr int kWorkerStartAttempts = 3;

// An exclusive lock on a run directory, so that two processes (a rerun while
// orphaned workers of a killed parent still run) never work on one run.
// Throws InputError naming the run if another process holds it.
class RunLock {
 public:
  RunLock(const std::filesystem::path& dir, const std::string& run);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace kelvin::cfd
