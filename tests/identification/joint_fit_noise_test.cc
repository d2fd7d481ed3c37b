// Acceptance 2 of issue 9: statistics of the joint fit over noise seeds (tens
// of seconds on a loaded machine: label validation). Truth is the KVLCC2 L7
// model set of Yasukawa & Yoshimura (2015), J. Mar. Sci. Technol.
// 20:37-52, Tables 1-3, as stored in data/ships/kvlcc2.yaml.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "identification/joint_fit.h"
#include "identification/virtual_captive.h"
#include "tests/test_utilities/test_utilities.h"
#include "tests/identification/identification_test_utilities.h"

namespace kelvin::ident {
namespace {

constexpr const auto& kNames = sim::HullCoefficients<double>::kNames;

using sim::testing::Kvlcc2;

using fixtures::StandardCampaign;

// Acceptance 2: 5% Gaussian noise (of each run's channel RMS), 20 seeds. All
// 20 coefficients are kept free (fix_unidentifiable = false) so that every
// reported standard error is tested.
//
// The first clause of the acceptance ("every recovered derivative lies within
// 3 reported standard errors of the truth") is a statement about one noisy
// campaign: it is asserted for the campaign of seed 1, the seed the loop
// starts from (chosen before any result was seen). Over all 20 seeds it is a
// coverage statement: a calibrated Gaussian estimate leaves 3 sigma with
// probability 0.27%, so about one of the 400 estimates is expected outside,
// and the count is bounded below.
TEST(JointFitNoiseTest, NoiseStandardErrorsMatchEmpiricalSpreadOverTwentySeeds) {
  const sim::ShipParameters ship = Kvlcc2();
  const data::CaptiveCampaign clean = StandardCampaign(ship, true);
  constexpr int kSeeds = 20;
  std::array<std::vector<double>, kCoefficientCount> estimate, std_error;
  int outside3 = 0, outside4 = 0;
  double first_campaign_worst_z = 0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    data::CaptiveCampaign c = clean;
    AddForceNoise(c, 0.05, static_cast<std::uint64_t>(seed));
    JointFitOptions o;
    o.fix_unidentifiable = false;
    const JointFitResult fit = FitCampaign(c, o, "noisy");
    ASSERT_TRUE(fit.converged) << fit.solver_report;
    for (int i = 0; i < kCoefficientCount; ++i) {
      const double se = std::sqrt(fit.covariance(i, i));
      ASSERT_GT(se, 0.0) << kNames[i];
      estimate[i].push_back(fit.coefficients[i]);
      std_error[i].push_back(se);
      const double z = std::abs(fit.coefficients[i] - ship.hull[i]) / se;
      if (seed == 1) first_campaign_worst_z = std::max(first_campaign_worst_z, z);
      if (z > 3) {
        ++outside3;
        std::printf("seed %d: %s is %.2f standard errors from the truth\n", seed,
                    std::string(kNames[i]).c_str(), z);
      }
      if (z > 4) ++outside4;
    }
  }
  // With calibrated standard errors 0.27% of the 400 estimates fall outside
  // 3 sigma (1.1 expected; P(more than 4) = 0.005), and 4 sigma essentially
  // never (P = 6e-5 each).
  std::printf("seed 1: worst estimate %.2f standard errors from the truth\n",
              first_campaign_worst_z);
  EXPECT_LE(first_campaign_worst_z, 3.0);
  EXPECT_LE(outside3, 4);
  EXPECT_EQ(outside4, 0);
  for (int i = 0; i < kCoefficientCount; ++i) {
    double mean = 0, var = 0, mean_se = 0;
    for (double v : estimate[i]) mean += v / kSeeds;
    for (double v : estimate[i]) var += (v - mean) * (v - mean) / (kSeeds - 1);
    for (double v : std_error[i]) mean_se += v / kSeeds;
    const double ratio = mean_se / std::sqrt(var);
    std::printf("%-10s reported/empirical standard error %.2f\n", std::string(kNames[i]).c_str(),
                ratio);
    EXPECT_GT(ratio, 0.5) << kNames[i];
    EXPECT_LT(ratio, 2.0) << kNames[i];
  }
}

}  // namespace
}  // namespace kelvin::ident
