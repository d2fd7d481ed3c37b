// The ITTC-1957 line against its analytic values at powers of ten, and the
// clear error outside its domain (Re <= 100, where log10 Re - 2 <= 0).
#include "data/reference/friction_lines.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "data/schema/errors.h"

namespace kelvin::data {
namespace {

using ::testing::HasSubstr;

TEST(FrictionLinesTest, Ittc57AtPowersOfTen) {
  // log10(10^k) - 2 = k - 2 exactly: C_F = 0.075 / (k - 2)^2.
  EXPECT_DOUBLE_EQ(Ittc57FrictionCoefficient(1e7), 0.075 / 25.0);  // 0.003
  EXPECT_NEAR(Ittc57FrictionCoefficient(1e7), 0.003, 1e-15);
  EXPECT_DOUBLE_EQ(Ittc57FrictionCoefficient(1e5), 0.075 / 9.0);
  EXPECT_DOUBLE_EQ(Ittc57FrictionCoefficient(1e9), 0.075 / 49.0);
}

TEST(FrictionLinesTest, Ittc57DecreasesWithReynolds) {
  double previous = Ittc57FrictionCoefficient(1e3);
  for (double re = 2e3; re < 1e10; re *= 2.0) {
    const double c_f = Ittc57FrictionCoefficient(re);
    EXPECT_LT(c_f, previous) << "Re = " << re;
    previous = c_f;
  }
}

TEST(FrictionLinesTest, Ittc57RejectsReynoldsNumbersOutsideItsDomain) {
  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  for (double re : {100.0, 50.0, 0.0, -1e6, nan, inf}) {
    try {
      Ittc57FrictionCoefficient(re);
      ADD_FAILURE() << "no error for Re = " << re;
    } catch (const ModelError& e) {
      EXPECT_THAT(e.what(), HasSubstr(fmt::format(
                                "Reynolds number {}: the ITTC-1957 friction line needs a finite Re "
                                "above 100",
                                re)));
    }
  }
  EXPECT_GT(Ittc57FrictionCoefficient(100.5), 0.0);  // just inside the domain: large but finite
}

}  // namespace
}  // namespace kelvin::data
