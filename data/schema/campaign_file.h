// Captive campaign files (YAML): which ship, which solver produces the
// forces, and the test matrix. `kelvin captive campaign.yaml` runs them
// (solver mmg: identification/virtual_captive.h, RunCampaign; solver cfd:
// cfd/campaign/cfd_campaign.h).
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
//     circular: [{drift_deg: 0, r_prime: 0.3}]   # rotating arm (steady)
//     appendages: {...}                  # cfd only: runs with the propeller and rudder
//                                        # (data/schema/appendage_runs.h)
//   sampling: {samples_per_period: 200, periods: 5, ramp_periods: 1}
//
// With `solver: cfd` every run is a `kelvin run` case with the prescribed
// motion (double body, no free surface yet), run by cfd/campaign:
//
//   campaign: {name: block, ship: block_ship.yaml, solver: cfd, speed: 1.0}
//   cfd:
//     case: block_case.yaml        # kelvin run case without motion/time.end (relative to this file)
//     hull_patches: [obstacle]     # default: the case's output.forces
//     centre: [0, 0, 0]            # midship in grid axes (m), N is about it
//     draft: 1.0                   # T of the prime system (default: the ship's d)
//     steps_per_period: 80         # harmonic runs: dt = period / steps_per_period
//     motion_ramp_periods: 1       # harmonic runs: the motion ramps up over this many periods
//                                  # (default sampling.ramp_periods); the analysis still discards
//                                  # sampling.ramp_periods periods, the rest settle at full motion
//     steady_ramp: 2.0             # s, start-up of steady runs
//     steady_duration: 10.0        # s, steady runs after the ramp at most (dt from the case)
//     settle: {tolerance: 0.01, window: 2.0}   # steady runs end once X, Y, N/Lpp (ship axes)
//                                  # change by < tolerance |(X, Y)| over window s (default
//                                  # window: min(2 Lpp / U, steady_duration)); the analysis uses
//                                  # that window; settle: false keeps the fixed duration
//     checkpoint_interval: 50      # steps
//     jobs: 1                      # runs executed at the same time (processes)
//     directory: runs/block        # run directories (default results/<name>, relative to this file)
//   tests: (as above)
//   sampling: {periods: 3, ramp_periods: 1}   # samples_per_period is not used
//
// For `cfd` the ship file needs only its `ship` and `principal` sections.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "data/schema/appendage_runs.h"
#include "data/schema/captive_plan.h"
#include "data/schema/captive_run.h"

namespace kelvin::data {

class ConfigNode;

struct CampaignFile {
  std::string name;
  std::filesystem::path ship_file;
  enum class Solver { kMmg, kCfd };
  Solver solver = Solver::kMmg;
  double speed = 0;  // m/s; 0 = the ship's approach speed
  double noise = 0;
  std::uint64_t seed = 1;
  CampaignDesign design;
  std::optional<AppendageDesign> appendages;  // tests.appendages (cfd only)
  VirtualCaptiveOptions sampling;

  // The `cfd:` section (solver cfd only).
  struct Cfd {
    std::filesystem::path case_file;
    std::vector<std::string> hull_patches;  // empty: the case's output.forces
    std::array<double, 3> centre = {0.0, 0.0, 0.0};  // m, grid axes
    double draft = 0;  // m; 0 = the ship's d
    int steps_per_period = 80;
    // Periods over which a harmonic run's motion ramps up (<= the discarded
    // sampling.ramp_periods; the periods in between run the full motion and
    // let the start-up disturbance leave the grid before the analysis).
    int motion_ramp_periods = 1;
    double steady_ramp = 2.0;       // s
    double steady_duration = 10.0;  // s, the longest a steady run goes on after the ramp
    // Steady runs end once X, Y and N / Lpp in ship axes change by less than
    // settle_tolerance |(X, Y)| over settle_window seconds (and not before
    // steady_ramp + settle_window); the analysis then uses that last window.
    bool settle = true;
    double settle_tolerance = 0.01;
    double settle_window = 0;  // s; 0: the smaller of 2 Lpp / U and steady_duration
    int checkpoint_interval = 50;   // steps
    int jobs = 1;
    std::filesystem::path directory;  // run directories
  };
  Cfd cfd;
  std::filesystem::path path;  // the campaign file
};

// The ship data of a campaign from the `ship` and `principal` sections of a
// ship file (mass = rho displacement, I_zG = mass (k_zz Lpp)^2 with k_zz 0.25
// unless given); other sections are not read. Throws ConfigError.
CaptiveShip LoadCaptiveShip(const std::filesystem::path& ship_file);

// Reads and validates a campaign file; every unknown key or bad value is a
// kelvin::ConfigError naming the file, line, key and what was expected.
CampaignFile LoadCampaignFile(const std::filesystem::path& path);
// The same from a campaign file already parsed; `path` locates the files it refers to.
CampaignFile LoadCampaignFile(const ConfigNode& root, const std::filesystem::path& path);

}  // namespace kelvin::data
