// Prescribed rigid-body motions of the captive tests (docs/formulation.md
// sections 2 and 6): the pose of the body and its rates as functions of time.
//
// Conventions of the motion laws are those of the captive schema
// (data/schema/captive_schema.md): earth axes x0 forward along the carriage,
// y0 to starboard, heading psi positive to starboard (clockwise seen from
// above), all for the body reference point (midship). With the smooth
// start-up factor s(t) = (1 - cos(pi t / t_ramp)) / 2 for t < t_ramp (1
// afterwards; s = 1 throughout when t_ramp = 0):
//   static drift:   carriage speed U s(t), psi = beta;
//   pure sway:      carriage U s(t), y0 = -s(t) y_a sin(omega t), psi = 0;
//   pure yaw:       carriage U s(t), psi = s(t) psi_a cos(omega t),
//                   y0 = s(t) (U psi_a / omega) sin(omega t);
//   yaw with drift: as pure yaw with psi = beta + s(t) psi_a cos(omega t);
//   circular:       speed U s(t) along a circle of radius U / r (r > 0 turns
//                   to starboard), psi = beta + course, so that u = U cos beta,
//                   v = -U sin beta and r are constant once t >= t_ramp.
// For t >= t_ramp every law is exactly the one of the captive schema, so the
// identification (which discards t < t_ramp) sees the textbook motion.
//
// Pose (cfd/motion/body_kinematics.h) also gives the placement of the grid.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "cfd/motion/body_kinematics.h"
#include "data/schema/config.h"

namespace kelvin::cfd {

// The smooth start-up factor s(t) above, its rate ds/dt and its integral
// from 0 (t_ramp = 0: s = 1 throughout).
double StartupFactor(double t, double t_ramp);
double StartupFactorRate(double t, double t_ramp);
double StartupFactorIntegral(double t, double t_ramp);

enum class PrescribedMotion { kStaticDrift, kPureSway, kPureYaw, kYawDrift, kCircularMotion };

// "static_drift", "pure_sway", "pure_yaw", "yaw_drift", "circular_motion"
// (the kind names of the captive schema).
std::string_view PrescribedMotionName(PrescribedMotion kind);

struct MotionOptions {
  PrescribedMotion kind = PrescribedMotion::kStaticDrift;
  double speed = 0.0;        // U, carriage speed (m/s), > 0
  double drift_angle = 0.0;  // beta (rad), |beta| < pi/2 (static drift, yaw with drift, circular)
  double sway_amplitude = 0.0;  // y_a (m), pure sway
  double yaw_amplitude = 0.0;   // psi_a (rad), pure yaw and yaw with drift
  double period = 0.0;          // 2 pi / omega (s), harmonic motions
  double yaw_rate = 0.0;        // r (rad/s), circular motion, non-zero
  double ramp_time = 0.0;       // t_ramp (s), >= 0; 0 is an impulsive start
  int periods = 0;              // harmonic runs: whole periods after the ramp (0 = not given)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // reference point (midship), grid axes (m)

  double omega() const;  // 2 pi / period, 0 for steady motions
  bool harmonic() const;
  // End time of a run of `periods` whole periods after the ramp (harmonic),
  // or 0 when `periods` is not set.
  double EndTime() const;
  // Throws ConfigError naming the key, the value and what was expected.
  void Validate() const;
};

// Reads the `motion:` section of a case file:
//   motion:
//     kind: pure_yaw          # static_drift | pure_sway | pure_yaw | yaw_drift | circular_motion
//     speed: 1.0              # m/s
//     drift_angle_deg: 10     # static drift, yaw with drift, circular motion
//     sway_amplitude: 0.05    # m, pure sway
//     yaw_amplitude_deg: 5    # pure yaw, yaw with drift
//     period: 8.0             # s, harmonic motions
//     yaw_rate: 0.2           # rad/s, circular motion
//     ramp_time: 2.5          # s
//     periods: 3              # optional: time.end = end of the 3rd whole period after the ramp
//     centre: [0.5, 0, 0]     # reference point (midship) in grid axes, m
// Keys a kind does not use are an error naming them.
MotionOptions LoadMotionOptions(const data::ConfigNode& node);

class RigidMotion : public BodyKinematics {
 public:
  explicit RigidMotion(MotionOptions options);  // validates
  const MotionOptions& options() const { return options_; }
  // Pose and rates at time t >= 0 (s), exact (no small-angle approximation).
  Pose At(double t) const override;
  const Eigen::Vector3d& centre() const override { return options_.centre; }
  double nominal_speed() const override { return options_.speed; }

 private:
  // Start-up factor s(t), its rate and its integral from 0.
  double Ramp(double t) const;
  double RampRate(double t) const;
  double RampIntegral(double t) const;

  MotionOptions options_;
};

}  // namespace kelvin::cfd
