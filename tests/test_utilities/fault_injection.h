// Fault injection for the tests of issue #24: a kelvin command started as a
// child process, killed with SIGKILL at chosen points (a random time, or the
// moment a file is created or renamed in its output) and started again after
// each kill until it completes.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/inotify.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

extern char** environ;

namespace kelvin::testing {

// A child process (posix_spawn) with its stdout and stderr in `log`. One that
// still runs when the object goes (a failed assertion) is killed, so that no
// test leaves a kelvin behind.
class Process {
 public:
  Process(const std::vector<std::string>& argv, const std::filesystem::path& log) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    const int rc = posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::system_error(rc, std::generic_category(), "cannot start " + argv[0]);
  }
  ~Process() {
    if (!status_) {
      Signal(SIGKILL);
      Wait();
    }
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  // Exit status, or -signal; nullopt while running.
  std::optional<int> Poll() {
    int status = 0;
    if (!status_ && waitpid(pid_, &status, WNOHANG) == pid_) status_ = Decode(status);
    return status_;
  }
  int Wait() {
    int status = 0;
    if (!status_ && waitpid(pid_, &status, 0) == pid_) status_ = Decode(status);
    return status_.value_or(-1);
  }
  void Signal(int signal) const { kill(pid_, signal); }
  pid_t pid() const { return pid_; }

 private:
  static int Decode(int status) {
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
  }
  pid_t pid_ = -1;
  std::optional<int> status_;
};

// When to kill a process. Due() is polled while it runs; each call waits
// about a millisecond at most.
class KillPoint {
 public:
  virtual ~KillPoint() = default;
  virtual bool Due() = 0;
};

// Due `seconds` after the point is made (just before its process starts).
class AfterSeconds final : public KillPoint {
 public:
  explicit AfterSeconds(double seconds)
      : at_(std::chrono::steady_clock::now() +
            std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                std::chrono::duration<double>(seconds))) {}
  bool Due() override {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return std::chrono::steady_clock::now() >= at_;
  }

 private:
  std::chrono::steady_clock::time_point at_;
};

// Due the moment a file whose name starts with `prefix` is created (IN_CREATE:
// a temporary file appears) or renamed into place (IN_MOVED_TO: a final name
// appears) in one of `dirs` or in a directory below them, now or later. inotify
// reports the event as it happens: a small temporary file lives about a
// millisecond, too short to be seen reliably by listing the directory.
class AtFileEvent final : public KillPoint {
 public:
  AtFileEvent(const std::vector<std::filesystem::path>& dirs, std::uint32_t event,
              std::string prefix)
      : fd_(inotify_init1(IN_NONBLOCK | IN_CLOEXEC)), event_(event), prefix_(std::move(prefix)) {
    if (fd_ < 0) throw std::system_error(errno, std::generic_category(), "inotify_init1");
    for (const auto& dir : dirs) Watch(dir);
  }
  ~AtFileEvent() override { close(fd_); }
  AtFileEvent(const AtFileEvent&) = delete;
  AtFileEvent& operator=(const AtFileEvent&) = delete;

  bool Due() override {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, 1) <= 0) return false;
    alignas(inotify_event) char buffer[16384];
    const ssize_t n = read(fd_, buffer, sizeof buffer);
    bool due = false;
    for (ssize_t at = 0; at < n;) {
      const auto* e = reinterpret_cast<const inotify_event*>(buffer + at);
      const std::string_view name = e->len > 0 ? std::string_view(e->name) : std::string_view();
      if ((e->mask & IN_ISDIR) && (e->mask & IN_CREATE)) {
        Watch(dirs_[e->wd] / name);
      } else if ((e->mask & event_) && name.starts_with(prefix_)) {
        due = true;
      }
      at += static_cast<ssize_t>(sizeof(inotify_event) + e->len);
    }
    return due;
  }

 private:
  void Watch(const std::filesystem::path& dir) {
    const int wd = inotify_add_watch(fd_, dir.c_str(), IN_CREATE | IN_MOVED_TO);
    if (wd < 0)
      throw std::system_error(errno, std::generic_category(), "inotify_add_watch " + dir.string());
    dirs_[wd] = dir;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      if (e.is_directory()) Watch(e.path());
    }
  }
  int fd_;
  std::uint32_t event_;
  std::string prefix_;
  std::map<int, std::filesystem::path> dirs_;  // by watch descriptor
};

// Whether a temporary file of `name` is in `dir` (data::TemporaryPathFor
// names them <name>.tmp.<pid>.<n>); with `pid`, one of that process: when it
// was killed, the kill came while it wrote that file.
inline bool HasTemporaryFile(const std::filesystem::path& dir, std::string_view name,
                             std::optional<pid_t> pid = std::nullopt) {
  const std::string prefix = std::string(name) + ".tmp." + (pid ? std::to_string(*pid) + "." : "");
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    if (e.path().filename().string().starts_with(prefix)) return true;
  }
  return false;
}

// A command killed at a sequence of points and started again after each kill.
struct KillSchedule {
  // The argv of the next start (it may depend on what the last one left).
  std::function<std::vector<std::string>()> command;
  std::filesystem::path log;  // stdout and stderr of the latest start
  // The point of kill number k (from 0), made just before the start it is
  // meant for; null: no more kills, the command is left to complete.
  std::function<std::unique_ptr<KillPoint>(int k)> point;
  // Called after kill number k of process `pid`, to check what it left.
  std::function<void(int k, pid_t pid)> after_kill;
  // The command completed before its kill point came: clear its output, so
  // that the kills left still land in a run.
  std::function<void()> start_over;
  int max_starts = 80;
};

struct KillOutcome {
  int kills = 0;
  int starts = 0;
  int started_over = 0;
  int status = -1;  // of the start that completed (-1: none within max_starts)
};

// Starts the command until it completes with no kill left. A point that came
// due as the process exited on its own (too late to kill it) counts as the
// completion, not as a kill.
inline KillOutcome RunWithKills(const KillSchedule& s) {
  KillOutcome out;
  while (out.starts < s.max_starts) {
    std::unique_ptr<KillPoint> point = s.point(out.kills);
    Process p(s.command(), s.log);
    ++out.starts;
    if (!point) {
      out.status = p.Wait();
      return out;
    }
    bool due = false;
    std::optional<int> status;
    // Due() waits up to a millisecond: the process is polled at about 1 kHz.
    while (!(status = p.Poll()) && !(due = point->Due())) {
    }
    if (due) {
      p.Signal(SIGKILL);
      status = p.Wait();
    }
    if (*status == -SIGKILL) {
      s.after_kill(out.kills++, p.pid());
    } else if (due && *status == 0) {
      out.status = 0;
      return out;
    } else if (*status == 0) {
      s.start_over();
      ++out.started_over;
    } else {
      out.status = *status;  // failed on its own
      return out;
    }
  }
  return out;
}

}  // namespace kelvin::testing
