// Captive campaign plans: the test matrix of a campaign in prime quantities
// (CampaignDesign), the sampling of its runs (VirtualCaptiveOptions) and the
// runs they make, named and with their prescribed motions (PlanRuns). Both
// producers of captive runs execute these plans: the virtual captive tests
// from an MMG model (identification/virtual_captive.h) and the CFD campaigns
// (cfd/campaign/cfd_campaign.h).
#pragma once

#include <string>
#include <vector>

#include "data/schema/captive_run.h"

namespace kelvin::data {

struct VirtualCaptiveOptions {
  // When true the series are balance readings, F_hyd - M_RB a (what a towing
  // tank measures); when false the hydrodynamic force alone (what CFD gives).
  bool include_rigid_body_inertia = true;
  int samples_per_period = 200;   // harmonic runs
  int periods = 5;                // whole periods analysed (after the ramp-up)
  int ramp_periods = 1;           // harmonic runs: periods before t_ramp
  double steady_duration = 20.0;  // s, static drift / circular motion after t_ramp
  double steady_rate = 10.0;      // Hz, sampling of steady runs
  double steady_ramp = 5.0;       // s, t_ramp of steady runs

  void Validate() const;  // throws kelvin::ArgumentError naming the option
};

// The sample times of one run as the options sample it: harmonic runs
// ramp_periods + periods whole periods of samples_per_period uniform
// samples, steady runs steady_rate from t = 0 over steady_ramp +
// steady_duration; t_ramp is ramp_periods periods or steady_ramp.
struct RunSampleTimes {
  double t_ramp = 0.0;  // s
  double dt = 0.0;      // s
  std::size_t samples = 0;
};
RunSampleTimes SampleTimes(const MotionParameters& motion, const VirtualCaptiveOptions& options);

// A campaign design in prime quantities, at speed U.
struct CampaignDesign {
  double U = 0;                          // m/s
  std::vector<double> drift_angles;      // rad, static drift runs
  double omega_prime = 3.0;              // omega Lpp / U of the harmonic runs
  std::vector<double> sway_amplitudes;   // v'_a = y_a omega / U, pure sway runs
  std::vector<double> yaw_amplitudes;    // r'_a = psi_a omega Lpp / U, pure yaw runs
  std::vector<double> yaw_drift_angles;  // rad, yaw with drift runs (at yaw_drift_amplitude)
  double yaw_drift_amplitude = 0.4;      // r'_a of the yaw with drift runs
  struct Circular {
    double beta = 0;     // rad
    double r_prime = 0;  // r Lpp / U
  };
  std::vector<Circular> circular;  // circular motion (rotating arm) runs

  void Validate() const;  // throws kelvin::ArgumentError naming the field
};

// The standard KVLCC2-style campaign of issue 9 at speed U: static drift at
// 0..20 deg, pure sway at v'_a = 0.1, 0.2, pure yaw at r'_a = 0.3, 0.6, and
// (with `combined`) yaw with drift at 6 and 12 deg.
CampaignDesign StandardDesign(double U, bool combined);

// The runs of a design for a ship of length Lpp: names (drift_+5.0deg,
// sway_v0.100, yaw_r0.300, ...) and motions, with t_ramp from `options`
// (ramp_periods periods for harmonic runs, steady_ramp for steady ones).
struct PlannedRun {
  std::string name;
  MotionParameters motion;
};
std::vector<PlannedRun> PlanRuns(const CampaignDesign& design, double Lpp,
                                 const VirtualCaptiveOptions& options);

}  // namespace kelvin::data
