#include "data/schema/campaign_file.h"

#include <fmt/format.h>

#include <cmath>

#include "data/schema/config.h"
#include "data/schema/errors.h"

namespace kelvin::data {

namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<double> Degrees(const ConfigNode& node, const char* key) {
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

std::vector<double> PositiveList(const ConfigNode& node, const char* key) {
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

namespace {

// `cfd.settle`: false, or {tolerance, window}.
void ReadSettle(const ConfigNode& n, CampaignFile::Cfd& cfd) {
  if (n.IsScalar()) {
    cfd.settle = n.As<bool>();
    return;
  }
  n.ExpectKeys({"tolerance", "window"});
  if (n.Has("tolerance")) {
    cfd.settle_tolerance = n.GetPositive("tolerance");
    if (cfd.settle_tolerance >= 1.0) n["tolerance"].Fail("a relative change in (0, 1)");
  }
  if (n.Has("window")) cfd.settle_window = n.GetPositive("window");
  if (cfd.settle_window > cfd.steady_duration) {
    n["window"].Fail(fmt::format("at most steady_duration = {} s (the window must fit in the run)",
                                 cfd.steady_duration));
  }
}

// Circular motion (rotating arm) runs: circular: [{drift_deg: 0, r_prime: 0.3}, ...]
// as (beta in rad, r', rate factor); `rate_factor` (default 1) only with `rates`.
std::vector<std::array<double, 3>> Circular(const ConfigNode& tests, bool rates) {
  std::vector<std::array<double, 3>> out;
  if (auto circ = tests.Find("circular")) {
    for (const auto& item : circ->Items()) {
      if (rates) {
        item.ExpectKeys({"drift_deg", "r_prime", "rate_factor"});
      } else {
        item.ExpectKeys({"drift_deg", "r_prime"});
      }
      const double beta = item.Get<double>("drift_deg", 0.0);
      if (std::abs(beta) >= 90) item["drift_deg"].Fail("an angle in degrees with |angle| < 90");
      const double r = item.Get<double>("r_prime");
      if (!(std::isfinite(r) && r != 0)) item["r_prime"].Fail("a non-zero yaw rate r' = r Lpp / U");
      const double rate = item.Has("rate_factor") ? item.GetPositive("rate_factor") : 1.0;
      out.push_back({beta * kDeg, r, rate});
    }
  }
  return out;
}

AppendageDesign ReadAppendages(const ConfigNode& a, const std::filesystem::path& path) {
  a.ExpectKeys({"ship", "propeller_rate", "swirl", "rate_factors", "rudder_deg", "drift_deg", "circular",
                "propeller_thickness", "rudder_sample_distance"});
  AppendageDesign d;
  d.ship_file = a.Get<std::string>("ship");
  if (d.ship_file.is_relative()) d.ship_file = path.parent_path() / d.ship_file;
  d.propeller_rate = a.GetPositive("propeller_rate");
  d.swirl = a.Get<bool>("swirl", true);
  d.rate_factors = PositiveList(a, "rate_factors");
  d.rudder_angles = Degrees(a, "rudder_deg");
  for (double x : d.rudder_angles) {
    if (x == 0.0) a["rudder_deg"].Fail("non-zero angles (the run at 0 is always made)");
  }
  d.drift_angles = Degrees(a, "drift_deg");
  for (const auto& [beta, r, rate] : Circular(a, true)) d.circular.push_back({beta, r, rate});
  if (a.Has("propeller_thickness")) d.propeller_thickness = a.GetPositive("propeller_thickness");
  if (a.Has("rudder_sample_distance")) d.rudder_sample_distance = a.GetPositive("rudder_sample_distance");
  return d;
}

}  // namespace

CampaignFile LoadCampaignFile(const std::filesystem::path& path) {
  return LoadCampaignFile(ConfigNode::LoadFile(path), path);
}

CampaignFile LoadCampaignFile(const ConfigNode& root, const std::filesystem::path& path) {
  root.ExpectKeys({"campaign", "tests", "sampling", "cfd"});
  CampaignFile f;
  f.path = path;
  const auto c = root["campaign"];
  c.ExpectKeys({"name", "ship", "solver", "speed", "noise", "seed"});
  f.name = c.Get<std::string>("name");
  f.ship_file = c.Get<std::string>("ship");
  if (f.ship_file.is_relative()) f.ship_file = path.parent_path() / f.ship_file;
  const std::string solver = c.Get<std::string>("solver", "mmg");
  if (solver == "cfd") {
    f.solver = CampaignFile::Solver::kCfd;
  } else if (solver != "mmg") {
    c["solver"].Fail(
        "'mmg' (virtual captive tests from the ship's MMG model) or 'cfd' (double-body CFD runs of the "
        "cfd: section; the linearized free surface of 'lfs' is not available yet)");
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
                "omega_prime", "circular", "appendages"});
  f.design.drift_angles = Degrees(t, "static_drift_deg");
  f.design.sway_amplitudes = PositiveList(t, "pure_sway_v_prime");
  f.design.yaw_amplitudes = PositiveList(t, "pure_yaw_r_prime");
  f.design.yaw_drift_angles = Degrees(t, "yaw_drift_deg");
  f.design.yaw_drift_amplitude = t.Get<double>("yaw_drift_r_prime", 0.4);
  f.design.omega_prime = t.Get<double>("omega_prime", 3.0);
  if (!(f.design.omega_prime > 0)) t["omega_prime"].Fail("a positive nondimensional frequency");
  for (const auto& [beta, r, rate] : Circular(t, false)) f.design.circular.push_back({beta, r});
  if (f.design.drift_angles.empty() && f.design.sway_amplitudes.empty() && f.design.yaw_amplitudes.empty() &&
      f.design.yaw_drift_angles.empty() && f.design.circular.empty()) {
    t.Fail("at least one test (static_drift_deg, pure_sway_v_prime, pure_yaw_r_prime, yaw_drift_deg or circular)");
  }
  if (auto a = t.Find("appendages")) {
    if (f.solver != CampaignFile::Solver::kCfd) a->Fail("no appendages: runs with the propeller and rudder need solver: cfd");
    f.appendages = ReadAppendages(*a, path);
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
  if (f.solver == CampaignFile::Solver::kCfd) {
    if (f.noise > 0) c["noise"].Fail("0: noise is for the mmg solver only");
    const auto n = root["cfd"];
    n.ExpectKeys({"case", "hull_patches", "centre", "draft", "steps_per_period", "motion_ramp_periods",
                  "steady_ramp", "steady_duration", "settle", "checkpoint_interval", "jobs", "directory"});
    CampaignFile::Cfd& cfd = f.cfd;
    cfd.case_file = n.Get<std::string>("case");
    if (cfd.case_file.is_relative()) cfd.case_file = path.parent_path() / cfd.case_file;
    if (auto h = n.Find("hull_patches")) {
      for (const auto& item : h->Items()) cfd.hull_patches.push_back(item.As<std::string>());
    }
    if (n.Has("centre")) {
      const std::vector<double> v = n["centre"].As<std::vector<double>>();
      if (v.size() != 3) n["centre"].Fail("a list of 3 coordinates in m (grid axes)");
      cfd.centre = {v[0], v[1], v[2]};
    }
    cfd.draft = n.Has("draft") ? n.GetPositive("draft") : 0.0;
    cfd.steps_per_period = n.Get<int>("steps_per_period", cfd.steps_per_period);
    if (cfd.steps_per_period < 8) n["steps_per_period"].Fail("at least 8 time steps per period");
    cfd.motion_ramp_periods = n.Get<int>("motion_ramp_periods", f.sampling.ramp_periods);
    if (cfd.motion_ramp_periods < 0 || cfd.motion_ramp_periods > f.sampling.ramp_periods) {
      n["motion_ramp_periods"].Fail(fmt::format(
          "a number of periods from 0 to sampling.ramp_periods = {} (the motion must be at full "
          "amplitude before the analysed periods)",
          f.sampling.ramp_periods));
    }
    if (n.Has("steady_ramp")) cfd.steady_ramp = n.GetPositive("steady_ramp");
    if (n.Has("steady_duration")) cfd.steady_duration = n.GetPositive("steady_duration");
    if (auto s = n.Find("settle")) ReadSettle(*s, cfd);
    cfd.checkpoint_interval = n.Get<int>("checkpoint_interval", cfd.checkpoint_interval);
    if (cfd.checkpoint_interval < 1) n["checkpoint_interval"].Fail("a number of steps >= 1");
    cfd.jobs = n.Get<int>("jobs", cfd.jobs);
    if (cfd.jobs < 1) n["jobs"].Fail("a number of concurrent runs >= 1");
    cfd.directory = n.Get<std::string>("directory", "results/" + f.name);
    if (cfd.directory.is_relative()) cfd.directory = path.parent_path() / cfd.directory;
    f.sampling.steady_ramp = cfd.steady_ramp;
    f.sampling.steady_duration = cfd.steady_duration;
    f.sampling.include_rigid_body_inertia = false;
  } else if (root.Has("cfd")) {
    root["cfd"].Fail("no cfd: section (it belongs to campaigns with solver: cfd)");
  }
  return f;
}

CaptiveShip LoadCaptiveShip(const std::filesystem::path& ship_file) {
  const auto root = ConfigNode::LoadFile(ship_file);
  CaptiveShip s;
  s.name = root["ship"].Get<std::string>("name");
  const auto p = root["principal"];
  p.ExpectKeys({"Lpp", "B", "d", "displacement", "x_G", "k_zz", "rho", "nu", "wetted_area"});
  s.Lpp = p.GetPositive("Lpp");
  s.B = p.GetPositive("B");
  s.d = p.GetPositive("d");
  s.rho = p.GetPositive("rho");
  s.mass = s.rho * p.GetPositive("displacement");
  s.x_G = p.Get<double>("x_G", 0.0);
  const double k_zz = p.Has("k_zz") ? p.GetPositive("k_zz") : 0.25;
  s.I_zG = s.mass * (k_zz * s.Lpp) * (k_zz * s.Lpp);
  return s;
}

}  // namespace kelvin::data
