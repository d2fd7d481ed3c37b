#include "identification/virtual_captive.h"

#include <fmt/format.h>

#include <cmath>
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

data::CaptiveRun GenerateRun(const sim::MmgModel<double>& model, const std::string& name,
                             data::MotionParameters motion,
                             const data::VirtualCaptiveOptions& options) {
  options.Validate();
  const data::CaptiveShip ship = CaptiveShipFrom(model.ship());
  data::CaptiveRun run;
  run.name = name;
  run.includes_rigid_body_inertia = options.include_rigid_body_inertia;
  const data::RunSampleTimes times = data::SampleTimes(motion, options);
  motion.t_ramp = times.t_ramp;
  const double dt = times.dt;
  const std::size_t samples = times.samples;
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

data::CaptiveCampaign GenerateCampaign(const sim::MmgModel<double>& model,
                                       const data::CampaignDesign& design,
                                       const data::VirtualCaptiveOptions& options) {
  data::CaptiveCampaign c;
  c.description = fmt::format("virtual captive tests of {} from the MMG model (U = {} m/s)",
                              model.ship().name, design.U);
  c.ship = CaptiveShipFrom(model.ship());
  for (const data::PlannedRun& run : data::PlanRuns(design, model.ship().principal.Lpp, options)) {
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

data::CaptiveCampaign RunCampaign(const data::CampaignFile& f) {
  if (f.solver != data::CampaignFile::Solver::kMmg) {
    throw ConfigError(f.name +
                      ": RunCampaign runs the mmg solver; cfd campaigns run through cfd/campaign");
  }
  const sim::ShipParameters ship = sim::LoadShip(f.ship_file);
  sim::RequireManeuveringModel(ship, f.ship_file.string());
  data::CampaignDesign design = f.design;
  design.U = f.speed > 0 ? f.speed : ship.approach_speed;
  if (!(design.U > 0)) {
    throw ConfigError(f.name +
                      ": no speed given and the ship file has no conditions.approach_speed");
  }
  design.Validate();
  data::CaptiveCampaign campaign =
      GenerateCampaign(sim::MmgModel<double>(ship), design, f.sampling);
  if (f.noise > 0) AddForceNoise(campaign, f.noise, f.seed);
  return campaign;
}

}  // namespace kelvin::ident
