// Captive runs with the propeller and the rudder working (issue 21): what a
// CFD campaign's `tests.appendages` runs measured, and what `kelvin identify`
// fits the MMG interaction coefficients to (identification/interaction_fit.h).
// One row per run, the means over the run's settled window, in the campaign
// HDF5 file beside the bare-hull runs (data/schema/captive_schema.md):
//
//   /appendages/runs        rows x 16, the columns of kAppendageColumns
//   /appendages/names       the run names
//   /appendages attributes  Lpp, D_p, A_R, H_R, x_R_prime, x_P_prime, rho (the ship
//                           file's propeller and rudder, and the water), ship_file
//
// Ship axes: x forward, y to starboard, loads about the reference point.
//
// The campaign file's test matrix (solver cfd only):
//
//   tests:
//     appendages:
//       ship: ../../ships/wigley.yaml   # the MMG ship file with the propeller and rudder
//       propeller_rate: 59.79           # 1/s, every run (the self-propulsion point)
//       swirl: true                     # the propeller's torque (propeller.swirl)
//       rate_factors: [0.8, 1.25]       # more straight-ahead runs at delta = 0, at these x rate
//       rudder_deg: [-35, -20, -10, 10, 20, 35]   # straight ahead (and one at 0 always)
//       drift_deg: [-8, -4, 4, 8]       # rudder amidships
//       circular: [{drift_deg: 0, r_prime: 0.3}]  # rudder amidships; rate_factor: 2 (default 1)
//                                       # also sets the propeller rate of a circular run
//       propeller_thickness: 0.1        # optional: the runs' propeller.thickness (of D)
//       rudder_sample_distance: 0.5     # optional: the runs' rudder.sample_distance (chords)
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace kelvin::data {

class H5Writer;

struct AppendageRun {
  std::string name;
  double u = 0, v = 0, r = 0;  // m/s, m/s, rad/s: the held motion
  double delta = 0;            // rad, rudder angle (positive turns to starboard)
  double n = 0;                // 1/s, propeller rate
  double X = 0, Y = 0, N = 0;  // N, N, N m: everything on the body (the carriage's load, negated)
  double T = 0;                // N, thrust
  double U_A = 0;              // m/s, advance speed at the disk (its induced velocity removed)
  double J = 0, K_T = 0;
  double F_N = 0;              // N, rudder normal force
  double u_R = 0, v_R = 0;     // m/s, rudder inflow (from ahead; towards starboard)
};

inline constexpr std::array<std::string_view, 16> kAppendageColumns = {
    "u", "v", "r", "delta", "n", "X", "Y", "N", "T", "U_A", "J", "K_T", "F_N", "u_R", "v_R", "reserved"};

// The ship file's geometry the fit needs.
struct AppendageGeometry {
  double Lpp = 0, D_p = 0, A_R = 0, H_R = 0, x_R_prime = 0, x_P_prime = 0;
  double rho = 0;  // kg/m^3
  std::string ship_file;
};

struct AppendageCampaign {
  AppendageGeometry geometry;
  std::vector<AppendageRun> runs;
};

struct AppendageDesign {
  std::filesystem::path ship_file;
  double propeller_rate = 0;          // 1/s
  bool swirl = true;
  std::vector<double> rate_factors;   // of propeller_rate
  std::vector<double> rudder_angles;  // rad
  std::vector<double> drift_angles;   // rad
  struct Circular {
    double beta = 0, r_prime = 0;
    double rate_factor = 1.0;  // of propeller_rate
  };
  std::vector<Circular> circular;
  double propeller_thickness = 0;      // the case's propeller.thickness (of D); 0: the case loader's default
  double rudder_sample_distance = 0;   // the case's rudder.sample_distance (chords); 0: the default
};

// One planned run: its name and the held motion, rudder and rate.
struct AppendageTest {
  std::string name;
  double u = 0, v = 0, r = 0, delta = 0, n = 0;
};
// The runs of a design at speed U for a ship of length Lpp: straight ahead
// at delta = 0 first, then the rates, the rudder angles, the drifts and the
// circular runs.
std::vector<AppendageTest> PlanAppendageTests(const AppendageDesign& design, double U, double Lpp);

// Writes the /appendages group into `w` (the caller commits).
void WriteAppendageRuns(const AppendageCampaign& campaign, H5Writer& w);
// True if the campaign file has appendage runs.
bool HasAppendageRuns(const std::filesystem::path& path);
// Reads them; throws kelvin::DataFileError naming the file and what is wrong
// (a missing attribute or dataset, a wrong width, non-finite values, a
// non-positive length, diameter or span). Without `geometry` the attributes
// are not read (one run's result file of a campaign).
AppendageCampaign ReadAppendageRuns(const std::filesystem::path& path, bool geometry = true);

}  // namespace kelvin::data
