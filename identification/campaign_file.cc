#include "identification/campaign_file.h"

#include <cmath>

#include "data/schema/config.h"
#include "data/schema/errors.h"

namespace kelvin::ident {

namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<double> Degrees(const data::ConfigNode& node, const char* key) {
  std::vector<double> out;
  if (auto child = node.Find(key)) {
    for (const auto& item : child->Items()) {
      const double v = item.As<double>();
      if (std::abs(v) >= 90) item.Fail("an angle in degrees with |angle| < 90");
      out.push_back(v * kDeg);
    }
  }
  return out;
}

std::vector<double> PositiveList(const data::ConfigNode& node, const char* key) {
  std::vector<double> out;
  if (auto child = node.Find(key)) {
    for (const auto& item : child->Items()) {
      const double v = item.As<double>();
      if (!(v > 0)) item.Fail("a positive amplitude");
      out.push_back(v);
    }
  }
  return out;
}

}  // namespace

CampaignFile LoadCampaignFile(const std::filesystem::path& path) {
  const auto root = data::ConfigNode::LoadFile(path);
  root.ExpectKeys({"campaign", "tests", "sampling"});
  CampaignFile f;
  const auto c = root["campaign"];
  c.ExpectKeys({"name", "ship", "solver", "speed", "noise", "seed"});
  f.name = c.Get<std::string>("name");
  f.ship_file = c.Get<std::string>("ship");
  if (f.ship_file.is_relative()) f.ship_file = path.parent_path() / f.ship_file;
  const std::string solver = c.Get<std::string>("solver", "mmg");
  if (solver != "mmg") {
    c["solver"].Fail("'mmg' (virtual captive tests from the ship's MMG model; the LFS CFD solver is not available yet)");
  }
  f.speed = c.Get<double>("speed", 0.0);
  if (f.speed < 0) c["speed"].Fail("a positive speed in m/s");
  f.noise = c.Get<double>("noise", 0.0);
  if (f.noise < 0 || f.noise > 1) c["noise"].Fail("a fraction between 0 and 1");
  const int seed = c.Get<int>("seed", 1);
  if (seed < 0) c["seed"].Fail("a non-negative integer");
  f.seed = static_cast<std::uint64_t>(seed);

  const auto t = root["tests"];
  t.ExpectKeys({"static_drift_deg", "pure_sway_v_prime", "pure_yaw_r_prime", "yaw_drift_deg", "yaw_drift_r_prime",
                "omega_prime"});
  f.design.drift_angles = Degrees(t, "static_drift_deg");
  f.design.sway_amplitudes = PositiveList(t, "pure_sway_v_prime");
  f.design.yaw_amplitudes = PositiveList(t, "pure_yaw_r_prime");
  f.design.yaw_drift_angles = Degrees(t, "yaw_drift_deg");
  f.design.yaw_drift_amplitude = t.Get<double>("yaw_drift_r_prime", 0.4);
  f.design.omega_prime = t.Get<double>("omega_prime", 3.0);
  if (!(f.design.omega_prime > 0)) t["omega_prime"].Fail("a positive nondimensional frequency");
  if (f.design.drift_angles.empty() && f.design.sway_amplitudes.empty() && f.design.yaw_amplitudes.empty() &&
      f.design.yaw_drift_angles.empty()) {
    t.Fail("at least one test (static_drift_deg, pure_sway_v_prime, pure_yaw_r_prime or yaw_drift_deg)");
  }
  if (auto s = root.Find("sampling")) {
    s->ExpectKeys({"samples_per_period", "periods", "ramp_periods"});
    f.sampling.samples_per_period = s->Get<int>("samples_per_period", f.sampling.samples_per_period);
    f.sampling.periods = s->Get<int>("periods", f.sampling.periods);
    f.sampling.ramp_periods = s->Get<int>("ramp_periods", f.sampling.ramp_periods);
    try {
      f.sampling.Validate();
    } catch (const ArgumentError& e) {
      s->Fail(std::string("valid sampling (") + e.what() + ")");
    }
  }
  return f;
}

CaptiveCampaign RunCampaign(const CampaignFile& f) {
  const sim::ShipParameters ship = sim::LoadShip(f.ship_file);
  CampaignDesign design = f.design;
  design.U = f.speed > 0 ? f.speed : ship.approach_speed;
  if (!(design.U > 0)) {
    throw ConfigError(f.name + ": no speed given and the ship file has no conditions.approach_speed");
  }
  design.Validate();
  CaptiveCampaign campaign = GenerateCampaign(sim::MmgModel<double>(ship), design, f.sampling);
  if (f.noise > 0) AddForceNoise(campaign, f.noise, f.seed);
  return campaign;
}

}  // namespace kelvin::ident
