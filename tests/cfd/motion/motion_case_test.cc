// `kelvin run` case files with a motion: section: the ship-axis loads in the
// history, a restart of a moving-mesh run that continues bit for bit, and one
// clear error for each bad input around the motion.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "cfd/run/run_case.h"
#include "cfd/grid/mesh_case.h"
#include "cfd/io/checkpoint.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/cfd/cfd_test_support.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using testing::WriteCase;
using ::testing::HasSubstr;

// A small 2D block on a yawing and swaying mesh (yaw with drift).
const char* kCase = R"(mesh:
  box: {min: [-3, -1.5, 0], max: [2, 1.5, 1], cells: [20, 12, 1], empty: z, obstacle: {min: [10, 5, 0], max: [14, 7, 1]}}
physics: {nu: 0.05, rho: 1000}
schemes: {time: backward, gradient: least_squares}
solution:
  n_outer: 2
  pressure: {solver: pcg_amg, relative_tolerance: 1.0e-6}
motion: {kind: yaw_drift, speed: 1.0, drift_angle_deg: 5, yaw_amplitude_deg: 10, period: 2.0, ramp_time: 0.5,
         periods: 1, centre: [-0.5, 0, 0.5]}
reference: {speed: 1.0, direction: [-1, 0, 0], length: 1.0, draft: 1.0}
time: {dt: 0.05}
boundary:
  xmin: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  xmax: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  ymin: {U: {type: inletOutlet, inflow: [0, 0, 0]}, p: {type: outletInlet, value: 0}}
  ymax: {U: {type: inletOutlet, inflow: [0, 0, 0]}, p: {type: outletInlet, value: 0}}
  obstacle: {U: {type: movingWallVelocity}, p: {type: zeroGradient}}
output: {directory: out, vtu_interval: 0, checkpoint_interval: 20, forces: [obstacle], captive: true}
)";

TEST(MotionCase, HistoryHoldsShipAxisLoadsAndTheMotion) {
  kelvin::testing::ScopedTempDir tmp;
  RunOptions o;
  o.progress = false;
  const RunSummary s = RunCase(WriteCase(tmp.path(), kCase), o);
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  EXPECT_EQ(s.steps, 80);  // ramp 0.5 s -> first boundary at 2 s, one period: end 4 s
  const data::H5Reader r(tmp / "out/history.h5");
  const data::Series y = r.Read("captive/Y"), n = r.Read("captive/N"),
                     yp = r.Read("captive/Y_prime");
  const data::Series psi = r.Read("captive/psi"), t = r.Read("captive/time");
  EXPECT_EQ(y.units, "N");
  EXPECT_EQ(n.units, "N m");
  ASSERT_EQ(y.rows, 80u);
  const double scale = 0.5 * 1000.0 * 1.0 * 1.0 * 1.0;
  for (std::size_t i = 0; i < y.rows; ++i) {
    EXPECT_DOUBLE_EQ(yp.values[i], y.values[i] / scale);
    EXPECT_DOUBLE_EQ(r.Read("captive/Y_pressure").values[i] + r.Read("captive/Y_viscous").values[i],
                     y.values[i]);
  }
  // psi = beta + psi_a cos(omega t) after the ramp.
  EXPECT_NEAR(psi.values.back(), (5.0 + 10.0 * std::cos(M_PI * t.values.back())) * M_PI / 180.0,
              1e-12);
  // The VTU shows the mesh where it is: the last field file exists.
  EXPECT_TRUE(fs::exists(tmp / "out/fields.pvd"));
}

TEST(MotionCase, RestartOfAMovingMeshContinuesBitForBit) {
  kelvin::testing::ScopedTempDir tmp;
  RunOptions o;
  o.progress = false;
  // Whole run, then the same case restarted from its step-40 checkpoint.
  RunCase(WriteCase(tmp.path(), kCase), o);
  const data::H5Reader whole(tmp / "out/history.h5");
  const std::vector<double> y_whole = whole.Read("captive/Y").values;

  std::string half = kCase;
  half.replace(half.find("periods: 1,"), 11, "");
  half.replace(half.find("time: {dt: 0.05}"), 16, "time: {dt: 0.05, end: 2.0}");
  const fs::path dir2 = tmp / "half";
  fs::create_directories(dir2);
  RunCase(WriteCase(dir2, half), o);
  o.restart = dir2 / "out/checkpoint.h5";
  o.output_override = tmp / "restarted";
  const RunSummary s = RunCase(WriteCase(tmp.path(), kCase), o);
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted);
  EXPECT_EQ(s.steps, 40);
  const std::vector<double> y_restarted =
      data::H5Reader(tmp / "restarted/history.h5").Read("captive/Y").values;
  ASSERT_EQ(y_restarted.size(), 40u);
  for (std::size_t i = 0; i < 40; ++i)
    EXPECT_EQ(y_restarted[i], y_whole[40 + i]) << "step " << 41 + i;
}

struct BadCase {
  std::string from, to, message;
};

class BadMotionCaseTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadMotionCaseTest, IsOneClearError) {
  kelvin::testing::ScopedTempDir tmp;
  std::string text = kCase;
  const auto at = text.find(GetParam().from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, GetParam().from.size(), GetParam().to);
  RunOptions o;
  o.progress = false;
  try {
    RunCase(WriteCase(tmp.path(), text), o);
    FAIL() << "accepted " << GetParam().to;
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("case.yaml"));
    EXPECT_THAT(e.what(), HasSubstr(GetParam().message));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Inputs, BadMotionCaseTest,
    ::testing::Values(BadCase{"time: {dt: 0.05}", "time: {dt: 0.05, end: 3}",
                              "key 'time.end' = '3': expected no end time: motion.periods sets it"},
                      BadCase{"motion: {kind: yaw_drift,",
                              "motion: {kind: yaw_drift, sway_amplitude: 1,",
                              "unknown key 'motion.sway_amplitude'"},
                      BadCase{"obstacle: {min: [10, 5, 0], max: [14, 7, 1]}",
                              "obstacle: {min: [10, 5, 0], max: [24, 7, 1]}",
                              "obstacle blocks [10, 24) along axis 0; expected within [0, 20]"},
                      BadCase{"band: 0.3}, p: {type: farField, value: 0, band: 0.3}}\n  xmax",
                              "band: -1}, p: {type: farField, value: 0, band: 0.3}}\n  xmax",
                              "key 'boundary.xmin.U.band' = '-1'"},
                      BadCase{"length: 1.0, draft: 1.0}", "length: 1.0}",
                              "expected reference.length and reference.draft (the prime-system scales)"},
                      BadCase{"captive: true}", "captive: {length: 1.0, draft: 1.0}}",
                              "output.captive is a flag now; the prime scales are reference.length"}));

TEST(MotionCase, MovingWallVelocityNeedsAMotion) {
  kelvin::testing::ScopedTempDir tmp;
  std::string text = kCase;
  const auto a = text.find("motion: {");
  text.erase(a, text.find("time: {") - a);
  text.replace(text.find("time: {dt: 0.05}"), 16, "time: {dt: 0.05, end: 1}");
  RunOptions o;
  o.progress = false;
  try {
    RunCase(WriteCase(tmp.path(), text), o);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_THAT(
        e.what(),
        HasSubstr("key 'boundary.obstacle.U.type' = 'movingWallVelocity': expected a condition "
                  "other than movingWallVelocity: it needs a motion: section"));
  }
}

}  // namespace
}  // namespace kelvin::cfd

namespace kelvin::cfd {
namespace {

// The case files of the repository's CFD campaigns with SST and the free
// surface (the Wigley campaign, the quickstart's coarse Wigley campaign and
// the KCS campaign, whose hull the user supplies) load on a hull grid with the patches they name, take the
// campaign's motion, and step: the free surface moves with the motion's
// point velocity, so on the first step of a pure sway from rest the
// solution stays finite and the free surface has a condition to apply.
TEST(MotionCase, CampaignCaseFilesLoadAndStepOnAHullGrid) {
  kelvin::testing::ScopedTempDir dir;
  const std::filesystem::path data = kelvin::testing::SourceDir() / "data/cases/captive_cfd";
  const MeshCase mesh_case = LoadMeshCase(data / "wigley_lfs_mesh.yaml");
  RunMeshCase(mesh_case, 1, dir / "grid");
  for (const char* name : {"wigley_lfs_case.yaml", "wigley_quick_case.yaml", "kcs_case.yaml"}) {
    CaseOverrides o;
    o.poly_mesh = dir / "grid/constant/polyMesh";
    MotionOptions m;
    m.kind = PrescribedMotion::kPureSway;
    m.speed = 1.0;
    m.sway_amplitude = 0.05;
    m.period = 2.0;
    m.ramp_time = 2.0;
    m.centre = Vector3(0.5, 0, 0);
    o.motion = m;
    o.dt = 0.02;
    o.end_time = 0.04;
    Case c = LoadCase(data::ConfigNode::LoadFile(data / name), data, o);
    ASSERT_TRUE(c.motion) << name;
    EXPECT_TRUE(c.solver->turbulence() != nullptr) << name;
    for (int i = 0; i < 2; ++i) EXPECT_TRUE(c.solver->Step(c.settings.time.dt).finite) << name;
  }
}

}  // namespace
}  // namespace kelvin::cfd
