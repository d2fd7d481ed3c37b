// The linearized free surface in case files (`kelvin run`): a run writes
// eta on the patch (VTP + PVD), a restart from the checkpoint continues
// bit for bit, and every bad input is one ConfigError naming the file and
// the key.
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <fstream>
#include <sstream>

#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/run/run_case.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/cfd/cfd_test_support.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using testing::ExpectCaseConfigError;
using testing::WriteCase;

// A coarse version of data/cases/kelvin_pressure_patch.yaml.
const char* kCase = R"(mesh:
  box: {min: [-1, 0, -0.5], max: [4, 2.5, 0], cells: [20, 10, 4], grading: [1, 1, 0.25]}
physics: {nu: 1.0e-6}
schemes: {convection: linear_upwind, time: backward}
solution:
  n_outer: 2
  pressure: {solver: pcg_amg, relative_tolerance: 1.0e-8, final_relative_tolerance: 1.0e-10}
time: {dt: 0.25, end: END}
boundary:
  xmin: {U: {type: fixedValue, value: [1.2495, 0, 0]}, p: {type: zeroGradient}}
  xmax: {U: {type: zeroGradient}, p: {type: fixedValue, value: 0}}
  ymin: {U: {type: slip}, p: {type: zeroGradient}}
  ymax: {U: {type: slip}, p: {type: zeroGradient}}
  zmin: {U: {type: slip}, p: {type: zeroGradient}}
  zmax:
    U: {type: zeroGradient}
    p:
      type: linearizedFreeSurface
      g: 9.81
      mesh_velocity: [-1.2495, 0, 0]
      advection: quick
      beach: {width: 1.25, strength: 1.0, sides: [xmax, ymax]}
      pressure_patch: {centre: [0, 0], radius: 0.5, head: 0.005}
output: {directory: out, vtu_interval: 2, checkpoint_interval: 2}
)";

std::string CaseText(double end = 1.0) {
  std::string s = kCase;
  s.replace(s.find("END"), 3, std::to_string(end));
  return s;
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::vector<double> FreeSurfaceState(const fs::path& checkpoint) {
  data::H5Reader r(checkpoint);
  // U conditions of the six patches come first, then p: zmax is p patch 5.
  return r.Read("bc/11").values;
}

// The free-surface state at t = 1 in `straight` (a run straight to t = 1 of
// text(1)) against t = 0.5 plus a restart to t = 1: identical bits.
template <typename Text>
void ExpectRestartBitForBit(const fs::path& straight_checkpoint, Text&& text) {
  RunOptions o;
  o.progress = false;
  const std::vector<double> straight = FreeSurfaceState(straight_checkpoint);
  kelvin::testing::ScopedTempDir tmp2;
  RunCase(WriteCase(tmp2.path(), text(0.5)), o);
  RunOptions restart = o;
  restart.restart = tmp2 / "out" / "checkpoint.h5";
  restart.output_override = tmp2 / "out2";
  const RunSummary s2 = RunCase(WriteCase(tmp2.path(), text(1.0)), restart);
  ASSERT_EQ(s2.status, RunSummary::Status::kCompleted) << s2.message;
  EXPECT_EQ(s2.steps, 2);
  const std::vector<double> restarted = FreeSurfaceState(tmp2 / "out2" / "checkpoint.h5");
  ASSERT_EQ(straight.size(), restarted.size());
  double max_eta = 0.0;
  for (std::size_t i = 0; i < straight.size(); ++i) {
    EXPECT_EQ(straight[i], restarted[i]) << "state value " << i;
    if (i >= 3 && i < 3 + 200) max_eta = std::max(max_eta, std::abs(straight[i]));
  }
  EXPECT_GT(max_eta, 1e-4);  // the pressure patch makes waves
}

TEST(FreeSurfaceCase, RunWritesEtaOnThePatchAndRestartsBitForBit) {
  kelvin::testing::ScopedTempDir tmp;
  RunOptions o;
  o.progress = false;
  const RunSummary s = RunCase(WriteCase(tmp.path(), CaseText(1.0)), o);
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  EXPECT_EQ(s.steps, 4);
  ASSERT_TRUE(fs::exists(tmp / "out" / "zmax.pvd"));
  ASSERT_TRUE(fs::exists(tmp / "out" / "zmax_000004.vtp"));
  std::stringstream vtp;
  vtp << std::ifstream(tmp / "out" / "zmax_000004.vtp").rdbuf();
  EXPECT_NE(vtp.str().find("NumberOfPolys=\"200\""), std::string::npos);
  EXPECT_NE(vtp.str().find("Name=\"eta\""), std::string::npos);
  EXPECT_NE(vtp.str().find("Name=\"beach_damping\""), std::string::npos);
  std::stringstream pvd;
  pvd << std::ifstream(tmp / "out" / "zmax.pvd").rdbuf();
  EXPECT_NE(pvd.str().find("zmax_000002.vtp"), std::string::npos);

  ExpectRestartBitForBit(tmp / "out" / "checkpoint.h5", [](double end) { return CaseText(end); });
}

std::string LocalFlowCaseText(double end) {
  return Replace(CaseText(end), "      advection: quick\n", "      advection: quick\n      linearization: local_flow\n");
}

// What `case_text` run with `o` logs; the run must complete.
std::string LoggedRun(const fs::path& dir, const std::string& case_text, const RunOptions& o) {
  std::ostringstream log;
  const auto previous = spdlog::default_logger();
  spdlog::set_default_logger(
      std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(log)));
  const RunSummary s = RunCase(WriteCase(dir, case_text), o);
  spdlog::set_default_logger(previous);
  EXPECT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  return log.str();
}

// The local-flow linearization keeps its base flow (here, without a rigid
// lid, the flow of the first step) in the checkpoint: its restart is bit for
// bit as well. A run that starts without a lid says that its base flow is
// not a double body.
TEST(FreeSurfaceCase, LocalFlowRunRestartsBitForBit) {
  kelvin::testing::ScopedTempDir tmp;
  RunOptions o;
  o.progress = false;
  const std::string log = LoggedRun(tmp.path(), LocalFlowCaseText(1.0), o);
  EXPECT_NE(log.find("local_flow without time.rigid_lid_windows"), std::string::npos) << log;
  ExpectRestartBitForBit(tmp / "out" / "checkpoint.h5", LocalFlowCaseText);
}

// A local-flow run restarted from a uniform-stream checkpoint taken after
// the release finds waves and no base flow to keep: it says so. The same
// restart as a uniform-stream run is silent.
TEST(FreeSurfaceCase, LocalFlowRestartFromAUniformStreamCheckpointWarns) {
  kelvin::testing::ScopedTempDir tmp;
  RunOptions o;
  o.progress = false;
  ASSERT_EQ(RunCase(WriteCase(tmp.path(), CaseText(0.5)), o).status, RunSummary::Status::kCompleted);
  RunOptions restart = o;
  restart.restart = tmp / "out" / "checkpoint.h5";
  auto restarted_log = [&](const std::string& text, const char* out) {
    restart.output_override = tmp / out;
    return LoggedRun(tmp.path(), text, restart);
  };
  const std::string warned = restarted_log(LocalFlowCaseText(1.0), "local");
  EXPECT_NE(warned.find("restarted from a checkpoint of a released surface without a base flow"), std::string::npos)
      << warned;
  EXPECT_EQ(warned.find("without time.rigid_lid_windows"), std::string::npos) << warned;  // a restart: not that one
  const std::string silent = restarted_log(CaseText(1.0), "uniform");
  EXPECT_EQ(silent.find("without a base flow"), std::string::npos) << silent;
}

TEST(FreeSurfaceCase, UnknownLinearizationIsAnError) {
  ExpectCaseConfigError(Replace(CaseText(), "      advection: quick\n", "      linearization: dawson\n"), "dawson");
}

TEST(FreeSurfaceCase, NegativeGravityIsAnError) {
  ExpectCaseConfigError(Replace(CaseText(), "g: 9.81", "g: -9.81"), "g");
}

TEST(FreeSurfaceCase, UnknownKeyNamesTheKey) {
  ExpectCaseConfigError(Replace(CaseText(), "advection: quick", "advektion: quick"), "advektion");
}

TEST(FreeSurfaceCase, UnknownAdvectionSchemeIsAnError) {
  ExpectCaseConfigError(Replace(CaseText(), "advection: quick", "advection: central"), "central");
}

TEST(FreeSurfaceCase, PatchNotInTheCalmWaterPlaneIsAnError) {
  // The condition on zmin (z = -0.5, normal -z) instead of zmax.
  std::string t = Replace(CaseText(), "  zmin: {U: {type: slip}, p: {type: zeroGradient}}\n", "");
  t = Replace(t, "  zmax:\n", "  zmax: {U: {type: slip}, p: {type: zeroGradient}}\n  zmin:\n");
  ExpectCaseConfigError(t, "not in the calm-water plane");
}

TEST(FreeSurfaceCase, VelocityMustBeZeroGradient) {
  ExpectCaseConfigError(
      Replace(CaseText(), "    U: {type: zeroGradient}\n    p:", "    U: {type: slip}\n    p:"),
      "zeroGradient on a linearizedFreeSurface patch");
}

TEST(FreeSurfaceCase, BeachNeedsAMeshVelocity) {
  ExpectCaseConfigError(Replace(CaseText(), "      mesh_velocity: [-1.2495, 0, 0]\n", ""),
                    "mesh_velocity");
}

TEST(FreeSurfaceCase, UnknownBeachSideIsAnError) {
  ExpectCaseConfigError(Replace(CaseText(), "sides: [xmax, ymax]", "sides: [xmax, outlet]"), "outlet");
}

TEST(FreeSurfaceCase, NegativeBeachWidthIsAnError) {
  ExpectCaseConfigError(Replace(CaseText(), "width: 1.25", "width: -1"), "width");
}

TEST(FreeSurfaceCase, VerticalMeshVelocityIsAnError) {
  ExpectCaseConfigError(
      Replace(CaseText(), "mesh_velocity: [-1.2495, 0, 0]", "mesh_velocity: [-1.2495, 0, 0.1]"),
      "mesh_velocity");
}

TEST(FreeSurfaceCase, UnknownWaterlinePatchIsAnError) {
  ExpectCaseConfigError(Replace(CaseText(), "      advection: quick\n",
                            "      advection: quick\n      waterline_patches: [hull]\n"),
                    "hull");
}

TEST(FreeSurfaceCase, PressurePatchNeedsAPositiveRadius) {
  ExpectCaseConfigError(Replace(CaseText(), "radius: 0.5", "radius: 0"), "radius");
}

}  // namespace
}  // namespace kelvin::cfd
