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
// interfaces) and on smoothly skewed hexahedra; that of the pressure error at
// least 1.5 on the uniform, smoothly skewed and median-dual meshes (issue 22;
// on the randomly perturbed and split-face meshes it is about 1.0 and 1.3,
// open).
//
// MmsTruncation measures the truncation error of the Laplacian itself, the
// discrete operator applied to the exact field against its analytic value:
// second order on uniform and smoothly skewed hexahedra, O(1) on the kinked
// faces of the median-dual cells unless the curvature correction
// (cfd/fv/diffusion_curvature.h) adds the face's second-order terms. The
// pressure takes up the gradient part of such an O(1) error (it fell no
// faster than O(1) on the median-dual meshes before the correction).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "cfd/fv/diffusion_curvature.h"
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

// The mesh under the smooth map x + a (sin(2 pi y) sin(pi x), sin(2 pi x) sin(pi y)):
// skewed, non-orthogonal cells that stay smooth under refinement (the
// square's sides stay where they are).
Mesh SmoothlyMapped(const Mesh& mesh, double a) {
  std::vector<Vector3> points = mesh.points();
  for (Vector3& x : points) {
    const double px = x.x(), py = x.y();
    x.x() = px + a * std::sin(2 * kPi * py) * std::sin(kPi * px);
    x.y() = py + a * std::sin(2 * kPi * px) * std::sin(kPi * py);
  }
  std::vector<std::vector<int>> faces;
  for (int f = 0; f < mesh.n_faces(); ++f) faces.emplace_back(mesh.face(f).begin(), mesh.face(f).end());
  return Mesh(std::move(points), std::move(faces), std::vector<int>(mesh.owner().begin(), mesh.owner().end()),
              std::vector<int>(mesh.neighbour().begin(), mesh.neighbour().end()), mesh.patches(), "mapped");
}

MmsResult SolveMms(int n, double perturbation, bool polyhedral, GradientScheme gradient, bool dual, bool face_centre,
                   bool curvature, double map, int correctors) {
  const Mesh mesh = map > 0.0 ? SmoothlyMapped(MakeMesh(n, perturbation, polyhedral, dual), map)
                              : MakeMesh(n, perturbation, polyhedral, dual);
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
  const bool skewed = perturbation > 0 || polyhedral || dual || map > 0.0;
  schemes.skew_correction = skewed;
  schemes.face_centre_correction = face_centre;
  schemes.curvature_correction = curvature;
  PimpleOptions pimple;
  pimple.n_outer = 1;
  pimple.n_correctors = correctors;
  // The lagged correction (0 extra solves) is unstable on the 2:1 polyhedral
  // mesh; iterating it within each corrector is not.
  pimple.n_non_orthogonal = polyhedral ? 2 : (skewed ? 1 : 0);
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

double ObservedOrder(double coarse_error, double fine_error, double coarse_h, double fine_h) {
  return std::log(coarse_error / fine_error) / std::log(coarse_h / fine_h);
}

struct MeshChoice {
  double perturbation = 0.0;
  bool polyhedral = false;  // 2:1 split faces
  bool dual = false;        // median-dual polygonal prisms
  bool face_centre = false;
  bool curvature = false;
  double map = 0.0;        // amplitude of SmoothlyMapped (0: none)
  int correctors = 2;      // PISO
  double min_pressure_order = 0.0;  // 0: reported, not asserted
};

void CheckOrder(const char* label, GradientScheme gradient, std::array<int, 3> sizes, const MeshChoice& m) {
  std::printf("%s\n", label);
  std::array<MmsResult, 3> r;
  for (int i = 0; i < 3; ++i) {
    r[i] = SolveMms(sizes[i], m.perturbation, m.polyhedral, gradient, m.dual, m.face_centre, m.curvature, m.map,
                    m.correctors);
  }
  auto order_u = [&](int i) { return ObservedOrder(r[i - 1].error_u, r[i].error_u, r[i - 1].h, r[i].h); };
  auto order_p = [&](int i) { return ObservedOrder(r[i - 1].error_p, r[i].error_p, r[i - 1].h, r[i].h); };
  for (int i = 1; i < 3; ++i) std::printf("  observed order %.3f (velocity), %.3f (pressure)\n", order_u(i), order_p(i));
  EXPECT_GE(order_u(2), 1.8) << label;
  if (m.min_pressure_order > 0.0) {
    EXPECT_GE(order_p(2), m.min_pressure_order) << label;
  }
}

TEST(MmsOrder, UniformHex) {
  CheckOrder("uniform hex, Gauss gradients", GradientScheme::kGaussLinear, {16, 32, 64},
             {.min_pressure_order = 1.5});
}

// Smoothly skewed hexahedra (SmoothlyMapped, amplitude 0.04: non-orthogonal
// up to 28 degrees), the grid family a refinement study assumes (the random
// perturbation of PerturbedHex is drawn anew on every grid). With the two
// PISO correctors of the other tests the run diverged on the finest grid
// (and took 1646 steps on the middle one) for every scheme variant tried
// (skew or non-orthogonal correction off, upwind, Gauss gradients); with four
// it converges at the same cost as on the other meshes.
TEST(MmsOrder, SmoothlySkewedHex) {
  CheckOrder("smoothly mapped hex (non-orthogonality up to 28 deg), least-squares gradients, 4 PISO correctors",
             GradientScheme::kLeastSquares, {16, 32, 64}, {.map = 0.04, .correctors = 4, .min_pressure_order = 1.5});
}

// Where the pressure order of this mesh and of the split-face one below is
// lost (measured 2026-12-06 with oracles in the solver, not kept): the error
// is a grid-scale pattern (cell to cell here, coarse against fine cells on
// split faces) whose interior part also falls at about first order. Exact
// velocity Hessians in the curvature correction (pressure orders 1.35, 1.10
// here; 1.33, 1.28 on split faces), a cell pressure gradient made exact on the
// exact field (1.40, 1.09; 1.52, 1.37), the pressure Laplacian corrected to the
// face centre with exact Hessians (1.35, 1.10; 1.36, 1.30) and the time step
// (x4 and x0.1: 1.34, 1.26 and 1.31, 1.25 on split faces) leave it. What
// remains is consistent with the Rhie-Chow term pinning grid-scale pressure
// modes with a strength of O(rAU) = O(h^2 / nu): a continuity truncation that
// is O(h) on irregular cells then leaves an O(h) pressure pattern.
TEST(MmsOrder, PerturbedHex) {
  CheckOrder("randomly perturbed hex (20% of h), least-squares gradients", GradientScheme::kLeastSquares,
             {16, 32, 64}, {.perturbation = 0.2});
}

// Without the curvature correction the pressure orders here were 0.73 and
// 0.48 (error 1.31e-2, 8.07e-3, 5.83e-3), the velocity's 1.88 and 1.95.
TEST(MmsOrder, PolyhedralMedianDual) {
  CheckOrder(
      "polyhedral (median-dual polygonal prisms, vertices perturbed 15%), least-squares gradients, curvature "
      "correction",
      GradientScheme::kLeastSquares, {16, 32, 64},
      {.perturbation = 0.15, .dual = true, .curvature = true, .min_pressure_order = 1.5});
}

// The 2:1 split-face mesh (every other block refined, as snappyHexMesh
// writes refinement interfaces): the owner-neighbour line misses the face
// centre by a quarter cell. With the interpolated non-orthogonal correction
// and least-squares gradients the velocity error stalled (9.3e-3, 3.8e-3,
// 2.9e-3 on 160, 640, 2560 cells: orders 1.29, 0.39): a smooth, nearly
// solid-body error in the interior, with a coarse/fine pressure oscillation
// that fell only as h. The face-centre form of the correction alone gave
// orders 1.84, 0.59; with Gauss gradients as well, second order.
// Pressure orders here are about 1.3, below the 1.5 of issue 22 (open). The
// curvature correction does not help in the solver: velocity orders 1.60 and
// 0.98 with Gauss gradients (face-centre form), 2.14 and 0.83 with least
// squares, as the cell gradients and their Hessians are not accurate enough
// on these cells; with exact Hessians it does its part
// (MmsTruncation.CurvatureTensorsOfSplitFaces).
TEST(MmsOrder, PolyhedralSplitFace) {
  CheckOrder("polyhedral (2:1 split-face cells), Gauss gradients, face-centre non-orthogonal correction",
             GradientScheme::kGaussLinear, {8, 16, 32}, {.polyhedral = true, .face_centre = true});
}

// ---------------------------------------------------------------- truncation

// Analytic Laplacian, gradient (J(i, j) = du_i/dx_j) and component Hessians
// of ExactU.
Vector3 ExactLaplacianU(const Vector3& x) {
  const double c = std::cos(kPi * x.y()), s = std::sin(kPi * x.y());
  return Vector3(2 * c - kPi * kPi * (1 + x.x() * x.x()) * c, 2 * kPi * x.x() * s, 0.0);
}
Matrix3 ExactGradU(const Vector3& x) {
  const double c = std::cos(kPi * x.y()), s = std::sin(kPi * x.y());
  Matrix3 j = Matrix3::Zero();
  j(0, 0) = 2 * x.x() * c;
  j(0, 1) = -kPi * (1 + x.x() * x.x()) * s;
  j(1, 0) = -(2 / kPi) * s;
  j(1, 1) = -2 * x.x() * c;
  return j;
}
std::array<Matrix3, 3> ExactHessiansU(const Vector3& x) {
  const double c = std::cos(kPi * x.y()), s = std::sin(kPi * x.y());
  std::array<Matrix3, 3> h{Matrix3::Zero(), Matrix3::Zero(), Matrix3::Zero()};
  h[0](0, 0) = 2 * c;
  h[0](0, 1) = h[0](1, 0) = -2 * kPi * x.x() * s;
  h[0](1, 1) = -kPi * kPi * (1 + x.x() * x.x()) * c;
  h[1](0, 1) = h[1](1, 0) = -2 * c;
  h[1](1, 1) = 2 * kPi * x.x() * s;
  return h;
}

enum class Derivatives { kLeastSquares, kExact };
enum class Curvature { kOff, kOn };

// RMS over the cells at least 0.2 from the walls of the Laplacian of the
// exact velocity (cell-centre values; the gradients of the non-orthogonal
// part and the Hessians of the curvature correction by least squares or
// exact) less its analytic value: the truncation error.
double LaplacianTruncation(const Mesh& mesh, Curvature curvature, Derivatives derivatives = Derivatives::kLeastSquares,
                           NonOrthogonalForm form = NonOrthogonalForm::kInterpolated) {
  auto U = testing::MakeField<Vector3>("U", mesh, [](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
    if (p.kind == PatchKind::kEmpty) return std::make_unique<Empty<Vector3>>();
    return std::make_unique<FixedValue<Vector3>>(ValueFunction<Vector3>([](const Vector3& x, double) { return ExactU(x); }));
  });
  for (int c = 0; c < mesh.n_cells(); ++c) U->values()[c] = ExactU(mesh.cell_centres()[c]);
  U->CorrectBoundary(0.0, std::vector<double>(mesh.n_faces(), 0.0));
  GradientOptions options;
  options.scheme = GradientScheme::kLeastSquares;
  const Gradient gradient(mesh, options);
  std::vector<Matrix3> grad(mesh.n_cells());
  std::array<std::vector<Matrix3>, 3> hessians;
  if (derivatives == Derivatives::kExact) {
    for (auto& h : hessians) h.resize(mesh.n_cells());
    for (int c = 0; c < mesh.n_cells(); ++c) {
      grad[c] = ExactGradU(mesh.cell_centres()[c]);
      const std::array<Matrix3, 3> h = ExactHessiansU(mesh.cell_centres()[c]);
      for (int i = 0; i < 3; ++i) hessians[i][c] = h[i];
    }
  } else {
    gradient.Compute(std::span<const Vector3>(U->values()), std::span<const Vector3>(U->boundary()), grad);
    hessians = ComponentHessians(gradient, grad);
  }
  const NonOrthGeometry geo(mesh, form);
  FvMatrix<Vector3> m(mesh);
  AddLaplacian(m, *U, 1.0, geo, &grad);
  if (curvature == Curvature::kOn) AddDiffusionCurvature(m, 1.0, DiffusionCurvatureTensors(mesh, geo, FaceFirstMoments(mesh)), hessians);
  const std::vector<double> A = m.A();
  const std::vector<Vector3> H = m.H(std::span<const Vector3>(U->values()));
  double sum = 0.0, volume = 0.0;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const Vector3& x = mesh.cell_centres()[c];
    if (std::min({x.x(), x.y(), 1 - x.x(), 1 - x.y()}) < 0.2) continue;
    const Vector3 minus_laplacian = A[c] * U->values()[c] - H[c];
    sum += mesh.cell_volumes()[c] * (minus_laplacian + ExactLaplacianU(x)).squaredNorm();
    volume += mesh.cell_volumes()[c];
  }
  return std::sqrt(sum / volume);
}

// Order of the truncation error between n and 2n (the mesh's h halves).
template <typename MakeMeshAt, typename Truncation>
double TruncationOrder(const char* label, int n, MakeMeshAt make, Truncation truncation) {
  const double coarse = truncation(make(n)), fine = truncation(make(2 * n));
  std::printf("%s: Laplacian truncation %.4e (n %d), %.4e (n %d)\n", label, coarse, n, fine, 2 * n);
  return std::log(coarse / fine) / std::log(2.0);
}

TEST(MmsTruncation, LaplacianIsSecondOrderOnUniformAndSmoothlySkewedHexahedra) {
  auto plain = [](const Mesh& mesh) { return LaplacianTruncation(mesh, Curvature::kOff); };
  EXPECT_GE(TruncationOrder("uniform hex", 64, [](int n) { return MakeMesh(n, 0.0, false, false); }, plain), 1.9);
  // Non-orthogonality up to 28 degrees.
  EXPECT_GE(TruncationOrder("mapped hex", 64,
                            [](int n) { return SmoothlyMapped(MakeMesh(n, 0.0, false, false), 0.04); }, plain),
            1.9);
}

// The median dual of a regular triangulation: every interior side face is
// kinked. Measured: 0.7322 at n 64 and 0.7266 at n 128 without the
// correction (order 0.01), 1.53e-3 and 3.80e-4 with it.
TEST(MmsTruncation, CurvatureCorrectionMakesTheLaplacianSecondOrderOnKinkedFaces) {
  auto dual = [](int n) { return MakeMesh(n, 0.0, false, true); };
  auto corrected = [](const Mesh& mesh) { return LaplacianTruncation(mesh, Curvature::kOn); };
  EXPECT_GE(TruncationOrder("median dual, curvature correction", 64, dual, corrected), 1.9);
  EXPECT_GT(LaplacianTruncation(dual(128), Curvature::kOff), 100.0 * corrected(dual(128)));
}

// The tensors of the 2:1 split faces (planar, their centres a quarter cell
// off the owner-neighbour line), in both non-orthogonal forms: with exact
// gradients and Hessians the corrected truncation falls at first order (the
// third derivatives are left), where the uncorrected one stays O(1) (2.21 and
// 1.01 at n 64). With least-squares Hessians of the exact gradients it also
// falls (1.75e-2 and 1.90e-2 at n 64); in the solver, whose own gradients
// feed them, it does not help (MmsOrder.PolyhedralSplitFace).
TEST(MmsTruncation, CurvatureTensorsOfSplitFaces) {
  auto split = [](int n) { return MakeMesh(n, 0.0, true, false); };
  for (NonOrthogonalForm form : {NonOrthogonalForm::kInterpolated, NonOrthogonalForm::kFaceCentre}) {
    auto exact = [form](const Mesh& mesh) {
      return LaplacianTruncation(mesh, Curvature::kOn, Derivatives::kExact, form);
    };
    EXPECT_GE(TruncationOrder("split faces, exact Hessians", 32, split, exact), 0.9);
    EXPECT_GT(LaplacianTruncation(split(64), Curvature::kOff, Derivatives::kExact, form), 40.0 * exact(split(64)));
  }
}

// The Rhie-Chow part of the correction takes the skew-corrected gradient:
// asked for without skew_correction, one error says so.
TEST(MmsTruncation, CurvatureCorrectionNeedsTheSkewCorrection) {
  const Mesh mesh = MakeMesh(4, 0.0, false, true);
  auto make = [&](bool skew) {
    SchemeOptions schemes;
    schemes.curvature_correction = true;
    schemes.skew_correction = skew;
    auto U = testing::MakeField<Vector3>("U", mesh, [](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
      if (p.kind == PatchKind::kEmpty) return std::make_unique<Empty<Vector3>>();
      return std::make_unique<FixedValue<Vector3>>(ValueFunction<Vector3>([](const Vector3& x, double) { return ExactU(x); }));
    });
    auto p = testing::MakeField<double>("p", mesh, [](const Patch&) -> std::unique_ptr<BoundaryCondition<double>> {
      return std::make_unique<ZeroGradient<double>>();
    });
    PimpleSolver solver(mesh, PhysicsOptions{}, schemes, PimpleOptions{}, std::move(U), std::move(p));
  };
  try {
    make(false);
    ADD_FAILURE() << "no error without skew_correction";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("schemes.curvature_correction: expected skew_correction true"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(make(true));
}

}  // namespace
}  // namespace kelvin::cfd
