// Issue 7, acceptance 4, on the Wigley hull with k-omega SST and the
// linearized free surface (data/cases/captive_cfd/wigley_lfs_*.yaml: 1 m
// hull, Re 1e6, Fn 0.32, 15k cells, the whole grid moving in still water).
// The campaign (4 static drift, 2 pure sway and 2 pure yaw runs) is computed
// and identified; the linear derivatives must have the physically expected
// signs (Y'v < 0, N'v < 0, Y'r > 0, N'r < 0) and magnitudes within a factor
// 2 of the empirical formulas of Inoue, Hirano & Kijima (1981),
// "Hydrodynamic derivatives on ship manoeuvring", International Shipbuilding
// Progress 28(321):112-125, for an even-keel hull with k = 2d/L = 0.125,
// C_B = 4/9, B/L = 0.1 (prime system 0.5 rho L d U^2):
//   Y'v = -(pi k / 2 + 1.4 C_B B/L) = -0.259,  Y'r = pi k / 4 = 0.098,
//   N'v = -k = -0.125,                         N'r = -(0.54 k - k^2) = -0.052.
// The formulas are regressions over merchant-ship models at low Froude
// number (no wave effect, within about +-20% of their data); the factor 2
// allows for a slender hull outside that data set and the free surface at
// Fn 0.32. Every run's nondimensional RMS fit residual is printed.
// Acceptance 4 also asks the PMM forces to be periodic after the ramp-up:
// the first-harmonic amplitudes of Y and N over the last period differ from
// those over the period before by less than 1% in every pure sway and pure
// yaw run.
// The same checks run on the quickstart's coarse campaign
// (wigley_quick_*.yaml: 5k cells, 48 steps per period).
// About 5.5 + 1.5 CPU-minutes (label slow).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

#include "identification/captive_io.h"
#include "identification/joint_fit.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::ident {
namespace {

namespace fs = std::filesystem;

using kelvin::testing::ReadText;

void Replace(std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

// Amplitude of the first harmonic (least squares on 1, sin, cos) of y over
// the samples [begin, end).
double FirstHarmonic(const std::vector<double>& t, const std::vector<double>& y, double omega,
                     std::size_t begin, std::size_t end) {
  Eigen::MatrixXd a(static_cast<Eigen::Index>(end - begin), 3);
  Eigen::VectorXd b(a.rows());
  for (std::size_t i = begin; i < end; ++i) {
    const auto row = static_cast<Eigen::Index>(i - begin);
    a.row(row) << 1.0, std::sin(omega * t[i]), std::cos(omega * t[i]);
    b(row) = y[i];
  }
  const Eigen::Vector3d c = a.colPivHouseholderQr().solve(b);
  return std::hypot(c(1), c(2));
}

// One CFD campaign of the repository: its files and the strings the test
// replaces to run it in a temporary directory.
struct CampaignCase {
  const char* name;       // campaign.name (the HDF5 file of the campaign)
  const char* mesh;       // mesh file
  const char* case_file;  // kelvin run case
  const char* grid;       // the case's poly_mesh path
  const char* campaign;   // campaign file
  const char* directory;  // the campaign's run directory
};

class WigleyLfsCampaign : public ::testing::TestWithParam<CampaignCase> {};

TEST_P(WigleyLfsCampaign, LinearDerivativesHaveTheExpectedSignsAndMagnitudes) {
  const CampaignCase& p = GetParam();
  const fs::path data = kelvin::testing::SourceDir() / "data/cases/captive_cfd";
  const std::string kelvin = (kelvin::testing::ToolsDir() / "kelvin").string();
  kelvin::testing::ScopedTempDir dir;
  const auto mesh = kelvin::testing::RunCommand(kelvin + " mesh " + (data / p.mesh).string() +
                                                " -o " + (dir / "grid").string());
  ASSERT_EQ(mesh.exit_code, 0) << mesh.output;
  std::string case_text = ReadText(data / p.case_file);
  Replace(case_text, p.grid, (dir / "grid/constant/polyMesh").string());
  std::ofstream(dir / "case.yaml") << case_text;
  std::string campaign = ReadText(data / p.campaign);
  Replace(campaign, "ship: wigley_ship.yaml", "ship: " + (data / "wigley_ship.yaml").string());
  Replace(campaign, std::string("case: ") + p.case_file, "case: " + (dir / "case.yaml").string());
  Replace(campaign, std::string("directory: ") + p.directory, "directory: " + (dir / "runs").string());
  std::ofstream(dir / "campaign.yaml") << campaign;
  const auto run = kelvin::testing::RunCommand(kelvin + " captive " + (dir / "campaign.yaml").string() +
                                               " --no-progress");
  ASSERT_EQ(run.exit_code, 0) << run.output;

  const CaptiveCampaign c = ReadCampaignH5(dir / "runs" / (std::string(p.name) + ".h5"));
  int harmonic_runs = 0;
  for (const CaptiveRun& r : c.runs) {
    if (!IsHarmonic(r.motion.kind)) continue;
    ++harmonic_runs;
    const double period = r.motion.Period();
    const std::size_t n = r.time.size();
    // Samples per period from the constant time step of the campaign.
    const auto per = static_cast<std::size_t>(std::llround(period / (r.time[1] - r.time[0])));
    ASSERT_GE(n, 2 * per) << r.name;
    ASSERT_GE(r.time[n - 2 * per], r.motion.t_ramp - 1e-9) << r.name << ": both periods after the ramp";
    for (int ch : {1, 2}) {
      const double last = FirstHarmonic(r.time, r.force[ch], r.motion.omega, n - per, n);
      const double before = FirstHarmonic(r.time, r.force[ch], r.motion.omega, n - 2 * per, n - per);
      const double change = std::abs(last - before) / last;
      std::printf("%-12s %s first harmonic: period-to-period change %.3f%%\n", r.name.c_str(),
                  ch == 1 ? "Y" : "N", 100 * change);
      EXPECT_LT(change, 0.01) << r.name << (ch == 1 ? " Y" : " N");
    }
  }
  EXPECT_EQ(harmonic_runs, 4);
  const JointFitResult fit = FitCampaign(c, JointFitOptions{}, p.name);
  ASSERT_TRUE(fit.converged) << fit.solver_report;
  for (const RunFitStatistics& r : fit.runs) {
    std::printf("%-16s RMS residual / RMS measured: X %.3g/%.3g  Y %.3g/%.3g  N %.3g/%.3g\n", r.run.c_str(),
                r.rms_residual[0], r.rms_measured[0], r.rms_residual[1], r.rms_measured[1], r.rms_residual[2],
                r.rms_measured[2]);
  }
  const double k = 2 * 0.0625 / 1.0, cb = 4.0 / 9.0, b_l = 0.1;
  struct Expected {
    const char* name;
    double inoue;
  };
  for (const Expected& e : {Expected{"Y_v", -(std::numbers::pi * k / 2 + 1.4 * cb * b_l)},
                            Expected{"Y_r", std::numbers::pi * k / 4}, Expected{"N_v", -k},
                            Expected{"N_r", -(0.54 * k - k * k)}}) {
    const int i = CoefficientIndex(e.name);
    ASSERT_GE(i, 0) << e.name;
    ASSERT_TRUE(fit.Identified(i)) << e.name;
    const double v = fit.coefficients[i];
    std::printf("%s = %.4f (Inoue et al. 1981: %.4f, ratio %.2f)\n", e.name, v, e.inoue, v / e.inoue);
    EXPECT_GT(v / e.inoue, 0.5) << e.name << " sign or magnitude";
    EXPECT_LT(v / e.inoue, 2.0) << e.name;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Campaigns, WigleyLfsCampaign,
    ::testing::Values(
        CampaignCase{"wigley_lfs", "wigley_lfs_mesh.yaml", "wigley_lfs_case.yaml",
                     "../../../build/grids/wigley_lfs_captive/constant/polyMesh",
                     "wigley_lfs_campaign.yaml", "../results/wigley_lfs"},
        // The quickstart's coarse campaign (tools/quickstart stage 3).
        CampaignCase{"wigley_quick", "wigley_quick_mesh.yaml", "wigley_quick_case.yaml",
                     "../../../build/grids/wigley_captive_quick/constant/polyMesh",
                     "wigley_quick_campaign.yaml", "../../../results/quickstart/wigley_cfd"}),
    [](const ::testing::TestParamInfo<CampaignCase>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace kelvin::ident
