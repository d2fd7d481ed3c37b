// Zero-pressure-gradient flat plate with k-omega SST and wall functions
// (issue: turbulence validation). References:
//  - ITTC-1957 model-ship correlation line, C_F = 0.075 / (log10 Re - 2)^2
//    (Proc. 8th ITTC, Madrid 1957);
//  - Schoenherr's turbulent flat-plate line, 0.242 / sqrt(C_F) = log10(Re C_F)
//    (Schoenherr 1932, Trans. SNAME 40);
//  - the log law u+ = ln(y+)/kappa + B with kappa = 0.41, B = 5.0-5.2;
//  - Prandtl-Schlichting local skin friction (2 log10 Re_x - 0.65)^-2.3
//    (Schlichting, Boundary-Layer Theory), plotted by the report script.
// The plate is fully turbulent from its leading edge (wall functions make it
// so), which is the flow both friction lines describe.
//
// Each run writes its plate data to $KELVIN_REPORT_DIR/flat_plate.h5 (when
// set), and tools/plot_flat_plate.py draws c_f(Re_x) and u+(y+) from it.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "cfd/verification/flat_plate.h"
#include "cfd/verification/gci.h"
#include "data/reference/friction_lines.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {
namespace {

FlatPlateResult RunPlate(double re, double y_plus, int cells_y, int cells_x, double refinement = 1.0,
                         double initial_viscosity_ratio = 0.0,
                         KOmegaSstOptions::WallOmega wall_omega = KOmegaSstOptions::WallOmega::kDiscreteSublayer) {
  FlatPlateOptions o;
  o.reynolds = re;
  o.y_plus = y_plus;
  o.cells_y = cells_y;
  o.cells_x = cells_x;
  o.refinement = refinement;
  FlatPlateRunOptions r;
  r.courant = 20.0;
  r.max_steps = 4000;
  r.initial_viscosity_ratio = initial_viscosity_ratio;
  r.wall_omega = wall_omega;
  FlatPlateResult res = RunFlatPlate(o, r);
  EXPECT_TRUE(res.converged) << "Re " << re << ": C_F still changing by " << res.C_F_change << ", largest residual "
                             << res.max_residual;
  EXPECT_EQ(res.bounded_cells, 0);
  const double ittc = data::Ittc57FrictionCoefficient(re);
  std::printf("Re_L %.3g, y+ %.1f (mean %.1f): C_F %.5e, ITTC-57 %+.2f%%, Schoenherr %+.2f%%, %d cells, %d steps\n",
              re, y_plus, res.wall.y_plus_mean, res.C_F, 100 * (res.C_F / ittc - 1),
              100 * (res.C_F / SchoenherrFrictionLine(re) - 1), res.cells, res.steps);
  return res;
}

void Report(const std::string& name, double re, const FlatPlateResult& r) {
  const char* dir = std::getenv("KELVIN_REPORT_DIR");
  if (!dir) return;
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = std::filesystem::path(dir) / "flat_plate.h5";
  static bool fresh = false;  // one report per test process
  if (!fresh) std::filesystem::remove(file);
  fresh = true;
  data::H5Writer w(file, std::filesystem::exists(file) ? data::H5Writer::Mode::kAppend : data::H5Writer::Mode::kCreate);
  const std::string g = "runs/" + name;
  w.WriteArray(g + "/x", r.x, {r.x.size()}, "m", "plate face centre (plate length 1 m)");
  w.WriteArray(g + "/cf", r.cf, {r.cf.size()}, "1", "local skin friction coefficient");
  w.WriteArray(g + "/y_plus", r.y_plus, {r.y_plus.size()}, "1", "cell-centre y+ at x_profile");
  w.WriteArray(g + "/u_plus", r.u_plus, {r.u_plus.size()}, "1", "u / u_tau at x_profile");
  w.SetAttribute(g, "reynolds", re);
  w.SetAttribute(g, "C_F", r.C_F);
  w.SetAttribute(g, "x_profile", r.x_profile);
  w.SetAttribute(g, "y_plus_mean", r.wall.y_plus_mean);
  w.Commit();
}

// Acceptance 1 and 2 at Re_L = 1e8 on a wall-function grid (y+ ~ 100).
TEST(FlatPlate, WallFunctionsAtReynolds1e8MatchFrictionLinesAndLogLaw) {
  const double re = 1e8;
  const FlatPlateResult r = RunPlate(re, 100.0, 60, 120);
  Report("re1e8_yplus100", re, r);
  EXPECT_GE(r.wall.y_plus_mean, 30.0);
  EXPECT_LE(r.wall.y_plus_mean, 100.0 * 1.1);
  const double ittc = data::Ittc57FrictionCoefficient(re);
  EXPECT_NEAR(r.C_F, ittc, 0.03 * ittc);
  EXPECT_NEAR(r.C_F, SchoenherrFrictionLine(re), 0.03 * SchoenherrFrictionLine(re));
  // u+ within 3% of the log-law band (kappa 0.41, B 5.0 to 5.2) for
  // 50 < y+ < 300.
  int checked = 0;
  for (std::size_t i = 0; i < r.y_plus.size(); ++i) {
    if (r.y_plus[i] <= 50.0 || r.y_plus[i] >= 300.0) continue;
    const double lo = std::log(r.y_plus[i]) / 0.41 + 5.0, hi = lo + 0.2;
    const double u = r.u_plus[i];
    const double off = u < lo ? (lo - u) / lo : u > hi ? (u - hi) / hi : 0.0;
    EXPECT_LE(off, 0.03) << "y+ " << r.y_plus[i] << " u+ " << u << " band " << lo << "-" << hi;
    ++checked;
  }
  EXPECT_GE(checked, 2);
  // The wall cell's eddy viscosity is the log law's, nu_t = kappa u_tau y
  // (nu_t / nu = kappa y+): its strain-rate limiter takes the log law's
  // u_tau / (kappa y), not the cell gradient's jump U_P / y_P to the wall
  // value, which is kappa u+ (about 7) times larger and would cut nu_t there
  // to a fraction (k_omega_sst.h). 10%: the SST log layer's own k / omega is
  // kappa u_tau y to within the 2-3% of its constants (beta*^0.5 sigma...).
  ASSERT_FALSE(r.nut_plus.empty());
  std::printf("wall cell: y+ %.1f, nu_t / nu %.2f, kappa y+ %.2f\n", r.y_plus[0], r.nut_plus[0],
              0.41 * r.y_plus[0]);
  EXPECT_NEAR(r.nut_plus[0] / (0.41 * r.y_plus[0]), 1.0, 0.10);
}

// Acceptance 3: moving the first cell from y+ 40 to y+ 100 changes C_F by
// less than 2%.
TEST(FlatPlate, WallFunctionResultIndependentOfYPlus) {
  const double re = 1e7;
  const FlatPlateResult a = RunPlate(re, 40.0, 60, 120);
  const FlatPlateResult b = RunPlate(re, 100.0, 60, 120);
  Report("re1e7_yplus40", re, a);
  Report("re1e7_yplus100", re, b);
  EXPECT_NEAR(a.wall.y_plus_mean, 40.0, 6.0);
  EXPECT_NEAR(b.wall.y_plus_mean, 100.0, 12.0);
  EXPECT_NEAR(b.C_F, a.C_F, 0.02 * a.C_F);
}

// Acceptance 4: three grids refined by sqrt(2) in every direction but the
// first cell's height, which stays at y+ 100; C_F converges monotonically.
// The observed order and GCI are printed (Celik et al. 2008 via ComputeGci).
// The wall functions' own dependence on the first cell's y+ is the test
// above; until 2026-12-07 this family refined the first cell too (y+ 100, 70,
// 50) and called the mix convergence (R 0.83; 1.32, divergent, with a wall
// omega that leaned less on the viscous value at y+ 50). Held at y+ 100:
// measured R 0.43.
TEST(FlatPlate, GridConvergenceIsMonotone) {
  const double re = 1e7, r = std::sqrt(2.0);
  const FlatPlateResult g3 = RunPlate(re, 100.0, 30, 60, 1.0);
  const FlatPlateResult g2 = RunPlate(re, 100.0 * r, 30, 60, r);
  const FlatPlateResult g1 = RunPlate(re, 100.0 * 2.0, 30, 60, 2.0);
  for (const FlatPlateResult* g : {&g1, &g2, &g3}) EXPECT_NEAR(g->wall.y_plus_mean, 100.0, 5.0);
  const GciResult gci = ComputeGci(g1.h, g2.h, g3.h, g1.C_F, g2.C_F, g3.C_F);
  std::printf("%s\n", gci.Report("flat plate C_F, Re_L 1e7, wall functions").c_str());
  EXPECT_EQ(gci.convergence, Convergence::kMonotonic);
  EXPECT_GT(gci.R, 0.0);
  EXPECT_LT(gci.R, 1.0);
}

// Wall-resolved plate (first cell at y+ about 1, the boundary layer tripped by
// nu_t / nu = 10 at the start): it must reach a steady state, every initial
// residual below 1e-4 (FlatPlateRunOptions). Before 2026-12-07 it did not:
// with k and omega unrelaxed it locked into an oscillation (largest residual
// 6e-2 on this grid) at C_F 55% below Schoenherr, and the C_F-only criterion
// called that converged.
//
// With the wall cell's viscous omega at the point value (kPointValue, as
// OpenFOAM's omegaWallFunction) the steady C_F is compared with OpenFOAM v1912
// simpleFoam kOmegaSST on the same mesh (tools/bench/flat_plate_peer.py,
// BENCHMARKS.md `flat_plate_peer`, case 1e7:1:60x60): kPeerCf, 1%, the
// difference of two implementations of one model on one mesh; both are 8.5%
// below Schoenherr's line. With kelvin's default, the value consistent with
// the discrete omega equation beyond the wall cell (SublayerOmegaScale()),
// C_F is within issue 22's 3% of the line (measured -0.21%; -0.11% on
// 100 x 80, -1.55% and -1.86% with the first cell at y+ 0.5 and 0.25, where
// the point value gives -5.85% and -4.09%: both tend to the same answer as the
// first cell shrinks, BENCHMARKS.md `flat_plate_peer`).
TEST(FlatPlate, WallResolvedPlateReachesASteadyStateOnSchoenherrsLineAndMatchesOpenFoam) {
  const double re = 1e7;
  const FlatPlateResult point = RunPlate(re, 1.0, 60, 60, 1.0, 10.0, KOmegaSstOptions::WallOmega::kPointValue);
  EXPECT_LT(point.max_residual, 1e-4);
  constexpr double kPeerCf = 2.68231e-3;
  EXPECT_NEAR(point.C_F, kPeerCf, 0.01 * kPeerCf);

  const FlatPlateResult consistent = RunPlate(re, 1.0, 60, 60, 1.0, 10.0);
  Report("re1e7_yplus1", re, consistent);
  EXPECT_LT(consistent.max_residual, 1e-4);
  const double schoenherr = SchoenherrFrictionLine(re);
  EXPECT_NEAR(consistent.C_F, schoenherr, 0.03 * schoenherr);
}

}  // namespace
}  // namespace kelvin::cfd
