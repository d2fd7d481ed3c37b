// `kelvin run` killed and stopped (issue #24's fault injection, on a
// free-running case: the Wigley surge decay of data/cases/free_running/ on
// the quickstart grid, checkpoints every 5 steps, 160 steps):
// - SIGKILL at 12 points (random times from a fixed seed, and every third
//   kill the moment a checkpoint's temporary file appears, i.e. during its
//   write), each followed by a restart from the checkpoint left behind: the
//   last run's final checkpoint is bit-identical to that of an uninterrupted
//   run, and after every kill the files under their final names are whole
//   (they open and hold the solver state);
// - SIGTERM stops the run after the step in progress with a checkpoint and
//   exit status 128 + 15, and the restart from it ends on the same state;
// - a full disk (a 1.8 MB tmpfs: room for one checkpoint, not for its
//   successor beside it) stops the run with one error that names the file,
//   the cause and the checkpoint kept, which still opens at its step;
// - on 2 MPI ranks (the lid-driven cavity), SIGTERM stops every rank after
//   the same step and the restart ends bit for bit on the uninterrupted state.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "data/schema/h5_file.h"
#include "tests/test_utilities/fault_injection.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using kelvin::testing::AfterSeconds;
using kelvin::testing::AtFileEvent;
using kelvin::testing::KillPoint;
using kelvin::testing::Process;

// The solver state of a checkpoint: every array and the step.
std::vector<std::vector<double>> State(const fs::path& checkpoint) {
  const data::H5Reader r(checkpoint);
  std::vector<std::vector<double>> s = {r.Read("U").values, r.Read("p").values, r.Read("phi").values,
                                        {r.NumberAttribute("/", "step"), r.NumberAttribute("/", "time")}};
  for (const char* scalar : {"run_free_body_2", "run_free_body_8", "run_free_body_14"}) {
    if (r.HasAttribute("/", scalar)) s.push_back({r.NumberAttribute("/", scalar)});  // a free body's pose
  }
  return s;
}

class FaultInjection : public ::testing::Test {
 protected:
  void SetUp() override {
    const fs::path src = kelvin::testing::SourceDir() / "data";
    kelvin_ = (kelvin::testing::ToolsDir() / "kelvin").string();
    const auto r = kelvin::testing::RunCommand(kelvin_ + " mesh " +
                                               (src / "cases/captive_cfd/wigley_quick_mesh.yaml").string() + " -o " +
                                               (tmp_ / "grid").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::string text = kelvin::testing::ReadText(src / "cases/free_running/wigley_surge_decay.yaml");
    auto replace = [&](const std::string& from, const std::string& to) {
      const auto at = text.find(from);
      ASSERT_NE(at, std::string::npos) << from;
      text.replace(at, from.size(), to);
    };
    replace("ship: ../../ships/wigley.yaml", "ship: " + (src / "ships/wigley.yaml").string());
    replace("../../../build/grids/wigley_captive_quick/constant/polyMesh", (tmp_ / "grid/constant/polyMesh").string());
    replace("checkpoint_interval: 50", "checkpoint_interval: 5");
    case_ = tmp_ / "case.yaml";
    std::ofstream(case_) << text;
  }
  std::vector<std::string> Args(const fs::path& out, bool restart) const {
    std::vector<std::string> a = {kelvin_, "run", case_.string(), "--no-progress", "-o", out.string()};
    if (restart) {
      a.push_back("--restart");
      a.push_back((out / "checkpoint.h5").string());
    }
    return a;
  }

  kelvin::testing::ScopedTempDir tmp_;
  std::string kelvin_;
  fs::path case_;
};

TEST_F(FaultInjection, KilledRunsRestartToTheStateOfAnUninterruptedRun) {
  const fs::path whole = tmp_ / "whole";
  ASSERT_EQ(Process(Args(whole, false), tmp_ / "whole.log").Wait(), 0);
  const auto reference = State(whole / "checkpoint.h5");

  const fs::path out = tmp_ / "killed";
  fs::create_directories(out);
  std::mt19937 rng(20261201);
  std::uniform_real_distribution<double> delay(0.3, 1.5);
  int during_write = 0;
  kelvin::testing::KillSchedule schedule;
  schedule.command = [&] { return Args(out, fs::exists(out / "checkpoint.h5")); };
  schedule.log = tmp_ / "killed.log";
  schedule.point = [&](int k) -> std::unique_ptr<KillPoint> {
    if (k >= 12) return nullptr;
    if (k % 3 == 2) return std::make_unique<AtFileEvent>(std::vector{out}, IN_CREATE, "checkpoint.h5.tmp.");
    return std::make_unique<AfterSeconds>(delay(rng));
  };
  schedule.after_kill = [&](int k, pid_t pid) {
    if (kelvin::testing::HasTemporaryFile(out, "checkpoint.h5", pid)) ++during_write;
    // Whatever carries a final name is whole.
    if (fs::exists(out / "checkpoint.h5")) {
      EXPECT_NO_THROW(State(out / "checkpoint.h5")) << "after kill " << k + 1;
    }
    if (fs::exists(out / "history.h5")) {
      EXPECT_NO_THROW(data::H5Reader(out / "history.h5").Read("time")) << "after kill " << k + 1;
    }
  };
  // Finished before all the kills (a write too quick to catch): start over.
  schedule.start_over = [&] {
    fs::remove_all(out);
    fs::create_directories(out);
  };
  const kelvin::testing::KillOutcome outcome = kelvin::testing::RunWithKills(schedule);
  const int kills = outcome.kills, status = outcome.status;
  std::printf("fault injection: %d SIGKILLs (%d during a checkpoint write), then the run completed with status %d\n",
              kills, during_write, status);
  ASSERT_EQ(status, 0) << kelvin::testing::ReadText(tmp_ / "killed.log");
  EXPECT_GE(kills, 12);
  EXPECT_GE(during_write, 3);
  // Each restart removed the temporaries the kill before it left.
  for (const char* name : {"checkpoint.h5", "history.h5"}) {
    EXPECT_FALSE(kelvin::testing::HasTemporaryFile(out, name)) << "a temporary " << name << " was left";
  }
  const auto final_state = State(out / "checkpoint.h5");
  ASSERT_EQ(final_state.size(), reference.size());
  for (std::size_t k = 0; k < reference.size(); ++k) {
    EXPECT_EQ(final_state[k], reference[k]) << "array " << k << " differs from the uninterrupted run";
  }
}

TEST_F(FaultInjection, SigtermStopsWithACheckpointAndTheRestartEndsOnTheSameState) {
  const fs::path whole = tmp_ / "whole";
  ASSERT_EQ(Process(Args(whole, false), tmp_ / "whole.log").Wait(), 0);
  const fs::path out = tmp_ / "term";
  Process p(Args(out, false), tmp_ / "term.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  p.Signal(SIGTERM);
  const int status = p.Wait();
  const std::string log = kelvin::testing::ReadText(tmp_ / "term.log");
  ASSERT_EQ(status, 128 + SIGTERM) << log;
  EXPECT_NE(log.find("interrupted by signal 15"), std::string::npos) << log;
  EXPECT_NE(log.find("--restart"), std::string::npos) << log;
  const auto stopped = State(out / "checkpoint.h5");
  EXPECT_LT(stopped[3][0], 160.0);  // stopped before the end
  ASSERT_EQ(Process(Args(out, true), tmp_ / "rest.log").Wait(), 0) << kelvin::testing::ReadText(tmp_ / "rest.log");
  EXPECT_EQ(State(out / "checkpoint.h5"), State(whole / "checkpoint.h5"));
}

TEST_F(FaultInjection, AFullDiskIsOneClearErrorAndKeepsTheLastCheckpoint) {
  const fs::path disk = tmp_ / "disk";
  fs::create_directories(disk);
  if (kelvin::testing::RunCommand("mount -t tmpfs -o size=1800k tmpfs " + disk.string()).exit_code != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here (needs root): the full-disk case is not exercised";
  }
  const fs::path out = disk / "out";
  const int status = Process(Args(out, false), tmp_ / "full.log").Wait();
  const std::string log = kelvin::testing::ReadText(tmp_ / "full.log");
  const auto kept = fs::exists(out / "checkpoint.h5") ? State(out / "checkpoint.h5") : decltype(State({})){};
  std::error_code ec;
  const bool leftovers = kelvin::testing::HasTemporaryFile(out, "checkpoint.h5");
  kelvin::testing::RunCommand("umount " + disk.string());
  EXPECT_EQ(status, 1) << log;
  EXPECT_NE(log.find("No space left on device"), std::string::npos) << log;
  EXPECT_NE(log.find("the checkpoint of step 5 is kept"), std::string::npos) << log;
  ASSERT_FALSE(kept.empty()) << "no checkpoint kept";
  EXPECT_EQ(kept[3][0], 5.0);
  EXPECT_FALSE(leftovers) << "a temporary file was left beside the checkpoint";
}

// On MPI ranks (`kelvin run --np 2`): the launcher forwards SIGTERM to each
// rank at its own moment; all stop after the same step with one checkpoint,
// and the restart on 2 ranks ends on the state of an uninterrupted 2-rank run,
// bit for bit.
TEST(FaultInjectionOnRanks, SigtermStopsEveryRankAfterTheSameStepAndTheRestartEndsOnTheSameState) {
  kelvin::testing::ScopedTempDir tmp;
  std::string text = kelvin::testing::ReadText(kelvin::testing::SourceDir() / "data/cases/cavity_re100.yaml");
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"  end: 5.0", "  end: 40.0"}, {"vtu_interval: 50", "vtu_interval: -1"},
           {"checkpoint_interval: 50", "checkpoint_interval: 20"}}) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  const fs::path case_file = tmp / "cavity.yaml";
  std::ofstream(case_file) << text;
  const std::string kelvin = (kelvin::testing::ToolsDir() / "kelvin").string();
  auto args = [&](const fs::path& out, bool restart) {
    std::vector<std::string> a = {kelvin, "run", "--np", "2", case_file.string(), "--no-progress", "-o", out.string()};
    if (restart) a.insert(a.end(), {"--restart", (out / "checkpoint.h5").string()});
    return a;
  };
  const fs::path whole = tmp / "whole";
  ASSERT_EQ(Process(args(whole, false), tmp / "whole.log").Wait(), 0) << kelvin::testing::ReadText(tmp / "whole.log");

  const fs::path out = tmp / "term";
  Process p(args(out, false), tmp / "term.log");
  // Stop once the run is under way: its first checkpoint (step 20) is there.
  for (int i = 0; i < 600 && !fs::exists(out / "checkpoint.h5"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  p.Signal(SIGTERM);
  const int status = p.Wait();
  const std::string log = kelvin::testing::ReadText(tmp / "term.log");
  EXPECT_NE(status, 0) << log;  // the launcher's status: Open MPI reports 1
  EXPECT_NE(log.find("interrupted by signal 15"), std::string::npos) << log;
  const auto stopped = State(out / "checkpoint.h5");
  std::printf("2 ranks stopped by SIGTERM after step %.0f of 800\n", stopped[3][0]);
  ASSERT_LT(stopped[3][0], 800.0) << "the run ended before the signal";
  ASSERT_EQ(Process(args(out, true), tmp / "rest.log").Wait(), 0) << kelvin::testing::ReadText(tmp / "rest.log");
  const auto a = State(out / "checkpoint.h5"), b = State(whole / "checkpoint.h5");
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(a[k], b[k]) << "array " << k << " differs from the uninterrupted run";
}

}  // namespace
}  // namespace kelvin::cfd
