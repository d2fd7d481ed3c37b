#include "cfd/campaign/worker_process.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/file.h>
#include <unistd.h>

#include <fstream>
#include <string_view>

#include "data/schema/errors.h"

extern char** environ;

namespace kelvin::cfd {

namespace fs = std::filesystem;

namespace {

// True for an environment entry of an MPI launch (see LauncherEnvironment).
bool FromAnMpiLaunch(std::string_view entry) {
  const std::string_view name = entry.substr(0, entry.find('='));
  for (const std::string_view prefix : {"PMIX_", "OMPI_COMM_WORLD_", "OMPI_MCA_orte_"}) {
    if (name.substr(0, prefix.size()) == prefix) return true;
  }
  for (const std::string_view launch :
       {"OMPI_MCA_ess", "OMPI_MCA_pmix", "OMPI_COMMAND", "OMPI_ARGV", "OMPI_APP_CTX_NUM_PROCS",
        "OMPI_NUM_APP_CTX", "OMPI_FIRST_RANKS", "OMPI_UNIVERSE_SIZE", "OMPI_FILE_LOCATION"}) {
    if (name == launch) return true;
  }
  return false;
}

}  // namespace

std::vector<char*> LauncherEnvironment() {
  std::vector<char*> env;
  for (char** e = environ; *e != nullptr; ++e) {
    if (!FromAnMpiLaunch(*e)) env.push_back(*e);
  }
  env.push_back(nullptr);
  return env;
}

std::vector<std::string> WorkerCommand(const WorkerProgram& program, const std::vector<std::string>& args) {
  std::vector<std::string> command;
  if (program.ranks > 1) command = {program.launcher.string(), "-n", std::to_string(program.ranks)};
  command.push_back(program.executable.string());
  command.insert(command.end(), args.begin(), args.end());
  return command;
}

std::vector<char*> ExecArgv(std::vector<std::string>& command) {
  std::vector<char*> argv;
  for (std::string& a : command) argv.push_back(a.data());
  argv.push_back(nullptr);
  return argv;
}

pid_t SpawnWorker(const WorkerProgram& program, const std::vector<std::string>& args,
                  const fs::path& log, const std::string& run) {
  const bool on_ranks = program.ranks > 1;
  const fs::path& exe = on_ranks ? program.launcher : program.executable;
  fs::create_directories(log.parent_path());
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<std::string> command = WorkerCommand(program, args);
  std::vector<char*> argv = ExecArgv(command);
  std::vector<char*> env = LauncherEnvironment();
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), on_ranks ? env.data() : environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw InputError(fmt::format("cannot start {} for run '{}' (error {})", exe.string(), run, rc));
  return pid;
}

std::string ErrorLine(const fs::path& path) {
  std::ifstream in(path);
  std::string line, last, error;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    last = line;
    if (error.empty() && line.rfind("kelvin: error:", 0) == 0) error = line;
  }
  return error.empty() ? last : error;
}

bool DiedStartingMpi(const fs::path& log) {
  std::ifstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    if (line.find("before MPI_INIT completed") != std::string::npos) return true;
  }
  return false;
}

RunLock::RunLock(const fs::path& dir, const std::string& run) {
  const fs::path path = dir / "lock";
  fd_ = ::open(path.c_str(), O_CREAT | O_RDWR, 0644);
  if (fd_ < 0 || ::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    if (fd_ >= 0) ::close(fd_);
    throw InputError(fmt::format("run '{}' is being computed by another process (lock {}); wait for it or stop it",
                                 run, path.string()));
  }
}

RunLock::~RunLock() { ::close(fd_); }

}  // namespace kelvin::cfd
