// Acceptance 3 of issue 6: the steady Kelvin pattern of a pressure patch
// moving at speed U over deep water.
//
// Mesh-fixed frame: uniform inflow U along +x, so the mesh moves through the
// still water with u_b = -U and the pattern is advected with +U. The patch is
// a Gaussian p_a = P0 exp(-(x^2 + y^2) / r^2) at the origin (a Havelock
// pressure distribution), r = lambda / 4, P0 / g = 5 mm, lambda = 2 pi U^2 / g
// = 1 m. Half domain (symmetry at y = 0): x in [-1, 4] lambda, y in
// [0, 2.5] lambda, depth lambda / 2, beaches over 1.25 lambda at x = 4 lambda
// and y = 2.5 lambda. Pseudo-transient marching at a Courant number of 5 to
// the steady state; the slow variants refine to 24 faces per wavelength and
// march at Courant 100 (see linearized_free_surface.h on large Courant
// numbers).
//
// Checks, against 2 pi U^2 / g and against the exact linear solution for the
// same patch and depth (PressurePatchWaves) sampled at the same faces:
// - transverse wavelength along the track behind the patch (zero crossings
//   between 0.75 and 2.75 lambda) within 3% of 2 pi U^2 / g;
// - the Kelvin wedge: the angular distribution of the wave energy between
//   1.5 and 2.75 wavelengths from the patch matches the exact solution's,
//   which at this distance still spreads a few degrees beyond 19.47 deg (the
//   Airy tail of the cusp caustic) and narrows with distance toward it;
// - wave amplitude behind the patch against the exact peak;
// - no waves upstream: ahead of the patch eta decays without a zero crossing
//   and stays small.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "cfd/verification/steady_waves.h"
#include "tests/cfd/freesurface/free_surface_test_support.h"

namespace kelvin::cfd {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;
constexpr double kLambda = 1.0;  // transverse wavelength 2 pi U^2 / g, m

// What the checks measure on one steady pattern, the computed one or the
// exact linear solution sampled at the same face centres.
struct PatternMeasures {
  double wavelength = 0.0;  // m, from the centreline crossings
  int crossings = 0;
  double angle95[2] = {0, 0};  // deg, angle holding 95% of eta^2 dA for r in [1.5 | 2.0, 2.75] lambda
  double beyond_wedge = 0.0;     // fraction of eta^2 dA (r in [1.5, 2.75] lambda) beyond 19.47 deg
  double beyond_wedge_10 = 0.0;  // ... beyond 29.47 deg
  double peak = 0.0;             // m, max |eta| behind the patch (x > lambda / 2)
  double max_upstream = 0.0;     // m, max |eta| on the centreline for x < -3 r
  bool upstream_monotone = true;  // centreline for x < -2 r: one sign, |eta| growing toward the patch
};

struct KelvinResult {
  PatternMeasures computed;
  PatternMeasures exact;  // PressurePatchWaves at the face centres
  double change = 0.0;    // max |eta change| over the last step / max |eta|
  int steps = 0;
};

struct KelvinRun {
  int cells_per_lambda = 16;  // surface faces per transverse wavelength
  double courant = 5.0;       // pseudo-time step U dt / dx
  int max_steps = 200;
  double tolerance = 3e-4;  // steady: max |d eta| / max |eta| per step
  int n_outer = 2;
  bool relax = false;  // U 0.7, p 0.3 in the non-final outer correctors
  double kinematic_courant = 0.0;
};

// Measures of the pattern `eta` on the faces of `fs` (spacing dx, inlet at
// x_inlet): centreline wavelength, peak, upstream decay and the angular
// distribution of wave energy.
PatternMeasures Measure(const LinearizedFreeSurface& fs, const std::vector<double>& eta, double dx,
                        double x_inlet) {
  constexpr double kRadius = 0.25 * kLambda;  // the patch
  PatternMeasures m;
  // Centreline: the first row of faces (y = dx / 2).
  const auto& x = fs.surface().centres();
  std::vector<std::pair<double, double>> line;
  for (int i = 0; i < fs.surface().size(); ++i) {
    if (x[i].y() < dx) line.emplace_back(x[i].x(), eta[i]);
  }
  std::sort(line.begin(), line.end());
  std::vector<double> crossings;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const auto [x0, e0] = line[i];
    const auto [x1, e1] = line[i + 1];
    if (x0 >= 0.75 * kLambda && x1 <= 2.75 * kLambda && e0 * e1 < 0.0) {
      crossings.push_back(x0 + (x1 - x0) * e0 / (e0 - e1));
    }
  }
  m.crossings = static_cast<int>(crossings.size());
  if (crossings.size() >= 2) {
    m.wavelength =
        2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  }
  for (int i = 0; i < fs.surface().size(); ++i) {
    if (x[i].x() > 0.5 * kLambda) m.peak = std::max(m.peak, std::abs(eta[i]));
  }
  // Upstream: the faces between the second face from the inlet and x = -2 r,
  // in the direction of the patch.
  double last = 0.0;
  for (const auto& [xc, e] : line) {
    if (xc < x_inlet + 1.5 * dx || xc > -2.0 * kRadius) continue;
    if (xc < -3.0 * kRadius) m.max_upstream = std::max(m.max_upstream, std::abs(e));
    if (last != 0.0 && (e * last <= 0.0 || std::abs(e) < std::abs(last))) m.upstream_monotone = false;
    last = e;
  }
  // Kelvin wedge, by the distribution of wave energy (eta^2 dA) over the
  // angle from the track in the annulus 1.5 to 2.75 wavelengths from the
  // patch, before the beaches. In the far field every steady wave lies within
  // 19.47 deg; this close to the patch the caustic on the cusp line is an Airy
  // function whose tail still reaches a few degrees beyond the line, and
  // narrows with distance: the exact solution has the same spread.
  std::vector<double> along(x.size()), across(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    along[i] = x[i].x();
    across[i] = x[i].y();
  }
  for (int band = 0; band < 2; ++band) {
    const testing::WedgeSpread w = testing::MeasureWedgeSpread(
        along, across, fs.surface().areas(), fs.damping(), eta, (band == 0 ? 1.5 : 2.0) * kLambda, 2.75 * kLambda);
    m.angle95[band] = w.angle95;
    if (band == 0) {
      m.beyond_wedge = w.beyond_wedge;
      m.beyond_wedge_10 = w.beyond_wedge_10;
    }
  }
  return m;
}

KelvinResult RunKelvin(const KelvinRun& run) {
  const int cells_per_lambda = run.cells_per_lambda;
  const double U = std::sqrt(kG * kLambda / (2.0 * kPi));
  const double r_patch = 0.25 * kLambda;
  const double p0 = kG * 0.005;
  BoxMeshOptions mo;
  mo.min = Vector3(-1.0 * kLambda, 0.0, -0.5 * kLambda);
  mo.max = Vector3(4.0 * kLambda, 2.5 * kLambda, 0.0);
  mo.cells = {5 * cells_per_lambda, static_cast<int>(2.5 * cells_per_lambda), 12};
  mo.grading = {1.0, 1.0, 0.25};  // top cells four times thinner than the bottom ones
  mo.kinds[0] = mo.kinds[1] = PatchKind::kPatch;
  mo.kinds[2] = PatchKind::kSymmetry;
  Mesh mesh = MakeBoxMesh(mo);
  mesh.RenumberCells();

  LinearizedFreeSurfaceOptions fso;
  fso.g = kG;
  fso.mesh_velocity = [U](const Vector3&, double) { return Vector3(-U, 0.0, 0.0); };
  fso.surface_pressure = [p0, r_patch](const Vector3& x, double) {
    return p0 * std::exp(-(x.x() * x.x() + x.y() * x.y()) / (r_patch * r_patch));
  };
  fso.advection = LinearizedFreeSurfaceOptions::Advection::kQuick;
  fso.kinematic_courant = run.kinematic_courant;
  fso.beach.width = 1.25;
  fso.beach.strength = 1.0;
  fso.beach.reference_speed = U;
  fso.beach.sides = {LinearizedFreeSurfaceOptions::Beach::Side::kXMax,
                     LinearizedFreeSurfaceOptions::Beach::Side::kYMax};

  auto Uf = testing::MakeField<Vector3>(
      "U", mesh, [U](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
        if (p.name == "xmin") return std::make_unique<FixedValue<Vector3>>(Vector3(U, 0.0, 0.0));
        if (p.name == "xmax" || p.name == "zmax") return std::make_unique<ZeroGradient<Vector3>>();
        return std::make_unique<Slip>();
      });
  LinearizedFreeSurface* fs = nullptr;
  auto pf = testing::MakeField<double>(
      "p", mesh, [&](const Patch& patch) -> std::unique_ptr<BoundaryCondition<double>> {
        if (patch.name == "zmax") {
          auto bc = std::make_unique<LinearizedFreeSurface>(mesh, mesh.FindPatch("zmax"), fso);
          fs = bc.get();
          return bc;
        }
        if (patch.name == "xmax") return std::make_unique<FixedValue<double>>(0.0);
        return std::make_unique<ZeroGradient<double>>();
      });
  for (Vector3& u : Uf->values()) u = Vector3(U, 0.0, 0.0);
  PhysicsOptions physics;
  physics.nu = 1e-6;
  SchemeOptions schemes;
  schemes.convection = ConvectionScheme::kLinearUpwind;
  schemes.gradient.scheme = GradientScheme::kLeastSquares;
  PimpleOptions pimple;
  pimple.n_outer = run.n_outer;
  pimple.n_correctors = 2;
  if (run.relax) {
    pimple.relax_U = 0.7;
    pimple.relax_p = 0.3;
  }
  pimple.pressure_solver.relative_tolerance = 1e-4;
  pimple.pressure_final_relative_tolerance = 1e-6;
  PimpleSolver solver(mesh, physics, schemes, pimple, std::move(Uf), std::move(pf));

  const double dx = kLambda / cells_per_lambda;
  const double dt = run.courant * dx / U;
  // Pseudo-time marching until eta changes by less than `tolerance` of its
  // maximum in one step.
  KelvinResult res;
  res.change = 1.0;
  while (res.change > run.tolerance && res.steps < run.max_steps) {
    const std::vector<double> before = fs->eta();
    const StepSummary s = solver.Step(dt);
    EXPECT_TRUE(s.finite);
    if (!s.finite) return res;
    ++res.steps;
    double max_eta = 0.0, max_change = 0.0;
    for (std::size_t i = 0; i < before.size(); ++i) {
      max_eta = std::max(max_eta, std::abs(fs->eta()[i]));
      max_change = std::max(max_change, std::abs(fs->eta()[i] - before[i]));
    }
    res.change = max_change / max_eta;
    if (std::getenv("KELVIN_VERBOSE")) {
      std::printf("step %d Co %.2f max eta %.4e change %.2e p iters %d\n", res.steps, s.courant_max,
                  max_eta, res.change, s.pressure_iterations);
    }
  }

  const auto& x = fs->surface().centres();
  res.computed = Measure(*fs, fs->eta(), dx, mo.min.x());

  // The exact linear solution on the same face centres: the periodic FFT
  // grid has the face spacing and its node (0, 0) on the first face centre.
  PressurePatchWaveOptions exact;
  exact.g = kG;
  exact.speed = U;
  exact.depth = -mo.min.z();
  exact.radius = r_patch;
  exact.head = p0 / kG;
  exact.spacing = dx;
  exact.origin_x = mo.min.x() + 0.5 * dx;
  exact.origin_y = mo.min.y() + 0.5 * dx;
  const PressurePatchWaves waves(exact);
  std::vector<double> eta_exact(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) eta_exact[i] = waves.Elevation(x[i].x(), x[i].y());
  res.exact = Measure(*fs, eta_exact, dx, mo.min.x());

  if (std::getenv("KELVIN_VERBOSE")) {
    for (int i = 0; i < fs->surface().size(); ++i) {
      std::printf("surface %.5f %.5f %.6e %.6e\n", x[i].x(), x[i].y(), fs->eta()[i], eta_exact[i]);
    }
  }
  return res;
}

void Print(const PatternMeasures& m, const char* what) {
  std::printf(
      "  %s: transverse wavelength %.4f m from %d crossings (%+.2f%% against 2 pi U^2/g); peak %.3e m; "
      "95%% of the wave energy within %.1f deg (r 1.5-2.75 lambda) and %.1f deg (r 2-2.75 lambda); "
      "%.1f%% beyond 19.47 deg, %.2f%% beyond 29.47 deg; upstream max |eta| %.3f of the peak, %s\n",
      what, m.wavelength, m.crossings, 100.0 * (m.wavelength / kLambda - 1.0), m.peak, m.angle95[0],
      m.angle95[1], 100.0 * m.beyond_wedge, 100.0 * m.beyond_wedge_10, m.max_upstream / m.peak,
      m.upstream_monotone ? "monotone, one sign (no waves)" : "oscillating");
}

void CheckPattern(const KelvinResult& r, const char* label) {
  const PatternMeasures& c = r.computed;
  const PatternMeasures& e = r.exact;
  std::printf("%s after %d steps (last relative change %.1e):\n", label, r.steps, r.change);
  Print(c, "kelvin");
  Print(e, "exact linear solution");
  EXPECT_LT(r.change, 3e-4);
  EXPECT_GE(c.crossings, 4);
  EXPECT_LT(std::abs(c.wavelength / kLambda - 1.0), 0.03);
  // The wedge. The exact solution itself is not confined to 19.47 deg this
  // close to the patch (the Airy tail of the caustic; 18.7% of the energy
  // between 1.5 and 2.75 wavelengths), so the computed pattern is held to
  // the exact one: the energy's angular spread within 1.5 deg, the energy
  // beyond the Kelvin line within 4 points, and nearly nothing 10 deg beyond
  // it. The tolerances cover the phase error of a 16-faces-per-wavelength
  // grid (the wavelength itself is 2% long) at the short divergent waves
  // that carry the energy near the cusp line (2/3 of the transverse length).
  // In both, the spread narrows with distance toward the 19.47 deg limit.
  EXPECT_NEAR(c.angle95[0], e.angle95[0], 1.5);
  EXPECT_NEAR(c.angle95[1], e.angle95[1], 1.5);
  EXPECT_LT(c.angle95[1], c.angle95[0]);
  EXPECT_LT(e.angle95[1], e.angle95[0]);
  EXPECT_NEAR(c.beyond_wedge, e.beyond_wedge, 0.04);
  EXPECT_LT(c.beyond_wedge_10, 0.02);
  EXPECT_LT(e.beyond_wedge_10, 0.02);
  // Amplitude: the wave crests behind the patch lose 13% (16 faces per
  // wavelength) and 7% (24) of the exact peak to the damping of the upwinded
  // kinematic condition; the loss shrinks with the grid.
  EXPECT_NEAR(c.peak / e.peak, 1.0, 0.15);
  // No waves upstream, as in the exact solution.
  EXPECT_TRUE(e.upstream_monotone);
  EXPECT_TRUE(c.upstream_monotone);
  EXPECT_LT(c.max_upstream, 0.05 * c.peak);
}

// 16 faces per wavelength, Courant number 5 along the stream: about 100
// pseudo-time steps and 30-40 s.
TEST(KelvinPattern, TransverseWavelengthWedgeAndNoUpstreamWaves) {
  CheckPattern(RunKelvin(KelvinRun{}), "Kelvin pattern, 16 faces per wavelength");
}

// The same at 24 faces per wavelength: a few minutes, so it runs only as
// the `slow` test kelvin_pattern_fine_test (KELVIN_FREE_SURFACE_FINE=1).
TEST(KelvinPattern, FineGrid) {
  if (!std::getenv("KELVIN_FREE_SURFACE_FINE"))
    GTEST_SKIP() << "slow; set KELVIN_FREE_SURFACE_FINE=1";
  KelvinRun run;
  run.cells_per_lambda = 24;
  run.max_steps = 300;
  CheckPattern(RunKelvin(run), "Kelvin pattern, 24 faces per wavelength");
}

// Courant number 100 along the stream (about 120 at the largest cell):
// relaxed PIMPLE with 4 outer correctors and the kinematic pseudo-time step
// capped at Courant 2 reach the same steady pattern as Courant 5 (slow, with
// the fine grid).
TEST(KelvinPattern, CourantOneHundredReachesTheSameSteadyPattern) {
  if (!std::getenv("KELVIN_FREE_SURFACE_FINE"))
    GTEST_SKIP() << "slow; set KELVIN_FREE_SURFACE_FINE=1";
  const KelvinResult reference = RunKelvin(KelvinRun{});
  KelvinRun run;
  run.courant = 100.0;
  run.max_steps = 300;
  run.n_outer = 4;
  run.relax = true;
  run.kinematic_courant = 2.0;
  const KelvinResult r = RunKelvin(run);
  CheckPattern(r, "Kelvin pattern at Courant 100");
  std::printf(
      "Courant 100 against 5: wavelength %.5f against %.5f m (%+.3f%%), peak %.5e against %.5e m\n",
      r.computed.wavelength, reference.computed.wavelength,
      100.0 * (r.computed.wavelength / reference.computed.wavelength - 1.0), r.computed.peak,
      reference.computed.peak);
  EXPECT_NEAR(r.computed.wavelength / reference.computed.wavelength, 1.0, 0.002);
  EXPECT_NEAR(r.computed.peak / reference.computed.peak, 1.0, 0.01);
}

}  // namespace
}  // namespace kelvin::cfd
