#include "simulator/mmg/derivative_set.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "data/schema/config.h"
#include "data/schema/errors.h"

namespace kelvin::sim {

DerivativeSet LoadDerivativeSet(const std::filesystem::path& path) {
  return LoadDerivativeSet(data::ConfigNode::LoadFile(path), path);
}

DerivativeSet LoadDerivativeSet(const data::ConfigNode& root, const std::filesystem::path& path) {
  if (!root.IsMap()) root.Fail("a derivative set (a map with a 'hull' section)");
  // The sections `kelvin identify` writes (identification/derivative_set_io.h),
  // and the check.
  root.ExpectKeys({"derivative_set", "hull", "standard_errors", "fit", "interaction", "interaction_fit", "check"});
  DerivativeSet set;
  set.file = path.string();
  if (const auto meta = root.Find("derivative_set")) {
    meta->ExpectKeys({"name", "ship", "source"});
    set.name = meta->Get<std::string>("name", "");
    if (const auto ship = meta->Find("ship")) {
      set.ship = ship->As<std::string>();
      set.ship_where = ship->Where();
    }
  }
  const data::ConfigNode hull = root["hull"];
  std::vector<std::string> names;
  for (const auto& n : HullCoefficients<double>::kNames) names.emplace_back(n);
  hull.ExpectKeys(names);
  for (int i = 0; i < HullCoefficients<double>::kCount; ++i) {
    set.hull[i] = hull.Get<double>(names[static_cast<std::size_t>(i)]);
    if (!std::isfinite(set.hull[i])) hull[names[static_cast<std::size_t>(i)]].Fail("a finite number");
  }
  if (const auto inter = root.Find("interaction")) {
    if (!inter->IsMap()) inter->Fail("a map of MMG interaction coefficients (t_P, epsilon, ...)");
    const std::vector<std::string> keys(kInteractionKeys.begin(), kInteractionKeys.end());
    inter->ExpectKeys(keys);
    for (const std::string& k : inter->Keys()) {
      set.interaction[k] = inter->Get<double>(k);
      if (!std::isfinite(set.interaction[k])) (*inter)[k].Fail("a finite number");
    }
  }
  if (const auto fit = root.Find("fit")) {
    if (const auto range = fit->Find("range")) {
      range->ExpectKeys({"drift_deg", "r_prime"});
      MotionRange r;
      r.drift = range->Get<double>("drift_deg") * std::numbers::pi / 180.0;
      r.r_prime = range->Get<double>("r_prime");
      if (!(r.drift >= 0 && r.drift <= std::numbers::pi)) (*range)["drift_deg"].Fail("an angle in [0, 180] deg");
      if (!(r.r_prime >= 0) || !std::isfinite(r.r_prime)) (*range)["r_prime"].Fail("a non-negative r'");
      set.range = r;
    }
  }
  if (const auto check = root.Find("check")) {
    check->ExpectKeys({"passed", "reference", "date", "summary"});
    DerivativeCheck c;
    c.passed = check->Get<bool>("passed");
    c.reference = check->Get<std::string>("reference", "");
    c.date = check->Get<std::string>("date", "");
    c.summary = check->Get<std::string>("summary", "");
    set.check = c;
  }
  return set;
}

void MotionRange::Include(double u, double v, double r, double Lpp) {
  const double U = std::hypot(u, v);
  if (!(U > 0.0)) return;
  drift = std::max(drift, std::atan2(std::abs(v), u));
  r_prime = std::max(r_prime, std::abs(r) * Lpp / U);
}

std::array<double*, kInteractionKeys.size()> InteractionFields(PropellerParameters& pp, RudderParameters& rp) {
  return {&pp.t_P,          &pp.w_P0,        &rp.epsilon, &rp.kappa, &rp.gamma_R_minus, &rp.gamma_R_plus,
          &rp.l_R_prime,    &rp.t_R,         &rp.a_H,     &rp.x_H_prime, &rp.f_alpha};
}

void ApplyInteraction(const std::map<std::string, double>& interaction, ShipParameters& ship) {
  const auto fields = InteractionFields(ship.propeller, ship.rudder);
  for (const auto& [key, value] : interaction) {
    const auto it = std::find(kInteractionKeys.begin(), kInteractionKeys.end(), key);
    KELVIN_CHECK(it != kInteractionKeys.end(), "an interaction key of kInteractionKeys");
    *fields[static_cast<std::size_t>(it - kInteractionKeys.begin())] = value;
  }
}

}  // namespace kelvin::sim
