#include "simulator/mmg/ship_parameters.h"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "data/reference/friction_lines.h"
#include "data/schema/config.h"
#include "data/schema/errors.h"

namespace kelvin::sim {

namespace {

constexpr double kDeg = M_PI / 180.0;

[[noreturn]] void Unphysical(const std::string& source, const std::string& key, double value,
                             const std::string& expected) {
  throw ModelError(fmt::format("{}: parameter '{}' = {}: expected {}", source, key, value, expected));
}

void Positive(const std::string& src, const std::string& key, double v) {
  if (!(v > 0) || !std::isfinite(v)) Unphysical(src, key, v, "a positive finite value");
}

void InRange(const std::string& src, const std::string& key, double v, double lo, double hi) {
  if (!(v >= lo && v < hi)) Unphysical(src, key, v, fmt::format("a value in [{}, {})", lo, hi));
}

void Finite(const std::string& src, const std::string& key, double v) {
  if (!std::isfinite(v)) Unphysical(src, key, v, "a finite value");
}

void ReadRudder(const data::ConfigNode& r, RudderParameters& rp) {
  r.ExpectKeys({"A_R", "H_R", "t_R", "a_H", "x_H_prime", "x_R_prime", "gamma_R_minus", "gamma_R_plus",
                "l_R_prime", "epsilon", "kappa", "f_alpha", "z_top"});
  rp.A_R = r.Get<double>("A_R");
  rp.H_R = r.Get<double>("H_R");
  rp.t_R = r.Get<double>("t_R");
  rp.a_H = r.Get<double>("a_H");
  rp.x_H_prime = r.Get<double>("x_H_prime");
  rp.x_R_prime = r.Get<double>("x_R_prime", -0.5);
  rp.gamma_R_minus = r.Get<double>("gamma_R_minus");
  rp.gamma_R_plus = r.Get<double>("gamma_R_plus");
  rp.l_R_prime = r.Get<double>("l_R_prime");
  rp.epsilon = r.Get<double>("epsilon");
  rp.kappa = r.Get<double>("kappa");
  rp.f_alpha = r.Get<double>("f_alpha");
  if (r.Has("z_top")) rp.z_top = r.Get<double>("z_top");
}

std::vector<double> Column(const data::ConfigNode& table, const char* key) {
  return table[key].As<std::vector<double>>();
}

void ReadCfdPropeller(const data::ConfigNode& pr, const std::filesystem::path& path, PropellerParameters& pp) {
  if (pr.Has("hub_ratio")) pp.hub_ratio = pr.Get<double>("hub_ratio");
  pp.y_P = pr.Get<double>("y_P", 0.0);
  if (pr.Has("z_P")) pp.z_P = pr.Get<double>("z_P");
  pp.blades = pr.Get<int>("blades", 0);
  if (auto t = pr.Find("open_water")) {
    t->ExpectKeys({"J", "K_T", "K_Q", "source"});
    OpenWaterCurve c;
    c.J = Column(*t, "J");
    c.K_T = Column(*t, "K_T");
    c.K_Q = Column(*t, "K_Q");
    c.origin = path.string() + ": propeller.open_water";
    pp.open_water = std::move(c);
  }
  if (auto q = pr.Find("K_Q_coefficients")) {
    const auto k = q->As<std::vector<double>>();
    if (k.size() != 3) q->Fail("a list of three coefficients [q0, q1, q2] of K_Q = q0 + q1 J + q2 J^2");
    pp.kq = std::array<double, 3>{k[0], k[1], k[2]};
  }
}

}  // namespace

void ShipParameters::Validate(const std::string& src) const {
  const Principal& p = principal;
  Positive(src, "principal.Lpp", p.Lpp);
  Positive(src, "principal.B", p.B);
  Positive(src, "principal.d", p.d);
  Positive(src, "principal.displacement", p.displacement);
  Positive(src, "principal.rho", p.rho);
  Positive(src, "principal.k_zz", p.k_zz);
  Positive(src, "principal.nu", p.nu);
  if (std::abs(p.x_G) >= 0.5 * p.Lpp) Unphysical(src, "principal.x_G", p.x_G, "|x_G| < Lpp/2");
  if (p.displacement >= p.Lpp * p.B * p.d) {
    Unphysical(src, "principal.displacement", p.displacement, "less than Lpp*B*d (block coefficient < 1)");
  }
  for (int i = 0; i < HullCoefficients<double>::kCount; ++i) {
    Finite(src, "hull." + std::string(HullCoefficients<double>::kNames[i]), hull[i]);
  }
  if (hull.m_x < 0) Unphysical(src, "hull.m_x_prime", hull.m_x, "a non-negative added mass");
  if (hull.m_y < 0) Unphysical(src, "hull.m_y_prime", hull.m_y, "a non-negative added mass");
  if (hull.J_z < 0) Unphysical(src, "hull.J_z_prime", hull.J_z, "a non-negative added inertia");
  const PropellerParameters& pp = propeller;
  Positive(src, "propeller.D_p", pp.D_p);
  if (pp.mmg) {
    InRange(src, "propeller.t_P", pp.t_P, 0.0, 1.0);
    InRange(src, "propeller.w_P0", pp.w_P0, 0.0, 1.0);
    if (!(pp.k0 > 0)) Unphysical(src, "propeller.k0", pp.k0, "K_T(0) > 0");
  }
  if (pp.hub_ratio) InRange(src, "propeller.hub_ratio", *pp.hub_ratio, 0.0, 0.5);
  if (pp.z_P) Positive(src, "propeller.z_P", *pp.z_P);
  Finite(src, "propeller.y_P", pp.y_P);
  if (pp.open_water) pp.open_water->Validate(src, "propeller.open_water");
  if (has_rudder) ValidateRudder(src);
  if (!(limits.rudder_max > 0 && limits.rudder_max <= M_PI / 2)) {
    Unphysical(src, "actuators.rudder_max_deg", limits.rudder_max / kDeg, "a value in (0, 90]");
  }
  Positive(src, "actuators.rudder_rate_deg_s", limits.rudder_rate / kDeg);
  if (limits.rps_rate < 0) Unphysical(src, "actuators.rps_rate", limits.rps_rate, "a non-negative value");
  Positive(src, "ship.scale", scale);
  if (approach_speed < 0) Unphysical(src, "conditions.approach_speed", approach_speed, "a non-negative speed");
}

void ShipParameters::ValidateRudder(const std::string& src) const {
  const RudderParameters& rp = rudder;
  Positive(src, "rudder.A_R", rp.A_R);
  Positive(src, "rudder.H_R", rp.H_R);
  InRange(src, "rudder.t_R", rp.t_R, 0.0, 1.0);
  Positive(src, "rudder.epsilon", rp.epsilon);
  Positive(src, "rudder.f_alpha", rp.f_alpha);
  if (rp.z_top && *rp.z_top < 0) Unphysical(src, "rudder.z_top", *rp.z_top, "a depth below the waterline (m, >= 0)");
  if (rp.gamma_R_minus < 0) Unphysical(src, "rudder.gamma_R_minus", rp.gamma_R_minus, "a non-negative value");
  if (rp.gamma_R_plus < 0) Unphysical(src, "rudder.gamma_R_plus", rp.gamma_R_plus, "a non-negative value");
}

ShipParameters LoadShip(const std::filesystem::path& path) { return LoadShip(data::ConfigNode::LoadFile(path), path); }

ShipParameters LoadShip(const data::ConfigNode& root, const std::filesystem::path& path) {
  using data::ConfigNode;
  root.ExpectKeys({"ship", "principal", "hull", "propeller", "rudder", "actuators", "conditions", "geometry"});
  ShipParameters s;

  const ConfigNode ship = root["ship"];
  ship.ExpectKeys({"name", "source", "scale_name", "scale"});
  s.name = ship.Get<std::string>("name");
  s.source = ship.Get<std::string>("source", "");
  s.scale_name = ship.Get<std::string>("scale_name", "");
  s.scale = ship.Get<double>("scale", 1.0);

  const ConfigNode p = root["principal"];
  p.ExpectKeys({"Lpp", "B", "d", "displacement", "x_G", "k_zz", "rho", "nu", "wetted_area"});
  s.principal.Lpp = p.Get<double>("Lpp");
  s.principal.B = p.Get<double>("B");
  s.principal.d = p.Get<double>("d");
  s.principal.displacement = p.Get<double>("displacement");
  s.principal.x_G = p.Get<double>("x_G");
  s.principal.k_zz = p.Get<double>("k_zz", 0.25);
  s.principal.rho = p.Get<double>("rho", 1025.0);
  s.principal.nu = p.Get<double>("nu", 1.1883e-6);
  s.principal.wetted_area = p.Get<double>("wetted_area", 0.0);

  s.has_hull = root.Has("hull");
  if (s.has_hull) {
    const ConfigNode h = root["hull"];
    std::vector<std::string> names(HullCoefficients<double>::kNames.begin(), HullCoefficients<double>::kNames.end());
    h.ExpectKeys(names);
    for (int i = 0; i < HullCoefficients<double>::kCount; ++i) s.hull[i] = h.Get<double>(names[i]);
  }

  const ConfigNode pr = root["propeller"];
  pr.ExpectKeys({"D_p", "t_P", "w_P0", "k0", "k1", "k2", "x_P_prime", "C1", "C2_pos", "C2_neg", "reverse_KT",
                 "hub_ratio", "y_P", "z_P", "open_water", "K_Q_coefficients", "blades"});
  auto& pp = s.propeller;
  pp.D_p = pr.Get<double>("D_p");
  // The MMG keys: required with a hull section, optional for a CFD-only file.
  pp.mmg = s.has_hull || pr.Has("k0");
  if (pp.mmg) {
    pp.t_P = pr.Get<double>("t_P");
    pp.w_P0 = pr.Get<double>("w_P0");
    pp.k0 = pr.Get<double>("k0");
    pp.k1 = pr.Get<double>("k1");
    pp.k2 = pr.Get<double>("k2");
  }
  ReadCfdPropeller(pr, path, pp);
  pp.x_P_prime = pr.Get<double>("x_P_prime");
  pp.C1 = pr.Get<double>("C1", 2.0);
  pp.C2_pos = pr.Get<double>("C2_pos", 1.6);
  pp.C2_neg = pr.Get<double>("C2_neg", 1.1);
  if (auto rev = pr.Find("reverse_KT")) {
    const auto k = rev->As<std::vector<double>>();
    if (k.size() != 3) rev->Fail("a list of three coefficients [k0, k1, k2]");
    pp.reverse_kt = std::array<double, 3>{k[0], k[1], k[2]};
  }

  s.has_rudder = root.Has("rudder");
  if (s.has_rudder) ReadRudder(root["rudder"], s.rudder);
  if (auto a = root.Find("actuators")) {
    a->ExpectKeys({"rudder_max_deg", "rudder_rate_deg_s", "rps_max", "rps_rate"});
    s.limits.rudder_max = a->Get<double>("rudder_max_deg", 35.0) * kDeg;
    s.limits.rudder_rate = a->Get<double>("rudder_rate_deg_s", 2.34) * kDeg;
    if (auto rps_max = a->Find("rps_max")) s.limits.rps_max = rps_max->As<double>();
    s.limits.rps_rate = a->Get<double>("rps_rate", 0.0);
  }
  if (auto c = root.Find("conditions")) {
    c->ExpectKeys({"approach_speed"});
    s.approach_speed = c->Get<double>("approach_speed", 0.0);
  }
  s.Validate(path.string());
  return s;
}

void RequireManeuveringModel(const ShipParameters& ship, const std::string& source) {
  std::vector<std::string> missing;
  if (!ship.has_hull) missing.push_back("hull derivatives (a hull section, or --derivatives)");
  if (!ship.has_rudder) missing.push_back("a rudder section");
  if (!ship.propeller.mmg) missing.push_back("the MMG propeller keys t_P, w_P0, k0, k1, k2");
  if (missing.empty()) return;
  std::string list;
  for (const std::string& m : missing) list += (list.empty() ? "" : "; ") + m;
  throw ConfigError(fmt::format("{}: ship '{}' is a hull for CFD only; the MMG model needs {}", source, ship.name, list));
}

OpenWaterCurve CfdOpenWater(const ShipParameters& ship, const std::string& source) {
  const PropellerParameters& pp = ship.propeller;
  if (pp.open_water) return *pp.open_water;
  if (!pp.mmg || !pp.kq) {
    throw ConfigError(fmt::format(
        "{}: propeller: the CFD propeller needs K_T and K_Q: an open_water: {{J, K_T, K_Q}} table, or k0, k1, k2 "
        "with K_Q_coefficients [q0, q1, q2]",
        source));
  }
  // Up to the J where K_T = 0 (k0 > 0 and K_T decreasing).
  const double a = pp.k2, b = pp.k1, c = pp.k0;
  const double J0 = std::abs(a) < 1e-12 ? -c / b : (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
  if (!(J0 > 0) || !std::isfinite(J0)) {
    throw ConfigError(fmt::format("{}: propeller.k0, k1, k2: K_T never reaches 0 for J > 0; expected a K_T falling with J",
                                  source));
  }
  OpenWaterCurve curve = OpenWaterCurve::FromQuadratics({pp.k0, pp.k1, pp.k2}, *pp.kq, J0);
  curve.origin = source + ": propeller.k0..k2, K_Q_coefficients";
  curve.Validate(source, "propeller (k0..k2, K_Q_coefficients)");
  return curve;
}

ShipParameters ScaleShip(const ShipParameters& ship, double lambda, bool friction_correction) {
  if (!(lambda > 0)) throw ModelError(fmt::format("scale factor {}: expected a positive ratio", lambda));
  ShipParameters s = ship;
  const double sq = std::sqrt(lambda);
  Principal& p = s.principal;
  p.Lpp *= lambda;
  p.B *= lambda;
  p.d *= lambda;
  p.displacement *= lambda * lambda * lambda;
  p.x_G *= lambda;
  p.wetted_area *= lambda * lambda;
  s.propeller.D_p *= lambda;
  s.rudder.A_R *= lambda * lambda;
  s.rudder.H_R *= lambda;
  if (s.rudder.z_top) *s.rudder.z_top *= lambda;
  s.limits.rudder_rate /= sq;
  if (s.limits.rps_max) *s.limits.rps_max /= sq;
  s.limits.rps_rate /= lambda;
  s.approach_speed *= sq;
  s.scale = ship.scale / lambda;
  if (friction_correction) {
    if (!(ship.principal.wetted_area > 0)) {
      throw ModelError(fmt::format(
          "ship '{}': the ITTC-1957 friction correction of R0' needs principal.wetted_area (m^2), which is not "
          "given",
          ship.name));
    }
    const double U_from = ship.approach_speed > 0 ? ship.approach_speed : 1.0;
    const double Re_from = U_from * ship.principal.Lpp / ship.principal.nu;
    const double Re_to = U_from * sq * p.Lpp / p.nu;
    const double dCF = data::Ittc57FrictionCoefficient(Re_to) - data::Ittc57FrictionCoefficient(Re_from);
    s.hull.R0 += dCF * ship.principal.wetted_area / (ship.principal.Lpp * ship.principal.d);
  }
  return s;
}

}  // namespace kelvin::sim
