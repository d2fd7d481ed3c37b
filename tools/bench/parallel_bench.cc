// The decomposed PIMPLE solver against the serial one (issue 23): the 3D
// lid-driven cube of tools/bench/pimple_vs_openfoam.py (laminar, Re 100,
// Euler, linear-upwind, 2 outer x 2 pressure correctors) on a polyMesh, run
// as a singleton (the serial solver) or under mpiexec (the decomposed one).
// Rank 0 prints one JSON line: the wall time of each step (after a barrier),
// the decomposition time, and per rank the peak resident memory, the owned
// and ghost cells, the neighbour ranks and the halo bytes of one exchange of a
// double per cell. tools/bench/parallel_speedup.py drives it.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <mpi.h>
#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <set>
#include <vector>

#include "cfd/linalg/hypre_solver.h"
#include "cfd/mesh/poly_mesh_reader.h"
#include "cfd/parallel/decompose.h"
#include "cfd/parallel/partition.h"
#include "cfd/solver/pimple_solver.h"

namespace kelvin::cfd {
namespace {

template <typename T>
std::unique_ptr<CellField<T>> Field(const std::string& name, const Mesh& mesh, bool velocity) {
  std::vector<std::unique_ptr<BoundaryCondition<T>>> bcs;
  for (const Patch& p : mesh.patches()) {
    if (!velocity || p.kind == PatchKind::kProcessor) {
      bcs.push_back(std::make_unique<ZeroGradient<T>>());
    } else if constexpr (std::is_same_v<T, Vector3>) {
      bcs.push_back(std::make_unique<FixedValue<T>>(p.name == "lid" ? Vector3(1, 0, 0) : Vector3(0, 0, 0)));
    }
  }
  return std::make_unique<CellField<T>>(name, mesh, std::move(bcs));
}

std::vector<double> Gathered(double value, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<double> all(size);
  MPI_Allgather(&value, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, comm);
  return all;
}

std::string List(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += fmt::format("{}{:.6g}", i ? ", " : "", v[i]);
  return s + "]";
}

// The machine's memory-bandwidth ceiling for the same launch: a STREAM-like
// triad c = a + 1.5 b on 3 x 160 MB per process, best of 10 sweeps, GB/s of
// each rank (run alone and on 2 ranks: the ratio of the sums bounds the
// speed-up of a bandwidth-bound solver).
int Triad() {
  EnsureMpi();
  const std::size_t n = 20'000'000;
  std::vector<double> a(n, 1.0), b(n, 2.0), c(n, 0.0);
  double best = 1e300;
  for (int sweep = 0; sweep < 10; ++sweep) {
    MPI_Barrier(MPI_COMM_WORLD);
    const double t = MPI_Wtime();
    for (std::size_t i = 0; i < n; ++i) c[i] = a[i] + 1.5 * b[i];
    best = std::min(best, MPI_Wtime() - t);
  }
  // (+ 0 * c[7]: reading c keeps the sweeps.)
  const std::vector<double> rates = Gathered(3.0 * 8.0 * static_cast<double>(n) / best / 1e9 + 0.0 * c[7], MPI_COMM_WORLD);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) std::printf("{\"triad_gb_s\": %s}\n", List(rates).c_str());
  return 0;
}

// A size from /proc/self/status (MB): "VmRSS:" resident now, "VmHWM:" its
// peak so far.
double StatusMb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string key;
  double kb = 0.0;
  while (in >> key) {
    if (key == field) {
      in >> kb;
      break;
    }
  }
  return kb / 1024.0;
}
double ResidentMb() { return StatusMb("VmRSS:"); }

// Heap in use now (MB): malloc's live bytes, what the process holds apart
// from freed pages glibc keeps (which the resident size includes).
double LiveHeapMb() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd) / 1048576.0;
}

int Run(const std::string& poly_mesh, int steps, double dt, double nu, bool ilu) {
  EnsureMpi();
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  auto whole = std::make_unique<Mesh>(ReadPolyMesh(poly_mesh));
  whole->RenumberCells();
  const long long n_cells = whole->n_cells();
  const double t0 = MPI_Wtime();
  LocalDomain local;
  if (size > 1) {
    const std::vector<int> part = PartitionCells(*whole, size, MPI_COMM_WORLD);
    local = Decompose(*whole, part, MPI_COMM_WORLD);
    whole.reset();  // the whole mesh is not kept
    malloc_trim(0);  // the decomposition's freed temporaries, as the run layer does (cfd/run/case_loader.cc)
  }
  const double decompose_s = MPI_Wtime() - t0;
  const Mesh& mesh = size > 1 ? *local.mesh : *whole;
  const double live_mesh = LiveHeapMb();
  const double peak_mesh = StatusMb("VmHWM:");  // the decomposition's high-water mark on ranks
  PhysicsOptions physics;
  physics.nu = nu;
  SchemeOptions schemes;
  schemes.convection = ConvectionScheme::kLinearUpwind;
  PimpleOptions pimple;
  pimple.n_outer = 2;
  pimple.n_correctors = 2;
  pimple.momentum_solver.relative_tolerance = 1e-6;
  if (ilu) pimple.momentum_solver.type = LinearSolverOptions::Type::kBiCgStabIlu;
  pimple.pressure_solver.relative_tolerance = 1e-2;
  pimple.pressure_final_relative_tolerance = 1e-6;
  PimpleSolver solver(mesh, physics, schemes, pimple, Field<Vector3>("U", mesh, true), Field<double>("p", mesh, false),
                      local.part);
  const double live_solver = LiveHeapMb();
  std::vector<double> step_s;
  double p_iters = 0.0, u_iters = 0.0;
  for (int s = 0; s < steps; ++s) {
    MPI_Barrier(MPI_COMM_WORLD);
    const double a = MPI_Wtime();
    const StepSummary summary = solver.Step(dt);
    MPI_Barrier(MPI_COMM_WORLD);
    step_s.push_back(MPI_Wtime() - a);
    p_iters += summary.pressure_iterations;
    u_iters += summary.momentum_iterations;
    if (!summary.finite) throw std::runtime_error("the cube diverged");
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const int owned = size > 1 ? local.part->n_owned : mesh.n_cells();
  const int ghosts = mesh.n_cells() - owned;
  std::set<int> neighbours;
  if (size > 1) {
    // A ghost's owner: the rank whose row range holds its global row.
    std::vector<double> first = Gathered(local.part->first_row, MPI_COMM_WORLD);
    for (int i = owned; i < mesh.n_cells(); ++i) {
      const int row = local.part->rows[i];
      neighbours.insert(static_cast<int>(std::upper_bound(first.begin(), first.end(), row) - first.begin()) - 1);
    }
  }
  const std::vector<double> rss = Gathered(usage.ru_maxrss / 1024.0, MPI_COMM_WORLD);
  const std::vector<double> resident = Gathered(ResidentMb(), MPI_COMM_WORLD);
  const std::vector<double> live_mesh_mb = Gathered(live_mesh, MPI_COMM_WORLD);
  const std::vector<double> peak_mesh_mb = Gathered(peak_mesh, MPI_COMM_WORLD);
  const std::vector<double> live_solver_mb = Gathered(live_solver, MPI_COMM_WORLD);
  const std::vector<double> live_end_mb = Gathered(LiveHeapMb(), MPI_COMM_WORLD);
  const std::vector<double> own = Gathered(owned, MPI_COMM_WORLD);
  const std::vector<double> ghost = Gathered(ghosts, MPI_COMM_WORLD);
  const std::vector<double> nbr = Gathered(static_cast<double>(neighbours.size()), MPI_COMM_WORLD);
  if (rank == 0) {
    std::printf("{\"ranks\": %d, \"cells\": %lld, \"decompose_s\": %.4f, \"step_s\": %s, \"pressure_iterations\": %.0f, \"momentum_iterations\": %.0f, "
                "\"rss_mb\": %s, \"resident_mb\": %s, \"live_mesh_mb\": %s, \"peak_mesh_mb\": %s, \"live_solver_mb\": %s, \"live_end_mb\": %s, \"owned\": %s, \"ghosts\": %s, \"neighbours\": %s}\n",
                size, n_cells, decompose_s, List(step_s).c_str(), p_iters, u_iters, List(rss).c_str(), List(resident).c_str(), List(live_mesh_mb).c_str(), List(peak_mesh_mb).c_str(),
                List(live_solver_mb).c_str(), List(live_end_mb).c_str(), List(own).c_str(),
                List(ghost).c_str(), List(nbr).c_str());
  }
  return 0;
}

}  // namespace
}  // namespace kelvin::cfd

int main(int argc, char** argv) {
  CLI::App app("decomposed PIMPLE on a lid-driven cube polyMesh (run under mpiexec for N ranks)");
  std::string poly_mesh;
  int steps = 6;
  double dt = 0.005;
  double nu = 0.01;
  bool ilu = false;
  bool triad = false;
  app.add_option("poly_mesh", poly_mesh, "constant/polyMesh of the cube (patches lid and walls)");
  app.add_flag("--triad", triad, "measure the memory bandwidth (STREAM triad) instead");
  app.add_option("--steps", steps, "time steps")->check(CLI::Range(2, 100000));
  app.add_option("--dt", dt, "time step (s)")->check(CLI::PositiveNumber);
  app.add_option("--nu", nu, "kinematic viscosity (m^2/s)")->check(CLI::PositiveNumber);
  app.add_flag("--momentum-ilu", ilu, "momentum by hypre BiCGStab + ILU(0) (default: BiCGStab + Jacobi)");
  CLI11_PARSE(app, argc, argv);
  try {
    if (triad) return kelvin::cfd::Triad();
    if (poly_mesh.empty()) throw std::runtime_error("no polyMesh given; expected constant/polyMesh of the cube");
    return kelvin::cfd::Run(poly_mesh, steps, dt, nu, ilu);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "parallel_bench: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
}
