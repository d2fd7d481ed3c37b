// Virtual captive tests: the forces a captive model would measure in the
// prescribed motions if the hull followed an MMG model exactly. Used to check
// the identification end to end (round trip) and to design campaigns.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "data/schema/captive_run.h"
#include "simulator/mmg/mmg_model.h"
#include "simulator/mmg/ship_parameters.h"

namespace kelvin::ident {

// The ship data of a campaign from an MMG ship definition.
data::CaptiveShip CaptiveShipFrom(const sim::ShipParameters& ship);

// An MMG ship definition (principal particulars only; propeller and rudder
// left empty) from campaign ship data, for evaluating the hull model.
sim::ShipParameters HullShipFrom(const data::CaptiveShip& ship);

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

// One run with the motion `motion` (its t_ramp is overwritten from the options).
data::CaptiveRun GenerateRun(const sim::MmgModel<double>& model, const std::string& name,
                             data::MotionParameters motion, const VirtualCaptiveOptions& options);

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
  data::MotionParameters motion;
};
std::vector<PlannedRun> PlanRuns(const CampaignDesign& design, double Lpp, const VirtualCaptiveOptions& options);

data::CaptiveCampaign GenerateCampaign(const sim::MmgModel<double>& model,
                                       const CampaignDesign& design,
                                       const VirtualCaptiveOptions& options);

// Adds Gaussian noise of standard deviation `fraction` x (RMS of the channel
// over the run's analysis window, i.e. after the ramp-up) to every force
// sample (std::mt19937_64 seeded with `seed`). Channels that are zero over
// the window (Y and N at zero drift) stay noise-free.
void AddForceNoise(data::CaptiveCampaign& campaign, double fraction, std::uint64_t seed);

}  // namespace kelvin::ident
