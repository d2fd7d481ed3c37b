// What the campaigns (captive: cfd_campaign.h; maneuvers:
// maneuver_campaign.h) share to run their jobs: a worker process per run (a
// kelvin subcommand, its output into the run's log), the error line of
// that log for the failure report, and an exclusive lock on a run directory.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace kelvin::cfd {

// The program a campaign starts for each run: kelvin itself, or kelvin under
// an MPI launcher (`launcher -n ranks kelvin ...`), so that each run is
// decomposed over its own ranks (cfd/README.md "MPI ranks").
struct WorkerProgram {
  std::filesystem::path executable;  // the kelvin program
  std::filesystem::path launcher;    // mpiexec; used when ranks > 1
  int ranks = 1;
};

// This process's environment (a null-terminated list for exec) without the
// variables Open MPI sets in an MPI process, singleton or rank (PMIX_*,
// OMPI_MCA_ess, OMPI_MCA_pmix, ...): for starting a launcher, which they make
// believe it runs inside that job (a singleton's OMPI_MCA_ess=singleton fails
// mpiexec, its OMPI_MCA_pmix=isolated crashes it). User settings such as
// OMPI_MCA_rmaps_base_oversubscribe stay.
std::vector<char*> LauncherEnvironment();

// The command line of `program args...`: `launcher -n ranks executable
// args...` when ranks > 1, else `executable args...`.
std::vector<std::string> WorkerCommand(const WorkerProgram& program, const std::vector<std::string>& args);
// Pointers to the strings of `command`, null-terminated, for exec (valid
// while `command` is).
std::vector<char*> ExecArgv(std::vector<std::string>& command);

// Starts `program args...` with stdout and stderr into `log` (created or
// truncated), a launcher with LauncherEnvironment(); returns its pid (the
// launcher's on ranks). Throws InputError naming `run` if it cannot start.
pid_t SpawnWorker(const WorkerProgram& program, const std::vector<std::string>& args,
                  const std::filesystem::path& log, const std::string& run);

// The first "kelvin: error:" line of a worker's log, else its last non-empty
// line ("" if there is none): under a launcher, the launcher's own report of
// the failed rank comes after kelvin's message.
std::string ErrorLine(const std::filesystem::path& path);

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
