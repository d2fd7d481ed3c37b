// The body-force propeller: the disk's loads integrate to the prescribed T
// and Q on any placement; a uniformly loaded disk in a uniform stream has
// the far wake of actuator-disk momentum theory; in open water the
// Propeller recovers the input K_T(J) after removing its induced velocity
// (its bad input: propeller_errors_test.cc).
#include "cfd/propulsion/actuator_disk.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

#include "cfd/mesh/box_mesh.h"
#include "cfd/propulsion/propeller.h"
#include "data/schema/errors.h"
#include "tests/cfd/cfd_test_support.h"
#include "tests/cfd/propulsion/propeller_test_support.h"
#include "tests/cfd/propulsion/stream_support.h"

namespace kelvin::cfd {
namespace {

using ::testing::HasSubstr;
using testing::HoughOrdwayDisk;
using testing::Kp505;
using testing::StillWater;
using testing::StretchedCoordinates;
using testing::TensorMesh;
using testing::UniformBox;
using testing::UniformFlow;
constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------
// Meshes


// ---------------------------------------------------------------------------
// Loads integrate to T and Q

// Hough-Ordway or uniform shape, as the test's own formula (r' = r / R).
double Shape(ActuatorDiskOptions::Distribution d, double r_prime, double hub) {
  if (d == ActuatorDiskOptions::Distribution::kUniform) return 1.0;
  const double rs = (r_prime - hub) / (1.0 - hub);
  return rs * std::sqrt(1.0 - rs);
}

// Integral of the shape over the annulus times the thickness, by the
// composite Simpson rule in r (independent of the class's closed form).
double ShapeIntegral(const ActuatorDiskOptions& o) {
  const double R = 0.5 * o.diameter, rh = o.hub_ratio * R;
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double r = rh + (R - rh) * i / n;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * Shape(o.distribution, r / R, o.hub_ratio) * 2 * kPi * r;
  }
  return o.thickness * sum * (R - rh) / n / 3.0;
}

struct Sums {
  double axial;   // sum rho s V . axis_E
  double torque;  // sum ((x - c_E) x rho s V) . axis_E
  double lateral; // |sum rho s V - (sum rho s V . axis_E) axis_E|
};

// From the solver's cell source and the (placed) mesh only.
Sums IntegrateSource(const PimpleSolver& solver, const Mesh& mesh, const Vector3& centre_E, const Vector3& axis_E,
                     double rho) {
  Sums s{0, 0, 0};
  Vector3 total = Vector3::Zero();
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const Vector3 F = rho * solver.cell_source()[c] * mesh.cell_volumes()[c];
    total += F;
    s.torque += (mesh.cell_centres()[c] - centre_E).cross(F).dot(axis_E);
  }
  s.axial = total.dot(axis_E);
  s.lateral = (total - s.axial * axis_E).norm();
  return s;
}


ActuatorDiskOptions TiltedDisk(ActuatorDiskOptions::Distribution d, int sense) {
  ActuatorDiskOptions o;
  o.centre = Vector3(0.031, -0.017, 0.009);
  o.axis = Vector3(1.0, 0.2, -0.1).normalized();
  o.diameter = 1.0;
  o.hub_ratio = 0.2;
  o.thickness = 0.15;
  o.distribution = d;
  o.sense = sense;
  return o;
}

void CheckIntegrals(ActuatorDiskOptions::Distribution d, int sense, bool rotated) {
  Mesh mesh = UniformBox(40);  // 20 cells across D
  const ActuatorDiskOptions o = TiltedDisk(d, sense);
  const ActuatorDisk disk(mesh, o);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Vector3 t = Vector3::Zero();
  if (rotated) {
    R = (Eigen::AngleAxisd(0.7, Vector3::UnitZ()) * Eigen::AngleAxisd(-0.3, Vector3(1, 1, 0).normalized()))
            .toRotationMatrix();
    t = Vector3(3.0, -1.5, 0.25);
  }
  mesh.SetPlacement(R, t);
  auto solver = StillWater(mesh);
  const double T = 123.4, Q = 17.9, rho = 998.2;
  std::vector<Vector3> source;
  disk.AddBodyForce(T, Q, rho, R, source);
  solver->SetCellSource(source);
  const Sums s = IntegrateSource(*solver, mesh, R * o.centre + t, R * o.axis, rho);
  std::printf("disk %s sense %+d %s: sum F.axis = %.12g (-T = %.12g), torque = %.12g (sense Q = %.12g), lateral "
              "%.3e N; discrete/analytic thrust %.5f torque %.5f; %zu cells, %.1f across D\n",
              d == ActuatorDiskOptions::Distribution::kUniform ? "uniform" : "Hough-Ordway", sense,
              rotated ? "rotated" : "unrotated", s.axial, -T, s.torque, sense * Q, s.lateral,
              disk.discrete_to_analytic_thrust(), disk.discrete_to_analytic_torque(), disk.cells().size(),
              disk.cells_across_diameter());
  // The acceptance asks for 0.1%; the normalization makes it round-off.
  EXPECT_NEAR(s.axial, -T, 1e-9 * T);
  EXPECT_NEAR(s.torque, sense * Q, 1e-9 * Q);
  // The swirl has no net force; the disk's axial force is along the axis
  // only up to the discrete asymmetry of a tilted disk on a box grid.
  EXPECT_LT(s.lateral, 0.01 * T + 0.1 * Q);
  // Sub-cell sampling: the discrete integrals within 1% of the analytic
  // ones at 20 cells across; the analytic one checked by quadrature.
  EXPECT_NEAR(disk.discrete_to_analytic_thrust(), 1.0, 0.01);
  EXPECT_NEAR(disk.discrete_to_analytic_torque(), 1.0, 0.01);
  double sampled = 0.0;
  for (double w : disk.axial_weights()) sampled += w;
  EXPECT_NEAR(sampled, 1.0, 1e-12);
}

TEST(ActuatorDiskLoads, HoughOrdwayIntegratesToTAndQ) {
  CheckIntegrals(ActuatorDiskOptions::Distribution::kHoughOrdway, +1, false);
  CheckIntegrals(ActuatorDiskOptions::Distribution::kHoughOrdway, -1, true);
}

TEST(ActuatorDiskLoads, UniformIntegratesToTAndQ) {
  CheckIntegrals(ActuatorDiskOptions::Distribution::kUniform, +1, true);
  CheckIntegrals(ActuatorDiskOptions::Distribution::kUniform, -1, false);
}

// Mean of the shape (and of shape / r') over the cube of side `side`
// centred at x, by the 16^3-point midpoint rule.
std::pair<double, double> CubeMean(const ActuatorDiskOptions& o, const Vector3& x, double side) {
  const int m = 16;
  double g_sum = 0.0, t_sum = 0.0;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      for (int k = 0; k < m; ++k) {
        const Vector3 p = x + side * (Vector3(i + 0.5, j + 0.5, k + 0.5) / m - Vector3::Constant(0.5));
        const Vector3 d = p - o.centre;
        const double r_prime = (d - d.dot(o.axis) * o.axis).norm() / (0.5 * o.diameter);
        const double g = Shape(o.distribution, r_prime, o.hub_ratio);
        g_sum += g;
        t_sum += g / r_prime;
      }
    }
  }
  return {g_sum / (m * m * m), t_sum / (m * m * m)};
}

// The radial distribution itself: on the cells wholly inside the disk, the
// axial force density is T <g>_cell / int g dV, with the test's own g, its
// cell mean over the cube by quadrature and the integral by Simpson's
// rule, and the tangential one Q <g / r'>_cell / (R int g dV) (the torque
// integral int r (g / r') dV = R int g dV). Within 1%: the sampled
// integrals of the class (tetrahedra split to a quarter of the thickness, 64 points each) against
// 4096-point cube means, and the normalization by the discrete sums
// (discrete/analytic within 0.3% here).
TEST(ActuatorDiskLoads, HoughOrdwayRadialShape) {
  const Mesh mesh = UniformBox(40);
  ActuatorDiskOptions o = TiltedDisk(ActuatorDiskOptions::Distribution::kHoughOrdway, +1);
  o.axis = Vector3::UnitX();
  const ActuatorDisk disk(mesh, o);
  std::vector<Vector3> source;
  const double T = 10.0, Q = 2.0, rho = 1.0;
  disk.AddBodyForce(T, Q, rho, Eigen::Matrix3d::Identity(), source);
  const double integral = ShapeIntegral(o);
  const double torque_integral = 0.5 * o.diameter * integral;
  int checked = 0;
  double worst_axial = 0.0, worst_tangential = 0.0;
  for (std::size_t i = 0; i < disk.cells().size(); ++i) {
    const int c = disk.cells()[i];
    if (disk.volume_fractions()[i] < 1.0 - 1e-9) continue;  // wholly inside (to round-off)
    const Vector3 d = mesh.cell_centres()[c] - o.centre;
    const Vector3 radial = d - d.dot(o.axis) * o.axis;
    const auto [g, g_over_r] = CubeMean(o, mesh.cell_centres()[c], 0.05);
    const double fx = -source[c].dot(o.axis) * rho;
    const double ft = source[c].dot(o.axis.cross(radial.normalized())) * rho;
    worst_axial = std::max(worst_axial, std::abs(fx / (T * g / integral) - 1.0));
    worst_tangential = std::max(worst_tangential, std::abs(ft / (Q * g_over_r / torque_integral) - 1.0));
    ++checked;
  }
  std::printf("Hough-Ordway shape on %d interior cells: worst axial %.4f, tangential %.4f\n", checked, worst_axial,
              worst_tangential);
  EXPECT_GT(checked, 200);
  EXPECT_LT(worst_axial, 0.01);
  EXPECT_LT(worst_tangential, 0.01);
}

// ---------------------------------------------------------------------------
// A disk in a uniform stream (no hull)

// Quarter domain x in [-3D, 6D], y, z in [0, 4D] (the full domain is
// [-3D, 6D] x [-4D, 4D]^2: blockage A / A_c = 1.2%), D = 1 at the origin,
// y = 0 and z = 0 symmetry planes through the axis. Cells of size h on
// x in [-0.5, 4], r < 0.625 (the disk and the contracted slipstream up to
// the wake window), stretched by `ratio` per cell outward.
Mesh QuarterDomain(double h, double ratio) {
  const std::vector<double> x = StretchedCoordinates(-3.0, -0.5, 4.0, 6.0, h, ratio);
  const std::vector<double> yz = StretchedCoordinates(0.0, 0.0, 0.625, 4.0, h, ratio);
  return TensorMesh({x, yz, yz}, {PatchKind::kPatch, PatchKind::kPatch, PatchKind::kSymmetry, PatchKind::kSymmetry,
                                  PatchKind::kSymmetry, PatchKind::kSymmetry});
}

// Grid k of the family (0 coarse, 1 medium, 2 fine): constant refinement
// ratio sqrt(2) in the core, and the stretching ratio refined with it.
Mesh FamilyGrid(int k) {
  const double refine = std::pow(std::sqrt(2.0), k);
  return QuarterDomain(0.125 / refine, std::pow(1.2, 1.0 / refine));
}

// Uniform inflow U at xmin, a fixed-pressure outflow at xmax, slip on the
// sides; laminar, nu = 1e-4 (Re_D = 1e4 at U = 1).
std::unique_ptr<PimpleSolver> StreamSolver(const Mesh& mesh, double U_inf) {
  return testing::StreamSolver(mesh, Vector3(U_inf, 0, 0), "xmin", "xmax");
}

// Marches to a steady state (max cell change per step below tol U); the
// number of steps.
int MarchToSteady(PimpleSolver& solver, double U_inf, double dt, double tol, int max_steps) {
  int steps = 0;
  double change = 1.0;
  while (change > tol * U_inf && steps < max_steps) {
    const std::vector<Vector3> before = solver.U().values();
    EXPECT_TRUE(solver.Step(dt).finite);
    change = 0.0;
    for (std::size_t c = 0; c < before.size(); ++c) change = std::max(change, (solver.U()[c] - before[c]).norm());
    ++steps;
  }
  EXPECT_LE(change, tol * U_inf) << "not steady after " << steps << " steps: max change " << change / U_inf << " U";
  return steps;
}

// Volume-weighted mean of u_x - U over the cells with r < r_max and
// x in [x0, x1].
double WakeExcess(const PimpleSolver& solver, double U_inf, double x0, double x1, double r_max) {
  const Mesh& mesh = solver.mesh();
  double sum = 0.0, vol = 0.0;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const Vector3& x = mesh.cell_centres()[c];
    if (x.x() < x0 || x.x() > x1 || std::hypot(x.y(), x.z()) > r_max) continue;
    sum += (solver.U()[c].x() - U_inf) * mesh.cell_volumes()[c];
    vol += mesh.cell_volumes()[c];
  }
  return sum / vol;
}

struct WakeResult {
  int cells = 0;
  double h = 0.0;            // representative size (V / N)^(1/3) of the core
  double u_core = 0.0;       // mean excess, r < 0.25 D, x in [2D, 4D]
  double u_axis = 0.0;       // same on the row of cells next to the axis
  double u_theory = 0.0;     // U (sqrt(1 + C_Th) - 1)
  double cpu_s = 0.0;
  int steps = 0;
};

// Uniform loading: momentum theory's far wake U (sqrt(1 + C_Th) - 1) is
// the result for a uniformly loaded disk (uniform total-head jump, so a
// uniform slipstream core); C_Th = 1.
WakeResult FarWake(int k) {
  const Mesh mesh = FamilyGrid(k);
  const double U = 1.0, rho = 1.0, C_T = 1.0;
  ActuatorDiskOptions o;
  o.diameter = 1.0;
  o.hub_ratio = 0.0;
  o.thickness = 0.2;
  o.axis = -Vector3::UnitX();  // thrust upstream: the disk pushes the water downstream
  o.distribution = ActuatorDiskOptions::Distribution::kUniform;
  const ActuatorDisk disk(mesh, o);
  const double T_full = C_T * 0.5 * rho * disk.area() * U * U;
  auto solver = StreamSolver(mesh, U);
  std::vector<Vector3> source;
  disk.AddBodyForce(disk.mesh_share() * T_full, 0.0, rho, Eigen::Matrix3d::Identity(), source);
  solver->SetCellSource(source);
  WakeResult r;
  const auto start = std::clock();
  r.steps = MarchToSteady(*solver, U, 0.25, 1e-5, 600);
  r.cpu_s = double(std::clock() - start) / CLOCKS_PER_SEC;
  r.cells = mesh.n_cells();
  r.h = 0.125 / std::pow(std::sqrt(2.0), k);
  r.u_core = WakeExcess(*solver, U, 2.0, 4.0, 0.25);
  r.u_axis = WakeExcess(*solver, U, 2.0, 4.0, 0.75 * r.h);
  r.u_theory = U * (std::sqrt(1.0 + C_T) - 1.0);
  std::printf("actuator_disk far_wake grid %d: %d cells, h = %.5f D, %.1f across D, share %.5f, %d steps, "
              "%.1f CPU s: u_core = %.5f, u_axis = %.5f, theory %.5f: core error %+.2f%%, axis %+.2f%%\n",
              k, r.cells, r.h, disk.cells_across_diameter(), disk.mesh_share(), r.steps, r.cpu_s, r.u_core,
              r.u_axis, r.u_theory, 100 * (r.u_core / r.u_theory - 1), 100 * (r.u_axis / r.u_theory - 1));
  return r;
}

double WakeError(const WakeResult& r) { return r.u_core / r.u_theory - 1.0; }

// The two coarse grids of the family (CI): the acceptance's 5% already
// holds on them.
TEST(ActuatorDiskStream, FarWakeCoarseGrids) {
  const WakeResult g0 = FarWake(0);
  const WakeResult g1 = FarWake(1);
  std::printf("actuator_disk far_wake trend (coarse -> medium): core %+.2f%% -> %+.2f%%\n", 100 * WakeError(g0),
              100 * WakeError(g1));
  EXPECT_NEAR(WakeError(g0), 0.0, 0.05);
  EXPECT_NEAR(WakeError(g1), 0.0, 0.05);
}

// The acceptance: within 5% of momentum theory on the finest of the three
// grids, with the trend over all three (`slow`).
TEST(ActuatorDiskStream, FarWakeFineGrid) {
  if (!std::getenv("KELVIN_ACTUATOR_DISK_FINE")) GTEST_SKIP() << "set KELVIN_ACTUATOR_DISK_FINE=1 (ctest -L slow)";
  const WakeResult g0 = FarWake(0), g1 = FarWake(1), g2 = FarWake(2);
  const double e21 = g1.u_core - g2.u_core, e32 = g0.u_core - g1.u_core;
  std::printf("actuator_disk far_wake trend (coarse, medium, fine): %+.2f%%, %+.2f%%, %+.2f%%; "
              "e32/e21 = %.3f (ratio sqrt 2)\n",
              100 * WakeError(g0), 100 * WakeError(g1), 100 * WakeError(g2), e21 != 0 ? e32 / e21 : 0.0);
  EXPECT_NEAR(WakeError(g2), 0.0, 0.05);
}

// Swirl: the torque the disk puts into the water leaves the domain as the
// flux of angular momentum about the axis, rho int (r x u)_x u_x dA, through
// every plane downstream of the disk (the inflow carries none; slip sides
// exert no tangential stress, and the radially symmetric swirl pressure no
// net moment on them). A full domain (symmetry planes through the axis
// cannot carry swirl), the coarse core h = D/8, the Hough-Ordway disk with
// torque; the flux is the slab mean over x in [0.25D, 0.75D], just behind
// the disk (x in [-0.1D, 0.1D]). Tolerance 3%: the collocated momentum
// equation conserves angular momentum only to its discretization error. The
// slab fluxes further down are printed: on this grid the swirl's flux decays
// by about 0.5% per diameter in the core (-0.9% at 0.5D, -3.4% at 3D) and
// faster in the stretched cells beyond 4D, the scheme's dissipation of
// swirl, not the disk's.
TEST(ActuatorDiskStream, TorqueLeavesAsTheAngularMomentumFluxOfTheSwirl) {
  const std::vector<double> x = StretchedCoordinates(-3.0, -0.5, 4.0, 6.0, 0.125, 1.2);
  const std::vector<double> yz = StretchedCoordinates(-4.0, -0.625, 0.625, 4.0, 0.125, 1.2);
  const Mesh mesh = TensorMesh({x, yz, yz}, {PatchKind::kPatch, PatchKind::kPatch, PatchKind::kSymmetry,
                                             PatchKind::kSymmetry, PatchKind::kSymmetry, PatchKind::kSymmetry});
  const double U = 1.0, rho = 1.0;
  ActuatorDiskOptions o;
  o.diameter = 1.0;
  o.hub_ratio = 0.2;
  o.thickness = 0.2;
  o.axis = -Vector3::UnitX();
  const ActuatorDisk disk(mesh, o);
  ASSERT_NEAR(disk.mesh_share(), 1.0, 0.01);
  const double T = 0.5 * 0.5 * rho * disk.area() * U * U, Q = 0.05;  // C_Th = 0.5; Q / (T R) = 0.2
  auto solver = StreamSolver(mesh, U);
  std::vector<Vector3> source;
  disk.AddBodyForce(T, Q, rho, Eigen::Matrix3d::Identity(), source);
  solver->SetCellSource(source);
  MarchToSteady(*solver, U, 0.25, 1e-5, 600);
  // The torque on the water is +Q about the disk's axis (-x): about +x the
  // swirl carries -Q downstream.
  auto slab_flux = [&](double x0, double x1) {
    double f = 0.0;
    for (int c = 0; c < mesh.n_cells(); ++c) {
      const Vector3& xc = mesh.cell_centres()[c];
      if (xc.x() < x0 || xc.x() > x1) continue;
      const Vector3& u = solver->U()[c];
      f += rho * (xc.y() * u.z() - xc.z() * u.y()) * u.x() * mesh.cell_volumes()[c];
    }
    return f / (x1 - x0);
  };
  for (double x0 : {-1.0, 0.25, 1.0, 2.0, 3.0, 4.0}) {
    std::printf("actuator_disk swirl: flux over x in [%.2f, %.2f] D: %.5f N m\n", x0, x0 + 0.5, slab_flux(x0, x0 + 0.5));
  }
  EXPECT_NEAR(slab_flux(-1.0, -0.5), 0.0, 1e-3 * Q);  // no swirl upstream
  const double flux = slab_flux(0.25, 0.75);
  std::printf("actuator_disk swirl: angular momentum flux %.5f N m against -Q = %.5f N m (%+.2f%%), %d cells\n", flux,
              -Q, 100 * (flux / -Q - 1), mesh.n_cells());
  EXPECT_NEAR(flux / -Q, 1.0, 0.03);
}

// ---------------------------------------------------------------------------
// Open water in CFD



struct OpenWaterPoint {
  double J_true, J, K_T, K_T_true, error, U_disk, J_disk_momentum, cpu_s;
};

// The propeller at n = 1/s, D = 1 in the stream U = J_true n D, coupled
// after every outer iteration until steady. No torque: the quarter
// domain's symmetry planes cannot carry swirl.
OpenWaterPoint OpenWater(int grid, double J_true) {
  const Mesh mesh = FamilyGrid(grid);
  const double n = 1.0, rho = 1.0, U = J_true * n;
  PropellerOptions po;
  po.apply_torque = false;
  po.mesh_share = 0.25;
  po.thrust_relaxation = 0.5;
  Propeller prop(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505(), po);
  auto solver = StreamSolver(mesh, U);
  PropellerState last;
  std::vector<Vector3> source;
  solver->SetOuterIterationHook([&](int) {
    source.assign(mesh.n_cells(), Vector3::Zero());
    last = prop.Update(*solver, nullptr, Eigen::Matrix3d::Identity(), n, rho, source);
    solver->SetCellSource(source);
  });
  const auto start = std::clock();
  MarchToSteady(*solver, U, 0.25 / U, 1e-5, 600);
  OpenWaterPoint p;
  p.cpu_s = double(std::clock() - start) / CLOCKS_PER_SEC;
  p.J_true = J_true;
  p.J = last.J;
  p.K_T = last.K_T;
  p.K_T_true = prop.curve().KT(J_true);
  p.error = p.K_T / p.K_T_true - 1.0;
  p.U_disk = last.U_disk;
  PropellerOptions closed = po;  // same share
  closed.correction = PropellerOptions::InflowCorrection::kDiskMomentum;
  const Propeller other(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505(), closed);
  p.J_disk_momentum = other.EffectiveInflow(last.U_disk, last.T, rho) / (n * 1.0);
  std::printf("actuator_disk open_water grid %d J_true %.2f: U_disk/U = %.4f, J = %.4f, K_T = %.5f (K_T(J_true) = "
              "%.5f): error %+.2f%%; the closed-form (disk momentum) correction would give J = %.4f, K_T error "
              "%+.2f%%; %.1f CPU s\n",
              grid, J_true, p.U_disk / U, p.J, p.K_T, p.K_T_true, 100 * p.error, p.J_disk_momentum,
              100 * (prop.curve().KT(p.J_disk_momentum) / p.K_T_true - 1), p.cpu_s);
  return p;
}

// On the medium grid of the family (11 cells across D; the coarse one has
// 8, below the disk's recommended 10, and misses 2% by 4%: see BENCHMARKS
// actuator_disk). KELVIN_ACTUATOR_DISK_OPEN_WATER_GRID picks another.
TEST(PropellerOpenWater, RecoversKTAtThreeJ) {
  const char* grid = std::getenv("KELVIN_ACTUATOR_DISK_OPEN_WATER_GRID");
  for (double J : {0.6, 0.7, 0.8}) {
    const OpenWaterPoint p = OpenWater(grid ? std::atoi(grid) : 1, J);
    EXPECT_NEAR(p.error, 0.0, 0.02) << "J_true = " << J;
  }
}

// ---------------------------------------------------------------------------
// The induced-velocity correction and the restart state

// Momentum theory forwards (U_A, T -> U_disk = U_A + u_a) and back.
TEST(PropellerInflow, InvertsMomentumTheory) {
  const Mesh mesh = UniformBox(20);
  ActuatorDiskOptions o = HoughOrdwayDisk();
  o.hub_ratio = 0.0;
  o.distribution = ActuatorDiskOptions::Distribution::kUniform;
  const double rho = 1025.0, U_A = 1.3;
  for (auto correction : {PropellerOptions::InflowCorrection::kAnnularMomentum,
                          PropellerOptions::InflowCorrection::kDiskMomentum}) {
    PropellerOptions po;
    po.correction = correction;
    const Propeller prop(ActuatorDisk(mesh, o), Kp505(), po);
    for (double C_T : {0.1, 1.0, 3.0}) {
      const double T = C_T * 0.5 * rho * prop.disk().area() * U_A * U_A;
      const double U_disk = U_A + 0.5 * U_A * (std::sqrt(1.0 + C_T) - 1.0);
      if (correction == PropellerOptions::InflowCorrection::kDiskMomentum) {
        EXPECT_NEAR(prop.EffectiveInflow(U_disk, T, rho), U_A, 1e-12 * U_A) << C_T;
      } else {
        // Uniform loading without hub: the annular form is the closed form
        // with the area the cells carry (the sampled disk, 0.1% from A).
        const double A_cells = prop.disk().discrete_volume() / o.thickness;
        EXPECT_NEAR(A_cells / prop.disk().area(), 1.0, 1e-3);
        EXPECT_NEAR(prop.EffectiveInflow(U_disk, T, rho), U_disk - T / (2 * rho * A_cells * U_disk), 1e-12 * U_A)
            << C_T;
      }
    }
  }
}

// The Hough-Ordway disk: the annular correction removes more than the
// closed form (the thrust-weighted induced velocity is T / (2 rho U A_eff),
// A_eff < A), and both remove nothing at zero thrust.
TEST(PropellerInflow, AnnularCorrectionForHoughOrdway) {
  const Mesh mesh = UniformBox(20);
  PropellerOptions annular, closed;
  closed.correction = PropellerOptions::InflowCorrection::kDiskMomentum;
  const Propeller a(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505(), annular);
  const Propeller c(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505(), closed);
  EXPECT_NEAR(a.EffectiveInflow(1.2, 0.0, 1.0), 1.2, 1e-14);
  EXPECT_NEAR(c.EffectiveInflow(1.2, 0.0, 1.0), 1.2, 1e-14);
  EXPECT_LT(a.EffectiveInflow(1.2, 0.3, 1.0), c.EffectiveInflow(1.2, 0.3, 1.0));
}


TEST(PropellerState, RestoredStateRepeatsUpdatesBitForBit) {
  const Mesh mesh = UniformBox(20);
  PropellerOptions po;
  po.thrust_relaxation = 0.6;
  Propeller prop(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505(), po);
  auto solver = UniformFlow(mesh, 0.8);
  std::vector<Vector3> s1, s2;
  prop.Update(*solver, nullptr, Eigen::Matrix3d::Identity(), 1.2, 1.0, s1);
  const Propeller::State saved = prop.GetState();
  s1.clear();
  const PropellerState a = prop.Update(*solver, nullptr, Eigen::Matrix3d::Identity(), 1.2, 1.0, s1);
  prop.SetState(saved);
  const PropellerState b = prop.Update(*solver, nullptr, Eigen::Matrix3d::Identity(), 1.2, 1.0, s2);
  EXPECT_EQ(a.T, b.T);
  EXPECT_EQ(a.Q, b.Q);
  EXPECT_EQ(a.J, b.J);
  EXPECT_EQ(a.U_A, b.U_A);
  EXPECT_EQ(s1, s2);
  // The body velocity is subtracted: a disk moving with the water sees no
  // flow through it.
  auto moving = [](int) { return Vector3(0.8, 0, 0); };
  EXPECT_THROW(prop.Update(*solver, moving, Eigen::Matrix3d::Identity(), 1.2, 1.0, s2), ConfigError);
}

TEST(PropellerState, FixedLoadAppliesThePrescribedLoad) {
  const Mesh mesh = UniformBox(20);
  Propeller prop(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505());
  auto solver = UniformFlow(mesh, 0.8);
  std::vector<Vector3> source;
  const PropellerState s = prop.UpdateFixedLoad(*solver, nullptr, Eigen::Matrix3d::Identity(), 5.0, 0.7, 1.0, source);
  solver->SetCellSource(source);
  const Sums sums = IntegrateSource(*solver, mesh, Vector3::Zero(), -Vector3::UnitX(), 1.0);
  EXPECT_NEAR(sums.axial, -5.0, 1e-12);
  EXPECT_NEAR(sums.torque, 0.7, 1e-12);
  EXPECT_NEAR(s.U_disk, 0.8, 1e-12);
  EXPECT_LT(s.U_A, s.U_disk);
  EXPECT_EQ(prop.GetState().thrust, 5.0);
}

}  // namespace
}  // namespace kelvin::cfd
