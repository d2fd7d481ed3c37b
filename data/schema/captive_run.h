// Captive (PMM / towing-tank / CFD) runs: the prescribed motion of one run,
// its exact body kinematics, and the measured force histories. The HDF5 and
// CSV layouts are documented in data/schema/captive_schema.md.
//
// Conventions are those of simulator/mmg (Yasukawa & Yoshimura 2015): ship
// axes at midship, x forward, y starboard, psi and r positive to starboard,
// beta = -atan(v_m / u), forces X, Y in N and the yaw moment N about midship
// in N m. Motions follow docs/formulation.md section 6:
//   static drift:  carriage at U along earth x, heading psi = beta; the speed
//                  ramps up as U (1 - cos(pi t / t_ramp)) / 2 over t_ramp;
//   pure sway:     y0(t) = -y_a sin(omega t), psi = 0, carriage at U;
//   pure yaw:      psi(t) = psi_a cos(omega t), y0(t) = (U psi_a / omega) sin(omega t);
//   yaw with drift: psi(t) = beta + psi_a cos(omega t), y0 as in pure yaw;
//   circular motion (rotating arm): steady u = U cos beta, v_m = -U sin beta,
//                  r = r' U / Lpp.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace kelvin::data {

enum class MotionKind { kStaticDrift, kPureSway, kPureYaw, kYawDrift, kCircularMotion };

// "static_drift", "pure_sway", "pure_yaw", "yaw_drift", "circular_motion".
std::string_view MotionKindName(MotionKind kind);
// Inverse of MotionKindName; throws kelvin::DataFileError naming `where` and
// listing the valid names.
MotionKind ParseMotionKind(std::string_view name, std::string_view where);
bool IsHarmonic(MotionKind kind);

// The parameters of a prescribed motion. Unused fields are zero.
struct MotionParameters {
  MotionKind kind = MotionKind::kStaticDrift;
  double U = 0;        // m/s, carriage speed (the speed of the prime system)
  double beta = 0;     // rad, drift angle (static drift, yaw with drift, circular)
  double y_a = 0;      // m, sway amplitude (pure sway)
  double psi_a = 0;    // rad, yaw amplitude (pure yaw, yaw with drift)
  double omega = 0;    // rad/s, circular frequency (harmonic motions)
  double r_prime = 0;  // yaw rate r Lpp / U (circular motion)
  double t_ramp = 0;   // s, start-up discarded by every analysis (and the speed
                       // ramp of static drift)

  double Period() const;  // 2 pi / omega for harmonic motions, 0 otherwise
};

// Body velocities and accelerations at midship.
struct BodyKinematics {
  double u = 0, v = 0, r = 0;     // m/s, m/s, rad/s
  double du = 0, dv = 0, dr = 0;  // m/s^2, m/s^2, rad/s^2
};

// Exact kinematics of the prescribed motion at time t (no small-angle
// approximation). `Lpp` is needed for circular motion only.
BodyKinematics KinematicsAt(const MotionParameters& motion, double Lpp, double t);

// Ship data a captive campaign carries (what the analysis needs).
struct CaptiveShip {
  std::string name;
  double Lpp = 0;   // m
  double B = 0;     // m (informative)
  double d = 0;     // m, draft (the T of the prime system)
  double rho = 0;   // kg/m^3
  double mass = 0;  // kg
  double x_G = 0;   // m, centre of gravity ahead of midship
  double I_zG = 0;  // kg m^2, yaw inertia about G

  // 0.5 rho Lpp d: force scale / U^2.
  double ForceScale() const { return 0.5 * rho * Lpp * d; }
};

enum class Channel { kX = 0, kY = 1, kN = 2 };
inline constexpr std::array<std::string_view, 3> kChannelNames = {"X", "Y", "N"};

struct CaptiveRun {
  std::string name;
  MotionParameters motion;
  // True when the series are what a balance between carriage and model
  // reads: the hydrodynamic force minus the rigid-body inertia force
  // (F_hyd - M_RB a). False when they are the hydrodynamic force alone (CFD).
  bool includes_rigid_body_inertia = false;
  // Steady runs that ended on a steady criterion (a CFD campaign's static
  // drift): the analysis uses the samples from max(t_ramp, t_settle), the
  // settled part. settled: 1 when the criterion was met, 0 when the run hit
  // its longest duration first, -1 when no criterion was applied; change is
  // the criterion's relative change over its window at the end.
  double t_settle = 0;  // s
  int settled = -1;
  double settle_change = 0;
  std::vector<double> time;                  // s, strictly increasing
  std::array<std::vector<double>, 3> force;  // X [N], Y [N], N [N m]
};

struct CaptiveCampaign {
  std::string description;
  CaptiveShip ship;
  std::vector<CaptiveRun> runs;
};

// The rigid-body inertia force M_RB a at midship for body kinematics k:
//   X_RB = m (du - v r - x_G r^2)
//   Y_RB = m (dv + u r + x_G dr)
//   N_RB = (I_zG + m x_G^2) dr + m x_G (dv + u r)
// (the left-hand side of the MMG motion equations without added masses).
std::array<double, 3> RigidBodyInertia(const CaptiveShip& ship, const BodyKinematics& k);

// "t = a to b s (n samples; settled: change c over the window)" for reports.
std::string DescribeWindow(const CaptiveRun& run, std::size_t begin, std::size_t end);

// Checks the ship data and every run: known motion parameters in range,
// matching series lengths, strictly increasing time, finite forces, and at
// least one whole period (harmonic) or kMinSteadySamples samples (steady)
// after t_ramp. Throws kelvin::DataFileError naming `source`, the run and the
// channel.
void ValidateCampaign(const CaptiveCampaign& campaign, std::string_view source);
inline constexpr int kMinSteadySamples = 10;

// Indices [begin, end) of the samples an analysis uses: for harmonic motions
// the whole periods (referenced to t = 0) after t_ramp, for steady motions
// every sample at t >= t_ramp. Throws DataFileError (naming source and run)
// when there is less than one whole period / kMinSteadySamples samples.
struct AnalysisWindow {
  std::size_t begin = 0, end = 0;
  int periods = 0;  // whole periods (harmonic) or 0
};
AnalysisWindow SelectWindow(const CaptiveRun& run, std::string_view source);

}  // namespace kelvin::data
