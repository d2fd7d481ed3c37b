// Inter-process test over udpm:// on loopback with TTL 0: `kelvin bridge`
// runs as a child process; this test process (the project's Listener) and
// Debian's lcm-logger (a third process, its log decoded back) must receive
// every state and event message, in order. Skips with a clear message when
// the machine has no multicast route (add one with
// `ip route add 224.0.0.0/4 dev lo`).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bridge/listener.h"
#include "simulator/maneuvers/runner.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/bridge/udpm_loopback.h"
#include "tests/test_utilities/test_utilities.h"

extern char** environ;

namespace kelvin::bridge {
namespace {

// A child process started with posix_spawn; killed (SIGKILL) if still running
// when destroyed, so no test leaves a process behind.
class Child {
 public:
  // stdout and stderr go to `output` if given.
  explicit Child(const std::vector<std::string>& argv, const std::string& output = "") {
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (!output.empty()) {
      posix_spawn_file_actions_addopen(&actions, 1, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      posix_spawn_file_actions_adddup2(&actions, 1, 2);
    }
    if (posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Child() {
    if (pid_ > 0 && !exited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  bool started() const { return pid_ > 0; }
  // Exit code if the child has exited, -1 while it runs.
  bool Poll(int* exit_code) {
    if (exited_) {
      *exit_code = code_;
      return true;
    }
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      exited_ = true;
      code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      *exit_code = code_;
      return true;
    }
    return false;
  }
  int Wait() {
    int code = -1;
    while (!Poll(&code)) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return code;
  }
  void Signal(int sig) {
    if (!exited_) ::kill(pid_, sig);
  }

 private:
  pid_t pid_ = -1;
  bool exited_ = false;
  int code_ = -1;
};

std::string ReadFile(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(BridgeUdpm, SecondProcessAndLcmLoggerReceiveEveryMessageInOrder) {
  if (const std::string why = testing::MulticastProblem(); !why.empty()) GTEST_SKIP() << why;
  const std::string url = testing::UniqueUdpmUrl();
  lcm::LCM lcm(url);
  if (!lcm.good()) GTEST_SKIP() << "LCM cannot open " << url << " (multicast unavailable on loopback)";
  const bool have_logger = testing::HaveProgram("lcm-logger");
  const testing::ScopedTempDir dir;
  const std::string log_path = (dir / "bridge.lcm").string();

  // The logger first; its log gets a probe message once it is listening.
  std::unique_ptr<Child> logger;
  if (have_logger) {
    const std::string exe = testing::RunCommand("command -v lcm-logger").output;
    logger = std::make_unique<Child>(std::vector<std::string>{
        exe.substr(0, exe.find('\n')), "--lcm-url=" + url, "--channel=KELVIN_IPC_.*", "--flush-interval=20", "-f",
        log_path});
    ASSERT_TRUE(logger->started());
    bool ready = false;
    for (int i = 0; i < 100 && !ready; ++i) {
      const char probe[] = "probe";
      lcm.publish("KELVIN_IPC_PROBE", probe, sizeof(probe));
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      std::error_code ec;
      ready = std::filesystem::file_size(log_path, ec) > 0 && !ec;
    }
    ASSERT_TRUE(ready) << "lcm-logger did not start logging " << url;
  }

  // The project's listener program, as a third process: started first, the
  // bridge only once it has subscribed; it stops 1 s after the last message.
  const std::string listen_log = (dir / "listen.log").string(), listen_csv = (dir / "listen.csv").string();
  Child listen({(testing::ToolsDir() / "kelvin").string(), "listen", "--lcm-url", url, "--channel-prefix",
                "KELVIN_IPC", "--idle-timeout", "1", "--timeout", "120", "-o", listen_csv},
               listen_log);
  ASSERT_TRUE(listen.started());
  for (int i = 0; i < 200 && ReadFile(listen_log).find("listen: subscribed") == std::string::npos; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  ASSERT_NE(ReadFile(listen_log).find("listen: subscribed to KELVIN_IPC_STATE"), std::string::npos)
      << ReadFile(listen_log);

  Listener listener(lcm, "KELVIN_IPC");
  Child bridge({(testing::ToolsDir() / "kelvin").string(), "-q", "bridge",
                (testing::SourceDir() / "data/ships/kvlcc2.yaml").string(), "--lcm-url", url, "--channel-prefix",
                "KELVIN_IPC", "--script", "zigzag:20/20:stbd", "--rate", "20", "--speedup", "25"});
  ASSERT_TRUE(bridge.started());
  int code = -1;
  const auto t_start = std::chrono::steady_clock::now();
  while (!bridge.Poll(&code)) {
    lcm.handleTimeout(20);
    ASSERT_LT(std::chrono::steady_clock::now() - t_start, std::chrono::seconds(60)) << "bridge did not finish";
  }
  ASSERT_EQ(code, 0);
  // What is still in flight.
  for (int i = 0; i < 25; ++i) lcm.handleTimeout(20);

  // The reference: the same zig-zag in fast time with the same fixed step.
  const sim::ShipParameters ship = sim::LoadShip(testing::SourceDir() / "data/ships/kvlcc2.yaml");
  const sim::MmgModel<double> model(ship);
  sim::RunOptions ro;
  ro.integrator.method = sim::SimulatorOptions::Method::kFixedStep;
  ro.integrator.fixed_step = 0.025;
  ro.output_interval = 0.05;
  const auto ref = sim::RunManeuver(model, sim::ManeuverSpec::Parse("zigzag:20/20:stbd"), ro);

  EXPECT_EQ(listener.malformed(), 0);
  EXPECT_EQ(listener.out_of_sequence(), 0);
  ASSERT_EQ(listener.states().size(), ref.trajectory.size());
  for (std::size_t i = 0; i < ref.trajectory.size(); ++i) {
    ASSERT_EQ(listener.states()[i].seq, static_cast<std::int64_t>(i));
    ASSERT_NEAR(listener.states()[i].x, ref.trajectory[i].x, 1e-9);
    ASSERT_NEAR(listener.states()[i].y, ref.trajectory[i].y, 1e-9);
  }
  ASSERT_EQ(listener.events().size(), 9u);  // START, 4 EXECUTE, 3 OVERSHOOT, STOP
  EXPECT_EQ(listener.events().front().kind, kelvin::maneuver_event_t::START);
  EXPECT_EQ(listener.events().back().kind, kelvin::maneuver_event_t::STOP);

  // kelvin listen got the same states (CSV with 17 significant digits).
  ASSERT_EQ(listen.Wait(), 0) << ReadFile(listen_log);
  EXPECT_NE(ReadFile(listen_log).find("listen: 2130 states (seq 0..2129, t 0.000..106.450 s), 9 events, 0 out of "
                                      "sequence, 0 malformed"),
            std::string::npos)
      << ReadFile(listen_log);
  std::istringstream csv(ReadFile(listen_csv));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.substr(0, 10), "seq,t,x,y,");
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    long seq = -1;
    double t = 0, x = 0, y = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%ld,%lf,%lf,%lf", &seq, &t, &x, &y), 4) << line;
    ASSERT_LT(rows, listener.states().size());
    EXPECT_EQ(seq, static_cast<long>(rows));
    EXPECT_EQ(x, listener.states()[rows].x);
    EXPECT_EQ(y, listener.states()[rows].y);
    ++rows;
  }
  EXPECT_EQ(rows, 2130u);

  if (!have_logger) GTEST_SKIP() << "lcm-logger not installed (Debian package lcm): the log half is not checked";
  logger->Signal(SIGINT);
  EXPECT_EQ(logger->Wait(), 0);
  lcm::LogFile log(log_path, "r");
  ASSERT_TRUE(log.good());
  std::vector<kelvin::ship_state_t> states;
  std::vector<kelvin::maneuver_event_t> events;
  long undecodable = 0;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    if (e->channel == "KELVIN_IPC_STATE") {
      kelvin::ship_state_t m;
      if (m.decode(e->data, 0, e->datalen) != e->datalen) ++undecodable;
      states.push_back(m);
    } else if (e->channel == "KELVIN_IPC_EVENT") {
      kelvin::maneuver_event_t m;
      if (m.decode(e->data, 0, e->datalen) != e->datalen) ++undecodable;
      events.push_back(m);
    }
  }
  EXPECT_EQ(undecodable, 0);
  ASSERT_EQ(states.size(), listener.states().size());
  ASSERT_EQ(events.size(), listener.events().size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    ASSERT_EQ(states[i].seq, static_cast<std::int64_t>(i));
    ASSERT_EQ(states[i].utime, listener.states()[i].utime);
    ASSERT_EQ(states[i].x, listener.states()[i].x);
    ASSERT_EQ(states[i].heading, listener.states()[i].heading);
  }
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].seq, static_cast<std::int64_t>(i));
    EXPECT_EQ(events[i].kind, listener.events()[i].kind);
    EXPECT_EQ(events[i].t, listener.events()[i].t);
  }
}

}  // namespace
}  // namespace kelvin::bridge
