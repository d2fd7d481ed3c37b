// Case files: a clear error for each bad input, a run that writes its
// outputs, a restart through the CLI, and a diverging run.
#include "cfd/run/run_case.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/cfd/cfd_test_support.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using testing::ExpectCaseConfigError;
using testing::WriteCase;

const char* kCase = R"(mesh:
  box: {max: [1, 1, 0.1], cells: [12, 12, 1], empty: z}
physics: {nu: 0.01}
schemes: {convection: linear_upwind}
solution:
  n_correctors: 2
  pressure: {solver: pcg_amg, relative_tolerance: 1.0e-6}
time: {dt: DT, end: END}
boundary:
  ymax: {U: {type: fixedValue, value: [1, 0, 0]}, p: {type: zeroGradient}}
  xmin: {U: {type: noSlip}, p: {type: zeroGradient}}
  xmax: {U: {type: noSlip}, p: {type: zeroGradient}}
  ymin: {U: {type: noSlip}, p: {type: zeroGradient}}
output: {directory: out, vtu_interval: 5, checkpoint_interval: 5, forces: [ymax]}
)";

std::string CaseText(double dt = 0.05, double end = 0.5) {
  std::string s = kCase;
  s.replace(s.find("DT"), 2, std::to_string(dt));
  s.replace(s.find("END"), 3, std::to_string(end));
  return s;
}

TEST(CaseRunner, UnknownKeyNamesTheKey) {
  std::string t = CaseText();
  t.replace(t.find("n_correctors"), 12, "n_corectors");
  ExpectCaseConfigError(t, "n_corectors");
}

TEST(CaseRunner, UnknownPatchIsAnError) {
  std::string t = CaseText();
  t.replace(t.find("  ymin:"), 7, "  floor:");
  ExpectCaseConfigError(t, "floor");
}

TEST(CaseRunner, PatchWithoutConditionIsAnError) {
  std::string t = CaseText();
  const std::size_t at = t.find("  ymin:");
  t.erase(at, t.find('\n', at) - at + 1);
  ExpectCaseConfigError(t, "ymin");
}

TEST(CaseRunner, UnknownConditionTypeIsAnError) {
  std::string t = CaseText();
  t.replace(t.find("type: noSlip"), 12, "type: sticky");
  ExpectCaseConfigError(t, "sticky");
}

TEST(CaseRunner, RunWritesFieldsHistoryAndCheckpoint) {
  kelvin::testing::ScopedTempDir tmp;
  RunOptions o;
  o.progress = false;
  const RunSummary s = RunCase(WriteCase(tmp.path(), CaseText()), o);
  EXPECT_EQ(s.status, RunSummary::Status::kCompleted);
  EXPECT_EQ(s.steps, 10);
  EXPECT_TRUE(fs::exists(tmp / "out" / "fields.pvd"));
  EXPECT_TRUE(fs::exists(tmp / "out" / "fields_000010.vtu"));
  EXPECT_TRUE(fs::exists(tmp / "out" / "checkpoint.h5"));
  data::H5Reader h(tmp / "out" / "history.h5");
  EXPECT_EQ(h.Read("time").rows, 10u);
  EXPECT_EQ(h.Read("forces/ymax/viscous").cols, 3u);
  // The lid drags the fluid along +x, so the fluid pulls the lid back.
  const data::Series fv = h.Read("forces/ymax/viscous");
  EXPECT_LT(fv.at(9, 0), 0.0);
  EXPECT_EQ(h.Read("residuals/p").units, "1");
  // Where the largest Courant number sits: in the top row of cells, which the
  // lid drives (row centre y = 11.5 / 12), every step.
  const data::Series at = h.Read("courant_location");
  ASSERT_EQ(at.rows, 10u);
  ASSERT_EQ(at.cols, 3u);
  for (std::size_t r = 0; r < at.rows; ++r) {
    EXPECT_NEAR(at.at(r, 1), 11.5 / 12.0, 1e-12) << "step " << r + 1;
    EXPECT_GT(at.at(r, 0), 0.0);
    EXPECT_LT(at.at(r, 0), 1.0);
  }
}

TEST(CaseRunner, CliRunAndRestart) {
  const fs::path kelvin = kelvin::testing::ToolsDir() / "kelvin";
  if (!fs::exists(kelvin)) GTEST_SKIP() << "kelvin CLI not built";
  kelvin::testing::ScopedTempDir tmp;
  const fs::path c = WriteCase(tmp.path(), CaseText(0.05, 0.25));
  auto r = kelvin::testing::RunCommand(kelvin.string() + " run --no-progress " + c.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // Continue from the checkpoint at t = 0.25 to t = 0.5.
  const fs::path c2 = WriteCase(tmp.path(), CaseText(0.05, 0.5));
  r = kelvin::testing::RunCommand(kelvin.string() + " run --no-progress --restart " +
                                  (tmp / "out" / "checkpoint.h5").string() + " -o " + (tmp / "out2").string() + " " +
                                  c2.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("completed 5 steps to t = 0.5"), std::string::npos) << r.output;
  r = kelvin::testing::RunCommand(kelvin.string() + " run " + (tmp / "missing.yaml").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
}

TEST(CaseRunner, DivergenceStopsWithAStatusAndKeepsTheLastGoodCheckpoint) {
  kelvin::testing::ScopedTempDir tmp;
  // An absurd body force: the first steps give |U| ~ 1e151 (finite), then
  // the products in the convective flux overflow.
  std::string t = CaseText(0.05, 1.0);
  t.replace(t.find("physics: {nu: 0.01}"), 19, "physics: {nu: 0.01, body_force: [1.0e153, 0, 0]}");
  t.replace(t.find("checkpoint_interval: 5"), 22, "checkpoint_interval: 1");
  RunOptions o;
  o.progress = false;
  const RunSummary s = RunCase(WriteCase(tmp.path(), t), o);
  ASSERT_EQ(s.status, RunSummary::Status::kDiverged) << s.message;
  EXPECT_NE(s.message.find("diverged at step"), std::string::npos) << s.message;
  // It says where the run was growing fastest before it failed.
  EXPECT_NE(s.message.find("the largest Courant number"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("in the cell at ("), std::string::npos) << s.message;
  EXPECT_LT(s.steps, 20);
  ASSERT_GE(s.steps, 2) << s.message;
  ASSERT_TRUE(fs::exists(tmp / "out" / "checkpoint.h5"));
  data::H5Reader r(tmp / "out" / "checkpoint.h5");
  EXPECT_EQ(r.NumberAttribute("/", "step"), s.steps - 1);
  for (double v : r.Read("U").values) EXPECT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace kelvin::cfd

namespace kelvin::cfd {
namespace {

// time.steady stops a run once the force has settled, and reference: {speed,
// direction} writes coefficients that are the force over 1/2 rho U^2 S (S: the patch
// area by default).
TEST(CaseRunner, CourantGrowthOnsetFindsTheLastRunAboveTwiceTheMedian) {
  // Median 1: a first surge that settled (indices 5-6), then the final growth
  // from index 9 on.
  const std::vector<double> co = {1, 1, 1, 1, 1, 5, 4, 1, 1, 3, 9, 50};
  const CourantOnset a = CourantGrowthOnset(co);
  EXPECT_TRUE(a.grew);
  EXPECT_EQ(a.step, 9u);
  EXPECT_DOUBLE_EQ(a.median, 1.0);
  // No growth at the end: the last step.
  const std::vector<double> flat = {2, 2, 3, 2};
  const CourantOnset b = CourantGrowthOnset(flat);
  EXPECT_FALSE(b.grew);
  EXPECT_EQ(b.step, 3u);
  // Growth right up to the end of a short history.
  const std::vector<double> late = {1, 1, 1, 10, 100};
  EXPECT_EQ(CourantGrowthOnset(late).step, 3u);
}

TEST(CaseRunner, SteadyStopAndResistanceCoefficients) {
  kelvin::testing::ScopedTempDir tmp;
  std::string t = CaseText(0.05, 50.0);
  t.replace(t.find("time: {dt: "), 11,
            "reference: {speed: 1, direction: [-2, 0, 0]}\n"
            "time: {steady: {quantities: [force], window: 0, window_steps: 10, tolerance: 1.0e-4, min_steps: 20}, dt: ");
  RunOptions o;
  o.progress = false;
  const RunSummary s = RunCase(WriteCase(tmp.path(), t), o);
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  EXPECT_TRUE(s.steady_converged) << s.message;
  EXPECT_LT(s.steps, 1000);  // stopped long before time.end
  EXPECT_GE(s.steps, 20);
  EXPECT_LT(s.steady_change, 1e-4);
  EXPECT_NE(s.message.find("steady: settled at step"), std::string::npos) << s.message;
  const data::H5Reader h(tmp.path() / "out" / "history.h5");
  const data::Series fp = h.Read("forces/ymax/pressure"), fv = h.Read("forces/ymax/viscous");
  const data::Series ct = h.Read("resistance/C_T"), cf = h.Read("resistance/C_F"), cp = h.Read("resistance/C_P");
  ASSERT_EQ(ct.rows, static_cast<std::size_t>(s.steps));
  const std::size_t last = ct.rows - 1;
  const double q = 0.5 * 1000.0 * 1.0 * 0.1;  // rho U^2 / 2 times the lid area 1 m x 0.1 m
  EXPECT_NEAR(cf.at(last), -fv.at(last, 0) / q, 1e-12 * std::abs(cf.at(last)));
  EXPECT_NEAR(cp.at(last), -fp.at(last, 0) / q, 1e-12 * std::abs(cf.at(last)));
  EXPECT_NEAR(ct.at(last), cf.at(last) + cp.at(last), 1e-15);
  EXPECT_GT(cf.at(last), 0.0);  // the fluid holds the lid back
  EXPECT_DOUBLE_EQ(h.Read("steady/converged").at(0), 1.0);
  EXPECT_NEAR(h.Read("resistance/reference").at(1), 0.1, 1e-12);
}

// A run on the steady criterion, with a time-step ramp, stopped before it
// settles and restarted from its checkpoint, settles at the step of the
// uninterrupted run and ends on the same state bit for bit: the checkpoint
// keeps the criterion's window and the phase (before, the restart refilled
// the window, waited out min_steps and ramped dt again).
TEST(CaseRunner, ARestartedSteadyRunSettlesAtTheStepOfAnUninterruptedOne) {
  kelvin::testing::ScopedTempDir tmp;
  auto text = [](double end) {
    std::string t = CaseText(0.05, end);
    t.replace(t.find("time: {dt: "), 11,
              "time: {steady: {quantities: [force], window: 0, window_steps: 10, tolerance: 1.0e-4, min_steps: 20}, "
              "ramp_steps: 6, dt: ");
    return t;
  };
  RunOptions o;
  o.progress = false;
  o.output_override = tmp / "whole";
  const RunSummary whole = RunCase(WriteCase(tmp.path(), text(50.0)), o);
  ASSERT_TRUE(whole.steady_converged) << whole.message;
  ASSERT_GT(whole.steps, 30);
  // Stop 8 steps before it settles: inside a full window, after the ramp
  // (time.end sets the step count at the nominal dt).
  o.output_override = tmp / "stopped";
  const RunSummary stopped = RunCase(WriteCase(tmp.path(), text(0.05 * (whole.steps - 8))), o);
  ASSERT_EQ(stopped.status, RunSummary::Status::kCompleted) << stopped.message;
  ASSERT_FALSE(stopped.steady_converged);
  ASSERT_EQ(stopped.steps, whole.steps - 8);
  o.restart = tmp / "stopped" / "checkpoint.h5";
  o.output_override = tmp / "restarted";
  const RunSummary restarted = RunCase(WriteCase(tmp.path(), text(50.0)), o);
  ASSERT_TRUE(restarted.steady_converged) << restarted.message;
  EXPECT_EQ(restarted.steps, 8) << restarted.message;
  const data::H5Reader a(tmp / "whole" / "checkpoint.h5"), b(tmp / "restarted" / "checkpoint.h5");
  EXPECT_EQ(a.NumberAttribute("/", "step"), b.NumberAttribute("/", "step"));
  EXPECT_EQ(a.NumberAttribute("/", "time"), b.NumberAttribute("/", "time"));
  for (const char* name : {"U", "p", "phi", "run/steady_window"}) {
    EXPECT_EQ(a.Read(name).values, b.Read(name).values) << name;
  }
}

TEST(CaseRunner, BadSteadyAndResistanceSectionsAreErrors) {
  const std::string t = CaseText();
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = t;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::string steady = "time: {steady: {quantities: [force], window: 0, tolerance: 1.0e-3";
  ExpectCaseConfigError(with("time: {dt: ", steady + ", window_steps: 0}, dt: "), "window_steps = 0");
  ExpectCaseConfigError(with("time: {dt: ", steady + ", min_steps: -2}, dt: "), "min_steps = -2");
  ExpectCaseConfigError(with("time: {dt: ", "time: {steady: {quantities: [force], window: 0, tolerance: -1}, dt: "),
                        "tolerance");
  ExpectCaseConfigError(with("time: {dt: ", "time: {steady: {quantities: [lift], window: 0}, dt: "),
                        "one of drag, force, eta");
  ExpectCaseConfigError(with("time: {dt: ", "time: {steady: {quantities: [eta], window: 0}, dt: "),
                        "no eta: the case has no linearizedFreeSurface patch");
  ExpectCaseConfigError(with("time: {dt: ", "time: {steady: {quantities: [drag], window: 0}, dt: "),
                        "force instead of drag, or a reference");
  ExpectCaseConfigError(with("time: {dt: ", "time: {rigid_lid_windows: 1, " + steady.substr(7) + "}, dt: "),
                        "a double body has no lid to release");
  std::string no_forces = with("time: {dt: ", steady + "}, dt: ");
  no_forces.replace(no_forces.find("forces: [ymax]"), 14, "forces: []");
  ExpectCaseConfigError(no_forces, "output.forces");
  const std::string ref = "reference: {speed: 1";
  ExpectCaseConfigError(with("time: {dt: ", ref + "}\ntime: {dt: "), "direction");
  ExpectCaseConfigError(with("time: {dt: ", ref + ", direction: [0, 0, 0]}\ntime: {dt: "), "non-zero finite vector");
  ExpectCaseConfigError(with("time: {dt: ", "reference: {speed: 0, direction: [1, 0, 0]}\ntime: {dt: "), "speed");
}

// A key of the older layouts is one error naming its replacement.
TEST(CaseRunner, OldKeysNameTheirReplacement) {
  const std::string t = CaseText();
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = t;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  ExpectCaseConfigError(with("time: {dt: ", "time: {steady: {window: 10, tolerance: 1.0e-3, min_steps: 20}, dt: "),
                        "expected a quantities list (drag, force, eta, ship_loads): the steady criterion changed");
  ExpectCaseConfigError(with("forces: [ymax]}", "forces: [ymax], resistance: {speed: 1, direction: [1, 0, 0]}}"),
                        "key 'output.resistance'");
  ExpectCaseConfigError(with("forces: [ymax]}", "forces: [ymax], resistance: {speed: 1, direction: [1, 0, 0]}}"),
                        "reference: {speed, direction, area}");
  const std::string res = "\nresistance: {hull: ymax, ";
  ExpectCaseConfigError(t + res + "steady: {tolerance: 1.0e-3}}\n", "time.steady {quantities: [drag, eta]");
  ExpectCaseConfigError(t + res + "inflow: [-1, 0, 0]}\n", "reference: {speed, direction}");
  ExpectCaseConfigError(t + res + "wetted_area: 1}\n", "reference.area");
  ExpectCaseConfigError(t + res + "length: 1}\n", "reference.length");
}

}  // namespace
}  // namespace kelvin::cfd
