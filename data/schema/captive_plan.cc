#include "data/schema/captive_plan.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "data/schema/errors.h"

namespace kelvin::data {

void VirtualCaptiveOptions::Validate() const {
  auto fail = [](std::string_view key, double value, std::string_view expected) {
    throw ArgumentError(
        fmt::format("virtual captive option '{}' = {}: expected {}", key, value, expected));
  };
  if (samples_per_period < 8) fail("samples_per_period", samples_per_period, "at least 8");
  if (periods < 1) fail("periods", periods, "at least 1");
  if (ramp_periods < 0) fail("ramp_periods", ramp_periods, "0 or more");
  if (!(steady_duration > 0)) fail("steady_duration", steady_duration, "a positive duration in s");
  if (!(steady_rate > 0)) fail("steady_rate", steady_rate, "a positive rate in Hz");
  if (!(steady_ramp > 0)) fail("steady_ramp", steady_ramp, "a positive duration in s");
}

void CampaignDesign::Validate() const {
  auto fail = [](std::string_view key, double value, std::string_view expected) {
    throw ArgumentError(
        fmt::format("campaign design field '{}' = {}: expected {}", key, value, expected));
  };
  if (!(U > 0)) fail("U", U, "a positive speed in m/s");
  if (!(omega_prime > 0)) fail("omega_prime", omega_prime, "a positive nondimensional frequency");
  for (double b : drift_angles) {
    if (!(std::abs(b) < 0.5 * std::numbers::pi)) fail("drift_angles", b, "|beta| < pi/2 rad");
  }
  for (double b : yaw_drift_angles) {
    if (!(std::abs(b) < 0.5 * std::numbers::pi)) fail("yaw_drift_angles", b, "|beta| < pi/2 rad");
  }
  for (double a : sway_amplitudes) {
    if (!(a > 0)) fail("sway_amplitudes", a, "positive amplitudes v'_a");
  }
  for (double a : yaw_amplitudes) {
    if (!(a > 0)) fail("yaw_amplitudes", a, "positive amplitudes r'_a");
  }
  for (const Circular& c : circular) {
    if (!(std::abs(c.beta) < 0.5 * std::numbers::pi))
      fail("circular.beta", c.beta, "|beta| < pi/2 rad");
    if (!(std::isfinite(c.r_prime) && c.r_prime != 0))
      fail("circular.r_prime", c.r_prime, "a non-zero yaw rate");
  }
  if (!yaw_drift_angles.empty() && !(yaw_drift_amplitude > 0)) {
    fail("yaw_drift_amplitude", yaw_drift_amplitude, "a positive amplitude r'_a");
  }
}

CampaignDesign StandardDesign(double U, bool combined) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  CampaignDesign d;
  d.U = U;
  d.drift_angles = {0.0, 4 * kDeg, 8 * kDeg, 12 * kDeg, 16 * kDeg, 20 * kDeg};
  d.sway_amplitudes = {0.1, 0.2};
  d.yaw_amplitudes = {0.3, 0.6};
  if (combined) d.yaw_drift_angles = {6 * kDeg, 12 * kDeg};
  return d;
}

std::vector<PlannedRun> PlanRuns(const CampaignDesign& design, double L,
                                 const VirtualCaptiveOptions& options) {
  design.Validate();
  constexpr double kRadToDeg = 180.0 / std::numbers::pi;
  const double omega = design.omega_prime * design.U / L;
  std::vector<PlannedRun> runs;
  auto add = [&](std::string name, MotionParameters m) {
    m.t_ramp = IsHarmonic(m.kind) ? options.ramp_periods * m.Period() : options.steady_ramp;
    runs.push_back({std::move(name), m});
  };
  for (double beta : design.drift_angles) {
    add(fmt::format("drift_{:+.1f}deg", beta * kRadToDeg),
        MotionParameters{.kind = MotionKind::kStaticDrift, .U = design.U, .beta = beta});
  }
  for (double v_a : design.sway_amplitudes) {
    add(fmt::format("sway_v{:.3f}", v_a), MotionParameters{.kind = MotionKind::kPureSway,
                                                           .U = design.U,
                                                           .y_a = v_a * design.U / omega,
                                                           .omega = omega});
  }
  for (double r_a : design.yaw_amplitudes) {
    add(fmt::format("yaw_r{:.3f}", r_a), MotionParameters{.kind = MotionKind::kPureYaw,
                                                          .U = design.U,
                                                          .psi_a = r_a / design.omega_prime,
                                                          .omega = omega});
  }
  for (double beta : design.yaw_drift_angles) {
    add(fmt::format("yaw_drift_{:+.1f}deg_r{:.3f}", beta * kRadToDeg, design.yaw_drift_amplitude),
        MotionParameters{.kind = MotionKind::kYawDrift,
                         .U = design.U,
                         .beta = beta,
                         .psi_a = design.yaw_drift_amplitude / design.omega_prime,
                         .omega = omega});
  }
  for (const CampaignDesign::Circular& arm : design.circular) {
    add(fmt::format("circular_{:+.1f}deg_r{:.3f}", arm.beta * kRadToDeg, arm.r_prime),
        MotionParameters{.kind = MotionKind::kCircularMotion,
                         .U = design.U,
                         .beta = arm.beta,
                         .r_prime = arm.r_prime});
  }
  return runs;
}

RunSampleTimes SampleTimes(const MotionParameters& motion, const VirtualCaptiveOptions& options) {
  RunSampleTimes r;
  if (IsHarmonic(motion.kind)) {
    const double T = motion.Period();
    r.t_ramp = options.ramp_periods * T;
    r.dt = T / options.samples_per_period;
    r.samples = static_cast<std::size_t>((options.ramp_periods + options.periods) * options.samples_per_period);
  } else {
    r.t_ramp = options.steady_ramp;
    r.dt = 1.0 / options.steady_rate;
    r.samples = static_cast<std::size_t>(std::llround((options.steady_ramp + options.steady_duration) / r.dt));
  }
  return r;
}

}  // namespace kelvin::data
