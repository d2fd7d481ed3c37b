// `kelvin run` with k-omega SST: outputs, bitwise restart, positivity, and
// one clear error per bad turbulence input.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "cfd/run/run_case.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/cfd/cfd_test_support.h"
#include "tests/cfd/vtk_read.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using testing::ExpectCaseConfigError;
using testing::WriteCase;

// Channel flow at Re_H = 1e4 entering a plane channel with both walls.
const char* kCase = R"(mesh:
  box: {max: [4, 1, 0.1], cells: [24, 20, 1], grading: [1, 1, 1], empty: z}
physics: {nu: 1.0e-4}
schemes: {convection: linear_upwind}
solution:
  n_correctors: 2
  relax: {U_final: 0.7, p_final: 0.3}
time: {dt: 0.05, end: END}
turbulence:
  model: kOmegaSST
  inflow: {intensity: 0.01, viscosity_ratio: 5, reference_speed: 1.0}
boundary:
  xmin: {U: {type: fixedValue, value: [1, 0, 0]}, p: {type: zeroGradient}}
  xmax: {U: {type: zeroGradient}, p: {type: fixedValue, value: 0}}
  ymin: {U: {type: noSlip}, p: {type: zeroGradient}}
  ymax: {U: {type: noSlip}, p: {type: zeroGradient}}
output: {directory: out, vtu_interval: 0, checkpoint_interval: 5, forces: [ymin]}
)";

std::string CaseText(double end) {
  std::string s = kCase;
  s.replace(s.find("END"), 3, std::to_string(end));
  return s;
}

// The y+ guard: the same 20-cell channel is a wall-function grid at
// Re_H = 1e5 (first-cell y+ about 140 after 10 steps) and far too coarse at
// Re_H = 1e6 (y+ about 1100 on all of both walls): only the second run
// warns, and the report gives the area distribution in both.
TEST(TurbulentCase, YPlusGuardFiresOnAGridTooCoarseForTheReynoldsNumber) {
  for (const double nu : {1e-5, 1e-6}) {
    kelvin::testing::ScopedTempDir tmp;
    std::string text = CaseText(0.5);
    text.replace(text.find("nu: 1.0e-4"), 10, fmt::format("nu: {:g}", nu));
    RunOptions o;
    o.progress = false;
    const RunSummary s = RunCase(WriteCase(tmp.path(), text), o);
    ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
    std::printf("nu %g:\n%s\n", nu, s.message.c_str());
    EXPECT_NE(s.message.find("y+ on ymin by area: <1 "), std::string::npos) << s.message;
    EXPECT_EQ(s.message.find("WARNING: 100% of the area of 'ymin' has a first-cell y+ of 300 or more") !=
                  std::string::npos,
              nu < 5e-6)
        << s.message;
  }
}

TEST(TurbulentCase, WritesTurbulenceOutputsAndStaysPositive) {
  kelvin::testing::ScopedTempDir tmp;
  RunOptions o;
  o.progress = false;
  const RunSummary s = RunCase(WriteCase(tmp.path(), CaseText(0.5)), o);
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  EXPECT_NE(s.message.find("y+ on ymin"), std::string::npos) << s.message;
  std::ifstream vtu(tmp / "out" / "fields_000010.vtu");
  std::stringstream text;
  text << vtu.rdbuf();
  for (const char* name : {"\"k\"", "\"omega\"", "\"nut\"", "\"yPlus\"", "\"wallShearStress\""}) {
    EXPECT_NE(text.str().find(name), std::string::npos) << name;
  }
  data::H5Reader h(tmp / "out" / "history.h5");
  const data::Series yp = h.Read("turbulence/y_plus/ymin");
  EXPECT_EQ(yp.rows, 10u);
  EXPECT_EQ(yp.cols, 3u);
  EXPECT_GT(yp.at(9, 0), 0.0);
  EXPECT_LE(yp.at(9, 0), yp.at(9, 1));
  EXPECT_LE(yp.at(9, 1), yp.at(9, 2));
  // Upwind turbulence convection and implicit sinks: no cell ever needed
  // the bound step.
  for (const char* name : {"turbulence/bounded/k", "turbulence/bounded/omega"}) {
    for (double v : h.Read(name).values) EXPECT_EQ(v, 0.0) << name;
  }
  // The flow drags the walls downstream (force on the patch along +x).
  EXPECT_GT(h.Read("forces/ymin/viscous").at(9, 0), 0.0);
  // Each wall's surface file carries the wall shear stress and y+ per face;
  // over the patch (24 faces of 4/24 x 0.1 m^2) the shear stress adds up to
  // the viscous force of the history (the default rho, 1000 kg/m^3).
  std::stringstream vtp;
  vtp << std::ifstream(tmp / "out" / "ymin_000010.vtp").rdbuf();
  const std::vector<double> tau = testing::VtkDoubles(vtp.str(), "wallShearStress");
  const std::vector<double> y_plus = testing::VtkDoubles(vtp.str(), "yPlus");
  ASSERT_EQ(tau.size(), 3u * 24u);
  ASSERT_EQ(y_plus.size(), 24u);
  double fx = 0.0;
  for (std::size_t i = 0; i < 24; ++i) fx += 1000.0 * tau[3 * i] * (4.0 / 24.0) * 0.1;
  EXPECT_NEAR(fx, h.Read("forces/ymin/viscous").at(9, 0), 1e-9 * std::abs(fx));
  EXPECT_NEAR(*std::max_element(y_plus.begin(), y_plus.end()), yp.at(9, 2), 1e-9 * yp.at(9, 2));
}

TEST(TurbulentCase, RestartIsBitwise) {
  kelvin::testing::ScopedTempDir tmp;
  RunOptions o;
  o.progress = false;
  ASSERT_EQ(RunCase(WriteCase(tmp.path(), CaseText(0.5)), o).status, RunSummary::Status::kCompleted);
  fs::rename(tmp / "out", tmp / "straight");
  ASSERT_EQ(RunCase(WriteCase(tmp.path(), CaseText(0.25)), o).status, RunSummary::Status::kCompleted);
  RunOptions r = o;
  r.restart = tmp / "out" / "checkpoint.h5";
  r.output_override = tmp / "restarted";
  ASSERT_EQ(RunCase(WriteCase(tmp.path(), CaseText(0.5)), r).status, RunSummary::Status::kCompleted);
  data::H5Reader a(tmp / "straight" / "checkpoint.h5"), b(tmp / "restarted" / "checkpoint.h5");
  for (const char* name : {"U", "p", "phi", "turbulence/k", "turbulence/omega", "turbulence/nut"}) {
    const auto va = a.Read(name).values, vb = b.Read(name).values;
    ASSERT_EQ(va.size(), vb.size()) << name;
    for (std::size_t i = 0; i < va.size(); ++i) ASSERT_EQ(va[i], vb[i]) << name << "[" << i << "]";
  }
}

TEST(TurbulentCase, BadInputsNameTheKey) {
  auto with = [](const std::string& from, const std::string& to) {
    std::string t = CaseText(0.1);
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  ExpectCaseConfigError(with("model: kOmegaSST", "model: kEpsilon"), "kOmegaSST or laminar");
  ExpectCaseConfigError(with("intensity: 0.01", "intensity: 2"), "intensity");
  ExpectCaseConfigError(with("viscosity_ratio: 5", "viscosity_ratio: -1"), "viscosity_ratio");
  ExpectCaseConfigError(with(", reference_speed: 1.0", ""), "reference_speed");
  ExpectCaseConfigError(with("  model: kOmegaSST", "  model: kOmegaSST\n  wall_treatment: spalding"), "wall_treatment");
  // turbulence.solver: the tolerances and iteration limit of the k and omega solves, not the method.
  ExpectCaseConfigError(with("  model: kOmegaSST", "  model: kOmegaSST\n  solver: {solver: cg}"), "solver");
  ExpectCaseConfigError(with("  model: kOmegaSST", "  model: kOmegaSST\n  solver: {relative_tolerance: 2}"),
                        "relative_tolerance = 2; expected in [0, 1)");
  std::string no_walls = with("ymin: {U: {type: noSlip}", "ymin: {U: {type: slip}");
  no_walls.replace(no_walls.find("ymax: {U: {type: noSlip}"), 24, "ymax: {U: {type: slip}");
  ExpectCaseConfigError(no_walls, "at least one wall patch");
}

}  // namespace
}  // namespace kelvin::cfd
