// Captive campaign files (YAML): which ship, which solver produces the
// forces, and the test matrix. `kelvin captive campaign.yaml` runs them.
//
//   campaign:
//     name: kvlcc2_virtual
//     ship: ../ships/kvlcc2.yaml   # relative to the campaign file
//     solver: mmg                  # virtual captive tests from the ship's MMG model
//     speed: 1.179                 # m/s (default: the ship's approach speed)
//     noise: 0.0                   # Gaussian force noise, fraction of channel RMS (mmg only)
//     seed: 1
//   tests:
//     static_drift_deg: [0, 2.5, 5, 7.5, 10, 15, 20]
//     pure_sway_v_prime: [0.1, 0.2]      # v'_a = y_a omega / U
//     pure_yaw_r_prime: [0.3, 0.6]       # r'_a = psi_a omega Lpp / U
//     yaw_drift_deg: [6, 12]
//     yaw_drift_r_prime: 0.4
//     omega_prime: 3.0                   # omega Lpp / U of the harmonic runs
//   sampling: {samples_per_period: 200, periods: 5, ramp_periods: 1}
//
// The LFS CFD solver (`solver: lfs`) joins with the captive CFD stage.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "identification/virtual_captive.h"

namespace kelvin::ident {

struct CampaignFile {
  std::string name;
  std::filesystem::path ship_file;
  enum class Solver { kMmg };
  Solver solver = Solver::kMmg;
  double speed = 0;  // m/s; 0 = the ship's approach speed
  double noise = 0;
  std::uint64_t seed = 1;
  CampaignDesign design;
  VirtualCaptiveOptions sampling;
};

// Reads and validates a campaign file; every unknown key or bad value is a
// kelvin::ConfigError naming the file, line, key and what was expected.
CampaignFile LoadCampaignFile(const std::filesystem::path& path);

// Runs the campaign with its solver and returns the captive runs.
CaptiveCampaign RunCampaign(const CampaignFile& file);

}  // namespace kelvin::ident
