// Captive campaigns for the schema tests, made without any hydrodynamic
// model (and the sample motion of the kinematics tests): the KVLCC2 L7 ship data (data/ships/kvlcc2.yaml) and runs sampled
// like the virtual captive generator samples them (harmonic runs: whole
// periods of uniform samples after ramp_periods periods; steady runs: a
// fixed rate from t = 0), with smooth synthetic forces (a linear hull minus
// the rigid-body inertia, i.e. balance readings).
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "data/schema/captive_plan.h"
#include "data/schema/captive_run.h"

namespace kelvin::data::fixtures {

// KVLCC2 L7: Lpp 7 m, B 1.27 m, d 0.46 m, 3.27 m^3, x_G 0.25 m, k_zz 0.25.
inline CaptiveShip Kvlcc2Ship() {
  CaptiveShip s;
  s.name = "KVLCC2";
  s.Lpp = 7.0;
  s.B = 1.27;
  s.d = 0.46;
  s.rho = 1025.0;
  s.mass = s.rho * 3.27;
  s.x_G = 0.25;
  s.I_zG = s.mass * (0.25 * s.Lpp) * (0.25 * s.Lpp);
  return s;
}

// A motion with every parameter set (each kind reads its own).
inline MotionParameters SampleMotion(MotionKind kind) {
  MotionParameters m;
  m.kind = kind;
  m.U = 1.2;
  m.beta = 0.15;
  m.y_a = 0.3;
  m.psi_a = 0.2;
  m.omega = 0.6;
  m.r_prime = 0.4;
  m.t_ramp = 4.0;
  return m;
}

// The schema tests' sampling: shorter than the generator's defaults.
inline VirtualCaptiveOptions Sampling() {
  VirtualCaptiveOptions o;
  o.samples_per_period = 50;
  o.periods = 2;
  o.steady_duration = 3.0;
  return o;
}

// One run of `motion` (its t_ramp set from `sampling`).
inline CaptiveRun SampledRun(const CaptiveShip& ship, const std::string& name,
                             MotionParameters motion, const VirtualCaptiveOptions& sampling = Sampling()) {
  CaptiveRun run;
  run.name = name;
  run.includes_rigid_body_inertia = true;
  const RunSampleTimes times = SampleTimes(motion, sampling);
  motion.t_ramp = times.t_ramp;
  const double dt = times.dt;
  const std::size_t samples = times.samples;
  run.motion = motion;
  const double q = ship.ForceScale();
  for (std::size_t i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) * dt;
    const BodyKinematics k = KinematicsAt(motion, ship.Lpp, t);
    const std::array<double, 3> rb = RigidBodyInertia(ship, k);
    const double r = k.r * ship.Lpp;
    run.time.push_back(t);
    run.force[0].push_back(q * (-0.022 * k.u * k.u) - rb[0]);
    run.force[1].push_back(q * (-0.315 * k.u * k.v + 0.083 * k.u * r) - rb[1]);
    run.force[2].push_back(q * ship.Lpp * (-0.137 * k.u * k.v - 0.049 * k.u * r) - rb[2]);
  }
  return run;
}

// Four runs at the KVLCC2 approach speed 1.179 m/s, omega' = 3: static
// drift at 0.1 rad, pure sway v'_a = 0.1, pure yaw r'_a = 0.3 and yaw with
// drift at 0.1 rad, r'_a = 0.4 (in that order).
inline CaptiveCampaign SmallCampaign() {
  CaptiveCampaign c;
  c.description = "schema test campaign";
  c.ship = Kvlcc2Ship();
  const double U = 1.179, omega = 3.0 * U / c.ship.Lpp;
  c.runs.push_back(
      SampledRun(c.ship, "drift_+5.7deg", {.kind = MotionKind::kStaticDrift, .U = U, .beta = 0.1}));
  c.runs.push_back(
      SampledRun(c.ship, "sway_v0.100",
                 {.kind = MotionKind::kPureSway, .U = U, .y_a = 0.1 * U / omega, .omega = omega}));
  c.runs.push_back(
      SampledRun(c.ship, "yaw_r0.300",
                 {.kind = MotionKind::kPureYaw, .U = U, .psi_a = 0.3 / 3.0, .omega = omega}));
  c.runs.push_back(SampledRun(
      c.ship, "yaw_drift_+5.7deg_r0.400",
      {.kind = MotionKind::kYawDrift, .U = U, .beta = 0.1, .psi_a = 0.4 / 3.0, .omega = omega}));
  return c;
}

}  // namespace kelvin::data::fixtures
