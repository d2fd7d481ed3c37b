#include "cfd/run/propeller_actuator.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "cfd/motion/rigid_motion.h"
#include "cfd/run/case_config.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

// The disk from the ship file: centre in grid axes (y to port, the calm
// waterline at z = 0), thrust along +x.
ActuatorDiskOptions DiskFromShip(const FreeRunningSettings& fr, const ConfigNode& node, const std::string& where) {
  const sim::PropellerParameters& pp = fr.ship.propeller;
  const std::string ship = fr.ship_file.string();
  if (!pp.z_P) throw ConfigError(fmt::format("{}: propeller.z_P: expected the depth of the shaft axis below the waterline (m) for the CFD propeller", ship));
  if (!pp.hub_ratio) throw ConfigError(fmt::format("{}: propeller.hub_ratio: expected r_hub / R for the CFD propeller", ship));
  ActuatorDiskOptions o;
  o.name = fmt::format("{} (the disk of {}: propeller.D_p, x_P_prime, y_P, z_P, hub_ratio)", where, ship);
  o.diameter = pp.D_p;
  o.hub_ratio = *pp.hub_ratio;
  o.centre = Vector3(fr.body.centre.x() + pp.x_P_prime * fr.ship.principal.Lpp, -pp.y_P, -*pp.z_P);
  o.axis = Vector3::UnitX();
  o.thickness = node.Get<double>("thickness", 0.25) * pp.D_p;
  o.distribution = GetEnum(node, "distribution", ActuatorDiskOptions::Distribution::kHoughOrdway,
                           {{"hough_ordway", ActuatorDiskOptions::Distribution::kHoughOrdway},
                            {"uniform", ActuatorDiskOptions::Distribution::kUniform}});
  return o;
}

SelfPropulsionOptions ReadSelfPropulsion(const ConfigNode& n) {
  n.ExpectKeys({"start_time", "response_time", "average_time", "towed_resistance"});
  SelfPropulsionOptions o;
  o.start_time = n.Has("start_time") ? n.GetPositive("start_time", true) : 0.0;
  o.response_time = n.Has("response_time") ? n.GetPositive("response_time") : 1.0;
  o.average_time = n.Has("average_time") ? n.GetPositive("average_time") : 2.0;
  o.towed_resistance = n.Has("towed_resistance") ? n.GetPositive("towed_resistance", true) : 0.0;
  return o;
}

}  // namespace

std::unique_ptr<BodyActuator> LoadPropellerActuator(const Case& c, const ConfigNode& root) {
  if (!root.Has("propeller")) return nullptr;
  const ConfigNode node = root["propeller"];
  if (!c.free_running) node.Fail("no propeller: section without motion: {kind: free} (the disk acts on a free body)");
  node.ExpectKeys({"thickness", "distribution", "correction", "thrust_relaxation", "rate", "self_propulsion", "swirl"});
  const FreeRunningSettings& fr = *c.free_running;
  const std::string where = node.Where();
  PropellerOptions po;
  po.name = fr.ship_file.string() + ": propeller";
  po.correction = GetEnum(node, "correction", PropellerOptions::InflowCorrection::kAnnularMomentum,
                          {{"annular", PropellerOptions::InflowCorrection::kAnnularMomentum},
                           {"disk", PropellerOptions::InflowCorrection::kDiskMomentum}});
  po.thrust_relaxation = node.Get<double>("thrust_relaxation", 0.7);
  po.apply_torque = node.Get<bool>("swirl", true);
  PropellerRunOptions ro;
  const ConfigNode rate = node["rate"];
  rate.ExpectKeys({"n", "ramp_time"});
  ro.n = rate.GetPositive("n");
  ro.ramp_time = rate.Has("ramp_time") ? rate.GetPositive("ramp_time", true) : fr.body.ramp_time;
  if (auto sp = node.Find("self_propulsion")) {
    ro.self_propulsion = ReadSelfPropulsion(*sp);
    if (fr.body.free[0]) (*sp).Fail("surge held (motion.free without surge): the controller balances the carriage force");
  }
  ro.speed = fr.body.initial[0];
  ro.external_x = fr.body.external.X;
  std::unique_ptr<PropellerActuator> a;
  ValidateAt(node, [&] {
    sim::OpenWaterCurve curve = sim::CfdOpenWater(fr.ship, fr.ship_file.string());
    // On ranks the disk is found on the whole mesh, as serially, and acts on the rank's cells of it.
    ActuatorDisk disk(c.whole_mesh ? *c.whole_mesh : *c.mesh, DiskFromShip(fr, node, where));
    if (c.part) disk.Localize(c.part, c.mesh->n_cells());
    a = std::make_unique<PropellerActuator>(Propeller(std::move(disk), std::move(curve), po), ro, c.settings.rho,
                                            fr.ship.propeller.y_P);
  });
  return a;
}

PropellerActuator::PropellerActuator(Propeller propeller, PropellerRunOptions options, double rho, double y_P)
    : propeller_(std::move(propeller)), options_(options), rho_(rho), y_P_(y_P), n_set_(options.n) {}

void PropellerActuator::BeforeStep(double t_new, double dt) {
  t_ = t_new;
  dt_ = dt;
  const auto& sp = options_.self_propulsion;
  if (sp && t_new > sp->start_time && t_new > options_.ramp_time) {
    // Integral control on the carriage force of the last step.
    const double dT_dn = last_.T > 0.0 && n_set_ > 0.0 ? 2.0 * last_.T / n_set_ : 0.0;
    if (dT_dn > 0.0) n_set_ += dt / sp->response_time * last_constraint_x_ / dT_dn;
    n_ = n_set_;
  } else {
    n_ = options_.n * StartupFactor(t_new, options_.ramp_time);
  }
}

void PropellerActuator::Update(const PimpleSolver& solver, const FreeBody& body, int /*outer*/,
                               std::vector<Vector3>& cell_source, PlanarLoad& load) {
  applied_ = false;
  if (!(n_ > 1e-9 * options_.n)) {
    last_ = {};
    return;
  }
  const Pose pose = body.At(t_);
  const Eigen::Matrix3d R = solver.mesh().placement_rotation();
  const Vector3 centre = pose.Rotation() * body.centre() + pose.Translation(body.centre());
  const Vector3 V = pose.Velocity(), W = pose.AngularVelocity();
  const auto x = solver.mesh().cell_centres();
  auto body_velocity = [&](int c) { return Vector3(V + W.cross(x[c] - centre)); };
  const bool start_up = t_ <= options_.ramp_time;
  last_ = propeller_.Update(solver, body_velocity, R, n_, rho_, cell_source, start_up);
  if (last_.clamped && !warned_) {
    // Start-up: the flow at the stern may still run ahead of the hull, or not
    // yet carry the disk's induced velocity; J is held inside the table.
    spdlog::info("propeller start-up at t = {:.4g} s: J held at {:.4g}, the end of the open-water table (U_A = "
                 "{:.4g} m/s, U_disk = {:.4g} m/s, n = {:.4g} 1/s), until the flow takes up the disk's load",
                 t_, last_.J, last_.U_A, last_.U_disk, n_);
    warned_ = true;
  }
  applied_ = true;
  load.X += last_.T;
  load.N += -y_P_ * last_.T;
}

void PropellerActuator::ApplyRestored(const PimpleSolver& solver, std::vector<Vector3>& cell_source) const {
  if (applied_) propeller_.ApplyState(rho_, solver.mesh().placement_rotation(), cell_source);
}

void PropellerActuator::Start(History& h) {
  state_col_ = h.Add("propeller/state", 3, "1/s, N, N m", "rate n, thrust T and torque Q of the body-force propeller");
  effective_col_ = h.Add("propeller/inflow", 5, "m/s, m/s, 1, 1, 1",
                         "U_disk (through the disk, relative to it), U_A (induced velocity removed), J, K_T, K_Q");
}

void PropellerActuator::AfterStep(const FreeBody& body, History& h) {
  last_constraint_x_ = body.constraint_load().X;
  h.Set(state_col_, Vector3(last_.n, last_.T, last_.Q));
  const std::vector<double> inflow = {last_.U_disk, last_.U_A, last_.J, last_.K_T, last_.K_Q};
  h.Set(effective_col_, std::span<const double>(inflow));
  if (options_.self_propulsion && t_ > options_.self_propulsion->start_time) {
    window_.push_back({dt_, last_.n, last_.T, last_.Q, last_.J, last_constraint_x_});
    window_length_ += dt_;
    while (window_length_ - window_.front().dt >= options_.self_propulsion->average_time * (1 - 1e-12)) {
      window_length_ -= window_.front().dt;
      window_.pop_front();
    }
  }
}

void PropellerActuator::AddCheckpointScalars(CheckpointScalars& s) const {
  const Propeller::State p = propeller_.GetState();
  s["propeller_thrust"] = p.thrust;
  s["propeller_torque"] = p.torque;
  s["propeller_n"] = p.n;
  s["propeller_n_set"] = n_set_;
  s["propeller_carriage_x"] = last_constraint_x_;
  s["propeller_window_steps"] = static_cast<double>(window_.size());
  s["propeller_window_length"] = window_length_;
  for (std::size_t i = 0; i < window_.size(); ++i) {
    const Sample& w = window_[i];
    const double values[kSampleFields] = {w.dt, w.n, w.T, w.Q, w.J, w.X_c};
    for (int k = 0; k < kSampleFields; ++k) s[fmt::format("propeller_window_{}_{}", i, k)] = values[k];
  }
  s["propeller_last_T"] = last_.T;
  s["propeller_applied"] = applied_ ? 1.0 : 0.0;
}

void PropellerActuator::RestoreScalars(const CheckpointScalars& s) {
  auto get = [&](const char* name) {
    const auto it = s.find(name);
    if (it == s.end()) throw DataFileError(fmt::format("the checkpoint has no {}; the case runs a propeller", name));
    return it->second;
  };
  propeller_.SetState({get("propeller_thrust"), get("propeller_torque"), get("propeller_n")});
  n_set_ = get("propeller_n_set");
  last_constraint_x_ = get("propeller_carriage_x");
  window_.clear();
  const auto steps = static_cast<std::size_t>(get("propeller_window_steps"));
  for (std::size_t i = 0; i < steps; ++i) {
    double v[kSampleFields];
    for (int k = 0; k < kSampleFields; ++k) v[k] = get(fmt::format("propeller_window_{}_{}", i, k).c_str());
    window_.push_back({v[0], v[1], v[2], v[3], v[4], v[5]});
  }
  window_length_ = get("propeller_window_length");
  last_.T = get("propeller_last_T");
  applied_ = get("propeller_applied") != 0.0;
  last_.n = n_set_;
}

PropellerActuator::Point PropellerActuator::SelfPropulsionPoint() const {
  Point p{};
  double w = 0.0;
  for (const Sample& s : window_) {
    w += s.dt;
    p.n += s.dt * s.n;
    p.T += s.dt * s.T;
    p.Q += s.dt * s.Q;
    p.J += s.dt * s.J;
    p.X_c += s.dt * s.X_c;
  }
  p.n /= w;
  p.T /= w;
  p.Q /= w;
  p.J /= w;
  p.X_c /= w;
  const double D = propeller_.disk().options().diameter;
  p.K_T = p.T / (rho_ * p.n * p.n * std::pow(D, 4));
  p.K_Q = p.Q / (rho_ * p.n * p.n * std::pow(D, 5));
  const double R_T = options_.self_propulsion->towed_resistance;
  p.t_deduction = R_T > 0.0 ? 1.0 - (R_T - options_.external_x) / p.T : std::nan("");
  // Thrust identity; a K_T beyond the table (a window not settled yet) has none.
  const sim::OpenWaterCurve& curve = propeller_.curve();
  const bool inside = p.K_T <= curve.KT(curve.J_min()) && p.K_T >= curve.KT(curve.J_max());
  p.J_T = inside ? curve.JFromKT(p.K_T) : std::nan("");
  p.w_T = 1.0 - p.J_T * p.n * D / options_.speed;
  return p;
}

void PropellerActuator::WriteHistory(data::H5Writer& w) const {
  if (!options_.self_propulsion || window_.empty()) return;
  const Point p = SelfPropulsionPoint();
  auto put = [&](const char* name, double v, const char* units, const char* what) {
    w.WriteArray(std::string("self_propulsion/") + name, std::vector<double>{v}, {1}, units, what);
  };
  put("n", p.n, "1/s", "propeller rate, mean over the averaging window");
  put("thrust", p.T, "N", "thrust T");
  put("torque", p.Q, "N m", "torque Q");
  put("K_T", p.K_T, "1", "T / (rho n^2 D^4)");
  put("K_Q", p.K_Q, "1", "Q / (rho n^2 D^5)");
  put("J", p.J, "1", "effective advance ratio of the disk (induced velocity removed)");
  put("J_T", p.J_T, "1", "advance ratio of the open-water curve at K_T (thrust identity)");
  put("wake_fraction", p.w_T, "1", "Taylor wake fraction from thrust identity, 1 - J_T n D / U");
  put("thrust_deduction", p.t_deduction, "1", "1 - (R_T - F_D) / T (NaN without towed_resistance)");
  put("carriage_force", p.X_c, "N", "mean carriage force left on the held surge (0 at the point)");
  put("window", window_length_, "s", "length of the averaging window (the last self_propulsion.average_time)");
}

std::vector<std::string> PropellerActuator::Finish() {
  std::vector<std::string> lines = {fmt::format(
      "propeller at the last step: n {:.4g} 1/s, T {:.4g} N, Q {:.4g} N m, J {:.4g} (U_disk {:.4g} m/s, U_A {:.4g} m/s)",
      last_.n, last_.T, last_.Q, last_.J, last_.U_disk, last_.U_A)};
  if (options_.self_propulsion && !window_.empty()) {
    const Point p = SelfPropulsionPoint();
    lines.push_back(fmt::format(
        "self-propulsion over the last {:.3g} s: n {:.4g} 1/s, T {:.4g} N, Q {:.4g} N m, K_T {:.4f}, 10 K_Q {:.4f}, "
        "J {:.4f}, t {:.4f}, w_T {:.4f}; carriage force left {:.3g} N",
        window_length_, p.n, p.T, p.Q, p.K_T, 10 * p.K_Q, p.J, p.t_deduction, p.w_T, p.X_c));
    if (std::abs(p.X_c) > 0.01 * std::abs(p.T)) {
      lines.push_back(fmt::format(
          "WARNING: not at the self-propulsion point: the carriage still supplies {:.3g} N ({:.1f}% of T); run longer "
          "or shorten self_propulsion.response_time",
          p.X_c, 100 * p.X_c / p.T));
    }
  }
  return lines;
}

}  // namespace kelvin::cfd
