// `kelvin captive` killed (issue #24's fault injection, on the coarse CFD
// campaign of the 2D block: 5 runs, checkpoints every 10 steps, the drift
// runs settling at steps 46, 43 and 43 of 50, 372 steps and about 2 s
// uninterrupted): SIGKILL at 14 points (random times from a fixed
// seed; the moment a checkpoint's, a run's samples' or result's temporary
// file appears, i.e. during its write; during the write of the campaign file
// and the moment it appears under its name), the same command started again
// after each kill:
// - after every kill each file under its final name is whole: it opens with
//   the HDF5 reader and holds what it should (the campaign file every run with
//   its extra channels, a run's samples one row per step up to its step, a
//   checkpoint the solver state);
// - the rerun completes, and every run's result.h5 and the campaign file hold
//   the same datasets and attributes, bit for bit, as those of an
//   uninterrupted campaign; the one exception is result.h5's cpu_seconds, the
//   process CPU time of the run's steps. (The files are not the same bytes:
//   HDF5 stamps each object header with the time it was written.)
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "data/schema/captive_io.h"
#include "data/schema/h5_file.h"
#include "tests/identification/block2d_campaign.h"
#include "tests/test_utilities/fault_injection.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::ident {
namespace {

namespace fs = std::filesystem;
namespace kt = kelvin::testing;

constexpr const char* kCampaignFile = "block2d_cfd.h5";  // campaign.name + ".h5"
constexpr int kRuns = 5;
// A criterion the drift runs meet before their end, so that kills land
// before and after it settles.
constexpr const char* kSettle = "  settle: {tolerance: 0.02, window: 1.0}\n";
// The files of a run directory, each written to a temporary file and renamed.
constexpr std::array<std::string_view, 4> kRunFiles = {"checkpoint.h5", "samples.h5", "result.h5",
                                                       "progress.txt"};
// The channels of a run's samples; those from X_pressure on are the extra
// channels of the campaign file.
constexpr std::array<std::string_view, 13> kCaptiveChannels = {
    "time",      "X",         "Y",         "N",       "X_pressure", "Y_pressure", "N_pressure",
    "X_viscous", "Y_viscous", "N_viscous", "X_prime", "Y_prime",    "N_prime"};
constexpr std::size_t kFirstExtraChannel = 4;

// --- everything an HDF5 file holds ---------------------------------------------

// A dataset (values, and its shape as text) or an attribute (number or text).
struct Entry {
  std::vector<double> numbers;
  std::string text;
  bool operator==(const Entry&) const = default;
};
using Contents = std::map<std::string, Entry>;  // "<object>" or "<object>@<attribute>"

std::vector<std::string> AttributeNames(hid_t file, const std::string& object) {
  std::vector<std::string> names;
  const data::H5Handle obj(H5Oopen(file, object.c_str(), H5P_DEFAULT));
  hsize_t at = 0;
  H5Aiterate2(
      obj.get(), H5_INDEX_NAME, H5_ITER_INC, &at,
      [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
        static_cast<std::vector<std::string>*>(out)->push_back(name);
        return 0;
      },
      &names);
  return names;
}

bool IsStringAttribute(hid_t file, const std::string& object, const std::string& name) {
  const data::H5Handle attr(
      H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT));
  const data::H5Handle type(H5Aget_type(attr.get()));
  return H5Tget_class(type.get()) == H5T_STRING;
}

bool IsGroup(hid_t file, const std::string& object) {
  const data::H5Handle obj(H5Oopen(file, object.c_str(), H5P_DEFAULT));
  return H5Iget_type(obj.get()) == H5I_GROUP;
}

void Walk(hid_t file, const data::H5Reader& r, const std::string& object, Contents& out) {
  for (const std::string& a : AttributeNames(file, object)) {
    out[object + "@" + a] = IsStringAttribute(file, object, a)
                                ? Entry{{}, r.StringAttribute(object, a)}
                                : Entry{{r.NumberAttribute(object, a)}, ""};
  }
  if (!IsGroup(file, object)) {
    const data::Series s = r.Read(object);
    out[object] = {s.values, std::to_string(s.rows) + " x " + std::to_string(s.cols)};
    return;
  }
  for (const std::string& child : r.List(object))
    Walk(file, r, (object == "/" ? "/" : object + "/") + child, out);
}

// Every group, dataset and attribute of an HDF5 file, read through the
// project's reader (the raw library only lists attributes and object types).
Contents ReadContents(const fs::path& path) {
  const data::H5Reader r(path);
  const data::H5Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  Contents out;
  Walk(file.get(), r, "/", out);
  return out;
}

// Whether two files hold the same, but for the entries in `skip`.
void ExpectSameContents(const fs::path& expected, const fs::path& actual,
                        const std::set<std::string>& skip = {}) {
  Contents a = ReadContents(expected), b = ReadContents(actual);
  for (const std::string& key : skip) {
    EXPECT_EQ(a.erase(key) + b.erase(key), 2u) << key << " is not in both " << actual;
  }
  std::set<std::string> keys;
  for (const auto& [key, entry] : a) keys.insert(key);
  for (const auto& [key, entry] : b) keys.insert(key);
  for (const std::string& key : keys) {
    EXPECT_TRUE(a.contains(key) && b.contains(key) && a[key] == b[key])
        << actual << ": " << key << " differs from the uninterrupted campaign's";
  }
  std::printf("  %s: %zu entries compared\n", actual.filename().c_str(), keys.size());
}

// --- what a kill may leave ---------------------------------------------------

// A run's samples or result: one row per step up to its step attribute.
void ExpectWholeSamples(const fs::path& path) {
  const data::H5Reader r(path);
  const auto step = static_cast<std::size_t>(r.NumberAttribute("/", "step"));
  EXPECT_GT(r.NumberAttribute("/", "cells"), 0.0) << path;
  for (std::string_view c : kCaptiveChannels) {
    EXPECT_EQ(r.Read("captive/" + std::string(c)).rows, step) << path << " captive/" << c;
  }
}

void ExpectWholeCheckpoint(const fs::path& path) {
  const data::H5Reader r(path);
  EXPECT_EQ(r.Read("U").rows, static_cast<std::size_t>(r.NumberAttribute("/", "n_cells"))) << path;
  EXPECT_EQ(r.Read("p").rows, static_cast<std::size_t>(r.NumberAttribute("/", "n_cells"))) << path;
  EXPECT_EQ(r.Read("phi").rows, static_cast<std::size_t>(r.NumberAttribute("/", "n_faces")))
      << path;
  EXPECT_GT(r.NumberAttribute("/", "step"), 0.0) << path;
}

// The campaign file: the captive schema (ReadCampaignH5 validates it), every
// run, and beside X, Y, N the extra channels the CFD campaign adds.
void ExpectWholeCampaign(const fs::path& path) {
  const data::CaptiveCampaign c = data::ReadCampaignH5(path);
  ASSERT_EQ(c.runs.size(), static_cast<std::size_t>(kRuns)) << path;
  const data::H5Reader r(path);
  EXPECT_TRUE(r.HasAttribute("/", "solver") && r.StringAttribute("/", "solver") == "cfd") << path;
  std::string missing;
  for (const data::CaptiveRun& run : c.runs) {
    for (std::size_t k = kFirstExtraChannel; k < kCaptiveChannels.size(); ++k) {
      const std::string ds = "runs/" + run.name + "/" + std::string(kCaptiveChannels[k]);
      if (!r.Has(ds) || r.Read(ds).rows != run.time.size()) missing += " " + ds;
    }
  }
  EXPECT_EQ(missing, "") << path << ": extra channels missing or short";
}

void ExpectWholeProgress(const fs::path& path) {
  std::ifstream in(path);
  int step = -1, steps = -1;
  double seconds = -1;
  EXPECT_TRUE((in >> step >> steps >> seconds) && step >= 0 && step <= steps && seconds >= 0)
      << path;
}

// Checks every file under its final name in the campaign's `runs` directory.
void ExpectWholeFiles(const fs::path& runs) {
  if (fs::exists(runs / kCampaignFile)) ExpectWholeCampaign(runs / kCampaignFile);
  for (const auto& e : fs::directory_iterator(runs)) {
    if (!e.is_directory()) continue;
    const fs::path d = e.path();
    if (fs::exists(d / "checkpoint.h5")) ExpectWholeCheckpoint(d / "checkpoint.h5");
    if (fs::exists(d / "samples.h5")) ExpectWholeSamples(d / "samples.h5");
    if (fs::exists(d / "result.h5")) ExpectWholeSamples(d / "result.h5");
    if (fs::exists(d / "progress.txt")) ExpectWholeProgress(d / "progress.txt");
  }
}

// The file process `pid` was writing when it was killed ("" if none).
std::string FileBeingWritten(const fs::path& runs, pid_t pid) {
  if (kt::HasTemporaryFile(runs, kCampaignFile, pid)) return kCampaignFile;
  for (const auto& e : fs::directory_iterator(runs)) {
    if (!e.is_directory()) continue;
    for (std::string_view name : kRunFiles) {
      if (kt::HasTemporaryFile(e.path(), name, pid)) return std::string(name);
    }
  }
  return "";
}

// Temporary files under `dir`: those of the writes a kill cut short stay.
int CountTemporaryFiles(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    n += e.path().filename().string().find(".tmp.") != std::string::npos;
  }
  return n;
}

// --- the test ------------------------------------------------------------------

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::vector<std::string> RunNames(const fs::path& runs) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(runs)) {
    if (e.is_directory()) names.push_back(e.path().filename().string());
  }
  return names;
}

// Kill k of the schedule: a random time for one in two (from the start of
// the process: its case and mesh loads and its steps), the creation of a
// checkpoint's, a run's samples' or result's temporary file (a kill during
// its write) for the others; then the campaign file's temporary file and its
// appearance under its name, when every run is done. Null: no more kills.
std::unique_ptr<kt::KillPoint> KillPointOf(int k, const fs::path& runs, std::mt19937& rng) {
  constexpr int kDuringRuns = 12;
  if (k < kDuringRuns && k % 2 == 0)
    return std::make_unique<kt::AfterSeconds>(std::uniform_real_distribution(0.05, 0.3)(rng));
  if (k < kDuringRuns) {
    const char* prefixes[] = {"checkpoint.h5.tmp.", "samples.h5.tmp.", "result.h5.tmp."};
    return std::make_unique<kt::AtFileEvent>(std::vector{runs}, IN_CREATE, prefixes[(k / 2) % 3]);
  }
  if (k == kDuringRuns)
    return std::make_unique<kt::AtFileEvent>(std::vector{runs}, IN_CREATE,
                                             std::string(kCampaignFile) + ".tmp.");
  if (k == kDuringRuns + 1)
    return std::make_unique<kt::AtFileEvent>(std::vector{runs}, IN_MOVED_TO, kCampaignFile);
  return nullptr;
}

TEST(CaptiveFaultInjection, AKilledCampaignCompletesWithTheResultsOfAnUninterruptedOne) {
  kt::ScopedTempDir tmp;
  const std::string kelvin = (kt::ToolsDir() / "kelvin").string();
  auto command = [&](const fs::path& campaign) {
    return std::vector<std::string>{kelvin, "captive", campaign.string(), "--no-progress"};
  };

  const fs::path whole = kt::WriteBlock2dCampaign(tmp / "whole", "", kSettle);
  auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(kt::Process(command(whole), tmp / "whole.log").Wait(), 0)
      << kt::ReadText(tmp / "whole.log");
  const double whole_seconds = Seconds(start);

  const fs::path campaign = kt::WriteBlock2dCampaign(tmp / "killed", "", kSettle);
  const fs::path runs = tmp / "killed/runs";
  fs::create_directories(runs);  // for the watches of the first kill points
  std::mt19937 rng(20261202);
  std::map<std::string, int> during_write;  // kills that came while a file was written, by file
  kt::KillSchedule schedule;
  schedule.command = [&] { return command(campaign); };
  schedule.log = tmp / "killed.log";
  schedule.point = [&](int k) { return KillPointOf(k, runs, rng); };
  schedule.after_kill = [&](int k, pid_t pid) {
    SCOPED_TRACE("after kill " + std::to_string(k + 1));
    ++during_write[FileBeingWritten(runs, pid)];
    EXPECT_NO_THROW(ExpectWholeFiles(runs));  // a file that does not open throws
  };
  schedule.start_over = [&] {
    fs::remove_all(runs);
    fs::create_directories(runs);
  };
  start = std::chrono::steady_clock::now();
  const kt::KillOutcome outcome = kt::RunWithKills(schedule);
  const double killed_seconds = Seconds(start);

  std::printf("uninterrupted campaign: %.2f s\n", whole_seconds);
  std::printf("killed: %d SIGKILLs in %d starts (%d started over), %.2f s\n", outcome.kills,
              outcome.starts, outcome.started_over, killed_seconds);
  int writes = 0;
  for (const auto& [file, n] : during_write) {
    std::printf("  %d during the write of %s\n", n, file.empty() ? "no file" : file.c_str());
    if (!file.empty()) writes += n;
  }
  std::printf("  %d temporary files left behind\n", CountTemporaryFiles(runs));
  ASSERT_EQ(outcome.status, 0) << kt::ReadText(tmp / "killed.log");
  // Each restart removed what the kill before it left half-written.
  EXPECT_EQ(CountTemporaryFiles(runs), 0);
  EXPECT_GE(outcome.kills, 13);
  EXPECT_GE(writes, 4) << "too few kills came during a write";

  const std::vector<std::string> names = RunNames(tmp / "whole/runs");
  ASSERT_EQ(names.size(), static_cast<std::size_t>(kRuns));
  for (const std::string& run : names) {
    ExpectSameContents(tmp / "whole/runs" / run / "result.h5", runs / run / "result.h5",
                       {"/@cpu_seconds"});
  }
  ExpectSameContents(tmp / "whole/runs" / kCampaignFile, runs / kCampaignFile);
}

}  // namespace
}  // namespace kelvin::ident
