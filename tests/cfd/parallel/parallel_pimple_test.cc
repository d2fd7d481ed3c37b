// The solver on MPI ranks (issue 23; run by ctest under mpiexec on 2 and 4
// ranks): the decomposition's local meshes and halo, the lid-driven cavity
// and a k-omega SST channel with the linear solvers' tolerances at 1e-10,
// whose lid force and wall friction must agree with the serial run's within
// 1e-8 relative at every step.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <mpi.h>

#include <cmath>
#include <numeric>

#include "cfd/linalg/hypre_solver.h"
#include "cfd/linalg/linear_solver.h"
#include "cfd/mesh/box_mesh.h"
#include "cfd/mesh/dual_mesh.h"
#include "cfd/parallel/decompose.h"
#include "cfd/parallel/partition.h"
#include "cfd/parallel/state_layout.h"
#include "cfd/turbulence/k_omega_sst.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd {
namespace {

int WorldSize() {
  EnsureMpi();
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

// Skewed polyhedral cells with split faces: every face kind the solver meets.
Mesh PolyhedralBox() {
  BoxMeshOptions o;
  o.cells = {6, 6, 6};
  o.polyhedral = true;
  o.perturbation = 0.15;
  return MakeBoxMesh(o);
}

LocalDomain DecomposeOverWorld(const Mesh& mesh) {
  PartitionOptions options;
  options.min_cells_per_rank = 1;  // test meshes of a few hundred cells
  const std::vector<int> rank = PartitionCells(mesh, WorldSize(), MPI_COMM_WORLD, options);
  return Decompose(mesh, rank, MPI_COMM_WORLD);
}

TEST(Decompose, OwnedCellsKeepTheirGeometry) {
  const Mesh whole = PolyhedralBox();
  const LocalDomain local = DecomposeOverWorld(whole);
  const DomainPart& part = *local.part;
  ASSERT_EQ(part.size, WorldSize());
  double volume = 0.0;
  for (int i = 0; i < local.mesh->n_cells(); ++i) {
    const long long c = part.cells[i];
    // Ghost cells too: their outer faces on the processor patch close them.
    EXPECT_NEAR(local.mesh->cell_volumes()[i], whole.cell_volumes()[c], 1e-12 * whole.cell_volumes()[c]);
    EXPECT_LT((local.mesh->cell_centres()[i] - whole.cell_centres()[c]).norm(), 1e-12);
    if (i < part.n_owned) volume += local.mesh->cell_volumes()[i];
  }
  EXPECT_NEAR(part.Sum(volume), whole.total_volume(), 1e-12 * whole.total_volume());
  EXPECT_EQ(static_cast<long long>(part.Sum(part.n_owned)), whole.n_cells());
  // The real patches hold the owned cells' boundary faces only: their areas add up to the whole's.
  for (std::size_t p = 0; p < whole.patches().size(); ++p) {
    double area = 0.0, whole_area = 0.0;
    const Patch& lp = local.mesh->patches()[p];
    for (int f = lp.start; f < lp.start + lp.size; ++f) area += local.mesh->face_area_magnitudes()[f];
    const Patch& wp = whole.patches()[p];
    for (int f = wp.start; f < wp.start + wp.size; ++f) whole_area += whole.face_area_magnitudes()[f];
    EXPECT_EQ(lp.name, wp.name);
    EXPECT_NEAR(part.Sum(area), whole_area, 1e-12 * whole_area) << lp.name;
  }
  EXPECT_EQ(local.mesh->patches().back().kind, PatchKind::kProcessor);
}

TEST(Decompose, HaloCarriesTheOwnersValues) {
  const Mesh whole = PolyhedralBox();
  const LocalDomain local = DecomposeOverWorld(whole);
  const DomainPart& part = *local.part;
  const int n = local.mesh->n_cells();
  std::vector<double> s(n, -1.0);
  std::vector<Vector3> v(n, Vector3::Constant(-1.0));
  std::vector<Matrix3> m(n, Matrix3::Constant(-1.0));
  for (int i = 0; i < part.n_owned; ++i) {
    const double g = static_cast<double>(part.cells[i]);
    s[i] = g;
    v[i] = Vector3(g, 2 * g, 3 * g);
    m[i] = g * Matrix3::Identity() + Matrix3::Ones();
  }
  part.halo->Update(std::span<double>(s));
  part.halo->Update(std::span<Vector3>(v));
  part.halo->Update(std::span<Matrix3>(m));
  for (int i = part.n_owned; i < n; ++i) {
    const double g = static_cast<double>(part.cells[i]);
    EXPECT_EQ(s[i], g);
    EXPECT_EQ(v[i], Vector3(g, 2 * g, 3 * g));
    EXPECT_EQ(m[i], g * Matrix3::Identity() + Matrix3::Ones());
  }
  if (part.size > 1) {
    EXPECT_GT(n, part.n_owned) << "a rank of a split mesh has ghost cells";
  }
  // Global rows: each rank's owned cells are contiguous, and a ghost's row is its owner's.
  std::vector<double> rows(n);
  for (int i = 0; i < n; ++i) rows[i] = part.rows[i];
  for (int i = 0; i < part.n_owned; ++i) EXPECT_EQ(part.rows[i], part.first_row + i);
  part.halo->Update(std::span<double>(rows));
  for (int i = part.n_owned; i < n; ++i) EXPECT_EQ(rows[i], part.rows[i]);
}

// A system on the cell graph defined by the cells' whole-mesh numbers, so that
// every rank builds its owned rows of the same global matrix: off-diagonal
// -(1 + skew) towards a higher-numbered neighbour and -(1 - skew) towards a
// lower one, a diagonal dominating by 1 + (cell mod 3). The rows of ghost
// cells are the identity (the solvers solve the owned rows only).
CsrMatrix CellGraphMatrix(const Mesh& mesh, std::span<const int> global, int n_rows, double skew) {
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> diag(mesh.n_cells(), 0.0);
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    const int P = mesh.owner()[f], N = mesh.neighbour()[f];
    const double pn = -(1.0 + (global[P] < global[N] ? skew : -skew));
    const double np = -(1.0 + (global[N] < global[P] ? skew : -skew));
    if (P < n_rows) {
      t.emplace_back(P, N, pn);
      diag[P] += std::abs(pn);
    }
    if (N < n_rows) {
      t.emplace_back(N, P, np);
      diag[N] += std::abs(np);
    }
  }
  for (int c = 0; c < mesh.n_cells(); ++c) {
    t.emplace_back(c, c, c < n_rows ? diag[c] + 1.0 + static_cast<double>(global[c] % 3) : 1.0);
  }
  CsrMatrix a(mesh.n_cells(), mesh.n_cells());
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

double ExactCellValue(long long global) { return std::sin(0.37 * static_cast<double>(global)) + 2.0; }

// BiCGStab (non-symmetric system) and CG (symmetric) with Jacobi on ranks,
// PETSc's on a shell matrix: the solution of the whole mesh's system at a
// tight tolerance, and at a loose one a true residual ||b - A x|| / ||b||
// within the relative tolerance asked for, as reported.
TEST(LinearSolversOnRanks, JacobiKrylovSolversReachTheWholeMeshSolution) {
  const Mesh whole = PolyhedralBox();
  const LocalDomain local = DecomposeOverWorld(whole);
  const DomainPart& part = *local.part;
  const Mesh& mesh = *local.mesh;
  const int n = mesh.n_cells();
  for (const auto type : {LinearSolverOptions::Type::kBiCgStabJacobi, LinearSolverOptions::Type::kCgJacobi}) {
    const bool cg = type == LinearSolverOptions::Type::kCgJacobi;
    const CsrMatrix a = CellGraphMatrix(mesh, part.cells, part.n_owned, cg ? 0.0 : 0.3);
    Eigen::VectorXd exact(n);
    for (int i = 0; i < n; ++i) exact[i] = ExactCellValue(part.cells[i]);
    const Eigen::VectorXd b = a * exact;  // owned rows: their whole-mesh values (ghost entries are current)
    for (const double rtol : {1e-12, 1e-3}) {
      LinearSolverOptions o;
      o.type = type;
      o.relative_tolerance = rtol;
      o.absolute_tolerance = 0.0;
      const auto solver = LinearSolver::Create(o, &part);
      std::vector<double> x(n, 0.0);
      const SolverSummary s = solver->Solve(a, std::span<const double>(b.data(), n), x);
      UpdateGhosts(&part, x);
      const Eigen::VectorXd r = b - a * Eigen::Map<const Eigen::VectorXd>(x.data(), n);
      double r2 = 0.0, b2 = 0.0, e = 0.0;
      for (int i = 0; i < part.n_owned; ++i) {
        r2 += r[i] * r[i];
        b2 += b[i] * b[i];
        e = std::max(e, std::abs(x[i] - exact[i]));
      }
      const double true_relative = std::sqrt(part.Sum(r2) / part.Sum(b2));
      const char* name = cg ? "CG" : "BiCGStab";
      EXPECT_TRUE(s.converged) << name << " rtol " << rtol;
      EXPECT_GT(s.iterations, 0) << name;
      EXPECT_LE(true_relative, rtol * (1.0 + 1e-6)) << name << " rtol " << rtol;
      EXPECT_NEAR(s.final_relative_residual, true_relative, 1e-3 * rtol) << name << " rtol " << rtol;
      const double largest_error = part.Max(e);
      if (rtol < 1e-6) {
        EXPECT_LT(largest_error, 1e-9) << name;
      }
    }
  }
}

// The lid-driven cavity at Re 100 on 24 x 24 cells; `part` null runs it serially on the whole mesh.
struct CavityRun {
  std::vector<double> lid_force;  // viscous x-force on the lid per unit density, every step
  std::vector<double> u;          // U_x of the owned cells at the end, in the whole mesh's order
};

// `curvature`: the skew and curvature corrections (cfd/fv/diffusion_curvature.h)
// on, for meshes with kinked faces.
std::unique_ptr<PimpleSolver> CavitySolver(const Mesh& mesh, std::shared_ptr<const DomainPart> part,
                                           bool curvature = false) {
  auto U = testing::MakeField<Vector3>("U", mesh, [](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
    if (p.kind == PatchKind::kEmpty) return std::make_unique<Empty<Vector3>>();
    if (p.kind == PatchKind::kProcessor) return std::make_unique<ZeroGradient<Vector3>>();
    if (p.name == "ymax") return std::make_unique<FixedValue<Vector3>>(Vector3(1, 0, 0));
    return std::make_unique<FixedValue<Vector3>>(Vector3(0, 0, 0));
  });
  auto p = testing::MakeField<double>("p", mesh, [](const Patch&) -> std::unique_ptr<BoundaryCondition<double>> {
    return std::make_unique<ZeroGradient<double>>();
  });
  PhysicsOptions physics;
  physics.nu = 0.01;
  SchemeOptions schemes;
  schemes.convection = ConvectionScheme::kLinearUpwind;
  schemes.time = TimeScheme::kBackward;  // two old levels of U and the flux in the state
  schemes.skew_correction = curvature;
  schemes.curvature_correction = curvature;
  schemes.gradient.scheme = curvature ? GradientScheme::kLeastSquares : schemes.gradient.scheme;
  PimpleOptions pimple;
  pimple.n_correctors = 2;
  pimple.momentum_solver.relative_tolerance = 1e-10;
  pimple.pressure_solver.relative_tolerance = 1e-10;
  pimple.pressure_final_relative_tolerance = 1e-10;
  pimple.momentum_solver.absolute_tolerance = 0.0;
  pimple.pressure_solver.absolute_tolerance = 0.0;
  return std::make_unique<PimpleSolver>(mesh, physics, schemes, pimple, std::move(U), std::move(p), part);
}

// Viscous x-force on the lid per unit density, summed over the ranks.
double LidForce(const PimpleSolver& solver, const DomainPart* part) {
  const Mesh& mesh = solver.mesh();
  const Patch& patch = mesh.patches()[mesh.FindPatch("ymax")];
  double force = 0.0;
  for (int f = patch.start; f < patch.start + patch.size; ++f) {
    const int c = mesh.owner()[f];
    const double dn = mesh.deltas()[f].dot(mesh.face_areas()[f]) / mesh.face_area_magnitudes()[f];
    force += 0.01 * mesh.face_area_magnitudes()[f] * (1.0 - solver.U()[c].x()) / dn;
  }
  return part ? part->Sum(force) : force;
}

CavityRun RunCavity(const Mesh& mesh, std::shared_ptr<const DomainPart> part, int steps, bool curvature = false) {
  auto solver = CavitySolver(mesh, part, curvature);
  CavityRun run;
  for (int s = 0; s < steps; ++s) {
    EXPECT_TRUE(solver->Step(0.02).finite);
    run.lid_force.push_back(LidForce(*solver, part.get()));
  }
  std::vector<double> ux(mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) ux[c] = solver->U()[c].x();
  run.u = part ? GatherCells(*part, ux) : ux;
  return run;
}

Mesh Cavity() {
  BoxMeshOptions o;
  o.cells = {24, 24, 1};
  o.max = Vector3(1.0, 1.0, 1.0 / 24);
  o.kinds[4] = o.kinds[5] = PatchKind::kEmpty;
  return MakeBoxMesh(o);
}

// Issue 23 acceptance 2: a run saved on N ranks continues serially, and a
// serial one on N ranks, through the state in the whole mesh's order; both
// end where the uninterrupted serial run ends (linear solves at 1e-10).
TEST(ParallelPimple, StateMovesBetweenRankCounts) {
  const Mesh whole = Cavity();
  const LocalDomain local = DecomposeOverWorld(whole);
  auto reference = CavitySolver(whole, nullptr);
  for (int s = 0; s < 20; ++s) reference->Step(0.02);
  const double expected = LidForce(*reference, nullptr);

  // N ranks for 10 steps, then serially.
  auto ranks = CavitySolver(*local.mesh, local.part);
  for (int s = 0; s < 10; ++s) ranks->Step(0.02);
  auto serial = CavitySolver(whole, nullptr);
  serial->SetState(GatherState(*local.part, *local.mesh, ranks->GetState()));
  for (int s = 0; s < 10; ++s) serial->Step(0.02);
  EXPECT_EQ(serial->step(), 20);
  EXPECT_NEAR(LidForce(*serial, nullptr), expected, 1e-8 * std::abs(expected));

  // Serially for 10 steps, then on N ranks.
  auto first = CavitySolver(whole, nullptr);
  for (int s = 0; s < 10; ++s) first->Step(0.02);
  auto second = CavitySolver(*local.mesh, local.part);
  second->SetState(ScatterState(*local.part, *local.mesh, first->GetState()));
  for (int s = 0; s < 10; ++s) second->Step(0.02);
  EXPECT_NEAR(LidForce(*second, local.part.get()), expected, 1e-8 * std::abs(expected));
  double du = 0.0;
  std::vector<double> ux(local.mesh->n_cells());
  for (int c = 0; c < local.mesh->n_cells(); ++c) ux[c] = second->U()[c].x();
  const std::vector<double> gathered = GatherCells(*local.part, ux);
  for (int c = 0; c < whole.n_cells(); ++c) du = std::max(du, std::abs(gathered[c] - reference->U()[c].x()));
  EXPECT_LT(du, 1e-8);
}

// A state of another mesh is refused with the sizes.
TEST(ParallelPimple, StateOfAnotherMeshIsRefused) {
  const Mesh whole = Cavity();
  const LocalDomain local = DecomposeOverWorld(whole);
  PimpleSolver::State other = CavitySolver(whole, nullptr)->GetState();
  other.p.resize(100);
  other.U.resize(100);
  try {
    ScatterState(*local.part, *local.mesh, other);
    FAIL() << "expected a DataFileError";
  } catch (const DataFileError& e) {
    EXPECT_NE(std::string(e.what()).find("has 100 values; the decomposed mesh has 576 cells"), std::string::npos)
        << e.what();
  }
}

// Output in pieces: a write that fails on the last rank alone (a full disk
// there) is raised on every rank with that rank's message, so all stop alike;
// when every piece is written nothing is raised.
TEST(Decompose, PieceWriteErrorOfOneRankIsRaisedOnEveryRank) {
  const Mesh whole = Cavity();
  const LocalDomain local = DecomposeOverWorld(whole);
  const DomainPart& part = *local.part;
  EXPECT_NO_THROW(OnEveryRank(&part, [] {}));
  const std::string message = fmt::format("fields_000010_r{}.vtu: No space left on device", part.size - 1);
  try {
    OnEveryRank(&part, [&] {
      if (part.rank == part.size - 1) throw DataFileError(message);
    });
    FAIL() << "expected a DataFileError on rank " << part.rank;
  } catch (const DataFileError& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

TEST(ParallelPimple, CavityLidForceMatchesSerialAtEveryStep) {
  const Mesh whole = Cavity();
  const int steps = 25;
  const CavityRun serial = RunCavity(whole, nullptr, steps);
  const LocalDomain local = DecomposeOverWorld(whole);
  const CavityRun parallel = RunCavity(*local.mesh, local.part, steps);
  ASSERT_EQ(parallel.lid_force.size(), serial.lid_force.size());
  double worst = 0.0;
  for (int s = 0; s < steps; ++s) {
    const double rel = std::abs(parallel.lid_force[s] - serial.lid_force[s]) / std::abs(serial.lid_force[s]);
    worst = std::max(worst, rel);
    EXPECT_LT(rel, 1e-8) << "step " << s + 1 << ": " << parallel.lid_force[s] << " on " << WorldSize()
                         << " ranks against " << serial.lid_force[s] << " serially";
  }
  double du = 0.0;
  for (std::size_t c = 0; c < serial.u.size(); ++c) du = std::max(du, std::abs(parallel.u[c] - serial.u[c]));
  EXPECT_LT(du, 1e-8);
  if (local.part->rank == 0) {
    std::printf("%d ranks: lid force %.10f after %d steps, max relative difference %.2e, max |du| %.2e\n",
                WorldSize(), parallel.lid_force.back(), steps, worst, du);
  }
}

// The cavity on median-dual polygonal prisms (kinked faces) with the
// curvature correction: its Hessians and face tensors on ranks, and the
// BDF2 branch of its Rhie-Chow moment term.
TEST(ParallelPimple, CurvatureCorrectedCavityMatchesSerialAtEveryStep) {
  DualMeshOptions o;
  o.divisions = {16, 16, 1};
  o.max = Vector3(1.0, 1.0, 1.0 / 16);
  o.perturbation = 0.15;
  o.kinds[4] = o.kinds[5] = PatchKind::kEmpty;
  const Mesh whole = MakeDualMesh(o);
  const int steps = 15;
  const CavityRun serial = RunCavity(whole, nullptr, steps, true);
  const LocalDomain local = DecomposeOverWorld(whole);
  const CavityRun parallel = RunCavity(*local.mesh, local.part, steps, true);
  for (int s = 0; s < steps; ++s) {
    EXPECT_LT(std::abs(parallel.lid_force[s] - serial.lid_force[s]) / std::abs(serial.lid_force[s]), 1e-8)
        << "step " << s + 1 << ": " << parallel.lid_force[s] << " on " << WorldSize() << " ranks against "
        << serial.lid_force[s] << " serially";
  }
  double du = 0.0;
  for (std::size_t c = 0; c < serial.u.size(); ++c) du = std::max(du, std::abs(parallel.u[c] - serial.u[c]));
  EXPECT_LT(du, 1e-8);
}

// A k-omega SST channel at Re_H 5e4 with a wall at ymin (cells graded 4:1
// towards it, so its first layers are prism columns, with the wall cells in
// the log layer: y+ about 25) and a slip wall at ymax, on skewed cells
// (non-orthogonal corrections) with the bounded TVD scheme for k and omega:
// every ghost array the model reads matters. `part` null runs it serially.
// Returns the wall's x friction force per unit density at every step.
std::unique_ptr<PimpleSolver> SstChannel(const Mesh& mesh, std::shared_ptr<const DomainPart> part,
                                         bool curvature = false) {
  auto U = testing::MakeField<Vector3>("U", mesh, [](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
    if (p.kind == PatchKind::kEmpty) return std::make_unique<Empty<Vector3>>();
    if (p.name == "xmin") return std::make_unique<FixedValue<Vector3>>(Vector3(1, 0, 0));
    if (p.name == "ymin") return std::make_unique<FixedValue<Vector3>>(Vector3(0, 0, 0), PatchRole::kWall);
    if (p.name == "ymax") return std::make_unique<Slip>();
    return std::make_unique<ZeroGradient<Vector3>>();  // xmax, processor
  });
  auto p = testing::MakeField<double>("p", mesh, [](const Patch& patch) -> std::unique_ptr<BoundaryCondition<double>> {
    if (patch.name == "xmax") return std::make_unique<FixedValue<double>>(0.0);
    return std::make_unique<ZeroGradient<double>>();
  });
  const double nu = 2e-5;
  PhysicsOptions physics;
  physics.nu = nu;
  SchemeOptions schemes;
  schemes.convection = ConvectionScheme::kLinearUpwind;
  schemes.skew_correction = curvature;
  schemes.curvature_correction = curvature;
  PimpleOptions pimple;
  pimple.n_correctors = 2;
  for (LinearSolverOptions* o : {&pimple.momentum_solver, &pimple.pressure_solver}) {
    o->relative_tolerance = 1e-10;
    o->absolute_tolerance = 0.0;
  }
  pimple.pressure_final_relative_tolerance = 1e-10;
  const std::vector<TurbulencePatchRole> roles = TurbulencePatchRoles(*U, *p);
  auto solver = std::make_unique<PimpleSolver>(mesh, physics, schemes, pimple, std::move(U), std::move(p), part);
  KOmegaSstOptions sst;
  sst.convection = ConvectionScheme::kLimited;
  sst.solver.relative_tolerance = 1e-10;
  sst.solver.absolute_tolerance = 0.0;
  solver->SetTurbulence(std::make_unique<KOmegaSst>(mesh, nu, sst, roles, part));
  return solver;
}

// The wall's x friction force per unit density (over the ranks).
double WallFriction(const PimpleSolver& solver) {
  const Mesh& mesh = solver.mesh();
  const Patch& wall = mesh.patches()[mesh.FindPatch("ymin")];
  double fx = 0.0;
  const auto& tau = solver.turbulence()->wall_shear_stress();
  for (int f = wall.start; f < wall.start + wall.size; ++f) {
    fx += tau[f - mesh.n_internal_faces()].x() * mesh.face_area_magnitudes()[f];
  }
  return solver.part() ? solver.part()->Sum(fx) : fx;
}

std::vector<double> RunSstChannel(const Mesh& mesh, std::shared_ptr<const DomainPart> part, int steps,
                                  bool curvature = false) {
  auto solver = SstChannel(mesh, std::move(part), curvature);
  std::vector<double> friction;
  for (int s = 0; s < steps; ++s) {
    EXPECT_TRUE(solver->Step(0.05).finite);
    friction.push_back(WallFriction(*solver));
  }
  return friction;
}

Mesh SstChannelMesh() {
  BoxMeshOptions o;
  o.max = Vector3(4.0, 1.0, 0.1);
  o.cells = {24, 20, 1};
  o.grading = {1.0, 4.0, 1.0};
  o.perturbation = 0.1;
  o.kinds = {PatchKind::kPatch, PatchKind::kPatch, PatchKind::kWall, PatchKind::kWall, PatchKind::kEmpty,
             PatchKind::kEmpty};
  return MakeBoxMesh(o);
}

// The SST state (k, omega, their old levels, nu_t and the wall function's
// face viscosity) moves between rank counts with the flow: saved on N ranks
// and continued serially, and the reverse, the wall friction ends within
// 1e-8 of the uninterrupted serial run's.
TEST(ParallelPimple, SstStateMovesBetweenRankCounts) {
  const Mesh whole = SstChannelMesh();
  const double expected = RunSstChannel(whole, nullptr, 12).back();
  const LocalDomain local = DecomposeOverWorld(whole);

  auto ranks = SstChannel(*local.mesh, local.part);
  for (int s = 0; s < 6; ++s) ranks->Step(0.05);
  auto serial = SstChannel(whole, nullptr);
  serial->SetState(GatherState(*local.part, *local.mesh, ranks->GetState()));
  for (int s = 0; s < 6; ++s) serial->Step(0.05);
  EXPECT_NEAR(WallFriction(*serial), expected, 1e-8 * std::abs(expected));

  auto first = SstChannel(whole, nullptr);
  for (int s = 0; s < 6; ++s) first->Step(0.05);
  auto second = SstChannel(*local.mesh, local.part);
  second->SetState(ScatterState(*local.part, *local.mesh, first->GetState()));
  for (int s = 0; s < 6; ++s) second->Step(0.05);
  EXPECT_NEAR(WallFriction(*second), expected, 1e-8 * std::abs(expected));
}



TEST(ParallelPimple, SstChannelWallFrictionMatchesSerialAtEveryStep) {
  const Mesh whole = SstChannelMesh();
  const int steps = 12;
  const LocalDomain local = DecomposeOverWorld(whole);
  // Also with the curvature correction, on nu_eff's faces.
  for (bool curvature : {false, true}) {
    const std::vector<double> serial = RunSstChannel(whole, nullptr, steps, curvature);
    const std::vector<double> parallel = RunSstChannel(*local.mesh, local.part, steps, curvature);
    ASSERT_EQ(parallel.size(), serial.size());
    double worst = 0.0;
    for (int s = 0; s < steps; ++s) {
      const double rel = std::abs(parallel[s] - serial[s]) / std::abs(serial[s]);
      worst = std::max(worst, rel);
      EXPECT_LT(rel, 1e-8) << "step " << s + 1 << ": " << parallel[s] << " on " << WorldSize()
                           << " ranks against " << serial[s] << " serially (curvature " << curvature << ")";
    }
    if (local.part->rank == 0) {
      std::printf("%d ranks%s: SST channel wall friction %.10f after %d steps, max relative difference %.2e\n",
                  WorldSize(), curvature ? ", curvature correction" : "", parallel.back(), steps, worst);
    }
  }
}

}  // namespace
}  // namespace kelvin::cfd
