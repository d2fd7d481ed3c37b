// Hull resistance with the linearized free surface (issue #6, acceptance 4
// and 5), `slow` (tens of CPU minutes). Runs `kelvin mesh` and `kelvin run`
// on the cases of data/cases/resistance in a scratch directory and checks:
// - Wigley hull: C_T at Fn = 0.25, 0.316, 0.408 within 5% of the
//   experimental values of the Bai & McCarthy (1979) compilation as issue #6
//   quotes them: 3.340e-3, 3.620e-3, 4.090e-3. The model length, Reynolds
//   number and water temperature of those experiments could not be
//   retrieved with the project's search; the 6 m model in fresh water at
//   15 C (Re 1.0e7 to 1.6e7) is our assumption. These three checks fail:
//   kelvin's C_T is 16-29% high, and the section lfs_resistance of
//   BENCHMARKS.md shows that on a model of a few metres the quoted values
//   leave only 0.2-0.4 of Michell's thin-ship wave resistance for the waves;
// - DTC (1:59.407) at 1.668 m/s: the run at maximum Courant number >= 100
//   converges (steady criterion met) and its R_T differs by < 0.5% from the
//   same run at Courant about 10. R_T is printed against the measured
//   31.83 N (el Moctar, Shigunov & Zorn 2012, Ship Technology Research
//   59(3), Table 4); the issue asks for the comparison, not a tolerance.
// - DTC on the finer 53k-cell grid (dtc_fine_mesh.yaml, 7 prism layers,
//   boundary non-orthogonality up to 56 deg at the bow waterline): the
//   free-surface run converges at Courant >= 100, and no crest rises above
//   the stagnation head U^2 / (2 g) (Bernoulli: p = rho g eta cannot exceed
//   the stagnation pressure of the inflow). Before the cell-limited
//   gradient (`limiter: cell` in the case) it diverged about 9 s of
//   pseudo-time after the rigid-lid release at any Courant number.
// Set KELVIN_LFS_RESISTANCE_KEEP=dir to keep the results.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "data/schema/h5_file.h"
#include "tests/cfd/freesurface/resistance_cases.h"

namespace kelvin {
namespace {

namespace fs = std::filesystem;

class LfsResistance : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { cases_ = new testing::ResistanceCases("KELVIN_LFS_RESISTANCE_KEEP"); }
  static void TearDownTestSuite() {
    delete cases_;
    cases_ = nullptr;
  }
  static fs::path Grid(const std::string& mesh_case, const std::string& name) { return cases_->Grid(mesh_case, name); }
  static fs::path Run(const std::string& name, const fs::path& grid, const std::string& grid_name) {
    return cases_->Run(name, grid, grid_name);
  }

  static double Value(const fs::path& h5, const std::string& name) { return data::H5Reader(h5).Read(name).at(0); }
  // Largest Courant number over the second half of the run beside resistance.h5.
  static double MaxCourant(const fs::path& h5) {
    const data::Series co = data::H5Reader(h5.parent_path() / "history.h5").Read("courant");
    double m = 0.0;
    for (std::size_t r = co.rows / 2; r < co.rows; ++r) m = std::max(m, co.values[r]);
    return m;
  }

  static void Wigley(const std::string& name, double fn, double ct_exp) {
    const fs::path grid = Grid("wigley_mesh.yaml", "wigley_lfs");
    Run("wigley_double_body", grid, "wigley_lfs");
    const fs::path h5 = Run(name, grid, "wigley_lfs");
    ASSERT_TRUE(fs::exists(h5));
    EXPECT_NEAR(Value(h5, "Fn"), fn, 5e-4);
    EXPECT_EQ(Value(h5, "converged"), 1.0);
    const double ct = Value(h5, "C_T");
    std::printf("Wigley Fn %.3f: C_T %.4e, experiment %.3e, ratio %.4f (C_F %.4e, C_P %.4e, C_W %.4e)\n", fn, ct,
                ct_exp, ct / ct_exp, Value(h5, "C_F"), Value(h5, "C_P"), Value(h5, "C_W"));
    EXPECT_NEAR(ct / ct_exp, 1.0, 0.05) << "Wigley C_T at Fn " << fn;
  }

  static inline testing::ResistanceCases* cases_ = nullptr;
};

TEST_F(LfsResistance, WigleyFn0250WithinFivePercentOfExperiment) { Wigley("wigley_fn0250", 0.250, 3.340e-3); }
TEST_F(LfsResistance, WigleyFn0316WithinFivePercentOfExperiment) { Wigley("wigley_fn0316", 0.316, 3.620e-3); }
TEST_F(LfsResistance, WigleyFn0408WithinFivePercentOfExperiment) { Wigley("wigley_fn0408", 0.408, 4.090e-3); }

TEST_F(LfsResistance, DtcConvergesAtCourant100AndMatchesCourant10) {
  const fs::path grid = Grid("dtc_mesh.yaml", "dtc_lfs");
  Run("dtc_double_body", grid, "dtc_lfs");
  const fs::path big = Run("dtc_lfs", grid, "dtc_lfs");
  const fs::path small = Run("dtc_lfs_cfl10", grid, "dtc_lfs");
  ASSERT_TRUE(fs::exists(big) && fs::exists(small));
  const double co_big = MaxCourant(big), co_small = MaxCourant(small);
  const double rt_big = Value(big, "R_T"), rt_small = Value(small, "R_T");
  std::printf("DTC: Courant %.0f R_T %.4f N, Courant %.1f R_T %.4f N, difference %+.3f%%; measured 31.83 N: "
              "ratio %.3f\n",
              co_big, rt_big, co_small, rt_small, 100 * (rt_big - rt_small) / rt_small, rt_big / 31.83);
  EXPECT_GE(co_big, 100.0);
  EXPECT_LE(co_small, 15.0);
  EXPECT_EQ(Value(big, "converged"), 1.0);
  EXPECT_EQ(Value(small, "converged"), 1.0);
  EXPECT_LT(std::abs(rt_big - rt_small) / rt_small, 0.005);
}

TEST_F(LfsResistance, DtcFineGridConvergesWithCrestsBelowStagnationHead) {
  const fs::path grid = Grid("dtc_fine_mesh.yaml", "dtc_fine");
  const fs::path db = Run("dtc_fine_double_body", grid, "dtc_fine");
  const fs::path lfs = Run("dtc_fine_lfs", grid, "dtc_fine");
  ASSERT_TRUE(fs::exists(db) && fs::exists(lfs));
  const double co_max = MaxCourant(lfs);
  const double speed = Value(lfs, "speed");
  const double head = speed * speed / (2.0 * 9.81);
  const double eta_max = Value(lfs, "eta_max"), eta_min = Value(lfs, "eta_min");
  std::printf("DTC fine grid: Courant %.0f, R_T %.4f N (R_F %.4f, R_P %.4f), double body R_T %.4f N "
              "(R_P %.4f); measured 31.83 N: ratio %.3f; eta %.4f to %.4f m, stagnation head %.4f m\n",
              co_max, Value(lfs, "R_T"), Value(lfs, "R_F"), Value(lfs, "R_P"), Value(db, "R_T"), Value(db, "R_P"),
              Value(lfs, "R_T") / 31.83, eta_min, eta_max, head);
  EXPECT_EQ(Value(db, "converged"), 1.0);
  EXPECT_EQ(Value(lfs, "converged"), 1.0);
  EXPECT_GE(co_max, 100.0);
  EXPECT_LT(eta_max, head);
}

}  // namespace
}  // namespace kelvin
