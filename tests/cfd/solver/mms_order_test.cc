// Order of accuracy by the method of manufactured solutions: steady
// Navier-Stokes with the exact solution
//   u = (1 + x^2) cos(pi y),  v = -(2 x / pi) sin(pi y),  p = cos(pi x) cos(pi y)
// (divergence free; its convection term is not a gradient, so velocity and
// pressure are coupled) and the matching momentum source, on the unit square
// (one cell thick, empty front and back), Dirichlet velocity from the exact
// solution, zero-gradient pressure (dp/dn = 0 on the walls for this p).
// The observed order of the velocity error between the two finest grids must
// be at least 1.8 on (a) uniform, (b) randomly perturbed and (c) polyhedral
// meshes (median-dual cells, and the 2:1 split-face cells of refinement
// interfaces).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "cfd/mesh/box_mesh.h"
#include "cfd/mesh/dual_mesh.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNu = 0.2;

Vector3 ExactU(const Vector3& x) {
  return Vector3((1 + x.x() * x.x()) * std::cos(kPi * x.y()), -(2 * x.x() / kPi) * std::sin(kPi * x.y()), 0.0);
}
double ExactP(const Vector3& x) { return std::cos(kPi * x.x()) * std::cos(kPi * x.y()); }

// s = (u . grad) u + grad p - nu lap u.
Vector3 Source(const Vector3& p, double) {
  const double x = p.x(), y = p.y();
  const double s = std::sin(kPi * y), c = std::cos(kPi * y);
  const double fx = 2 * x * (1 + x * x) - kPi * std::sin(kPi * x) * c - kNu * c * (2 - kPi * kPi * (1 + x * x));
  const double fy = s * c * (2 * x * x - 2) / kPi - kPi * std::cos(kPi * x) * s - kNu * 2 * kPi * x * s;
  return Vector3(fx, fy, 0.0);
}

struct MmsResult {
  double h = 0.0;
  double error_u = 0.0;  // volume-weighted RMS of |u - u_exact|
  double error_p = 0.0;
};

Mesh MakeMesh(int n, double perturbation, bool polyhedral, bool dual) {
  if (dual) {
    DualMeshOptions o;
    o.divisions = {n, n, 1};
    o.max = Vector3(1.0, 1.0, 0.1);
    o.perturbation = perturbation;
    o.seed = 7 + n;
    o.kinds[4] = o.kinds[5] = PatchKind::kEmpty;
    return MakeDualMesh(o);
  }
  BoxMeshOptions mo;
  mo.cells = {n, n, 1};
  mo.max = Vector3(1.0, 1.0, 0.1);
  mo.perturbation = perturbation;
  mo.polyhedral = polyhedral;
  mo.seed = 7 + n;
  mo.kinds[4] = mo.kinds[5] = PatchKind::kEmpty;
  return MakeBoxMesh(mo);
}

MmsResult SolveMms(int n, double perturbation, bool polyhedral, GradientScheme gradient, bool dual, bool face_centre) {
  const Mesh mesh = MakeMesh(n, perturbation, polyhedral, dual);
  auto U = testing::MakeField<Vector3>("U", mesh, [](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
    if (p.kind == PatchKind::kEmpty) return std::make_unique<Empty<Vector3>>();
    return std::make_unique<FixedValue<Vector3>>(ValueFunction<Vector3>([](const Vector3& x, double) { return ExactU(x); }));
  });
  auto p = testing::MakeField<double>("p", mesh, [](const Patch&) -> std::unique_ptr<BoundaryCondition<double>> {
    return std::make_unique<ZeroGradient<double>>();
  });
  PhysicsOptions physics;
  physics.nu = kNu;
  physics.source = Source;
  SchemeOptions schemes;
  schemes.convection = ConvectionScheme::kLinearUpwind;
  schemes.gradient.scheme = gradient;
  schemes.skew_correction = perturbation > 0 || polyhedral || dual;
  schemes.face_centre_correction = face_centre;
  PimpleOptions pimple;
  pimple.n_outer = 1;
  pimple.n_correctors = 2;
  // The lagged correction (0 extra solves) is unstable on the 2:1 polyhedral
  // mesh; iterating it within each corrector is not.
  pimple.n_non_orthogonal = polyhedral ? 2 : (perturbation > 0 || dual ? 1 : 0);
  pimple.momentum_solver.relative_tolerance = 1e-10;
  pimple.pressure_solver.relative_tolerance = 1e-8;
  pimple.pressure_final_relative_tolerance = 1e-10;
  PimpleSolver solver(mesh, physics, schemes, pimple, std::move(U), std::move(p));
  // Courant number about 2 on the hex meshes, 1 on the polyhedral ones (the
  // lagged non-orthogonal correction is unstable there at Courant 2). The
  // steady state does not depend on dt (transient-consistent Rhie-Chow).
  const double dt = polyhedral ? 0.25 / n : 1.0 / n;
  double change = 1.0;
  int steps = 0;
  while (change > 1e-10 && steps < 3000) {
    const std::vector<Vector3> before = solver.U().values();
    const StepSummary s = solver.Step(dt);
    EXPECT_TRUE(s.finite);
    if (!s.finite) break;
    change = 0.0;
    for (int c = 0; c < mesh.n_cells(); ++c) change = std::max(change, (solver.U()[c] - before[c]).norm());
    ++steps;
  }
  EXPECT_LT(change, 1e-9) << "not converged to a steady state";
  MmsResult r;
  r.h = std::sqrt(1.0 / mesh.n_cells());
  double vol = 0.0, eu = 0.0, ep = 0.0, p_mean = 0.0, p_exact_mean = 0.0;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const double v = mesh.cell_volumes()[c];
    p_mean += v * solver.p()[c];
    p_exact_mean += v * ExactP(mesh.cell_centres()[c]);
    vol += v;
  }
  p_mean /= vol;
  p_exact_mean /= vol;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const double v = mesh.cell_volumes()[c];
    eu += v * (solver.U()[c] - ExactU(mesh.cell_centres()[c])).squaredNorm();
    const double dp = (solver.p()[c] - p_mean) - (ExactP(mesh.cell_centres()[c]) - p_exact_mean);
    ep += v * dp * dp;
  }
  r.error_u = std::sqrt(eu / vol);
  r.error_p = std::sqrt(ep / vol);
  std::printf("  n %3d cells %6d steps %4d  |e_u| %.4e  |e_p| %.4e\n", n, mesh.n_cells(), steps, r.error_u,
              r.error_p);
  return r;
}

double ObservedOrder(const MmsResult& coarse, const MmsResult& fine) {
  return std::log(coarse.error_u / fine.error_u) / std::log(coarse.h / fine.h);
}

void CheckOrder(const char* label, double perturbation, bool polyhedral, GradientScheme gradient,
                std::array<int, 3> sizes, bool dual = false, bool face_centre = false) {
  std::printf("%s\n", label);
  std::array<MmsResult, 3> r;
  for (int i = 0; i < 3; ++i) r[i] = SolveMms(sizes[i], perturbation, polyhedral, gradient, dual, face_centre);
  for (std::size_t i = 1; i < r.size(); ++i) {
    std::printf("  observed order %.3f (velocity), %.3f (pressure)\n", ObservedOrder(r[i - 1], r[i]),
                std::log(r[i - 1].error_p / r[i].error_p) / std::log(r[i - 1].h / r[i].h));
  }
  EXPECT_GE(ObservedOrder(r[1], r[2]), 1.8) << label;
}

TEST(MmsOrder, UniformHex) {
  CheckOrder("uniform hex, Gauss gradients", 0.0, false, GradientScheme::kGaussLinear, {16, 32, 64});
}

TEST(MmsOrder, PerturbedHex) {
  CheckOrder("randomly perturbed hex (20% of h), least-squares gradients", 0.2, false, GradientScheme::kLeastSquares,
             {16, 32, 64});
}

TEST(MmsOrder, PolyhedralMedianDual) {
  CheckOrder("polyhedral (median-dual polygonal prisms, vertices perturbed 15%), least-squares gradients", 0.15,
             false, GradientScheme::kLeastSquares, {16, 32, 64}, true);
}

// The 2:1 split-face mesh (every other block refined, as snappyHexMesh
// writes refinement interfaces): the owner-neighbour line misses the face
// centre by a quarter cell. With the interpolated non-orthogonal correction
// and least-squares gradients the velocity error stalled (9.3e-3, 3.8e-3,
// 2.9e-3 on 160, 640, 2560 cells: orders 1.29, 0.39): a smooth, nearly
// solid-body error in the interior, with a coarse/fine pressure oscillation
// that fell only as h. The face-centre form of the correction alone gave
// orders 1.84, 0.59; with Gauss gradients as well, second order.
// Pressure orders here are about 1.3, below the 1.5 of issue 22 (open).
TEST(MmsOrder, PolyhedralSplitFace) {
  CheckOrder("polyhedral (2:1 split-face cells), Gauss gradients, face-centre non-orthogonal correction", 0.0, true,
             GradientScheme::kGaussLinear, {8, 16, 32}, false, true);
}

}  // namespace
}  // namespace kelvin::cfd
