// Static drift of a ship hull in 3D (acceptance 3 of issue 7 on a hull
// rather than a block): the coarse hull-fitted Wigley grid of
// data/cases/captive_cfd (15k cells, both sides of the centreplane, mirror
// symmetric), laminar at Re = 2000, double body. Mirrored drift angles give
// mirrored flows at every time step, so Y and N are antisymmetric and X
// symmetric long before the flow is steady; 100 steps (ramp 1 s + 1 s).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "cfd/run/run_case.h"
#include "cfd/motion/ship_forces.h"
#include "data/schema/config.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

using kelvin::testing::ReadText;

PlanarLoad Drift(const fs::path& poly_mesh, double degrees, int steps) {
  std::string text = ReadText(kelvin::testing::SourceDir() / "data/cases/captive_cfd/wigley_case.yaml");
  const std::string mesh_line = "mesh: {poly_mesh: ../../../build/grids/wigley_captive/constant/polyMesh}";
  text.replace(text.find(mesh_line), mesh_line.size(), "mesh: {poly_mesh: " + poly_mesh.string() + "}");
  text += "motion: {kind: static_drift, speed: 1.0, ramp_time: 1.0, centre: [0.5, 0, 0], drift_angle_deg: " +
          std::to_string(degrees) + "}\n";
  text.replace(text.find("time: {dt: 0.02}"), 16, "time: {dt: 0.02, end: 2.0}");
  const Case c = LoadCase(data::ConfigNode::LoadString(text, "wigley_case.yaml"), ".");
  const std::vector<int> hull = {c.mesh->FindPatch("hull")};
  PlanarLoad load;
  for (int i = 0; i < steps; ++i) {
    const StepSummary s = c.solver->Step(c.settings.time.dt);
    EXPECT_TRUE(s.finite);
    load = ComputeHullLoads(*c.solver, hull, 1000.0, 5e-4, c.motion->body().At(s.time),
                            c.motion->body().centre())
               .Total();
  }
  return load;
}

TEST(WigleyDrift, YAndNAreAntisymmetricXSymmetric) {
  kelvin::testing::ScopedTempDir tmp;
  const auto mesh = kelvin::testing::RunCommand(
      (kelvin::testing::ToolsDir() / "kelvin").string() + " -q mesh " +
      (kelvin::testing::SourceDir() / "data/cases/captive_cfd/wigley_mesh.yaml").string() + " -o " +
      (tmp / "grid").string());
  ASSERT_EQ(mesh.exit_code, 0) << mesh.output;
  const fs::path poly_mesh = tmp / "grid/constant/polyMesh";
  ASSERT_TRUE(fs::exists(poly_mesh / "owner")) << mesh.output;
  const PlanarLoad p = Drift(poly_mesh, 10.0, 100), m = Drift(poly_mesh, -10.0, 100);
  const double dy = std::abs(p.Y + m.Y) / std::abs(p.Y);
  const double dn = std::abs(p.N + m.N) / std::abs(p.N);
  const double dx = std::abs(p.X - m.X) / std::abs(p.X);
  const double scale = 0.5 * 1000.0 * 1.0 * 0.0625;  // 0.5 rho L T U^2
  std::printf("Wigley drift +-10 deg at t = 2 s: X %.6g / %.6g N, Y %.6g / %.6g N, N %.6g / %.6g N m\n", p.X, m.X,
              p.Y, m.Y, p.N, m.N);
  std::printf("asymmetry Y %.3g N %.3g X %.3g; Y' %.4f N' %.4f\n", dy, dn, dx, p.Y / scale, p.N / scale);
  EXPECT_LT(dy, 0.01);
  EXPECT_LT(dn, 0.01);
  EXPECT_LT(dx, 0.01);
  // beta > 0 (v < 0): Y > 0 and the destabilizing Munk moment N > 0.
  EXPECT_GT(p.Y, 0.0);
  EXPECT_GT(p.N, 0.0);
  EXPECT_LT(p.X, 0.0);
}

}  // namespace
}  // namespace kelvin::cfd
