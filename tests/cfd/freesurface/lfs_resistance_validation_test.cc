// Hull resistance with the linearized free surface (issue #6, acceptance 4
// and 5), `slow` (tens of CPU minutes). Runs `kelvin mesh` and `kelvin run`
// on the cases of data/cases/resistance in a scratch directory and checks:
// - Wigley hull: C_T at Fn = 0.25, 0.316, 0.408 within 5% of the
//   experimental values of the Bai & McCarthy (1979) compilation as issue #6
//   quotes them: 3.340e-3, 3.620e-3, 4.090e-3. The model length, Reynolds
//   number and water temperature of those experiments could not be
//   retrieved with the project's search; the 6 m model in fresh water at
//   15 C (Re 1.0e7 to 1.6e7) is our assumption, chosen so that the ITTC-57
//   friction line plus a plausible wave part is consistent with the values;
// - DTC (1:59.407) at 1.668 m/s: the run at maximum Courant number >= 100
//   converges (steady criterion met) and its R_T differs by < 0.5% from the
//   same run at Courant about 10. R_T is printed against the measured
//   31.83 N (el Moctar, Shigunov & Zorn 2012, Ship Technology Research
//   59(3), Table 4); the issue asks for the comparison, not a tolerance.
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
  auto courant = [](const fs::path& h5) {
    const data::Series co = data::H5Reader(h5.parent_path() / "history.h5").Read("courant");
    double m = 0.0;
    for (std::size_t r = co.rows / 2; r < co.rows; ++r) m = std::max(m, co.values[r]);
    return m;
  };
  const double co_big = courant(big), co_small = courant(small);
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

}  // namespace
}  // namespace kelvin
