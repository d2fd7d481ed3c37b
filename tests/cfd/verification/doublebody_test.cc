// Double-body steady flow with k-omega SST and wall functions, issue #5
// acceptance 3: the viscous resistance C_V = C_F + C_P of the double body
// against (1 + k) C_F0, with C_F0 the ITTC-57 line 0.075 / (log10 Re - 2)^2
// (Proc. 8th ITTC, Madrid 1957). The pressure (form) part C_P must be
// positive and small.
//
// Wigley hull at Re = 5e6 (data/cases/doublebody/wigley.yaml): 1 + k = 1.08,
// UNVERIFIED. It is recalled as the ITTC cooperative experiments on Wigley
// parabolic models (Kajitani et al. 1983, 17th ITTC Resistance Committee;
// Prohaska values of the tanks about 1.05-1.12); a search of the stored
// public documents, pages, code and issues (2026-11-22) found neither the
// report nor a text quoting a Wigley form factor.
//
// DTC model 1:59.407 at 1.668 m/s, Re = 9.1e6 (data/cases/doublebody/
// dtc.yaml): 1 + k = 1.094 from el Moctar, Shigunov & Zorn (2012), Duisburg
// Test Case: Post-Panamax container ship for benchmarking, Ship Technology
// Research 59(3), Table 4 (SVA Potsdam model tests): k = 0.094 with
// C_W = C_T - (1 + k) C_F. Confirmed from a secondary source only: the table
// as quoted in the public repository pankgeorg/ShipFlow.jl, whose six rows
// satisfy that relation with k = 0.094 to the printed digits.
//
// WigleyFineGrid (ctest label `slow`, several CPU minutes): grid 1 of the
// study family (164,864 cells, first-cell y+ target 35), the grid the
// acceptance is judged on: C_V within 5% of (1 + k) C_F0, C_P > 0.
// DtcGrid1 (ctest label `slow`, about 20 CPU minutes): grid 1 of
// data/cases/mesh/dtc_snappy.yaml (snappyHexMesh, ~0.2M cells, first-cell
// y+ ~ 95): C_V within 5% of (1 + k) C_F0; 0 < C_P < 2 k / (1 + k) C_V, twice
// the viscous pressure share the form factor implies.
// WigleyCoarseGrid (label `validation`, about 30 CPU seconds): grid 3 of the
// family (20,608 cells, y+ target 70). Asserted: the force settles, C_P is
// positive and below 10% of C_V, the side force vanishes by symmetry, and C_V
// is within 10% of (1 + k) C_F0. The wider band is this grid's
// discretization error measured by the three-grid study (BENCHMARKS.md,
// section doublebody, run 2026-11-22): grid 3 C_V = 3.377e-3 is 4.3% below
// the Richardson-extrapolated 3.529e-3 (observed order 3.2, GCI_fine 0.6%),
// which itself is 3.8% below (1 + k) C_F0 = 3.668e-3; grid 1 gives 3.512e-3
// (0.957 of the reference).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "cfd/grid/mesh_case.h"
#include "cfd/run/run_case.h"
#include "cfd/verification/flat_plate.h"
#include "data/reference/friction_lines.h"
#include "data/schema/h5_file.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using kelvin::testing::ScopedTempDir;
using kelvin::testing::SourceDir;

constexpr double kFormFactor = 1.08;  // Wigley, unverified, see the header
constexpr double kReynolds = 2.0 * 2.5 / 1.0e-6;
constexpr double kDtcFormFactor = 1.094;  // DTC, see the header
constexpr double kDtcReynolds = 1.668 * 5.976 / 1.09e-6;

struct DoubleBody {
  double C_T = 0, C_F = 0, C_P = 0;
  double side_force_ratio = 0;  // |F_y| / |F_x|: zero by symmetry
  double y_plus_mean = 0;
  bool settled = false;
  int steps = 0;
  long cells = 0;
};

DoubleBody RunDoubleBody(const fs::path& poly_mesh, const fs::path& out,
                         const char* case_file = "data/cases/doublebody/wigley.yaml",
                         double form_factor = kFormFactor, double reynolds = kReynolds) {
  RunOptions ro;
  ro.poly_mesh_override = poly_mesh;
  ro.output_override = out;
  ro.progress = false;
  const RunSummary s = RunCase(SourceDir() / case_file, ro);
  EXPECT_EQ(s.status, RunSummary::Status::kCompleted) << s.message;
  const data::H5Reader h(out / "history.h5");
  DoubleBody r;
  r.C_T = h.Read("resistance/C_T").values.back();
  r.C_F = h.Read("resistance/C_F").values.back();
  r.C_P = h.Read("resistance/C_P").values.back();
  const data::Series fp = h.Read("forces/hull/pressure"), fv = h.Read("forces/hull/viscous");
  const std::size_t last = fp.rows - 1;
  r.side_force_ratio = std::abs(fp.at(last, 1) + fv.at(last, 1)) / std::abs(fp.at(last, 0) + fv.at(last, 0));
  const data::Series yp = h.Read("turbulence/y_plus/hull");
  r.y_plus_mean = yp.at(yp.rows - 1, 1);
  r.settled = s.steady_converged;
  r.steps = s.steps;
  const double c_f0 = data::Ittc57FrictionCoefficient(reynolds);
  std::printf(
      "%s, %d steps (settled %d): C_F %.4e (C_F/C_F0 %.3f), C_P %.3e, C_V %.4e, "
      "C_V/((1+k) C_F0) %.3f, y+ mean %.1f, |Y|/|X| %.1e\n",
      case_file, r.steps, r.settled, r.C_F, r.C_F / c_f0, r.C_P, r.C_T, r.C_T / (form_factor * c_f0),
      r.y_plus_mean, r.side_force_ratio);
  return r;
}

// Builds the study family in tmp/grids and runs the case on grid `level`.
DoubleBody RunGrid(const ScopedTempDir& tmp, int level) {
  const MeshCase mc = LoadMeshCase(SourceDir() / "data/cases/doublebody/wigley_mesh.yaml");
  RunMeshCase(mc, 3, tmp / "grids");
  return RunDoubleBody(tmp / "grids" / ("grid" + std::to_string(level)) / "constant/polyMesh", tmp / "run");
}

TEST(DoubleBodyTest, WigleyFineGrid) {
  if (!std::getenv("KELVIN_DOUBLEBODY_SLOW")) GTEST_SKIP() << "ctest label slow (KELVIN_DOUBLEBODY_SLOW=1)";
  ScopedTempDir tmp;
  const DoubleBody r = RunGrid(tmp, 1);
  const double c_v_ref = kFormFactor * data::Ittc57FrictionCoefficient(kReynolds);
  EXPECT_TRUE(r.settled);
  EXPECT_NEAR(r.C_T, c_v_ref, 0.05 * c_v_ref);
  EXPECT_GT(r.C_P, 0.0);
  EXPECT_LT(r.C_P, 0.10 * r.C_T);
  EXPECT_LT(r.side_force_ratio, 1e-3);
}

TEST(DoubleBodyTest, DtcGrid1) {
  if (!std::getenv("KELVIN_DOUBLEBODY_SLOW")) GTEST_SKIP() << "ctest label slow (KELVIN_DOUBLEBODY_SLOW=1)";
  if (!fs::exists("/usr/share/openfoam/etc/bashrc")) GTEST_SKIP() << "Debian openfoam not installed";
  ScopedTempDir tmp;
  MeshCase mc = LoadMeshCase(SourceDir() / "data/cases/mesh/dtc_snappy.yaml");
  mc.write_vtu = false;
  RunMeshCase(mc, 1, tmp / "grid");
  const DoubleBody r = RunDoubleBody(tmp / "grid/constant/polyMesh", tmp / "run",
                                     "data/cases/doublebody/dtc.yaml", kDtcFormFactor, kDtcReynolds);
  const double c_v_ref = kDtcFormFactor * data::Ittc57FrictionCoefficient(kDtcReynolds);
  EXPECT_TRUE(r.settled);
  EXPECT_NEAR(r.C_T, c_v_ref, 0.05 * c_v_ref);
  EXPECT_GT(r.C_P, 0.0);
  EXPECT_LT(r.C_P, 2.0 * (kDtcFormFactor - 1.0) / kDtcFormFactor * r.C_T);
  // Issue #25 acceptance 2: the friction of the default grid between 0.97
  // and 1.07 of ITTC-57, and the hull y+ mean within a factor 1.5 of the
  // mesh case's target.
  const double c_f0 = data::Ittc57FrictionCoefficient(kDtcReynolds);
  EXPECT_GE(r.C_F / c_f0, 0.97);
  EXPECT_LE(r.C_F / c_f0, 1.07);
  EXPECT_GT(r.y_plus_mean, mc.y_plus / 1.5);
  EXPECT_LT(r.y_plus_mean, mc.y_plus * 1.5);
}

TEST(DoubleBodyTest, WigleyCoarseGrid) {
  ScopedTempDir tmp;
  const DoubleBody r = RunGrid(tmp, 3);
  const double c_v_ref = kFormFactor * data::Ittc57FrictionCoefficient(kReynolds);
  EXPECT_TRUE(r.settled);
  EXPECT_NEAR(r.C_T, c_v_ref, 0.10 * c_v_ref);
  EXPECT_GT(r.C_P, 0.0);
  EXPECT_LT(r.C_P, 0.10 * r.C_T);
  EXPECT_LT(r.side_force_ratio, 1e-3);
}

}  // namespace
}  // namespace kelvin::cfd
