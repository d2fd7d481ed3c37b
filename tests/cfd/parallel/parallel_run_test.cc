// `kelvin run` on MPI ranks (issue 23; run by ctest under mpiexec on 2 and 4
// ranks): a captive case of a 2D block on a yawing and swaying mesh (yaw with
// drift, ship-axis loads every step) is decomposed by the run layer; with the
// linear solvers' tolerances at 1e-12 its loads agree with the serial run's
// at every step, its checkpoint restarts on another number of ranks, its
// fields are gathered into one VTU of the whole mesh, and what cannot run on
// ranks is refused with one error.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "cfd/linalg/hypre_solver.h"
#include "cfd/run/run_case.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

int WorldRank() {
  EnsureMpi();
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

// A directory every rank sees: made by rank 0, its name broadcast.
class SharedTempDir {
 public:
  SharedTempDir() {
    std::string name;
    if (WorldRank() == 0) {
      std::random_device rd;
      name = (fs::temp_directory_path() / ("kelvin_ranks_" + std::to_string(rd()) + std::to_string(rd()))).string();
      fs::create_directories(name);
    }
    int n = static_cast<int>(name.size());
    MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD);
    name.resize(static_cast<std::size_t>(n));
    MPI_Bcast(name.data(), n, MPI_CHAR, 0, MPI_COMM_WORLD);
    path_ = name;
  }
  ~SharedTempDir() {
    MPI_Barrier(MPI_COMM_WORLD);
    std::error_code ec;
    if (WorldRank() == 0) fs::remove_all(path_, ec);
  }
  SharedTempDir(const SharedTempDir&) = delete;
  SharedTempDir& operator=(const SharedTempDir&) = delete;
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

// Yaw with drift of a block in a 20 x 12 box (232 cells): a moving mesh,
// far-field and inlet-outlet conditions, ship-axis loads every step.
const char* kCase = R"(mesh:
  box: {min: [-3, -1.5, 0], max: [2, 1.5, 1], cells: [20, 12, 1], empty: z, obstacle: {min: [10, 5, 0], max: [14, 7, 1]}}
physics: {nu: 0.05, rho: 1000}
schemes: {time: backward, gradient: least_squares}
solution:
  n_outer: 2
  momentum: {solver: bicgstab, relative_tolerance: 1.0e-12}
  pressure: {solver: pcg_amg, relative_tolerance: 1.0e-12}
motion: {kind: yaw_drift, speed: 1.0, drift_angle_deg: 5, yaw_amplitude_deg: 10, period: 2.0, ramp_time: 0.5,
         periods: 1, centre: [-0.5, 0, 0.5]}
reference: {speed: 1.0, direction: [-1, 0, 0], length: 1.0, draft: 1.0}
time: {dt: 0.05}
boundary:
  xmin: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  xmax: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  ymin: {U: {type: inletOutlet, inflow: [0, 0, 0]}, p: {type: outletInlet, value: 0}}
  ymax: {U: {type: inletOutlet, inflow: [0, 0, 0]}, p: {type: outletInlet, value: 0}}
  obstacle: {U: {type: movingWallVelocity}, p: {type: zeroGradient}}
output: {directory: out, vtu_interval: 0, checkpoint_interval: 20, forces: [obstacle], captive: true}
partition: {min_cells_per_rank: 20}
)";

// The case cut at t = 2 s (step 40 of 80): its last checkpoint is the restart point.
std::string FirstHalf(std::string text) {
  text.replace(text.find("periods: 1,"), 11, "");
  text.replace(text.find("time: {dt: 0.05}"), 16, "time: {dt: 0.05, end: 2.0}");
  return text;
}

fs::path Write(const fs::path& dir, const std::string& text) {
  if (WorldRank() == 0) {
    fs::create_directories(dir);
    std::ofstream(dir / "case.yaml") << text;
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return dir / "case.yaml";
}

RunSummary RunIn(const fs::path& case_file, MPI_Comm ranks, const fs::path& restart = {},
               const fs::path& output = {}) {
  RunOptions o;
  o.progress = false;
  o.ranks = ranks;
  o.restart = restart;
  o.output_override = output;
  return RunCase(case_file, o);
}

struct Loads {
  std::vector<double> X, Y, N;
};

Loads ReadLoads(const fs::path& history) {
  const data::H5Reader r(history);
  return {r.Read("captive/X").values, r.Read("captive/Y").values, r.Read("captive/N").values};
}

// Largest difference at any step of `b` against the last b.size() rows of
// `a`, relative to the largest |a| of the series.
double Mismatch(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_LE(b.size(), a.size());
  const std::size_t offset = a.size() - b.size();
  double scale = 0.0, diff = 0.0;
  for (double v : a) scale = std::max(scale, std::abs(v));
  for (std::size_t i = 0; i < b.size(); ++i) diff = std::max(diff, std::abs(a[offset + i] - b[i]));
  return diff / scale;
}

double Mismatch(const Loads& a, const Loads& b) {
  return std::max({Mismatch(a.X, b.X), Mismatch(a.Y, b.Y), Mismatch(a.N, b.N)});
}

int WorldSize() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

// The serial reference: every rank runs it in a directory of its own.
Loads SerialLoads(const std::string& text) {
  kelvin::testing::ScopedTempDir own;
  const fs::path case_file = testing::WriteCase(own.path(), text);
  const RunSummary s = RunIn(case_file, MPI_COMM_NULL);
  EXPECT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  return ReadLoads(own / "out/history.h5");
}

TEST(RunOnRanks, ShipLoadsMatchTheSerialRunAtEveryStep) {
  const Loads serial = SerialLoads(kCase);
  ASSERT_EQ(serial.Y.size(), 80u);
  SharedTempDir dir;
  const RunSummary s = RunIn(Write(dir / "ranks", kCase), MPI_COMM_WORLD);
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  EXPECT_EQ(s.steps, 80);
  const Loads ranks = ReadLoads(dir / "ranks/out/history.h5");
  ASSERT_EQ(ranks.Y.size(), 80u);
  const double mismatch = Mismatch(serial, ranks);
  if (WorldRank() == 0) {
    std::printf("%d ranks: yaw-with-drift X, Y, N over 80 steps, max difference %.2e of the largest load\n",
                WorldSize(), mismatch);
  }
  EXPECT_LT(mismatch, 1e-8);
  // One VTU of the whole mesh (232 cells), written once.
  if (WorldRank() == 0) {
    std::ifstream vtu(dir / "ranks/out/fields_000080.vtu");
    std::stringstream text;
    text << vtu.rdbuf();
    EXPECT_THAT(text.str(), HasSubstr("NumberOfCells=\"232\""));
  }
}

TEST(RunOnRanks, CheckpointRestartsOnAnotherNumberOfRanks) {
  const Loads serial = SerialLoads(kCase);
  SharedTempDir dir;
  // First half on the ranks, second half serially (each rank reads the same file).
  ASSERT_EQ(RunIn(Write(dir / "half_ranks", FirstHalf(kCase)), MPI_COMM_WORLD).status, RunSummary::Status::kCompleted);
  {
    kelvin::testing::ScopedTempDir own;
    const RunSummary s =
        RunIn(testing::WriteCase(own.path(), kCase), MPI_COMM_NULL, dir / "half_ranks/out/checkpoint.h5");
    ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
    EXPECT_EQ(s.steps, 40);
    const double mismatch = Mismatch(serial, ReadLoads(own / "out/history.h5"));
    if (WorldRank() == 0) std::printf("%d ranks then serial: max difference %.2e\n", WorldSize(), mismatch);
    EXPECT_LT(mismatch, 1e-8);
  }
  // First half serially (rank 0), second half on the ranks.
  MPI_Barrier(MPI_COMM_WORLD);
  if (WorldRank() == 0) {
    std::ofstream(dir / "serial_half.yaml") << FirstHalf(kCase);
    RunIn(dir / "serial_half.yaml", MPI_COMM_NULL, {}, dir / "half_serial");
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const RunSummary s =
      RunIn(Write(dir / "rest", kCase), MPI_COMM_WORLD, dir / "half_serial/checkpoint.h5");
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  EXPECT_EQ(s.steps, 40);
  const double mismatch = Mismatch(serial, ReadLoads(dir / "rest/out/history.h5"));
  if (WorldRank() == 0) std::printf("serial then %d ranks: max difference %.2e\n", WorldSize(), mismatch);
  EXPECT_LT(mismatch, 1e-8);
}

// A checkpoint of another mesh is refused on every rank with the sizes.
TEST(RunOnRanks, CheckpointOfAnotherMeshIsRefused) {
  SharedTempDir dir;
  std::string other = FirstHalf(kCase);
  other.replace(other.find("cells: [20, 12, 1]"), 18, "cells: [24, 12, 1]");
  ASSERT_EQ(RunIn(Write(dir / "other", other), MPI_COMM_WORLD).status, RunSummary::Status::kCompleted);
  try {
    RunIn(Write(dir / "this", kCase), MPI_COMM_WORLD, dir / "other/out/checkpoint.h5");
    ADD_FAILURE() << "expected a DataFileError";
  } catch (const DataFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("checkpoint has 280 cells"));
    EXPECT_THAT(e.what(), HasSubstr("the mesh has 232"));
  }
}

// Too few cells per rank: one error with the counts and the rank count that fits.
TEST(RunOnRanks, TooFewCellsPerRankIsRefused) {
  SharedTempDir dir;
  std::string text = kCase;
  text.replace(text.find("min_cells_per_rank: 20"), 22, "min_cells_per_rank: 200");
  try {
    RunIn(Write(dir / "small", text), MPI_COMM_WORLD);
    ADD_FAILURE() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("232 cells"));
    EXPECT_THAT(e.what(), HasSubstr("200"));
  }
}

// What does not run on ranks yet is refused before the mesh is cut.
TEST(RunOnRanks, FreeRunningIsRefused) {
  SharedTempDir dir;
  std::string text = kCase;
  const auto a = text.find("motion: {");
  text.replace(a, text.find("reference:") - a, "motion: {kind: free}\n");
  try {
    RunIn(Write(dir / "free", text), MPI_COMM_WORLD);
    ADD_FAILURE() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("a free-running motion (motion.kind: free) does not run on"));
    EXPECT_THAT(e.what(), HasSubstr("expected one rank"));
  }
}

}  // namespace
}  // namespace kelvin::cfd
