// The GCI procedure on synthetic data with known answers and on the worked
// example of Celik et al. (2008), J. Fluids Eng. 130:078001, Table 1
// (first column: N = 18000, 8000, 4500 cells; phi = 6.063, 5.972, 5.863;
// published p = 1.53, phi_ext = 6.1685, e_a21 = 1.5%, e_ext21 = 1.7%,
// GCI21 = 2.2%).
#include "cfd/verification/gci.h"

#include <gtest/gtest.h>

#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

TEST(GciTest, RecoversOrderAndLimitOfAPowerLaw) {
  // phi(h) = 2 + 0.3 h^1.7 with non-constant refinement ratios.
  auto phi = [](double h) { return 2.0 + 0.3 * std::pow(h, 1.7); };
  const double h1 = 0.1, h2 = 0.14, h3 = 0.2;
  const GciResult g = ComputeGci(h1, h2, h3, phi(h1), phi(h2), phi(h3));
  EXPECT_EQ(g.convergence, Convergence::kMonotonic);
  EXPECT_NEAR(g.p, 1.7, 1e-9);
  EXPECT_NEAR(g.phi_ext, 2.0, 1e-12);
  // In the asymptotic range, GCI32 = r^p GCI21 up to the phi2/phi1 normalization.
  EXPECT_NEAR(g.asymptotic_ratio, phi(h1) / phi(h2), 1e-9);
}

TEST(GciTest, CelikWorkedExample) {
  // The paper's 2D example uses h = (A/N)^(1/2): r21 = 1.5, r32 = 1.333.
  const double V = 1.0;  // any area: only the ratios matter
  const double h1_2d = std::sqrt(V / 18000), h2_2d = std::sqrt(V / 8000), h3_2d = std::sqrt(V / 4500);
  EXPECT_NEAR(h2_2d / h1_2d, 1.5, 1e-12);
  const GciResult g = ComputeGci(h1_2d, h2_2d, h3_2d, 6.063, 5.972, 5.863);
  EXPECT_EQ(g.convergence, Convergence::kMonotonic);
  EXPECT_NEAR(g.p, 1.53, 0.005);
  EXPECT_NEAR(g.phi_ext, 6.1685, 0.0005);
  EXPECT_NEAR(100 * g.e_a21, 1.5, 0.05);
  EXPECT_NEAR(100 * g.e_ext21, 1.7, 0.05);
  EXPECT_NEAR(100 * g.gci21, 2.2, 0.05);
}

TEST(GciTest, RepresentativeCellSizeIsTheCubeRoot) {
  EXPECT_NEAR(RepresentativeCellSize(8.0, 1000.0), 0.2, 1e-15);
}

TEST(GciTest, ClassifiesOscillatoryAndDivergent) {
  EXPECT_EQ(ComputeGci(1, 2, 4, 1.0, 1.1, 0.95).convergence, Convergence::kOscillatory);
  EXPECT_EQ(ComputeGci(1, 2, 4, 1.0, 1.1, 1.15).convergence, Convergence::kDivergent);
}

TEST(GciTest, BadGridSequencesAreRejected) {
  EXPECT_THROW(ComputeGci(2, 1, 4, 1, 1, 1), ArgumentError);
  try {
    ComputeGci(1, 1.05, 2, 1, 1.1, 1.3);
    FAIL();
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("refinement ratios of at least 1.1"), std::string::npos);
  }
}

}  // namespace
}  // namespace kelvin::cfd
