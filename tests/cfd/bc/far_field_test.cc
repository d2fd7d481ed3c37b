// Coefficients of the far-field conditions decided by the relative flux
// (OutletInlet, FarField), and the block obstacle of the box mesh.
#include <gtest/gtest.h>

#include "cfd/bc/outlet_inlet.h"
#include "cfd/mesh/box_mesh.h"

namespace kelvin::cfd {
namespace {

Mesh UnitBox() {
  BoxMeshOptions o;
  o.cells = {2, 2, 2};
  return MakeBoxMesh(o);
}

TEST(OutletInlet, FixedWhereTheFlowLeavesZeroGradientWhereItEnters) {
  const Mesh mesh = UnitBox();
  const Patch& patch = mesh.patches()[1];  // xmax, 4 faces of area 0.25
  std::vector<double> flux(mesh.n_faces(), 0.0);
  flux[patch.start] = 0.1;       // out
  flux[patch.start + 1] = -0.1;  // in
  flux[patch.start + 2] = 0.0;   // no flow: zero gradient
  OutletInlet<double> bc(2.5);
  std::vector<double> cells(mesh.n_cells(), 0.0);
  bc.Update(BcContext{mesh, patch, 0.0, flux}, cells);
  const double dc = 1.0 / 0.25;  // 1 / distance from the cell centre
  EXPECT_EQ(bc.value_internal()[0], 0.0);
  EXPECT_EQ(bc.value_boundary()[0], 2.5);
  EXPECT_DOUBLE_EQ(bc.gradient_internal()[0], -dc);
  EXPECT_DOUBLE_EQ(bc.gradient_boundary()[0], 2.5 * dc);
  for (int i : {1, 2}) {
    EXPECT_EQ(bc.value_internal()[i], 1.0);
    EXPECT_EQ(bc.value_boundary()[i], 0.0);
    EXPECT_EQ(bc.gradient_internal()[i], 0.0);
    EXPECT_EQ(bc.gradient_boundary()[i], 0.0);
  }
}

TEST(FarField, BlendsDirichletAndNeumannSmoothlyInTheRelativeNormalVelocity) {
  const Mesh mesh = UnitBox();
  const Patch& patch = mesh.patches()[1];
  const double area = 0.25, dc = 4.0, band = 0.2;
  const Vector3 inflow(0.3, -0.1, 0.0);
  std::vector<double> cells_p(mesh.n_cells(), 0.0);
  std::vector<Vector3> cells_u(mesh.n_cells(), Vector3::Zero());
  FarField<Vector3> u(inflow, true, band);
  FarField<double> p(1.5, false, band);
  double last_w = 2.0;
  for (double un : {-0.5, -0.2, -0.1, 0.0, 0.1, 0.2, 0.5}) {
    std::vector<double> flux(mesh.n_faces(), 0.0);
    flux[patch.start] = un * area;
    const BcContext ctx{mesh, patch, 0.0, flux};
    u.Update(ctx, cells_u);
    p.Update(ctx, cells_p);
    // Weight of the inflow value: 1 at u_n <= -band, 0 at u_n >= band.
    const double w = 1.0 - u.value_internal()[0].x();
    const double x = std::clamp(0.5 * (1.0 - un / band), 0.0, 1.0);
    EXPECT_NEAR(w, x * x * (3 - 2 * x), 1e-15) << un;
    EXPECT_LE(w, last_w);
    last_w = w;
    EXPECT_NEAR((u.value_boundary()[0] - w * inflow).norm(), 0.0, 1e-15);
    EXPECT_NEAR((u.gradient_internal()[0] + w * dc * Vector3::Ones()).norm(), 0.0, 1e-14);
    EXPECT_NEAR((u.gradient_boundary()[0] - w * dc * inflow).norm(), 0.0, 1e-14);
    // The pressure is fixed with the complementary weight.
    EXPECT_NEAR(p.value_internal()[0], w, 1e-15);
    EXPECT_NEAR(p.value_boundary()[0], (1 - w) * 1.5, 1e-15);
    EXPECT_NEAR(p.gradient_internal()[0], -(1 - w) * dc, 1e-14);
  }
  EXPECT_EQ(last_w, 0.0);
}

TEST(BoxMesh, ObstacleIsAClosedWallPatch) {
  BoxMeshOptions o;
  o.min = Vector3(-2, -1, 0);
  o.max = Vector3(2, 1, 1);
  o.cells = {8, 4, 2};
  o.obstacle_min = {3, 1, 0};
  o.obstacle_max = {5, 3, 1};
  for (bool polyhedral : {false, true}) {
    o.polyhedral = polyhedral;
    const Mesh mesh = MakeBoxMesh(o);
    const int obstacle = mesh.FindPatch("obstacle");
    ASSERT_EQ(obstacle, 6);
    EXPECT_NEAR(mesh.total_volume(), 8.0 - 1.0 * 1.0 * 0.5, 1e-12);
    const Patch& patch = mesh.patches()[obstacle];
    Vector3 sum = Vector3::Zero();
    double area = 0.0;
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      sum += mesh.face_areas()[f];
      area += mesh.face_area_magnitudes()[f];
    }
    // The block touches zmin: its walls are the top and four sides.
    EXPECT_NEAR(area, 1.0 + 2 * (1.0 * 0.5) + 2 * (1.0 * 0.5), 1e-12);
    EXPECT_NEAR((sum - Vector3(0, 0, -1.0)).norm(), 0.0, 1e-12);  // normals point into the block
  }
}

}  // namespace
}  // namespace kelvin::cfd
