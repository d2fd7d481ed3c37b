// `kelvin run` on MPI ranks (issue 23; run by ctest under mpiexec on 2 and 4
// ranks): a captive case of a 2D block on a yawing and swaying mesh (yaw with
// drift, ship-axis loads every step) is decomposed by the run layer; with the
// linear solvers' tolerances at 1e-12 its loads agree with the serial run's
// at every step, its checkpoint restarts on another number of ranks, its
// fields are gathered into one VTU of the whole mesh, and what cannot run on
// ranks is refused with one error. A block piercing the linearized free
// surface (its face mesh cut by the partition) runs likewise, with its
// resistance report, and so does a free-running turn with its propeller and
// rudder.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cfd/grid/mesh_case.h"
#include "cfd/linalg/hypre_solver.h"
#include "cfd/run/run_case.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/cfd/cfd_test_support.h"
#include "tests/cfd/vtk_read.h"
#include "tests/test_utilities/test_utilities.h"

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

// The serial reference: every rank runs `text` in a directory of its own
// (from `restart` if given) and `read` takes what it needs from the output
// directory before the directory goes.
template <typename Read>
auto SerialRun(const std::string& text, Read read, const fs::path& restart = {}) {
  kelvin::testing::ScopedTempDir own;
  const RunSummary s = RunIn(testing::WriteCase(own.path(), text), MPI_COMM_NULL, restart);
  EXPECT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  return read(own / "out");
}

Loads SerialLoads(const std::string& text) {
  return SerialRun(text, [](const fs::path& out) { return ReadLoads(out / "history.h5"); });
}

std::string FileText(const fs::path& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in) << file;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The values of the Float64 array `name` of a VTK XML file, in file order.
std::vector<double> VtkArray(const fs::path& file, const std::string& name) {
  std::vector<double> out = testing::VtkDoubles(FileText(file), name);
  EXPECT_FALSE(out.empty()) << name << " in " << file;
  return out;
}

// The x coordinates of the points of a VTK XML file.
std::vector<double> VtkPointsX(const fs::path& file) {
  const std::vector<double> xyz = testing::VtkDoubles(FileText(file), "Points");
  EXPECT_FALSE(xyz.empty()) << file;
  std::vector<double> out;
  for (std::size_t i = 0; i < xyz.size(); i += 3) out.push_back(xyz[i]);
  return out;
}

// The files a parallel index (.pvtu, .pvtp) names, beside it.
std::vector<fs::path> VtkPieces(const fs::path& index) {
  const std::string text = FileText(index);
  std::vector<fs::path> out;
  const std::string key = "Source=\"";
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
    const std::size_t begin = at + key.size();
    out.push_back(index.parent_path() / text.substr(begin, text.find('"', begin) - begin));
  }
  return out;
}

// The array `name` over every piece of an index, sorted (pieces hold each
// rank's cells or faces in its local order).
std::vector<double> SortedOverPieces(const fs::path& index, const std::string& name) {
  std::vector<double> out;
  for (const fs::path& piece : VtkPieces(index)) {
    const std::vector<double> v = VtkArray(piece, name);
    out.insert(out.end(), v.begin(), v.end());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Largest difference of two equally long lists, relative to the largest
// magnitude of the first (infinity when the lengths differ).
double ListMismatch(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.empty()) return std::numeric_limits<double>::infinity();
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(a[i]));
  }
  return diff / scale;
}

TEST(RunOnRanks, ShipLoadsMatchTheSerialRunAtEveryStep) {
  std::vector<double> serial_p, serial_x;
  const Loads serial = SerialRun(kCase, [&](const fs::path& out) {
    serial_p = VtkArray(out / "fields_000080.vtu", "p");
    serial_x = VtkPointsX(out / "fields_000080.vtu");
    std::sort(serial_p.begin(), serial_p.end());
    return ReadLoads(out / "history.h5");
  });
  ASSERT_EQ(serial.Y.size(), 80u);
  ASSERT_EQ(serial_p.size(), 232u);
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
  // The fields in one piece per rank, each cell of the whole mesh (232) in
  // exactly one piece with the serial run's pressure: the sorted values agree
  // as the loads do, within 1e-8 (the files hold exact doubles).
  if (WorldRank() == 0) {
    const fs::path index = dir / "ranks/out/fields_000080.pvtu";
    EXPECT_EQ(VtkPieces(index).size(), static_cast<std::size_t>(WorldSize()));
    EXPECT_THAT(FileText(index), HasSubstr("Name=\"U\" NumberOfComponents=\"3\""));
    EXPECT_LT(ListMismatch(serial_p, SortedOverPieces(index, "p")), 1e-8);
    // The pieces are the placed mesh, as the serial file is (the mesh has
    // moved about 4.5 m from its body-fixed x in [-3, 2]): the same extent in x.
    std::vector<double> x;
    for (const fs::path& piece : VtkPieces(index)) {
      const std::vector<double> px = VtkPointsX(piece);
      x.insert(x.end(), px.begin(), px.end());
    }
    ASSERT_FALSE(x.empty());
    ASSERT_FALSE(serial_x.empty());
    EXPECT_NEAR(*std::min_element(x.begin(), x.end()), *std::min_element(serial_x.begin(), serial_x.end()), 1e-8);
    EXPECT_NEAR(*std::max_element(x.begin(), x.end()), *std::max_element(serial_x.begin(), serial_x.end()), 1e-8);
    EXPECT_THAT(FileText(dir / "ranks/out/fields.pvd"), HasSubstr("file=\"fields_000080.pvtu\""));
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

// A block piercing the linearized free surface in a 12 x 8 x 2 box (186
// cells; tests/cfd/freesurface/resistance_test.cc): the free surface's face
// mesh is cut by the partition, the surface starts as a rigid lid and is
// released after one flow-through (6 s), and the resistance report gathers
// the hull faces. Linear solvers at 1e-12; the steady criterion is never met,
// so the run takes its 40 steps.
const char* kFreeSurfaceCase = R"(mesh:
  box: {min: [0, -2, -1], max: [6, 2, 0], cells: [12, 8, 2], obstacle: {min: [4, 3, 1], max: [7, 5, 2]}}
physics: {nu: 1.0e-2, rho: 998.0}
schemes: {convection: upwind, gradient: gauss}
solution:
  n_outer: 2
  relax: {U: 0.7, p: 0.3, U_final: 1, p_final: 1}
  momentum: {solver: bicgstab, relative_tolerance: 1.0e-12}
  pressure: {solver: pcg_amg, relative_tolerance: 1.0e-12}
reference: {speed: 1, direction: [-1, 0, 0], length: 1.5}
time: {dt: 0.5, end: 20, rigid_lid_windows: 1,
       steady: {quantities: [drag, eta], tolerance: 1.0e-12, min_windows: 1}}
boundary:
  xmax: {U: {type: fixedValue, value: [-1, 0, 0]}, p: {type: zeroGradient}}
  xmin: {U: {type: zeroGradient}, p: {type: fixedValue, value: 0}}
  ymin: {U: {type: slip}, p: {type: zeroGradient}}
  ymax: {U: {type: slip}, p: {type: zeroGradient}}
  zmin: {U: {type: slip}, p: {type: zeroGradient}}
  obstacle: {U: {type: noSlip}, p: {type: zeroGradient}}
  zmax:
    U: {type: zeroGradient}
    p: {type: linearizedFreeSurface, mesh_velocity: [1, 0, 0], kinematic_courant: 2, waterline_patches: [obstacle],
        limit_advection: true, beach: {width: 0.5, strength: 1.0, sides: [xmin, ymin, ymax]}}
output: {directory: out, vtu_interval: 0, checkpoint_interval: 20, forces: [obstacle]}
resistance: {hull: obstacle, free_surface: zmax, wave_cuts: [1.0], wave_cut_points: 24}
partition: {min_cells_per_rank: 20}
)";

// What a free-surface run reports, step by step and at its end.
struct SurfaceRun {
  std::vector<double> force;  // obstacle pressure and viscous force, 6 per step
  std::vector<double> eta;    // resistance.h5 surface/eta, the whole pattern at the end
  double c_t = 0.0, r_t = 0.0, r_wl = 0.0;
};

SurfaceRun ReadSurfaceRun(const fs::path& out) {
  const data::H5Reader h(out / "history.h5");
  const data::Series fp = h.Read("forces/obstacle/pressure"), fv = h.Read("forces/obstacle/viscous");
  SurfaceRun r;
  for (std::size_t i = 0; i < fp.rows; ++i) {
    for (std::size_t d = 0; d < 3; ++d) r.force.push_back(fp.at(i, d));
    for (std::size_t d = 0; d < 3; ++d) r.force.push_back(fv.at(i, d));
  }
  const data::H5Reader res(out / "resistance.h5");
  r.eta = res.Read("surface/eta").values;
  r.c_t = res.Read("C_T").at(0);
  r.r_t = res.Read("R_T").at(0);
  r.r_wl = res.Read("R_WL").at(0);
  return r;
}

// The case stopped at t = 10 s (after the lid's release): its last checkpoint is the restart point.
std::string SurfaceFirstHalf(std::string text) {
  text.replace(text.find("end: 20,"), 8, "end: 10,");
  return text;
}

// The same case with the kinematic condition linearized about the local flow
// (its base flow, set under the lid, is gathered from the ranks' fluxes).
std::string LocalFlow(std::string text) {
  const std::string at = "limit_advection: true,";
  text.replace(text.find(at), at.size(), at + " linearization: local_flow,");
  return text;
}

void ExpectSurfaceRunMatchesSerial(const std::string& text) {
  const SurfaceRun serial = SerialRun(text, ReadSurfaceRun);
  ASSERT_EQ(serial.force.size(), 40u * 6);
  SharedTempDir dir;
  const RunSummary s = RunIn(Write(dir / "ranks", text), MPI_COMM_WORLD);
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  EXPECT_THAT(s.message, HasSubstr("resistance on 'obstacle'"));  // rank 0's report, on every rank
  const SurfaceRun ranks = ReadSurfaceRun(dir / "ranks/out");
  ASSERT_EQ(ranks.force.size(), serial.force.size());
  ASSERT_EQ(ranks.eta.size(), serial.eta.size());
  const double force = Mismatch(serial.force, ranks.force), eta = Mismatch(serial.eta, ranks.eta);
  if (WorldRank() == 0) {
    std::printf("%d ranks, free surface: forces over 40 steps within %.2e of the largest, final eta within %.2e, "
                "C_T %.12e against %.12e serially\n",
                WorldSize(), force, eta, ranks.c_t, serial.c_t);
  }
  EXPECT_LT(force, 1e-8);
  EXPECT_LT(eta, 1e-8);
  EXPECT_LT(std::abs(ranks.c_t - serial.c_t), 1e-8 * std::abs(serial.c_t));
  // R_WL (0.33 N, quadratic in the waterline's eta) corrects R_T (514 N): it agrees as a force of that size.
  EXPECT_LT(std::abs(ranks.r_wl - serial.r_wl), 1e-8 * std::abs(serial.r_t)) << ranks.r_wl << " N against "
                                                                              << serial.r_wl << " N";
  // The surface in one piece per rank: every face of the whole patch (96
  // faces less the block's 3 x 2) in one piece, with the serial run's eta.
  if (WorldRank() == 0) {
    const fs::path index = dir / "ranks/out/zmax_000040.pvtp";
    EXPECT_EQ(VtkPieces(index).size(), static_cast<std::size_t>(WorldSize()));
    std::vector<double> serial_eta = serial.eta;
    std::sort(serial_eta.begin(), serial_eta.end());
    ASSERT_EQ(serial_eta.size(), 90u);
    EXPECT_LT(ListMismatch(serial_eta, SortedOverPieces(index, "eta")), 1e-8);
  }
}

TEST(FreeSurfaceOnRanks, ForcesAndPatternMatchTheSerialRunAtEveryStep) { ExpectSurfaceRunMatchesSerial(kFreeSurfaceCase); }

TEST(FreeSurfaceOnRanks, LocalFlowMatchesTheSerialRunAtEveryStep) {
  ExpectSurfaceRunMatchesSerial(LocalFlow(kFreeSurfaceCase));
}

// A free-surface checkpoint holds the whole pattern: a run saved on the
// ranks continues serially, and a serial one on the ranks, to the end of
// the uninterrupted serial run.
void ExpectSurfaceRestartsAcrossRanks(const std::string& text) {
  const SurfaceRun serial = SerialRun(text, ReadSurfaceRun);
  SharedTempDir dir;
  ASSERT_EQ(RunIn(Write(dir / "half_ranks", SurfaceFirstHalf(text)), MPI_COMM_WORLD).status,
            RunSummary::Status::kCompleted);
  const SurfaceRun continued = SerialRun(text, ReadSurfaceRun, dir / "half_ranks/out/checkpoint.h5");
  const double to_serial = Mismatch(serial.force, continued.force), eta_serial = Mismatch(serial.eta, continued.eta);
  MPI_Barrier(MPI_COMM_WORLD);
  if (WorldRank() == 0) {
    std::ofstream(dir / "serial_half.yaml") << SurfaceFirstHalf(text);
    RunIn(dir / "serial_half.yaml", MPI_COMM_NULL, {}, dir / "half_serial");
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const RunSummary s = RunIn(Write(dir / "rest", text), MPI_COMM_WORLD, dir / "half_serial/checkpoint.h5");
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  const SurfaceRun rest = ReadSurfaceRun(dir / "rest/out");
  const double to_ranks = Mismatch(serial.force, rest.force), eta_ranks = Mismatch(serial.eta, rest.eta);
  if (WorldRank() == 0) {
    std::printf("free surface, %d ranks then serial: forces %.2e, eta %.2e; serial then %d ranks: %.2e, %.2e\n",
                WorldSize(), to_serial, eta_serial, WorldSize(), to_ranks, eta_ranks);
  }
  EXPECT_EQ(continued.force.size(), 20u * 6);
  EXPECT_EQ(rest.force.size(), 20u * 6);
  EXPECT_LT(std::max(to_serial, to_ranks), 1e-8);
  EXPECT_LT(std::max(eta_serial, eta_ranks), 1e-8);
}

TEST(FreeSurfaceOnRanks, CheckpointRestartsOnAnotherNumberOfRanks) { ExpectSurfaceRestartsAcrossRanks(kFreeSurfaceCase); }

// The base flow, frozen at the release, before the checkpoint at
// t = 10 s, is in the checkpoint of the whole surface.
TEST(FreeSurfaceOnRanks, LocalFlowCheckpointRestartsOnAnotherNumberOfRanks) {
  ExpectSurfaceRestartsAcrossRanks(LocalFlow(kFreeSurfaceCase));
}

// The free-running Wigley turn (data/cases/free_running/wigley_turning.yaml:
// the body-force propeller and rudder, steered by the simulator's maneuver
// controller, on the quickstart's 5k-cell captive grid) cut to 3 s with the
// rudder executed at 2.2 s, just after the release at 2 s; every linear
// solver at 1e-10. The actuators are found on the whole mesh and act on each
// rank's cells of it; the body moves alike on every rank.
std::string TurningCase(const fs::path& grid) {
  std::string text = kelvin::testing::ReadText(kelvin::testing::SourceDir() / "data/cases/free_running/wigley_turning.yaml");
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  };
  replace("ship: ../../ships/wigley.yaml", "ship: " + fs::absolute(kelvin::testing::SourceDir() / "data/ships/wigley.yaml").string());
  replace("../../../build/grids/wigley_captive_quick/constant/polyMesh", (grid / "constant/polyMesh").string());
  replace("execute_time: 5.0", "execute_time: 2.2");
  replace("end: 80.0", "end: 3.0");
  replace("relative_tolerance: 1.0e-6}", "relative_tolerance: 1.0e-10}");
  replace("relative_tolerance: 1.0e-4, final_relative_tolerance: 1.0e-6",
          "relative_tolerance: 1.0e-10, final_relative_tolerance: 1.0e-10");
  replace("turbulence:\n", "turbulence:\n  solver: {relative_tolerance: 1.0e-10}\n");
  replace("directory: ../../../results/free_running/wigley_turning", "directory: out");
  return text + "partition: {min_cells_per_rank: 500}\n";
}

// Per step: the body's trajectory, velocities and loads and the actuators' states, by name.
std::map<std::string, std::vector<double>> ReadBody(const fs::path& history) {
  const data::H5Reader h(history);
  std::map<std::string, std::vector<double>> out;
  for (const char* name : {"body/trajectory", "body/velocity", "body/hull_load", "body/actuator_load", "rudder/state",
                           "propeller/state"}) {
    out[name] = h.Read(name).values;
  }
  return out;
}

TEST(FreeRunningOnRanks, TheTurnMatchesTheSerialRunAtEveryStep) {
  // 15 s on 2 ranks, 35 s on 4 oversubscribed ones: CI runs it on 2, tools/bench/ranks_same_answers.py on 4.
  if (WorldSize() != 2) GTEST_SKIP() << "run on 2 ranks (4 ranks: BENCHMARKS ranks_same_answers)";
  SharedTempDir dir;
  // Rank 0 meshes; a failure there stops every rank (none waits for a grid that never comes).
  int meshed = 1;
  if (WorldRank() == 0) {
    try {
      RunMeshCase(LoadMeshCase(kelvin::testing::SourceDir() / "data/cases/captive_cfd/wigley_quick_mesh.yaml"), 1,
                  dir / "grid");
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
      meshed = 0;
    }
  }
  MPI_Bcast(&meshed, 1, MPI_INT, 0, MPI_COMM_WORLD);
  ASSERT_EQ(meshed, 1) << "the grid of the turn could not be made";
  const std::string text = TurningCase(dir / "grid");
  const auto serial = SerialRun(text, [](const fs::path& out) { return ReadBody(out / "history.h5"); });
  const RunSummary s = RunIn(Write(dir / "ranks", text), MPI_COMM_WORLD);
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  EXPECT_THAT(s.message, HasSubstr("turning"));  // the maneuver report of rank 0, on every rank
  const auto ranks = ReadBody(dir / "ranks/out/history.h5");
  ASSERT_EQ(serial.at("body/velocity").size(), 75u * 3);
  // Each column against its own largest value over the run (delta and the order are 0 before the execute).
  double worst = 0.0;
  for (const auto& [name, values] : serial) {
    ASSERT_EQ(ranks.at(name).size(), values.size()) << name;
    for (std::size_t k = 0; k < 3; ++k) {
      double scale = 0.0, diff = 0.0;
      for (std::size_t i = k; i < values.size(); i += 3) {
        scale = std::max(scale, std::abs(values[i]));
        diff = std::max(diff, std::abs(values[i] - ranks.at(name)[i]));
      }
      if (scale == 0.0) {
        EXPECT_EQ(diff, 0.0) << name << " component " << k;
        continue;
      }
      worst = std::max(worst, diff / scale);
      EXPECT_LT(diff / scale, 1e-8) << name << " component " << k;
    }
  }
  const std::vector<double>& rudder = serial.at("rudder/state");
  EXPECT_GT(std::abs(rudder[rudder.size() - 3]), 0.1);  // the blade is over by the end
  if (WorldRank() == 0) {
    std::printf("free running on %d ranks: body, propeller and rudder within %.2e of their largest at every step\n",
                WorldSize(), worst);
    EXPECT_TRUE(fs::exists(dir / "ranks/out/maneuver.h5"));
  }
}

}  // namespace
}  // namespace kelvin::cfd
