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
// Fn 0.32.
// Acceptance 4 also asks the identified set to reproduce the CFD forces of
// every run: in every run and channel (X, Y, N) the nondimensional RMS
// residual of the fit must stay below kResidualBound = 1/3 of the run's RMS
// force. The forces carry no noise to speak of (period-to-period change
// below 0.1%, see below), so the residual is model error alone: the cubic
// polynomial's truncation over the drift range and, in the PMM runs, the
// frequency-dependent force the quasi-steady MMG standard model has no term
// for, above all N_vdot in pure sway (zero for a fore-aft symmetric hull in
// slender-body theory; what the wake and the waves give it leaves a force in
// quadrature with the modelled one). A residual of a third of the signal
// still means every run's force within a third in amplitude and about 20
// degrees in phase (the model explains 8/9 of its variance), much tighter
// than the factor 2 allowed against the regression of other hulls above;
// a run the set does not describe sits near 1 (as N' of pure sway did at
// omega' = 3, tau = omega U / g = 0.31). At omega' = 1.2 the bound admits
// an unmodelled N'_vdot up to |N'_v| / (3 omega') = 0.026, as large as the
// value measured at omega' = 3. Y and N of the straight-ahead run vanish by
// symmetry; there the residual is measured against the channel's largest
// RMS in the campaign. Residuals, ratios and the classical PMM derivatives
// (PMM against static drift) are printed.
// Acceptance 4 also asks the PMM forces to be periodic after the ramp-up:
// the first-harmonic amplitudes of Y and N over the last period differ from
// those over the period before by less than 1% in every pure sway and pure
// yaw run.
// The same checks run on the quickstart's coarse campaign
// (wigley_quick_*.yaml: 5k cells, 96 steps per period).
// About 10 + 2 CPU-minutes (label slow).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

#include "data/schema/captive_io.h"
#include "identification/joint_fit.h"
#include "identification/pmm_analysis.h"
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

// Largest RMS residual / RMS force of any run and channel (see the header).
constexpr double kResidualBound = 1.0 / 3.0;

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

  const data::CaptiveCampaign c =
      data::ReadCampaignH5(dir / "runs" / (std::string(p.name) + ".h5"));
  int harmonic_runs = 0;
  for (const data::CaptiveRun& r : c.runs) {
    if (!data::IsHarmonic(r.motion.kind)) continue;
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
  // Every run reproduced: in each channel the RMS residual of the identified
  // set is below kResidualBound times the run's RMS force (see the header).
  // Y and N of the straight-ahead run vanish by symmetry (and so does the
  // model's), so there the residual is measured against the largest RMS of
  // that channel over the campaign.
  std::array<double, 3> largest{};
  for (const RunFitStatistics& r : fit.runs) {
    for (int ch = 0; ch < 3; ++ch) largest[ch] = std::max(largest[ch], r.rms_measured[ch]);
  }
  for (const RunFitStatistics& r : fit.runs) {
    const auto it = std::find_if(c.runs.begin(), c.runs.end(),
                                 [&](const data::CaptiveRun& x) { return x.name == r.run; });
    ASSERT_NE(it, c.runs.end()) << r.run;
    const bool straight =
        it->motion.kind == data::MotionKind::kStaticDrift && it->motion.beta == 0.0;
    std::printf("%-16s RMS residual / RMS measured:", r.run.c_str());
    for (int ch = 0; ch < 3; ++ch) {
      const double reference = straight && ch > 0 ? largest[ch] : r.rms_measured[ch];
      const double ratio = r.rms_residual[ch] / reference;
      std::printf("  %c %.3g/%.3g = %.3f", "XYN"[ch], r.rms_residual[ch], reference, ratio);
      EXPECT_LT(ratio, kResidualBound) << r.run << " " << "XYN"[ch];
    }
    std::printf("\n");
  }
  // PMM against static drift (printed): the in-phase part of the pure sway
  // first harmonic against the static drift regression.
  for (const ClassicalEstimate& e : AnalyseCampaign(c, p.name).estimates) {
    if (e.name == "Y_v" || e.name == "N_v" || e.name == "N_vdot" || e.name == "Y_rdot" ||
        e.name == "N_r")
      std::printf("classical %-6s = %+.4f (%s)\n", e.name.c_str(), e.value, e.source.c_str());
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
