#include "identification/virtual_captive.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <random>

#include "data/schema/errors.h"
#include "identification/captive_force_model.h"

namespace kelvin::ident {

data::CaptiveShip CaptiveShipFrom(const sim::ShipParameters& ship) {
  data::CaptiveShip s;
  s.name = ship.name;
  s.Lpp = ship.principal.Lpp;
  s.B = ship.principal.B;
  s.d = ship.principal.d;
  s.rho = ship.principal.rho;
  s.mass = ship.mass();
  s.x_G = ship.principal.x_G;
  s.I_zG = ship.I_zG();
  return s;
}

sim::ShipParameters HullShipFrom(const data::CaptiveShip& ship) {
  sim::ShipParameters s;
  s.principal.Lpp = ship.Lpp;
  s.principal.B = ship.B;
  s.principal.d = ship.d;
  s.principal.rho = ship.rho;
  s.principal.displacement = ship.mass / ship.rho;
  s.principal.x_G = ship.x_G;
  s.principal.k_zz = std::sqrt(ship.I_zG / ship.mass) / ship.Lpp;
  return s;
}

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

data::CaptiveRun GenerateRun(const sim::MmgModel<double>& model, const std::string& name,
                             data::MotionParameters motion, const VirtualCaptiveOptions& options) {
  options.Validate();
  const data::CaptiveShip ship = CaptiveShipFrom(model.ship());
  data::CaptiveRun run;
  run.name = name;
  run.includes_rigid_body_inertia = options.include_rigid_body_inertia;
  std::size_t samples = 0;
  double dt = 0;
  if (data::IsHarmonic(motion.kind)) {
    const double T = motion.Period();
    motion.t_ramp = options.ramp_periods * T;
    dt = T / options.samples_per_period;
    samples = static_cast<std::size_t>((options.ramp_periods + options.periods) *
                                       options.samples_per_period);
  } else {
    motion.t_ramp = options.steady_ramp;
    dt = 1.0 / options.steady_rate;
    samples = static_cast<std::size_t>(
        std::llround((options.steady_ramp + options.steady_duration) / dt));
  }
  run.motion = motion;
  run.time.resize(samples);
  for (auto& f : run.force) f.resize(samples);
  for (std::size_t i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) * dt;
    const data::BodyKinematics k = data::KinematicsAt(motion, ship.Lpp, t);
    std::array<double, 3> f = CaptiveHydrodynamicForce(model, k);
    if (options.include_rigid_body_inertia) {
      const std::array<double, 3> rb = data::RigidBodyInertia(ship, k);
      for (int c = 0; c < 3; ++c) f[c] -= rb[c];
    }
    run.time[i] = t;
    for (int c = 0; c < 3; ++c) run.force[c][i] = f[c];
  }
  return run;
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

std::vector<PlannedRun> PlanRuns(const CampaignDesign& design, double L, const VirtualCaptiveOptions& options) {
  design.Validate();
  constexpr double kRadToDeg = 180.0 / std::numbers::pi;
  const double omega = design.omega_prime * design.U / L;
  std::vector<PlannedRun> runs;
  auto add = [&](std::string name, data::MotionParameters m) {
    m.t_ramp = data::IsHarmonic(m.kind) ? options.ramp_periods * m.Period() : options.steady_ramp;
    runs.push_back({std::move(name), m});
  };
  for (double beta : design.drift_angles) {
    add(fmt::format("drift_{:+.1f}deg", beta * kRadToDeg),
        data::MotionParameters{
            .kind = data::MotionKind::kStaticDrift, .U = design.U, .beta = beta});
  }
  for (double v_a : design.sway_amplitudes) {
    add(fmt::format("sway_v{:.3f}", v_a),
        data::MotionParameters{.kind = data::MotionKind::kPureSway,
                               .U = design.U,
                               .y_a = v_a * design.U / omega,
                               .omega = omega});
  }
  for (double r_a : design.yaw_amplitudes) {
    add(fmt::format("yaw_r{:.3f}", r_a), data::MotionParameters{.kind = data::MotionKind::kPureYaw,
                                                                .U = design.U,
                                                                .psi_a = r_a / design.omega_prime,
                                                                .omega = omega});
  }
  for (double beta : design.yaw_drift_angles) {
    add(fmt::format("yaw_drift_{:+.1f}deg_r{:.3f}", beta * kRadToDeg, design.yaw_drift_amplitude),
        data::MotionParameters{.kind = data::MotionKind::kYawDrift,
                               .U = design.U,
                               .beta = beta,
                               .psi_a = design.yaw_drift_amplitude / design.omega_prime,
                               .omega = omega});
  }
  for (const CampaignDesign::Circular& arm : design.circular) {
    add(fmt::format("circular_{:+.1f}deg_r{:.3f}", arm.beta * kRadToDeg, arm.r_prime),
        data::MotionParameters{.kind = data::MotionKind::kCircularMotion,
                               .U = design.U,
                               .beta = arm.beta,
                               .r_prime = arm.r_prime});
  }
  return runs;
}

data::CaptiveCampaign GenerateCampaign(const sim::MmgModel<double>& model,
                                       const CampaignDesign& design,
                                       const VirtualCaptiveOptions& options) {
  data::CaptiveCampaign c;
  c.description = fmt::format("virtual captive tests of {} from the MMG model (U = {} m/s)",
                              model.ship().name, design.U);
  c.ship = CaptiveShipFrom(model.ship());
  for (const PlannedRun& run : PlanRuns(design, model.ship().principal.Lpp, options)) {
    c.runs.push_back(GenerateRun(model, run.name, run.motion, options));
  }
  return c;
}

void AddForceNoise(data::CaptiveCampaign& campaign, double fraction, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (data::CaptiveRun& run : campaign.runs) {
    const data::AnalysisWindow w = data::SelectWindow(run, "AddForceNoise");
    for (auto& f : run.force) {
      double sum2 = 0;
      for (std::size_t i = w.begin; i < w.end; ++i) sum2 += f[i] * f[i];
      const double sigma = fraction * std::sqrt(sum2 / static_cast<double>(w.end - w.begin));
      for (double& x : f) x += sigma * normal(rng);
    }
  }
}

}  // namespace kelvin::ident
