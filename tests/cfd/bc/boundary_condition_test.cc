// The four coefficients of every boundary condition against their
// definitions: value = vi phi_P + vb, snGrad = gi phi_P + gb.
#include "cfd/bc/boundary_condition.h"

#include <gtest/gtest.h>

#include "cfd/bc/outlet_inlet.h"
#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/mesh/box_mesh.h"
#include "cfd/turbulence/turbulence_model.h"

namespace kelvin::cfd {
namespace {

class BcTest : public ::testing::Test {
 protected:
  BcTest() : mesh_(MakeMesh()) {}
  static Mesh MakeMesh() {
    BoxMeshOptions o;
    o.cells = {4, 2, 1};
    o.max = Vector3(2.0, 1.0, 0.5);  // cell 0.5 x 0.5 x 0.5: dc = 1 / 0.25 = 4
    return MakeBoxMesh(o);
  }
  const Patch& patch(const std::string& name) const { return mesh_.patches()[mesh_.FindPatch(name)]; }
  Mesh mesh_;
  std::vector<Vector3> u_ = std::vector<Vector3>(8, Vector3(1.0, -2.0, 3.0));
  std::vector<double> s_ = std::vector<double>(8, 5.0);
};

TEST_F(BcTest, FixedValue) {
  FixedValue<double> bc(7.0);
  bc.Update({mesh_, patch("xmax"), 0.0, {}}, s_);
  for (std::size_t i = 0; i < bc.value_internal().size(); ++i) {
    EXPECT_EQ(bc.value_internal()[i], 0.0);
    EXPECT_EQ(bc.value_boundary()[i], 7.0);
    EXPECT_DOUBLE_EQ(bc.gradient_internal()[i], -4.0);
    EXPECT_DOUBLE_EQ(bc.gradient_boundary()[i], 28.0);
    // snGrad = (7 - 5) / 0.25.
    EXPECT_DOUBLE_EQ(bc.gradient_internal()[i] * 5.0 + bc.gradient_boundary()[i], 8.0);
  }
  EXPECT_TRUE(bc.fixes_value());
}

TEST_F(BcTest, FixedValueFollowsPositionAndTime) {
  FixedValue<double> bc(ValueFunction<double>([](const Vector3& x, double t) { return x.y() + 10 * t; }));
  const Patch& p = patch("xmax");
  bc.Update({mesh_, p, 0.5, {}}, s_);
  for (int i = 0; i < p.size; ++i) {
    EXPECT_DOUBLE_EQ(bc.value_boundary()[i], mesh_.face_centres()[p.start + i].y() + 5.0);
  }
}

TEST_F(BcTest, ZeroGradient) {
  ZeroGradient<Vector3> bc;
  bc.Update({mesh_, patch("ymin"), 0.0, {}}, u_);
  EXPECT_EQ(bc.value_internal()[0], Vector3::Ones());
  EXPECT_EQ(bc.value_boundary()[0], Vector3::Zero());
  EXPECT_EQ(bc.gradient_internal()[0], Vector3::Zero());
  EXPECT_EQ(bc.gradient_boundary()[0], Vector3::Zero());
  EXPECT_FALSE(bc.fixes_value());
}

TEST_F(BcTest, SlipRemovesTheNormalComponent) {
  Slip bc;
  const Patch& p = patch("ymax");  // normal +y
  bc.Update({mesh_, p, 0.0, {}}, u_);
  const Vector3 value = bc.value_internal()[0].cwiseProduct(u_[0]) + bc.value_boundary()[0];
  EXPECT_TRUE(value.isApprox(Vector3(1.0, 0.0, 3.0)));
  const Vector3 sn = bc.gradient_internal()[0].cwiseProduct(u_[0]) + bc.gradient_boundary()[0];
  EXPECT_TRUE(sn.isApprox(Vector3(0.0, 2.0 * 4.0, 0.0)));  // (u_b - u_P) * dc
}

TEST_F(BcTest, MovingWallIsRigidBodyVelocity) {
  MovingWall bc([](double t) {
    MovingWall::Motion m;
    m.velocity = Vector3(t, 0, 0);
    m.angular_velocity = Vector3(0, 0, 2.0);
    m.centre = Vector3(1.0, 0.5, 0.0);
    return m;
  });
  const Patch& p = patch("ymax");
  bc.Update({mesh_, p, 3.0, {}}, u_);
  for (int i = 0; i < p.size; ++i) {
    const Vector3 x = mesh_.face_centres()[p.start + i];
    const Vector3 expected = Vector3(3.0, 0, 0) + Vector3(0, 0, 2.0).cross(x - Vector3(1.0, 0.5, 0.0));
    EXPECT_TRUE(bc.value_boundary()[i].isApprox(expected));
    EXPECT_EQ(bc.value_internal()[i], Vector3::Zero());
  }
}

TEST_F(BcTest, InletOutletSwitchesOnTheFluxSign) {
  const Patch& p = patch("xmax");
  std::vector<double> flux(mesh_.n_faces(), 0.0);
  flux[p.start] = -1.0;     // entering
  flux[p.start + 1] = 1.0;  // leaving
  InletOutlet<double> bc(9.0);
  bc.Update({mesh_, p, 0.0, flux}, s_);
  EXPECT_EQ(bc.value_internal()[0], 0.0);
  EXPECT_EQ(bc.value_boundary()[0], 9.0);
  EXPECT_EQ(bc.value_internal()[1], 1.0);
  EXPECT_EQ(bc.value_boundary()[1], 0.0);
  EXPECT_EQ(bc.gradient_internal()[1], 0.0);
}

TEST_F(BcTest, MixedInterpolatesBetweenDirichletAndNeumann) {
  const Patch& p = patch("xmax");
  Mixed<double> bc(2.0, 3.0, 0.25);
  bc.Update({mesh_, p, 0.0, {}}, s_);
  // phi_b = f ref + (1 - f)(phi_P + g / dc) = 0.25*2 + 0.75*(5 + 0.75) = 4.8125
  EXPECT_DOUBLE_EQ(bc.value_internal()[0] * 5.0 + bc.value_boundary()[0], 4.8125);
  // snGrad = f dc (ref - phi_P) + (1 - f) g = 0.25*4*(-3) + 0.75*3 = -0.75
  EXPECT_DOUBLE_EQ(bc.gradient_internal()[0] * 5.0 + bc.gradient_boundary()[0], -0.75);
  // Robin form p_b = alpha p_P + beta with alpha = 1 - f <= 1 keeps the
  // pressure matrix SPD.
  EXPECT_DOUBLE_EQ(bc.value_internal()[0], 0.75);
  bc.fraction()[0] = 1.0;
  bc.Update({mesh_, p, 0.0, {}}, s_);
  EXPECT_DOUBLE_EQ(bc.value_internal()[0] * 5.0 + bc.value_boundary()[0], 2.0);
}

TEST(PatchRoles, EachConditionStatesItsRole) {
  EXPECT_EQ(FixedValue<Vector3>(Vector3(1, 0, 0)).role(), PatchRole::kInflow);
  EXPECT_EQ(FixedValue<Vector3>(Vector3(0, 0, 0), PatchRole::kWall).role(), PatchRole::kWall);
  EXPECT_EQ(FixedValue<double>(0.0).role(), PatchRole::kUnspecified);
  EXPECT_EQ(MovingWall([](double) { return MovingWall::Motion{}; }).role(), PatchRole::kWall);
  EXPECT_EQ(Slip().role(), PatchRole::kSymmetry);
  EXPECT_EQ(Empty<Vector3>().role(), PatchRole::kEmpty);
  EXPECT_EQ(Empty<double>().role(), PatchRole::kEmpty);
  EXPECT_EQ(ZeroGradient<Vector3>().role(), PatchRole::kUnspecified);
  EXPECT_EQ(InletOutlet<Vector3>(Vector3::Zero()).role(), PatchRole::kOutflow);
  EXPECT_EQ(OutletInlet<double>(0.0).role(), PatchRole::kOutflow);
  EXPECT_EQ(FarField<Vector3>(Vector3::Zero(), true, 0.1).role(), PatchRole::kOutflow);
  EXPECT_EQ(Mixed<double>(0.0, 0.0, 0.5).role(), PatchRole::kUnspecified);
}

// The mapping the case loader used on the YAML type strings: empty ->
// kEmpty, fixedValue -> kInflow, movingWall / movingWallVelocity / noSlip ->
// kWall, slip or a linearizedFreeSurface pressure -> kSymmetry, else kOutflow.
TEST(PatchRoles, TurbulenceRolesFollowTheTypedConditions) {
  BoxMeshOptions o;
  o.cells = {3, 3, 2};
  o.min = Vector3(0, 0, -1);
  o.max = Vector3(1, 1, 0);
  const Mesh mesh = MakeBoxMesh(o);
  const auto wall = [] { return std::make_unique<FixedValue<Vector3>>(Vector3(0, 0, 0), PatchRole::kWall); };
  const auto moving = [] { return std::make_unique<MovingWall>([](double) { return MovingWall::Motion{}; }); };
  struct Row {
    std::string patch;
    std::unique_ptr<BoundaryCondition<Vector3>> u;
    std::unique_ptr<BoundaryCondition<double>> p;
    TurbulencePatchRole expected;
  };
  std::vector<Row> rows;
  rows.push_back({"xmin", std::make_unique<FixedValue<Vector3>>(Vector3(1, 0, 0)),
                  std::make_unique<ZeroGradient<double>>(), TurbulencePatchRole::kInflow});
  rows.push_back({"xmax", std::make_unique<InletOutlet<Vector3>>(Vector3::Zero()),
                  std::make_unique<OutletInlet<double>>(0.0), TurbulencePatchRole::kOutflow});
  rows.push_back({"ymin", wall(), std::make_unique<ZeroGradient<double>>(), TurbulencePatchRole::kWall});
  rows.push_back({"ymax", std::make_unique<Slip>(), std::make_unique<ZeroGradient<double>>(),
                  TurbulencePatchRole::kSymmetry});
  rows.push_back({"zmin", moving(), std::make_unique<ZeroGradient<double>>(), TurbulencePatchRole::kWall});
  rows.push_back({"zmax", std::make_unique<ZeroGradient<Vector3>>(),
                  std::make_unique<LinearizedFreeSurface>(mesh, mesh.FindPatch("zmax"), LinearizedFreeSurfaceOptions{}),
                  TurbulencePatchRole::kSymmetry});
  std::vector<std::unique_ptr<BoundaryCondition<Vector3>>> ub(mesh.patches().size());
  std::vector<std::unique_ptr<BoundaryCondition<double>>> pb(mesh.patches().size());
  std::vector<TurbulencePatchRole> expected(mesh.patches().size());
  for (Row& r : rows) {
    const int k = mesh.FindPatch(r.patch);
    ASSERT_GE(k, 0) << r.patch;
    ub[k] = std::move(r.u);
    pb[k] = std::move(r.p);
    expected[k] = r.expected;
  }
  const VectorField U("U", mesh, std::move(ub));
  const ScalarField p("p", mesh, std::move(pb));
  EXPECT_EQ(TurbulencePatchRoles(U, p), expected);

  // The pressure condition decides only where the velocity condition does
  // not: zero gradient is an outflow, empty stays empty.
  EXPECT_EQ(TurbulencePatchRoleOf(ZeroGradient<Vector3>(), FixedValue<double>(0.0)), TurbulencePatchRole::kOutflow);
  EXPECT_EQ(TurbulencePatchRoleOf(Empty<Vector3>(), Empty<double>()), TurbulencePatchRole::kEmpty);
  EXPECT_EQ(TurbulencePatchRoleOf(FarField<Vector3>(Vector3::Zero(), true, 0.1),
                                  FarField<double>(0.0, false, 0.1)),
            TurbulencePatchRole::kOutflow);
}

}  // namespace
}  // namespace kelvin::cfd
