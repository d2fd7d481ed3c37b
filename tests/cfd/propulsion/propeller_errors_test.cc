// The body-force propeller's bad input: one clear error each (options, a
// disk outside the mesh or in the hull, a cell next to a wall, too few cells
// across, J outside the open-water table, reversed flow, bad rates), and J
// held at the table's end during a start-up.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "cfd/propulsion/actuator_disk.h"
#include "cfd/propulsion/propeller.h"
#include "data/schema/errors.h"
#include "tests/cfd/propulsion/propeller_test_support.h"

namespace kelvin::cfd {
namespace {

using ::testing::HasSubstr;
using testing::HoughOrdwayDisk;
using testing::Kp505;
using testing::UniformBox;
using testing::UniformFlow;

// Bad input: one clear error each

void ExpectDiskError(const Mesh& mesh, const ActuatorDiskOptions& o, const std::vector<std::string>& parts) {
  try {
    const ActuatorDisk disk(mesh, o);
    ADD_FAILURE() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    for (const std::string& p : parts) EXPECT_THAT(e.what(), HasSubstr(p));
  }
}

TEST(ActuatorDiskErrors, BadOptions) {
  const Mesh mesh = UniformBox(10);
  auto with = [](const std::function<void(ActuatorDiskOptions&)>& f) {
    ActuatorDiskOptions o;
    o.diameter = 0.8;
    f(o);
    return o;
  };
  ExpectDiskError(mesh, with([](auto& o) { o.diameter = -1.0; }), {"propeller.diameter = -1", "positive"});
  ExpectDiskError(mesh, with([](auto& o) { o.hub_ratio = 0.5; }), {"propeller.hub_ratio = 0.5", "[0, 0.5)"});
  ExpectDiskError(mesh, with([](auto& o) { o.hub_ratio = -0.1; }), {"propeller.hub_ratio = -0.1"});
  ExpectDiskError(mesh, with([](auto& o) { o.thickness = 0.0; }), {"propeller.thickness = 0", "positive"});
  ExpectDiskError(mesh, with([](auto& o) { o.axis = Vector3(1, 1, 0); }), {"propeller.axis = (1, 1, 0)", "unit"});
  ExpectDiskError(mesh, with([](auto& o) { o.sense = 0; }), {"propeller.sense = 0", "+1 or -1"});
  ExpectDiskError(mesh, with([](auto& o) { o.centre.y() = NAN; }), {"propeller.centre", "finite"});
  ExpectDiskError(mesh, with([](auto& o) { o.name = "case.yaml: propulsion.propeller"; o.diameter = 0; }),
                  {"case.yaml: propulsion.propeller.diameter = 0"});
}

TEST(ActuatorDiskErrors, OutsideTheMesh) {
  ActuatorDiskOptions o;
  o.centre = Vector3(10.0, 0.0, 0.0);
  ExpectDiskError(UniformBox(10), o, {"propeller.centre = (10, 0, 0)", "contains no cell", "box mesh"});
}

// A hull (a block obstacle, wall patch `obstacle`) behind the disk.
Mesh BoxWithHull() {
  BoxMeshOptions mo;
  mo.min = Vector3(-1, -1, -1);
  mo.max = Vector3(1, 1, 1);
  mo.cells = {20, 20, 20};
  mo.kinds.fill(PatchKind::kPatch);
  mo.obstacle_min = {12, 8, 8};  // x in [0.2, 0.6], y, z in [-0.2, 0.2]
  mo.obstacle_max = {16, 12, 12};
  return MakeBoxMesh(mo);
}

TEST(ActuatorDiskErrors, OverlapsTheHull) {
  const Mesh mesh = BoxWithHull();
  ActuatorDiskOptions o;
  o.diameter = 0.6;
  o.thickness = 0.1;
  o.hub_ratio = 0.2;
  o.centre = Vector3(0.0, 0.0, 0.0);  // 0.15 clear of the hull: fine
  EXPECT_NO_THROW(ActuatorDisk(mesh, o));
  o.centre = Vector3(0.12, 0.0, 0.0);  // 0.03 clear: less than half a cell
  ExpectDiskError(mesh, o, {"propeller.centre = (0.12, 0, 0)", "touches wall patch 'obstacle'"});
  o.centre = Vector3(0.4, 0.0, 0.0);  // inside the hull, the blades through it
  ExpectDiskError(mesh, o, {"touches wall patch 'obstacle'"});
}

// A shaft boss (wall patch `obstacle`, x in [0, 0.6]) ending inside the
// disk's thickness: within the hub radius it is where the propeller sits,
// wider than the hub it cuts the loaded annulus.
TEST(ActuatorDiskErrors, BossInsideTheHubIsAllowed) {
  BoxMeshOptions mo;
  mo.min = Vector3(-1, -1, -1);
  mo.max = Vector3(1, 1, 1);
  mo.cells = {20, 20, 20};
  mo.kinds.fill(PatchKind::kPatch);
  mo.obstacle_min = {10, 9, 9};  // y, z in [-0.1, 0.1]: face centres at r <= 0.112
  mo.obstacle_max = {16, 11, 11};
  ActuatorDiskOptions o;
  o.diameter = 1.2;
  o.thickness = 0.1;
  o.hub_ratio = 0.3;  // r_hub = 0.18
  o.centre = Vector3(-0.02, 0.0, 0.0);  // x in [-0.07, 0.03]: the boss end is inside
  EXPECT_NO_THROW(ActuatorDisk(MakeBoxMesh(mo), o));
  mo.obstacle_min = {10, 8, 8};  // y, z in [-0.2, 0.2]: face centres out to r 0.21
  mo.obstacle_max = {16, 12, 12};
  ExpectDiskError(MakeBoxMesh(mo), o, {"touches wall patch 'obstacle'", "outside the hub radius"});
}

TEST(ActuatorDiskErrors, CellNextToAWall) {
  BoxMeshOptions mo;
  mo.min = Vector3(-1, -1, -1);
  mo.max = Vector3(1, 1, 1);
  mo.cells = {10, 10, 10};  // walls on every side
  ActuatorDiskOptions o;
  o.diameter = 1.95;
  ExpectDiskError(MakeBoxMesh(mo), o, {"touches wall patch 'y"});
}

// Coarse: a warning, not an error.
TEST(ActuatorDiskErrors, FewCellsAcrossIsAWarning) {
  ActuatorDiskOptions o;
  o.diameter = 1.0;
  const ActuatorDisk disk(UniformBox(8), o);
  EXPECT_NEAR(disk.cells_across_diameter(), 4.0, 1e-9);
}

TEST(PropellerErrors, JOutsideTheTable) {
  const Mesh mesh = UniformBox(20);
  Propeller prop(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505());
  auto solver = UniformFlow(mesh, 2.0);
  std::vector<Vector3> source;
  try {
    prop.Update(*solver, nullptr, Eigen::Matrix3d::Identity(), 1.0, 1.0, source);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("propeller.open_water: J = 2"));
    EXPECT_THAT(e.what(), HasSubstr("outside the table's range [0, 1.05]"));
  }
}

TEST(PropellerErrors, ReversedFlowAndBadRate) {
  const Mesh mesh = UniformBox(20);
  Propeller prop(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505());
  auto solver = UniformFlow(mesh, -0.5);
  std::vector<Vector3> source;
  try {
    prop.Update(*solver, nullptr, Eigen::Matrix3d::Identity(), 1.0, 1.0, source);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("reversed (U_disk = -0.5"));
  }
  try {
    prop.Update(*solver, nullptr, Eigen::Matrix3d::Identity(), 0.0, 1.0, source);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("propeller.n = 0"));
  }
}

// In the start-up ramp a J outside the table is held at its end: J_min
// (bollard pull, K_T(0)) for reversed flow and for a correction that removes
// more than the flow through the disk carries, J_max for a light disk. After
// the ramp the same states are errors (PropellerErrors above).
TEST(PropellerStartUp, JOutsideTheTableIsHeldAtItsEnd) {
  const Mesh mesh = UniformBox(20);
  const sim::OpenWaterCurve curve = Kp505();
  const double D = HoughOrdwayDisk().diameter, n = 1.0, rho = 1.0;
  std::vector<Vector3> source;
  {
    Propeller prop(ActuatorDisk(mesh, HoughOrdwayDisk()), curve);
    const PropellerState s =
        prop.Update(*UniformFlow(mesh, -0.5), nullptr, Eigen::Matrix3d::Identity(), n, rho, source, true);
    EXPECT_TRUE(s.clamped);
    EXPECT_EQ(s.U_A, 0.0);
    EXPECT_EQ(s.J, curve.J_min());
    EXPECT_DOUBLE_EQ(s.T, rho * n * n * std::pow(D, 4) * curve.KT(curve.J_min()));
  }
  {
    // A heavy load from the last step over a slow stream: U_A < 0 from the
    // momentum correction.
    Propeller prop(ActuatorDisk(mesh, HoughOrdwayDisk()), curve);
    prop.SetState({10.0, 0.0, n});
    const PropellerState s =
        prop.Update(*UniformFlow(mesh, 0.05), nullptr, Eigen::Matrix3d::Identity(), n, rho, source, true);
    EXPECT_LT(s.U_A, 0.0);
    EXPECT_TRUE(s.clamped);
    EXPECT_EQ(s.J, curve.J_min());
  }
  {
    Propeller prop(ActuatorDisk(mesh, HoughOrdwayDisk()), curve);
    const PropellerState s =
        prop.Update(*UniformFlow(mesh, 2.0), nullptr, Eigen::Matrix3d::Identity(), n, rho, source, true);
    EXPECT_TRUE(s.clamped);
    EXPECT_EQ(s.J, curve.J_max());
  }
  {
    Propeller prop(ActuatorDisk(mesh, HoughOrdwayDisk()), curve);
    const PropellerState s =
        prop.Update(*UniformFlow(mesh, 0.8), nullptr, Eigen::Matrix3d::Identity(), 1.2, rho, source, true);
    EXPECT_FALSE(s.clamped);  // inside the table: the same as after the ramp
    Propeller after(ActuatorDisk(mesh, HoughOrdwayDisk()), curve);
    EXPECT_EQ(s.J, after.Update(*UniformFlow(mesh, 0.8), nullptr, Eigen::Matrix3d::Identity(), 1.2, rho, source).J);
  }
}

TEST(PropellerErrors, BadOptionsAndTable) {
  const Mesh mesh = UniformBox(10);
  PropellerOptions po;
  po.thrust_relaxation = 0.0;
  try {
    Propeller(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505(), po);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("propeller.thrust_relaxation = 0"));
  }
  po = PropellerOptions{};
  po.mesh_share = 0.5;  // a full disk declared as a half
  try {
    Propeller(ActuatorDisk(mesh, HoughOrdwayDisk()), Kp505(), po);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("propeller.mesh_share = 0.5"));
  }
  sim::OpenWaterCurve bad = Kp505();
  bad.K_T[3] = 0.9;
  try {
    Propeller(ActuatorDisk(mesh, HoughOrdwayDisk()), bad);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("propeller.open_water.K_T: [3] = 0.9"));
  }
}

}  // namespace
}  // namespace kelvin::cfd
