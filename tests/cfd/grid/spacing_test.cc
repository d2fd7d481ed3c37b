// Node distributions and the y+ wall-spacing estimate.
#include "cfd/grid/spacing.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

using ::testing::HasSubstr;

template <typename F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SpacingTest, GeometricNodesHaveTheFirstSpacingAConstantRatioAndExactEnds) {
  const std::vector<double> s = GeometricNodes(30, 2.5, 1e-4);
  ASSERT_EQ(s.size(), 31u);
  EXPECT_EQ(s.front(), 0.0);
  EXPECT_EQ(s.back(), 2.5);
  EXPECT_NEAR(s[1], 1e-4, 1e-12);
  const double q = GeometricRatio(30, 2.5, 1e-4);
  // The sum of the geometric series equals the length.
  EXPECT_NEAR(1e-4 * (std::pow(q, 30) - 1) / (q - 1), 2.5, 1e-9);
  for (int i = 1; i < 30; ++i) EXPECT_NEAR((s[i + 1] - s[i]) / (s[i] - s[i - 1]), q, 1e-9);
}

// Growth from the wall, then uniform at the cap: the spacing never exceeds
// it, grows by a constant ratio until it reaches it, and the ends are exact.
TEST(SpacingTest, CappedGeometricNodesGrowThenStayAtTheCap) {
  const double h1 = 1e-3, cap = 0.25, length = 9.0;
  const int n = 50;
  const auto s = CappedGeometricNodes(n, length, h1, cap);
  ASSERT_EQ(s.size(), 51u);
  EXPECT_EQ(s.front(), 0.0);
  EXPECT_EQ(s.back(), length);
  // Uncapped, the same count would end with cells far above the cap.
  const auto free = GeometricNodes(n, length, h1);
  EXPECT_GT(free[n] - free[n - 1], 4 * cap);
  int at_cap = 0;
  const double q = (s[2] - s[1]) / (s[1] - s[0]);
  EXPECT_GT(q, 1.0);
  for (int i = 0; i < n; ++i) {
    const double h = s[i + 1] - s[i];
    EXPECT_LE(h, cap * (1 + 1e-9)) << "cell " << i;
    if (h > cap * (1 - 1e-9)) {
      ++at_cap;
    } else if (i > 0) {
      EXPECT_NEAR(h / (s[i] - s[i - 1]), q, 1e-9 * q) << "cell " << i;
    }
  }
  EXPECT_GT(at_cap, 25);  // most of the 9 m at 0.25 m
  EXPECT_NEAR(s[1] - s[0], h1, 1e-12);
  // No cap needed: the plain distribution.
  EXPECT_EQ(CappedGeometricNodes(n, length, h1, 0.0), free);
  EXPECT_EQ(CappedGeometricNodes(n, length, h1, 100.0), free);
  // Too few cells for the cap: the error says how many are needed.
  try {
    CappedGeometricNodes(20, length, h1, cap);
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("at least 37 cells are needed"), std::string::npos) << e.what();
  }
}

TEST(SpacingTest, GeometricRatioBelowOneWhenTheFirstSpacingIsLarge) {
  const std::vector<double> s = GeometricNodes(10, 1.0, 0.2);
  EXPECT_LT(GeometricRatio(10, 1.0, 0.2), 1.0);
  EXPECT_NEAR(s[1], 0.2, 1e-12);
  EXPECT_EQ(s.back(), 1.0);
}

TEST(SpacingTest, TwoSidedNodesAreMonotoneWithTheEndSpacingsToFirstOrder) {
  for (int n : {20, 80, 320}) {
    const double h0 = 0.2 / n, h1 = 0.6 / n;  // relative to the mean 1/n
    const std::vector<double> s = TwoSidedNodes(n, 1.0, h0, h1);
    for (int i = 0; i < n; ++i) EXPECT_GT(s[i + 1], s[i]);
    EXPECT_EQ(s.back(), 1.0);
    // The first cell is n times the integral of the spacing profile
    // h(xi) = h0 + (h1 - h0) xi + c sin(pi xi) over [0, 1/n], with
    // c = pi/2 (1/n - (h0 + h1)/2): h0 to first order in 1/n.
    const double c = 0.5 * M_PI * (1.0 / n - 0.5 * (h0 + h1));
    const double first = h0 + 0.5 * (h1 - h0) / n + c * n * (1 - std::cos(M_PI / n)) / M_PI;
    EXPECT_NEAR(s[1] - s[0], first, 1e-14);
    const double last = h1 - 0.5 * (h1 - h0) / n + c * n * (1 - std::cos(M_PI / n)) / M_PI;
    EXPECT_NEAR(s[n] - s[n - 1], last, 1e-14);
    EXPECT_NEAR((s[1] - s[0]) / h0, 1.0, 10.0 / n);
  }
}

TEST(SpacingTest, Ittc57AndTheFirstCellHeight) {
  // h = 2 y+ L / (Re sqrt(C_F/2)) with the ITTC-57 C_F(1e7) = 0.075 / 25 =
  // 0.003 (log10(1e7) - 2 = 5 exactly): the cell centre at h/2 has the
  // target y+.
  const double h = FirstCellHeight(30.0, 1e7, 2.0);
  EXPECT_NEAR(h, 2 * 30.0 * 2.0 / (1e7 * std::sqrt(0.0015)), 1e-15);
  EXPECT_NEAR(YPlusAt(0.5 * h, 1e7, 2.0), 30.0, 1e-12);
}

TEST(SpacingTest, BadArgumentsNameTheValue) {
  EXPECT_THAT(ErrorOf([] { GeometricNodes(0, 1.0, 0.1); }), HasSubstr("got n = 0"));
  EXPECT_THAT(ErrorOf([] { GeometricNodes(10, 1.0, -0.1); }), HasSubstr("first spacing = -0.1 m"));
  EXPECT_THAT(ErrorOf([] { GeometricNodes(10, 1.0, 2.0); }),
              HasSubstr("first spacing 2 m is larger than the length 1 m"));
  EXPECT_THAT(ErrorOf([] { TwoSidedNodes(10, 1.0, 0.5, 0.5); }),
              HasSubstr("end spacings 0.5 m and 0.5 m are too large for 10 cells over 1 m"));
}

}  // namespace
}  // namespace kelvin::cfd
