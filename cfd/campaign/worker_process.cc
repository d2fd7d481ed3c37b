#include "cfd/campaign/worker_process.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/file.h>
#include <unistd.h>

#include <fstream>

#include "data/schema/errors.h"

extern char** environ;

namespace kelvin::cfd {

namespace fs = std::filesystem;

pid_t SpawnWorker(const fs::path& exe, const std::vector<std::string>& args, const fs::path& log,
                  const std::string& run) {
  fs::create_directories(log.parent_path());
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<std::string> all = {exe.string()};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw InputError(fmt::format("cannot start {} for run '{}' (error {})", exe.string(), run, rc));
  return pid;
}

std::string LastLine(const fs::path& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
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
