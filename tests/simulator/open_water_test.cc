// Open-water curves: the monotone cubic is exact on the nodes, monotone
// between them, close to smooth data, inverted by JFromKT; every bad table
// is a ConfigError naming the file, the key, the index and the value.
#include "simulator/mmg/open_water.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "data/schema/errors.h"

namespace kelvin::sim {
namespace {

using ::testing::HasSubstr;

// KP505 (the KCS propeller) open-water table, NMRI data for SIMMAN 2008
// (data/reference/kp505_open_water.csv), K_Q = 10KQ / 10.
OpenWaterCurve Kp505() {
  OpenWaterCurve c;
  c.J = {0.00, 0.10, 0.20, 0.30, 0.40, 0.50, 0.60, 0.70, 0.80, 0.90, 1.00, 1.05};
  c.K_T = {0.5327, 0.4937, 0.4469, 0.3922, 0.3425, 0.2895, 0.2407, 0.1931, 0.1414, 0.0870, 0.0293, -0.0033};
  for (double q : {0.7517, 0.7058, 0.6538, 0.5895, 0.5314, 0.4702, 0.4090, 0.3478, 0.2805, 0.2132, 0.1275, 0.0786}) {
    c.K_Q.push_back(q / 10.0);
  }
  return c;
}

TEST(OpenWaterCurve, ExactOnTheNodes) {
  const OpenWaterCurve c = Kp505();
  c.Validate("kp505.csv", "propeller.open_water");
  for (std::size_t i = 0; i < c.J.size(); ++i) {
    EXPECT_NEAR(c.KT(c.J[i]), c.K_T[i], 1e-15) << i;
    EXPECT_NEAR(c.KQ(c.J[i]), c.K_Q[i], 1e-15) << i;
  }
}

TEST(OpenWaterCurve, MonotoneBetweenTheNodes) {
  const OpenWaterCurve c = Kp505();
  double kt_prev = c.KT(0.0), kq_prev = c.KQ(0.0);
  for (int i = 1; i <= 10500; ++i) {
    const double j = 1.05 * i / 10500.0;
    const double kt = c.KT(j), kq = c.KQ(j);
    ASSERT_LT(kt, kt_prev) << "J = " << j;
    ASSERT_LT(kq, kq_prev) << "J = " << j;
    kt_prev = kt;
    kq_prev = kq;
  }
}

// A table with a steep drop that a plain cubic spline overshoots: the
// interpolant stays within the bracketing nodes on every interval.
TEST(OpenWaterCurve, NoOvershootAtASteepDrop) {
  OpenWaterCurve c;
  c.J = {0.0, 0.1, 0.2, 0.3, 0.4};
  c.K_T = {0.5, 0.499, 0.498, 0.1, 0.099};
  c.K_Q = {0.05, 0.0499, 0.0498, 0.01, 0.0099};
  c.Validate("steep.yaml", "propeller.open_water");
  for (int i = 0; i <= 400; ++i) {
    const double j = 0.4 * i / 400.0;
    const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(j / 0.1), 3);
    EXPECT_LE(c.KT(j), c.K_T[k] + 1e-15) << j;
    EXPECT_GE(c.KT(j), c.K_T[k + 1] - 1e-15) << j;
  }
}

// A quadratic tabulated at 101 points: the cubic between them is within
// O(h^4) of the quadratic (h = 0.012; 1e-6 is far above that and far below
// any K_T that matters).
TEST(OpenWaterCurve, FromQuadraticsReproducesThePolynomials) {
  const std::array<double, 3> k = {0.5253, -0.3878, -0.1135};  // a K_T(J) of the MMG form
  const std::array<double, 3> q = {0.0710, -0.0250, -0.0300};
  const OpenWaterCurve c = OpenWaterCurve::FromQuadratics(k, q, 1.2);
  c.Validate("quadratic.yaml", "propeller");
  for (int i = 0; i <= 997; ++i) {
    const double j = 1.2 * i / 997.0;
    EXPECT_NEAR(c.KT(j), k[0] + k[1] * j + k[2] * j * j, 1e-6) << j;
    EXPECT_NEAR(c.KQ(j), q[0] + q[1] * j + q[2] * j * j, 1e-6) << j;
  }
}

TEST(OpenWaterCurve, InverseRoundTrips) {
  const OpenWaterCurve c = Kp505();
  for (int i = 0; i <= 210; ++i) {
    const double j = 1.05 * i / 210.0;
    EXPECT_NEAR(c.JFromKT(c.KT(j)), j, 1e-12) << j;
  }
  for (std::size_t i = 0; i < c.J.size(); ++i) EXPECT_NEAR(c.JFromKT(c.K_T[i]), c.J[i], 1e-12) << i;
  EXPECT_TRUE(c.Covers(0.0));
  EXPECT_TRUE(c.Covers(1.05));
  EXPECT_FALSE(c.Covers(1.0500001));
  EXPECT_FALSE(c.Covers(-1e-9));
}

TEST(OpenWaterCurve, OutOfRangeNamesTheValueAndTheRange) {
  OpenWaterCurve c = Kp505();
  c.origin = "ship.yaml: propeller.open_water";
  try {
    c.KT(1.2);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ship.yaml: propeller.open_water"));
    EXPECT_THAT(e.what(), HasSubstr("J = 1.2"));
    EXPECT_THAT(e.what(), HasSubstr("[0, 1.05]"));
  }
  EXPECT_THROW(c.KQ(-0.1), ConfigError);
  try {
    c.JFromKT(0.6);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("K_T = 0.6"));
  }
}

// Validate a modified KP505 table and expect one ConfigError with each part.
void ExpectBadTable(const std::function<void(OpenWaterCurve&)>& modify, const std::vector<std::string>& parts) {
  OpenWaterCurve c = Kp505();
  modify(c);
  try {
    c.Validate("ship.yaml", "propeller.open_water");
    ADD_FAILURE() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ship.yaml"));
    for (const std::string& p : parts) EXPECT_THAT(e.what(), HasSubstr(p));
  }
}

TEST(OpenWaterCurveErrors, TooFewPoints) {
  ExpectBadTable(
      [](OpenWaterCurve& c) {
        c.J.resize(2);
        c.K_T.resize(2);
        c.K_Q.resize(2);
      },
      {"propeller.open_water.J", "2 points", "at least 3"});
}

TEST(OpenWaterCurveErrors, LengthsDiffer) {
  ExpectBadTable([](OpenWaterCurve& c) { c.K_Q.pop_back(); }, {"propeller.open_water", "K_Q 11", "same number"});
  ExpectBadTable([](OpenWaterCurve& c) { c.K_T.push_back(-0.1); }, {"K_T 13", "same number"});
}

TEST(OpenWaterCurveErrors, NonFinite) {
  ExpectBadTable([](OpenWaterCurve& c) { c.K_T[4] = std::nan(""); },
                 {"propeller.open_water.K_T", "[4] = nan", "finite"});
  ExpectBadTable([](OpenWaterCurve& c) { c.J[2] = INFINITY; }, {"propeller.open_water.J", "[2] = inf", "finite"});
}

TEST(OpenWaterCurveErrors, JNotIncreasing) {
  ExpectBadTable([](OpenWaterCurve& c) { c.J[5] = 0.4; },
                 {"propeller.open_water.J", "[5] = 0.4 after [4] = 0.4", "strictly increasing"});
}

TEST(OpenWaterCurveErrors, KTNotDecreasing) {
  ExpectBadTable([](OpenWaterCurve& c) { c.K_T[3] = 0.45; },
                 {"propeller.open_water.K_T", "[3] = 0.45 after [2] = 0.4469", "strictly decreasing"});
}

TEST(OpenWaterCurveErrors, KQNotDecreasing) {
  ExpectBadTable([](OpenWaterCurve& c) { c.K_Q[7] = c.K_Q[6]; },
                 {"propeller.open_water.K_Q", "[7] = 0.0409 after [6] = 0.0409", "strictly decreasing"});
}

TEST(OpenWaterCurveErrors, BadQuadratics) {
  EXPECT_THROW(OpenWaterCurve::FromQuadratics({0.5, -0.4, -0.1}, {0.07, -0.03, -0.03}, 0.0), ConfigError);
  EXPECT_THROW(OpenWaterCurve::FromQuadratics({0.5, -0.4, -0.1}, {0.07, -0.03, -0.03}, 1.0, 2), ConfigError);
  // A quadratic that turns over inside [0, J_max] is caught by Validate.
  const OpenWaterCurve c = OpenWaterCurve::FromQuadratics({0.5, 0.2, -0.5}, {0.07, -0.03, -0.03}, 1.0);
  EXPECT_THROW(c.Validate("ship.yaml", "propeller"), ConfigError);
}

}  // namespace
}  // namespace kelvin::sim
