// Lid-driven cavity on a 129 x 129 x 1 grid against Ghia, Ghia & Shin (1982):
// max |u - u_Ghia| and |v - v_Ghia| <= 0.02 (lid speed 1) over every tabulated
// point on the two centrelines.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "cfd/mesh/box_mesh.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd {
namespace {

struct CavityResult {
  double max_du = 0.0;
  double max_dv = 0.0;
  int steps = 0;
  double continuity = 0.0;
};

CavityResult RunCavity(double re, int n, double dt, int max_steps) {
  BoxMeshOptions mo;
  mo.cells = {n, n, 1};
  mo.max = Vector3(1.0, 1.0, 1.0 / n);
  mo.kinds[4] = mo.kinds[5] = PatchKind::kEmpty;
  Mesh mesh = MakeBoxMesh(mo);
  mesh.RenumberCells();
  auto U = testing::MakeField<Vector3>("U", mesh, [](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
    if (p.kind == PatchKind::kEmpty) return std::make_unique<Empty<Vector3>>();
    if (p.name == "ymax") return std::make_unique<FixedValue<Vector3>>(Vector3(1, 0, 0));
    return std::make_unique<FixedValue<Vector3>>(Vector3(0, 0, 0));
  });
  auto p = testing::MakeField<double>("p", mesh, [](const Patch&) -> std::unique_ptr<BoundaryCondition<double>> {
    return std::make_unique<ZeroGradient<double>>();
  });
  PhysicsOptions physics;
  physics.nu = 1.0 / re;
  SchemeOptions schemes;
  schemes.convection = ConvectionScheme::kLinearUpwind;
  PimpleOptions pimple;
  pimple.n_outer = 1;
  pimple.n_correctors = 2;
  pimple.momentum_solver.relative_tolerance = 1e-6;
  pimple.pressure_solver.relative_tolerance = 1e-4;
  pimple.pressure_final_relative_tolerance = 1e-6;
  PimpleSolver solver(mesh, physics, schemes, pimple, std::move(U), std::move(p));
  CavityResult r;
  double change = 1.0;
  // March in time to the steady state: stop when max |dU/dt| < 1e-4 (lid
  // speed 1, cavity side 1).
  while (r.steps < max_steps && change > 1e-4) {
    const std::vector<Vector3> before = solver.U().values();
    const StepSummary s = solver.Step(dt);
    EXPECT_TRUE(s.finite);
    if (!s.finite) return r;
    r.continuity = s.continuity_error;
    change = 0.0;
    for (int c = 0; c < mesh.n_cells(); ++c) change = std::max(change, (solver.U()[c] - before[c]).norm());
    change /= dt;
    ++r.steps;
  }
  std::printf("Re %.0f: %d steps, last max |dU/dt| %.2e\n", re, r.steps, change);
  // Sample the centrelines: linear interpolation between cell centres (and
  // the wall values at the ends).
  auto sample = [&](bool vertical, double s) {
    // vertical: u along x = 0.5 at height y = s; else v along y = 0.5 at x = s.
    std::vector<std::pair<double, double>> line;  // (coordinate, value)
    for (int c = 0; c < mesh.n_cells(); ++c) {
      const Vector3& x = mesh.cell_centres()[c];
      if (vertical && std::abs(x.x() - 0.5) < 1e-9) line.emplace_back(x.y(), solver.U()[c].x());
      if (!vertical && std::abs(x.y() - 0.5) < 1e-9) line.emplace_back(x.x(), solver.U()[c].y());
    }
    line.emplace_back(0.0, 0.0);
    line.emplace_back(1.0, vertical ? 1.0 : 0.0);
    std::sort(line.begin(), line.end());
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      if (s >= line[i].first && s <= line[i + 1].first) {
        const double t = (s - line[i].first) / (line[i + 1].first - line[i].first);
        return (1 - t) * line[i].second + t * line[i + 1].second;
      }
    }
    return std::nan("");
  };
  const std::vector<testing::GhiaPoint> ghia = testing::LoadGhia();
  EXPECT_EQ(ghia.size(), 34u) << "data/reference/ghia1982_cavity.csv not found or incomplete";
  for (const testing::GhiaPoint& g : ghia) {
    const double ref = re < 500 ? g.re100 : g.re1000;
    if (g.section == "u_vs_y") {
      const double d = std::abs(sample(true, g.coord) - ref);
      EXPECT_TRUE(std::isfinite(d)) << "u at y = " << g.coord;
      r.max_du = std::max(r.max_du, d);
    } else {
      const double d = std::abs(sample(false, g.coord) - ref);
      EXPECT_TRUE(std::isfinite(d)) << "v at x = " << g.coord;
      r.max_dv = std::max(r.max_dv, d);
    }
  }
  std::printf("Re %.0f: max |u - u_Ghia| = %.4f, max |v - v_Ghia| = %.4f, continuity %.2e\n", re, r.max_du,
              r.max_dv, r.continuity);
  return r;
}

TEST(Cavity, Re100MatchesGhia) {
  const CavityResult r = RunCavity(100.0, 129, 0.05, 300);
  EXPECT_LE(r.max_du, 0.02);
  EXPECT_LE(r.max_dv, 0.02);
}

TEST(Cavity, Re1000MatchesGhia) {
  const CavityResult r = RunCavity(1000.0, 129, 0.05, 1000);
  EXPECT_LE(r.max_du, 0.02);
  EXPECT_LE(r.max_dv, 0.02);
}

}  // namespace
}  // namespace kelvin::cfd
