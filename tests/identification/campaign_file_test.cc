// Campaign files: the repository's KVLCC2 campaign loads and runs, and every
// bad value is one clear error naming the file, key and expectation.
#include "identification/campaign_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "data/schema/errors.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::ident {
namespace {

using kelvin::testing::ScopedTempDir;
using ::testing::HasSubstr;

TEST(CampaignFileTest, RepositoryCampaignRuns) {
  const CampaignFile f = LoadCampaignFile(kelvin::testing::SourceDir() / "data/cases/kvlcc2_virtual_captive.yaml");
  EXPECT_EQ(f.name, "kvlcc2_virtual_captive");
  EXPECT_EQ(f.design.drift_angles.size(), 7u);
  EXPECT_NEAR(f.design.drift_angles[1], 2.5 * M_PI / 180, 1e-15);
  EXPECT_EQ(f.design.sway_amplitudes, (std::vector<double>{0.1, 0.2}));
  const CaptiveCampaign c = RunCampaign(f);
  EXPECT_EQ(c.runs.size(), 13u);  // 7 drift + 2 sway + 2 yaw + 2 yaw with drift
  EXPECT_EQ(c.ship.name, "KVLCC2");
}

struct BadCampaign {
  const char* text;
  const char* message;
};

class BadCampaignTest : public ::testing::TestWithParam<BadCampaign> {};

TEST_P(BadCampaignTest, GivesOneClearError) {
  ScopedTempDir dir;
  const auto path = dir / "c.yaml";
  std::ofstream(path) << GetParam().text;
  try {
    LoadCampaignFile(path);
    FAIL() << "accepted:\n" << GetParam().text;
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
    EXPECT_THAT(e.what(), HasSubstr(GetParam().message));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Files, BadCampaignTest,
    ::testing::Values(
        BadCampaign{"campaign: {name: a, ship: s.yaml, solver: lfs}\ntests: {pure_sway_v_prime: [0.1]}\n",
                    "key 'campaign.solver' = 'lfs': expected 'mmg'"},
        BadCampaign{"campaign: {name: a, ship: s.yaml, noise: 2}\ntests: {pure_sway_v_prime: [0.1]}\n",
                    "key 'campaign.noise' = '2': expected a fraction between 0 and 1"},
        BadCampaign{"campaign: {name: a, ship: s.yaml}\ntests: {static_drift_deg: [5, 95]}\n",
                    "key 'tests.static_drift_deg[1]' = '95': expected an angle in degrees with |angle| < 90"},
        BadCampaign{"campaign: {name: a, ship: s.yaml}\ntests: {pure_sway: [0.1]}\n",
                    "unknown key 'tests.pure_sway'"},
        BadCampaign{"campaign: {name: a, ship: s.yaml}\ntests: {omega_prime: 2}\n", "expected at least one test"},
        BadCampaign{"campaign: {name: a, ship: s.yaml}\ntests: {pure_yaw_r_prime: [-0.3]}\n",
                    "key 'tests.pure_yaw_r_prime[0]' = '-0.3': expected a positive amplitude"},
        BadCampaign{"campaign: {ship: s.yaml}\ntests: {pure_yaw_r_prime: [0.3]}\n",
                    "missing required key 'campaign.name'"}));

}  // namespace
}  // namespace kelvin::ident
