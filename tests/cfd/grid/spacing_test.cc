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
  // log10(1e7) - 2 = 5 exactly.
  EXPECT_DOUBLE_EQ(Ittc57Friction(1e7), 0.075 / 25.0);
  // h = 2 y+ L / (Re sqrt(C_F/2)): the cell centre at h/2 has the target y+.
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
