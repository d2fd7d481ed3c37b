#include "cfd/run/free_running_loader.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "cfd/run/case_config.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::array<bool, 3> ReadFreeDofs(const ConfigNode& node) {
  std::array<bool, 3> free = {false, false, false};
  for (const ConfigNode& item : node.Items()) {
    const std::string name = item.As<std::string>();
    if (name == "surge") {
      free[0] = true;
    } else if (name == "sway") {
      free[1] = true;
    } else if (name == "yaw") {
      free[2] = true;
    } else {
      node.Fail(fmt::format("a list of surge, sway, yaw (got '{}')", name));
    }
  }
  return free;
}

// The added masses of the ship file in SI units: m_x, m_y in kg (prime times
// 0.5 rho L^2 d), J_z in kg m^2 (prime times 0.5 rho L^4 d).
std::array<double, 3> ShipAddedMass(const sim::ShipParameters& ship) {
  const sim::Principal& p = ship.principal;
  const double mass_scale = 0.5 * p.rho * p.Lpp * p.Lpp * p.d;
  return {ship.hull.m_x * mass_scale, ship.hull.m_y * mass_scale, ship.hull.J_z * mass_scale * p.Lpp * p.Lpp};
}

void ReadCoupling(const ConfigNode& node, FreeBodyOptions& o) {
  node.ExpectKeys({"scheme", "added_mass", "relaxation"});
  o.coupling = GetEnum(node, "scheme", BodyCoupling::kStabilised,
                       {{"stabilised", BodyCoupling::kStabilised}, {"explicit", BodyCoupling::kExplicit}});
  o.relaxation = node.Get<double>("relaxation", 1.0);
  if (auto am = node.Find("added_mass")) {
    if (am->IsScalar()) {
      const std::string text = am->As<std::string>();
      if (text == "none") {
        o.added_mass = {0.0, 0.0, 0.0};
      } else if (text != "ship") {
        am->Fail("ship, none, or a list [m_x, m_y, J_z] in kg, kg, kg m^2");
      }
    } else {
      const std::vector<double> v = am->As<std::vector<double>>();
      if (v.size() != 3) am->Fail("a list [m_x, m_y, J_z] in kg, kg, kg m^2");
      o.added_mass = {v[0], v[1], v[2]};
    }
  }
}

}  // namespace

bool IsFreeMotion(const ConfigNode& motion) {
  return motion.Has("kind") && motion["kind"].IsScalar() && motion.Get<std::string>("kind") == "free";
}

FreeRunningSettings LoadFreeRunning(const ConfigNode& node, const std::filesystem::path& case_dir, bool bdf2) {
  node.ExpectKeys({"kind", "ship", "centre", "free", "initial", "heading_deg", "ramp_time", "release_time",
                   "external_load", "coupling", "hull_patches", "divergence_factor"});
  FreeRunningSettings s;
  s.ship_file = case_dir / node.Get<std::string>("ship");
  try {
    s.ship = sim::LoadShip(s.ship_file);
  } catch (const InputError& e) {
    node["ship"].Fail(fmt::format("a ship file the simulator reads ({})", e.what()));
  }
  FreeBodyOptions& o = s.body;
  o.mass = s.ship.mass();
  o.x_G = s.ship.principal.x_G;
  o.I_zG = s.ship.I_zG();
  o.bdf2 = bdf2;
  o.centre = GetVector(node, "centre");
  o.free = ReadFreeDofs(node["free"]);
  const ConfigNode init = node["initial"];
  init.ExpectKeys({"u", "v", "r"});
  o.initial = {init.Get<double>("u", 0.0), init.Get<double>("v", 0.0), init.Get<double>("r", 0.0)};
  o.initial_heading = node.Get<double>("heading_deg", 0.0) * kDeg;
  o.ramp_time = node.Has("ramp_time") ? node.GetPositive("ramp_time", /*allow_zero=*/true) : 0.0;
  o.release_time = node.Has("release_time") ? node.GetPositive("release_time", /*allow_zero=*/true) : o.ramp_time;
  if (auto ext = node.Find("external_load")) {
    ext->ExpectKeys({"X", "Y", "N"});
    o.external = {ext->Get<double>("X", 0.0), ext->Get<double>("Y", 0.0), ext->Get<double>("N", 0.0)};
  }
  o.coupling = BodyCoupling::kStabilised;
  o.added_mass = ShipAddedMass(s.ship);
  if (auto c = node.Find("coupling")) ReadCoupling(*c, o);
  o.divergence_factor = node.Get<double>("divergence_factor", 10.0);
  if (auto h = node.Find("hull_patches")) {
    for (const ConfigNode& item : h->Items()) s.hull_patches.push_back(item.As<std::string>());
  }
  ValidateAt(node, [&] { o.Validate("motion"); });
  return s;
}

}  // namespace kelvin::cfd
